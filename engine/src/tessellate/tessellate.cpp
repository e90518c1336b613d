// Tessellation pattern and mesh assembly (see curvenet/tessellate.hpp).
//
// Vertex numbering is fixed before any evaluation: network vertices first,
// then the interior samples of each segment, then each face's interior
// samples. Faces then fill disjoint ranges in parallel, and triangles are
// concatenated in face order, so the output does not depend on threads.
#include "curvenet/tessellate.hpp"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>

#include <unistd.h>

#include "bezier/bezier_surface.hpp"
#include "curvenet/error.hpp"
#include "curvenet/kernels/kernels.hpp"
#include "patches/patch.hpp"
#include "plans/face_errors.hpp"
#include "plans/plan.hpp"
#include "parallel/fork_join.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

struct RowPoint {
  std::uint32_t id;
  double t;    ///< position along the row in [0, 1]
  Vec2 domain; ///< domain point
};

/// Where zip writes: triangles straight into the mesh, and (when not null)
/// each triangle's domain points, vertex by vertex.
struct TriangleSink {
  std::array<std::uint32_t, 3> *triangles;
  std::array<Vec2, 3> *domains;
  std::size_t capacity, written = 0;
  void add(const RowPoint &a, const RowPoint &b, const RowPoint &c) {
    CURVENET_CHECK(written < capacity, "a sector makes more triangles than its rows allow");
    triangles[written] = {a.id, b.id, c.id};
    if (domains) domains[written] = {a.domain, b.domain, c.domain};
    ++written;
  }
};

/// Triangulates the strip between two rows running in the same direction,
/// `lower` nearer the side; counter-clockwise in the domain. It makes
/// (lower.size() − 1) + (upper.size() − 1) triangles.
void zip(const std::vector<RowPoint> &lower, const std::vector<RowPoint> &upper, TriangleSink &out) {
  size_t j = 0, l = 0;
  while (j + 1 < lower.size() || l + 1 < upper.size()) {
    const bool advanceLower =
        l + 1 >= upper.size() || (j + 1 < lower.size() && lower[j + 1].t <= upper[l + 1].t + 1e-12);
    if (advanceLower) {
      out.add(lower[j], lower[j + 1], upper[l]);
      ++j;
    } else {
      out.add(lower[j], upper[l + 1], upper[l]);
      ++l;
    }
  }
}

/// zip for two evenly spaced rows, `lower` one point longer than `upper`
/// (a sector's rows from the second on), written without its comparisons
/// (a fan sector's triangles were 5 % of a tessellation). Lower triangle
/// L(j, l) = (l_j, l_{j+1}, u_l), upper U(j, l) = (l_j, u_{l+1}, u_l): in
/// zip's order they alternate, L(j, j) U(j + 1, j), until both rows end at
/// t = 1, where the lower triangle comes first: L(m − 2, m − 2),
/// L(m − 1, m − 2), U(m, m − 2) for m upper points — the order of
/// kernels::zipRows, which writes them a vector at a time.
/// The rows are their points' ids alone: zipEven reads nothing else.
void zipEven(const std::vector<std::uint32_t> &lower, const std::vector<std::uint32_t> &upper, TriangleSink &out) {
  const std::size_t m = upper.size();
  CURVENET_CHECK(m >= 1 && lower.size() == m + 1 && out.written + 2 * m - 1 <= out.capacity,
                 "a sector makes more triangles than its rows allow");
  static_assert(sizeof(std::array<std::uint32_t, 3>) == 3 * sizeof(std::uint32_t), "triangles as consecutive ids");
  kernels::zipRows(m, lower.data(), upper.data(), out.triangles[out.written].data());
  out.written += 2 * m - 1;
}

struct Layout {
  std::vector<int> faceResolution;         ///< rows per centre–side triangle of each face
  std::vector<int> segmentIntervals;       ///< samples per segment
  std::vector<std::uint32_t> segmentBase;  ///< first interior sample id
  std::vector<std::uint32_t> faceBase;     ///< first interior id of each face
  std::uint32_t vertexCount;
};

// Samples per tile when face interiors are evaluated through plans: big
// enough to amortize the per-tile setup of the kernels, small enough that a
// tile's structure-of-arrays scratch stays in the L2 cache and that large
// faces split across threads.
constexpr std::size_t kTileSamples = 512;
// Below this many samples in all, tessellation runs serially.
constexpr std::size_t kSerialSamples = 4096;

/// The layout with each face's resolution and each segment's intervals
/// given (a segment's intervals are its own: both faces along it use them).
Layout makeLayout(const Surface &surface, std::vector<int> faceResolution, std::vector<int> segmentIntervals) {
  const Network &net = surface.network();
  Layout layout;
  layout.faceResolution = std::move(faceResolution);
  layout.segmentIntervals = std::move(segmentIntervals);
  // Segments on 2-sided faces need their midpoint as a sample (a domain corner).
  for (size_t f = 0; f < net.faces().size(); ++f)
    if (net.faces()[f].sideCount() == 2)
      for (const FaceSide &side : net.faces()[f].sides)
        if (side.segments.size() == 1 && layout.segmentIntervals[side.segments[0]] % 2)
          ++layout.segmentIntervals[side.segments[0]];
  std::uint32_t next = static_cast<std::uint32_t>(net.vertices().size());
  for (size_t e = 0; e < net.segments().size(); ++e) {
    layout.segmentBase.push_back(next);
    next += static_cast<std::uint32_t>(layout.segmentIntervals[e] - 1);
  }
  for (int f = 0; f < surface.faceCount(); ++f) {
    layout.faceBase.push_back(next);
    next += faceInteriorCount(surface.domainSides(f), layout.faceResolution[f]);
  }
  layout.vertexCount = next;
  return layout;
}

/// The uniform layout: `resolution` everywhere.
Layout makeLayout(const Surface &surface, int resolution) {
  return makeLayout(surface, std::vector<int>(static_cast<std::size_t>(surface.faceCount()), resolution),
                    std::vector<int>(surface.network().segments().size(), resolution));
}

/// Sample ids along segment e at index j ∈ [0, intervals].
std::uint32_t segmentSampleId(const Network &net, const Layout &layout, int e, int j) {
  const Segment &seg = net.segments()[e];
  if (j == 0) return static_cast<std::uint32_t>(seg.start);
  if (j == layout.segmentIntervals[e]) return static_cast<std::uint32_t>(seg.end);
  return layout.segmentBase[e] + static_cast<std::uint32_t>(j - 1);
}

/// Boundary rows of every domain side of face f, in domain-side order.
std::vector<std::vector<RowPoint>> boundaryRows(const Surface &surface, const Layout &layout, int f) {
  const Network &net = surface.network();
  const Face &face = net.faces()[f];
  // Loop side k as (id, side parameter) pairs, in the loop direction.
  std::vector<std::vector<std::pair<std::uint32_t, double>>> loopSides(face.sideCount());
  for (int k = 0; k < face.sideCount(); ++k) {
    const FaceSide &side = face.sides[k];
    auto &list = loopSides[k];
    for (size_t j = 0; j < side.segments.size(); ++j) {
      const int e = side.segments[j], m = layout.segmentIntervals[e];
      const double b0 = j == 0 ? 0.0 : side.breaks[j - 1], b1 = j + 1 == side.segments.size() ? 1.0 : side.breaks[j];
      for (int step = j == 0 ? 0 : 1; step <= m; ++step) {
        const int sample = side.segmentReversed[j] ? m - step : step;
        list.emplace_back(segmentSampleId(net, layout, e, sample), b0 + (b1 - b0) * step / m);
      }
    }
  }
  const int n = surface.domainSides(f);
  std::vector<std::vector<RowPoint>> rows(n);
  for (int i = 0; i < n; ++i) {
    const Surface::DomainSideRange range = surface.domainSideRange(f, i);
    const double width = range.sTo - range.sFrom;
    const Vec2 p0 = surface.domainCorner(f, i), p1 = surface.domainCorner(f, i + 1);
    for (const auto &[id, s] : loopSides[range.faceSide]) {
      if (s < range.sFrom - 1e-12 || s > range.sTo + 1e-12) continue;
      const double t = std::clamp((s - range.sFrom) / width, 0.0, 1.0);
      rows[i].push_back({id, t, p0 + (p1 - p0) * t});
    }
    CURVENET_CHECK(rows[i].size() >= 2 && rows[i].front().t == 0.0 && rows[i].back().t == 1.0,
                   "face " + std::to_string(f) + " domain side " + std::to_string(i) + " has no sample at a corner");
  }
  return rows;
}

/// Samples of one face: a rotation group (EvaluationPlan::Group).
struct Tile {
  int face;
  EvaluationPlan::Group samples;
};

/// The plan and the tiles of samples of every face `wanted` accepts: its
/// rotation groups, members of at most kTileSamples.
template <class Wanted>
std::vector<Tile> planTiles(const Surface &surface, const std::vector<int> &faceResolution,
                            std::vector<std::shared_ptr<const EvaluationPlan>> &plans, std::size_t &total,
                            const Wanted &wanted) {
  std::vector<Tile> tiles;
  total = 0;
  plans.assign(static_cast<std::size_t>(surface.faceCount()), nullptr);
  for (int f = 0; f < surface.faceCount(); ++f) {
    if (!wanted(f)) continue;
    plans[f] = evaluationPlan(planKey(surface.faceOptions(f), surface.domainSides(f), faceResolution[f]));
    const std::size_t size = plans[f]->size();
    for (const EvaluationPlan::Group &g : plans[f]->groups(kTileSamples)) tiles.push_back({f, g});
    total += size;
  }
  return tiles;
}

/// run(tile) for every tile: serially for small totals, else one tile per
/// task. Engine errors (a face's ribbon tables are built on its first tile)
/// name the tile's face.
template <class Run> void forEachTile(const std::vector<Tile> &tiles, std::size_t total, const Run &run) {
  const auto runNamingFace = [&](const Tile &tile) { namingFace(tile.face, [&] { run(tile); }); };
  if (total < kSerialSamples) {
    for (const Tile &tile : tiles) runNamingFace(tile);
    return;
  }
  // One tile per task (grain 1): a tile is already ~10⁵ flops.
  parallel::parallelFor(tbb::blocked_range<std::size_t>(0, tiles.size(), 1),
                        [&](const tbb::blocked_range<std::size_t> &range) {
                          for (std::size_t t = range.begin(); t < range.end(); ++t) runNamingFace(tiles[t]);
                        });
}

/// Vertices of the whole mesh at `resolution` (faceInteriorCount, and r per
/// segment: one more than it has), in floating point so that no resolution
/// overflows it.
double meshVertices(const Surface &surface, int resolution) {
  const double r = resolution;
  double count = static_cast<double>(surface.network().vertices().size()) +
                 static_cast<double>(surface.network().segments().size()) * r;
  for (int f = 0; f < surface.faceCount(); ++f) {
    const double n = surface.domainSides(f);
    count += 1 + n * (r - 1) + n * (r - 1) * (r - 2) / 2;
  }
  return count;
}

/// Refuses a resolution below 1, or one whose mesh the 32-bit vertex
/// indices of Mesh could not number.
void checkResolution(const Surface &surface, int resolution) {
  if (resolution < 1) throw InputError("", "resolution", "must be at least 1");
  const double vertices = meshVertices(surface, resolution);
  if (vertices > static_cast<double>(std::numeric_limits<std::uint32_t>::max())) {
    char count[32];
    std::snprintf(count, sizeof count, "%.3g", vertices);
    throw InputError("", "resolution",
                     std::to_string(resolution) + " gives " + count +
                         " vertices, more than a mesh's 32-bit indices can number (4294967295)");
  }
}

} // namespace

std::size_t faceInteriorPoints(const Surface &surface, int resolution) {
  checkResolution(surface, resolution);
  std::size_t count = 0;
  for (int f = 0; f < surface.faceCount(); ++f) count += faceInteriorCount(surface.domainSides(f), resolution);
  return count;
}

std::size_t evaluateFaceInteriors(const Surface &surface, std::span<Vec3> out, const TessellationOptions &options) {
  const std::size_t count = faceInteriorPoints(surface, options.resolution);
  if (out.size() < count)
    throw InputError("", "output", "holds " + std::to_string(out.size()) + " points for " + std::to_string(count));
  const int faces = surface.faceCount();
  const bool transfinite = faces > 0 && SurfaceAccess::patch(surface, 0) != nullptr;
  if (!transfinite || !options.usePlans) {
    // The Bézier schemes (and the pointwise reference): tessellate's own points.
    TessellationOptions uniform = options;
    uniform.tolerance = 0; // face interiors are at options.resolution
    const Mesh mesh = tessellate(surface, uniform);
    const Layout layout = makeLayout(surface, options.resolution);
    const auto interior = mesh.positions.begin() + static_cast<std::ptrdiff_t>(layout.faceBase.front());
    CURVENET_CHECK(static_cast<std::size_t>(mesh.positions.end() - interior) == count,
                   "face interiors: mesh and layout disagree on the sample count");
    std::copy(interior, mesh.positions.end(), out.begin());
    return count;
  }
  std::optional<tbb::global_control> limit;
  if (options.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, options.threads);
  std::vector<std::shared_ptr<const EvaluationPlan>> plans;
  std::size_t total = 0;
  const std::vector<Tile> tiles =
      planTiles(surface, std::vector<int>(static_cast<std::size_t>(faces), options.resolution), plans, total,
                [](int) { return true; });
  CURVENET_CHECK(total == count, "face interiors: plans and layout disagree on the sample count");
  std::vector<std::size_t> faceBase(static_cast<std::size_t>(faces) + 1, 0);
  for (int f = 0; f < faces; ++f) faceBase[f + 1] = faceBase[f] + plans[f]->size();
  const Vec3 origin = surface.origin();
  forEachTile(tiles, total, [&](const Tile &tile) {
    // The kernel writes the points, the surface's origin added.
    SurfaceAccess::patch(surface, tile.face)
        ->evaluatePlannedGroup(*plans[tile.face], tile.samples,
                               PositionSink::interleaved(out.data() + faceBase[tile.face] + tile.samples.first, origin));
  });
  return count;
}

std::vector<Vec3> evaluateFaceInteriors(const Surface &surface, const TessellationOptions &options) {
  std::vector<Vec3> points(faceInteriorPoints(surface, options.resolution));
  evaluateFaceInteriors(surface, points, options);
  return points;
}

std::string memoryShortfall(double bytes) {
  // MemAvailable from /proc/meminfo, else the physical memory, else unknown.
  double available = 0;
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  double kilobytes = 0;
  while (meminfo >> key >> kilobytes >> unit)
    if (key == "MemAvailable:") {
      available = kilobytes * 1024;
      break;
    }
  if (!(available > 0)) {
    const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGE_SIZE);
    available = pages > 0 && pageSize > 0 ? static_cast<double>(pages) * static_cast<double>(pageSize) : 0;
  }
  if (!(available > 0) || bytes <= 0.8 * available) return {};
  char message[128];
  std::snprintf(message, sizeof message, "needs about %.3g GiB of memory but only %.3g GiB is available",
                bytes / 0x1p30, available / 0x1p30);
  return message;
}

std::size_t estimateMeshVertices(const Surface &surface, int resolution) {
  const double vertices = meshVertices(surface, std::max(resolution, 1));
  return vertices < 0x1p63 ? static_cast<std::size_t>(vertices) : std::numeric_limits<std::size_t>::max();
}

namespace {
/// The faces one tessellation pass writes: all of them, or those with only[f] set.
struct FaceSelection {
  const std::vector<char> *only = nullptr;
  bool operator()(int f) const { return !only || (*only)[f]; }
};

/// Every face's boundary rows, one list per side, in parallel.
using BoundaryRows = std::vector<std::vector<std::vector<RowPoint>>>;

/// Sizes `mesh` for `layout` (a full pass) or checks that it already has
/// that layout (a pass over some faces).
void prepareMesh(const Surface &surface, const Layout &layout, bool partial, bool record, Mesh &mesh) {
  if (partial) {
    CURVENET_CHECK(mesh.positions.size() == layout.vertexCount && mesh.normals.size() == layout.vertexCount &&
                       mesh.faceTriangleStart.size() == static_cast<std::size_t>(surface.faceCount()) + 1 &&
                       mesh.domainPoints.size() == (record ? layout.vertexCount : 0),
                   "re-tessellation of a mesh with another layout, resolution or domain-point setting");
  } else {
    mesh.positions.resize(layout.vertexCount);
    mesh.normals.resize(layout.vertexCount);
    if (record) mesh.domainPoints.resize(layout.vertexCount);
    else mesh.domainPoints.clear();
    // A reused mesh (tessellate into a Mesh): the boundary samples a full
    // pass leaves alone — those of segments no face borders, normals no face
    // owns — read as in a fresh mesh. Every face-interior sample is written.
    const std::size_t boundary = layout.faceBase.empty() ? layout.vertexCount : layout.faceBase.front();
    std::fill_n(mesh.positions.begin(), boundary, Vec3{});
    std::fill_n(mesh.normals.begin(), boundary, Vec3{});
    if (record) std::fill_n(mesh.domainPoints.begin(), boundary, MeshDomainPoint{});
  }
}

/// Boundary positions come from the curves themselves: vertices, then the
/// samples of every segment a selected face borders.
void writeBoundaryPositions(const Network &net, const Layout &layout, const FaceSelection &wanted, Mesh &mesh) {
  for (size_t v = 0; v < net.vertices().size(); ++v) mesh.positions[v] = net.vertices()[v].position;
  for (size_t e = 0; e < net.segments().size(); ++e) {
    const auto &adjacent = net.segments()[e].faces;
    if (!std::any_of(adjacent.begin(), adjacent.end(), [&](int f) { return f >= 0 && wanted(f); })) continue;
    for (int j = 1; j < layout.segmentIntervals[e]; ++j)
      mesh.positions[segmentSampleId(net, layout, static_cast<int>(e), j)] =
          net.segments()[e].curve.point(double(j) / layout.segmentIntervals[e]);
  }
}

/// Boundary normals from the lowest-numbered face that shows each point
/// (deterministic): owners first, in face order, then the owners' normals in
/// parallel, each point evaluated by one fixed face whatever the thread count.
/// With plans (`planned`), a face side sampled as a uniform layout samples
/// it (t = j / r, one segment) takes its geometry-free data from the face's
/// plan (Patch::evaluatePlannedBoundary); other sides, and every side
/// without plans, solve their sweeps (Surface::evaluate on a batch).
void evaluateBoundaryNormals(const Surface &surface, const Layout &layout, const BoundaryRows &rows,
                             const FaceSelection &wanted, bool planned, bool record, Mesh &mesh) {
  struct BoundaryNormal {
    std::uint32_t id;
    int face, side; ///< side: the domain side of a planned point, −1 for the others
    std::uint32_t index; ///< planned: j of t = j / r
    Vec2 domain;
  };
  std::vector<BoundaryNormal> boundary;
  std::vector<std::shared_ptr<const EvaluationPlan>> plans(static_cast<std::size_t>(surface.faceCount()));
  {
    std::vector<char> hasNormal(layout.vertexCount, 0);
    for (int f = 0; f < surface.faceCount(); ++f) {
      const int r = layout.faceResolution[f];
      if (wanted(f) && planned && r >= 2) {
        plans[f] = evaluationPlan(planKey(surface.faceOptions(f), surface.domainSides(f), r));
        if (!plans[f]->hasBoundary()) plans[f] = nullptr;
      }
      // The face's planned points side by side, then the others (corners
      // among them: there the formula's corner terms meet their singular
      // limit, which the pointwise evaluation takes at the exact corner).
      std::vector<BoundaryNormal> others;
      for (int i = 0; i < static_cast<int>(rows[f].size()); ++i) {
        const auto &row = rows[f][i];
        bool uniform = plans[f] && row.size() == static_cast<std::size_t>(r) + 1;
        for (std::size_t q = 0; uniform && q < row.size(); ++q) uniform = row[q].t == double(q) / r;
        for (std::size_t q = 0; q < row.size(); ++q) {
          const RowPoint &p = row[q];
          if (hasNormal[p.id]) continue;
          hasNormal[p.id] = 1;
          if (!wanted(f)) continue; // owned by a face kept as it was
          const bool fromPlan = uniform && q > 0 && q + 1 < row.size();
          (fromPlan ? boundary : others).push_back({p.id, f, fromPlan ? i : -1, static_cast<std::uint32_t>(q), p.domain});
        }
      }
      boundary.insert(boundary.end(), others.begin(), others.end());
    }
  }
  // Batches of one face's boundary points (one face side's when planned;
  // `boundary` lists them face by face) through the batched evaluation: a
  // point's normal depends only on its batch and its place in it, never on
  // the threads, and a re-tessellation sees the same batches.
  constexpr std::size_t kBoundaryBatch = 1024;
  std::vector<std::pair<std::size_t, std::size_t>> batches;
  for (std::size_t begin = 0; begin < boundary.size();) {
    std::size_t end = begin;
    const BoundaryNormal &head = boundary[begin];
    while (end < boundary.size() && end - begin < kBoundaryBatch && boundary[end].face == head.face &&
           boundary[end].side == head.side)
      ++end;
    batches.push_back({begin, end});
    begin = end;
  }
  parallel::parallelFor(std::size_t{0}, batches.size(), [&](std::size_t item) {
    // Named, not a structured binding: the inner lambda captures begin
    // (C++20 allows it; clang 14, the fuzz build's compiler, does not).
    const std::size_t begin = batches[item].first, end = batches[item].second;
    const BoundaryNormal &head = boundary[begin];
    const std::size_t count = end - begin;
    if (head.side >= 0) {
      thread_local std::vector<std::uint32_t> index;
      index.resize(count);
      for (std::size_t k = begin; k < end; ++k) index[k - begin] = boundary[k].index;
      SurfaceAccess::patch(surface, head.face)
          ->evaluatePlannedBoundary(*plans[head.face], head.side, index.data(), count,
                                    [&](std::size_t at, std::size_t size, const double *const r[9]) {
                                      for (std::size_t k = 0; k < size; ++k) {
                                        const BoundaryNormal &b = boundary[begin + at + k];
                                        const Vec3 point{r[0][k], r[1][k], r[2][k]};
                                        const Vec3 du{r[3][k], r[4][k], r[5][k]}, dv{r[6][k], r[7][k], r[8][k]};
                                        const Vec3 normal = cross(du, dv);
                                        const double size2 = squaredNorm(normal);
                                        // As Surface::evaluate on a batch: the pointwise evaluation decides
                                        // where the derivatives are parallel or the formula failed.
                                        mesh.normals[b.id] =
                                            size2 > 1e-24 * squaredNorm(du) * squaredNorm(dv) && isFinite(point) &&
                                                    std::isfinite(size2)
                                                ? normalized(normal)
                                                : surface.evaluate(b.face, b.domain).normal;
                                      }
                                    });
    } else {
      thread_local std::vector<Vec2> uv;
      thread_local std::vector<SurfacePoint> points;
      uv.resize(count), points.resize(count);
      for (std::size_t k = begin; k < end; ++k) uv[k - begin] = boundary[k].domain;
      surface.evaluate(head.face, uv, points);
      for (std::size_t k = begin; k < end; ++k) mesh.normals[boundary[k].id] = points[k - begin].normal;
    }
    if (record)
      for (std::size_t k = begin; k < end; ++k) mesh.domainPoints[boundary[k].id] = {boundary[k].face, boundary[k].domain};
  });
}

/// Face interiors through evaluation plans: the plans first (each distinct
/// key built once, itself in parallel), then tiles of samples in parallel.
void evaluatePlannedInteriors(const Surface &surface, const Layout &layout, const FaceSelection &wanted, bool record,
                              ProgressCounter &progress, Mesh &mesh) {
  std::vector<std::shared_ptr<const EvaluationPlan>> plans(surface.faceCount());
  const Vec3 origin = surface.origin(); // patches evaluate in the surface's own frame
  const double offset[3] = {origin.x, origin.y, origin.z};
  std::size_t total = 0;
  const std::vector<Tile> tiles = planTiles(surface, layout.faceResolution, plans, total, wanted);
  forEachTile(tiles, total, [&](const Tile &tile) {
    const Patch &patch = *SurfaceAccess::patch(surface, tile.face);
    const EvaluationPlan &plan = *plans[tile.face];
    const std::size_t count = tile.samples.count;
    // Each block of the jet pass goes straight from the kernel's arrays
    // into the mesh: the point with the origin, the unit normal. The
    // group's members together: they share the G² corners' weights.
    patch.evaluatePlannedGroup(plan, tile.samples, [&](int m, std::size_t at, std::size_t size, const double *const r[9]) {
      const std::size_t first = tile.samples.first + m * tile.samples.stride;
      const std::size_t id = layout.faceBase[tile.face] + first + at;
      // Where du and dv are parallel the pointwise evaluation decides the normal.
      thread_local std::vector<std::uint32_t> degenerate;
      degenerate.resize(size);
      const std::size_t flat =
          kernels::jetVertices(size, r, offset, &mesh.positions[id].x, &mesh.normals[id].x, degenerate.data());
      for (std::size_t j = 0; j < flat; ++j)
        mesh.normals[id + degenerate[j]] = surface.evaluate(tile.face, plan.samples()[first + at + degenerate[j]]).normal;
      if (record)
        for (std::size_t k = 0; k < size; ++k) mesh.domainPoints[id + k] = {tile.face, plan.samples()[first + at + k]};
    });
    progress.advance(count * static_cast<std::size_t>(tile.samples.members));
  });
}

/// The fan sectors (face f, side i) of the selected faces, each with its
/// triangle count and its first triangle in the mesh. A sector's count is
/// known from its rows — (b − 1) + r(r − 1) for b samples on its domain side
/// (zip's count, row by row) — so each writes straight into its place, the
/// faces' sectors in order. A full pass sizes the mesh's triangles here.
struct SectorLayout {
  std::vector<std::pair<int, int>> sectors;
  std::vector<std::size_t> count, destination;
};

SectorLayout layOutSectors(const Surface &surface, const Layout &layout, const BoundaryRows &rows,
                           const FaceSelection &wanted, bool partial, Mesh &mesh) {
  const int faces = surface.faceCount();
  SectorLayout out;
  for (int f = 0; f < faces; ++f)
    if (wanted(f))
      for (int i = 0; i < surface.domainSides(f); ++i) out.sectors.push_back({f, i});
  out.count.resize(out.sectors.size());
  std::vector<std::size_t> faceTriangles(faces, 0);
  for (std::size_t item = 0; item < out.sectors.size(); ++item) {
    const auto [f, i] = out.sectors[item];
    const std::size_t r = static_cast<std::size_t>(layout.faceResolution[f]);
    out.count[item] = rows[f][i].size() - 1 + r * (r - 1);
    faceTriangles[f] += out.count[item];
  }
  if (partial) {
    // The same topology gives every face the same triangle count; only the
    // zipping order along sides with T-nodes can move with the curves.
    for (int f = 0; f < faces; ++f)
      if (wanted(f))
        CURVENET_CHECK(faceTriangles[f] == mesh.faceTriangleStart[f + 1] - mesh.faceTriangleStart[f],
                       "face " + std::to_string(f) + " changed its triangle count");
  } else {
    mesh.faceTriangleStart.assign(1, 0);
    for (int f = 0; f < faces; ++f)
      mesh.faceTriangleStart.push_back(mesh.faceTriangleStart.back() + static_cast<std::uint32_t>(faceTriangles[f]));
    mesh.triangles.resize(mesh.faceTriangleStart.back());
  }
  out.destination.resize(out.sectors.size());
  for (std::size_t item = 0; item < out.sectors.size(); ++item) {
    const bool first = item == 0 || out.sectors[item - 1].first != out.sectors[item].first;
    out.destination[item] =
        first ? mesh.faceTriangleStart[out.sectors[item].first] : out.destination[item - 1] + out.count[item - 1];
  }
  return out;
}

/// Triangles of fan sector `item`, row by row from its boundary side to the
/// centre; without plans also the sector's interior samples (evaluated point
/// by point, and counted in `progress`).
void zipSector(const Surface &surface, const Layout &layout, const BoundaryRows &rows, const SectorLayout &sectors,
               std::size_t item, bool planned, bool record, ProgressCounter &progress, Mesh &mesh,
               std::vector<std::array<Vec2, 3>> *domains) {
  const int f = sectors.sectors[item].first, i = sectors.sectors[item].second; // plain names: the lambdas capture f
  const int n = surface.domainSides(f), r = layout.faceResolution[f];
  const std::uint32_t base = layout.faceBase[f];
  const std::uint32_t centre = base;
  auto spoke = [&](int side, int k) { // level k ∈ [1, r−1] on the spoke from corner `side` to the centre
    return base + 1 + static_cast<std::uint32_t>(((side % n + n) % n) * (r - 1) + (k - 1));
  };
  const std::uint32_t interiorBase = base + 1 + static_cast<std::uint32_t>(n * (r - 1));
  const std::uint32_t perTriangle = static_cast<std::uint32_t>((r - 1) * (r - 2) / 2);
  std::size_t placed = 0;
  auto place = [&](std::uint32_t id, const Vec2 &uv) {
    if (planned) return; // evaluated through the plan
    const SurfacePoint p = surface.evaluate(f, uv);
    mesh.positions[id] = p.point;
    mesh.normals[id] = p.normal;
    if (record) mesh.domainPoints[id] = {f, uv};
    ++placed;
  };
  if (i == 0) place(centre, {0, 0});
  const std::size_t destination = sectors.destination[item];
  TriangleSink out{mesh.triangles.data() + destination, domains ? domains->data() + destination : nullptr,
                   sectors.count[item]};
  const Vec2 p0 = surface.domainCorner(f, i), p1 = surface.domainCorner(f, i + 1);
  // Domain points are wanted only for samples evaluated here or triangles' domains.
  const bool wantDomains = !planned || domains;
  thread_local std::vector<RowPoint> lower, upper;
  thread_local std::vector<std::uint32_t> lowerIds, upperIds;
  lower.assign(rows[f][i].begin(), rows[f][i].end());
  std::uint32_t offset = interiorBase + static_cast<std::uint32_t>(i) * perTriangle;
  for (int k = 1; k <= r; ++k) {
    // From the second row on both rows are the sector's own, evenly spaced:
    // zipEven pairs them by index from their ids alone, and only zip (the
    // first row, or triangles' domains wanted) reads a row's points.
    const bool byIndex = k >= 2 && !out.domains;
    const int m = r - k; // the row's last index
    // The row: the centre alone at k = r, else its two spokes' points with
    // the sector's own in between, consecutive ids.
    upperIds.resize(static_cast<std::size_t>(m) + 1);
    if (k == r) {
      upperIds[0] = centre;
    } else {
      upperIds.front() = spoke(i, k), upperIds.back() = spoke(i + 1, k);
      std::iota(upperIds.begin() + 1, upperIds.end() - 1, offset);
      offset += static_cast<std::uint32_t>(m - 1);
    }
    if (!byIndex || wantDomains) {
      const Vec2 a = p0 * (1.0 - double(k) / r), b = p1 * (1.0 - double(k) / r);
      upper.resize(upperIds.size());
      for (int j = 0; j <= m; ++j) {
        RowPoint &point = upper[static_cast<std::size_t>(j)];
        point.id = upperIds[static_cast<std::size_t>(j)];
        point.t = m ? double(j) / m : 0.0;
        point.domain = k == r ? Vec2{0, 0} : a + (b - a) * point.t;
        // The centre is placed with sector 0, the spoke at j = m belongs to
        // the next fan triangle.
        if (wantDomains && k < r && j < m) place(point.id, point.domain);
      }
    }
    if (byIndex) zipEven(lowerIds, upperIds, out);
    else zip(lower, upper, out);
    std::swap(lower, upper), std::swap(lowerIds, upperIds);
  }
  CURVENET_CHECK(out.written == sectors.count[item], "face " + std::to_string(f) + " sector " + std::to_string(i) +
                                                         ": triangle count differs from its rows'");
  if (placed) progress.advance(placed);
}

/// Fills `mesh` with the tessellation of `surface` (see the header), or —
/// with `only` — re-evaluates only the faces f with only[f] set in a mesh
/// that already holds the whole tessellation of a surface of the same
/// topology: their interior samples, their boundary samples and the normals
/// those faces own, and their triangles. Everything is computed exactly as a
/// full run computes it, so the result equals a full tessellation.
/// `layout` gives every face's resolution and every segment's intervals;
/// with `domains`, every triangle's domain points (in its face's domain)
/// go there, in triangle order.
void tessellateInto(const Surface &surface, const TessellationOptions &options, const Layout &layout,
                    const std::vector<char> *only, Mesh &mesh, std::vector<std::array<Vec2, 3>> *domains = nullptr) {
  const int faces = surface.faceCount();
  const FaceSelection wanted{only};
  const bool partial = only != nullptr, record = options.recordDomainPoints;
  std::optional<tbb::global_control> limit;
  if (options.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, options.threads);

  prepareMesh(surface, layout, partial, record, mesh);
  std::uint64_t interiorSamples = 0;
  for (int f = 0; f < faces; ++f)
    if (wanted(f)) interiorSamples += faceInteriorCount(surface.domainSides(f), layout.faceResolution[f]);
  ProgressCounter progress(options.progress, interiorSamples);
  BoundaryRows rows(faces);
  parallel::parallelFor(0, faces, [&](int f) { rows[f] = boundaryRows(surface, layout, f); });

  writeBoundaryPositions(surface.network(), layout, wanted, mesh);
  const bool planned = options.usePlans && faces > 0 && SurfaceAccess::patch(surface, 0) != nullptr;
  evaluateBoundaryNormals(surface, layout, rows, wanted, planned, record, mesh);
  if (planned) evaluatePlannedInteriors(surface, layout, wanted, record, progress, mesh);

  // Triangles per fan sector: the sectors of a face are independent (their
  // own interior samples, spokes by formula), so even a single face spreads
  // over the threads.
  const SectorLayout sectors = layOutSectors(surface, layout, rows, wanted, partial, mesh);
  if (domains) {
    CURVENET_CHECK(!partial, "triangle domain points are recorded for whole tessellations");
    domains->resize(mesh.triangles.size());
  }
  parallel::parallelFor(std::size_t{0}, sectors.sectors.size(), [&](std::size_t item) {
    zipSector(surface, layout, rows, sectors, item, planned, record, progress, mesh, domains);
  });
  if (partial) return;
  progress.finish();
}

/// Per face: the largest chordal deviation of its triangles — the exact
/// surface at the domain midpoints of their edges and at their centroids
/// against the mesh's linear interpolation there — and the largest angle
/// (radians) between the face's normals at the two ends of their edges.
struct FaceAccuracy {
  std::vector<double> deviation, angle;
};

/// The normals measured are the face's own: a vertex on a segment or at a
/// network vertex is shared by the faces around it and carries one face's
/// normal (the mesh is watertight), which across a crease is not the
/// other's — measured from the mesh, the angle there is the crease's, and
/// no resolution brings it down (a real sketch's creases asked resolution
/// 4096 of their faces and ran out of memory). Vertex ids below
/// `firstInterior` are those shared ones (Layout: network vertices and
/// segment samples first).
FaceAccuracy measureAccuracy(const Surface &surface, const Mesh &mesh, const std::vector<std::array<Vec2, 3>> &domains,
                             std::uint32_t firstInterior) {
  const int faces = surface.faceCount();
  FaceAccuracy accuracy{std::vector<double>(faces, 0.0), std::vector<double>(faces, 0.0)};
  parallel::parallelFor(0, faces, [&](int f) {
    const std::uint32_t first = mesh.faceTriangleStart[f], last = mesh.faceTriangleStart[f + 1];
    // Per triangle: the midpoints of edges (0, 1), (1, 2), (2, 0), then the centroid.
    std::vector<Vec2> at, shared;
    at.reserve(4 * static_cast<std::size_t>(last - first));
    for (std::uint32_t t = first; t < last; ++t) {
      const auto &d = domains[t];
      at.push_back((d[0] + d[1]) * 0.5), at.push_back((d[1] + d[2]) * 0.5), at.push_back((d[2] + d[0]) * 0.5);
      at.push_back((d[0] + d[1] + d[2]) * (1.0 / 3));
      for (int k = 0; k < 3; ++k)
        if (mesh.triangles[t][k] < firstInterior) shared.push_back(d[k]);
    }
    std::vector<Vec3> exact(at.size());
    surface.evaluatePositions(f, at, exact);
    std::vector<SurfacePoint> own(shared.size());
    surface.evaluate(f, shared, own);
    double deviation = 0, angle = 0;
    std::size_t next = 0; // the next of `own`, in the order `shared` was filled
    for (std::uint32_t t = first; t < last; ++t) {
      const auto &tri = mesh.triangles[t];
      const Vec3 *e = &exact[4 * static_cast<std::size_t>(t - first)];
      const Vec3 &a = mesh.positions[tri[0]], &b = mesh.positions[tri[1]], &c = mesh.positions[tri[2]];
      deviation = std::max({deviation, norm(e[0] - (a + b) * 0.5), norm(e[1] - (b + c) * 0.5),
                            norm(e[2] - (c + a) * 0.5), norm(e[3] - (a + b + c) * (1.0 / 3))});
      Vec3 normal[3];
      for (int k = 0; k < 3; ++k) normal[k] = tri[k] < firstInterior ? own[next++].normal : mesh.normals[tri[k]];
      for (int k = 0; k < 3; ++k) angle = std::max(angle, angleBetween(normal[k], normal[(k + 1) % 3]));
    }
    accuracy.deviation[f] = deviation, accuracy.angle[f] = angle;
  });
  return accuracy;
}

/// Where a layout's face interiors begin: the ids below are shared by faces.
std::uint32_t firstInteriorVertex(const Layout &layout) {
  return layout.faceBase.empty() ? layout.vertexCount : layout.faceBase.front();
}

/// Triangles of the uniform tessellation at `resolution`, counted from its
/// boundary rows: a fan sector whose domain side carries b samples has
/// (b − 1) + r(r − 1) triangles (tessellateInto's rows zipped).
std::size_t uniformTriangles(const Surface &surface, int resolution) {
  const Layout layout = makeLayout(surface, resolution);
  std::size_t count = 0;
  const std::size_t r = static_cast<std::size_t>(resolution);
  for (int f = 0; f < surface.faceCount(); ++f)
    for (const std::vector<RowPoint> &row : boundaryRows(surface, layout, f)) count += row.size() - 1 + r * (r - 1);
  return count;
}

/// Each segment's intervals: the largest resolution of the faces along it,
/// so that both of them see it sampled at least as finely as they need.
std::vector<int> segmentIntervalsFor(const Surface &surface, const std::vector<int> &faceResolution) {
  const auto &segments = surface.network().segments();
  std::vector<int> intervals(segments.size(), 1);
  for (std::size_t e = 0; e < segments.size(); ++e)
    for (int f : segments[e].faces)
      if (f >= 0) intervals[e] = std::max(intervals[e], faceResolution[f]);
  return intervals;
}

/// Bytes a pass of the tolerance loop holds per mesh vertex at its peak:
/// positions and normals (48), about two triangles (24) with their domain
/// points (96), the evaluation plans of the faces' resolutions (~90 a
/// sample, cached), and while trimming a candidate mesh beside the kept
/// one (168) — with room for the caller's output.
constexpr double kToleranceBytesPerVertex = 500;

/// Whether a layout's mesh fits the 32-bit vertex ids and the memory
/// available now (memoryShortfall).
bool layoutFits(const Layout &layout) {
  return layout.vertexCount < std::numeric_limits<std::uint32_t>::max() / 2 &&
         memoryShortfall(kToleranceBytesPerVertex * layout.vertexCount).empty();
}

Layout toleranceLayout(const Surface &surface, const std::vector<int> &resolution) {
  return makeLayout(surface, resolution, segmentIntervalsFor(surface, resolution));
}

/// The tessellation to options.tolerance (see TessellationOptions): every
/// face starts at a probe resolution; each pass measures every face
/// (measureAccuracy) and resolves the faces that miss the tolerance or the
/// angle, with the chordal deviation taken to fall as 1/r² and the angle as
/// 1/r (the first pass may also coarsen faces that need less), by at most
/// kMaxGrowth a pass. Two things stop a face's refinement short of the
/// limits, and the report names them: an angle that does not fall when the
/// face's resolution grows (normals that turn over within a sample spacing
/// of a corner whatever the spacing: a fold there, or a corner whose
/// curves leave it in nearly the same direction), and the memory available
/// (the pass is scaled back to what fits and is the last).
Mesh tessellateToTolerance(const Surface &surface, const TessellationOptions &options, TessellationReport *report) {
  if (!(options.tolerance > 0 && options.tolerance < 1))
    throw InputError("", "tolerance", "must lie in (0, 1) (relative to the diagonal)");
  if (!(options.angle >= 0 && options.angle < 90)) throw InputError("", "angle", "must lie in [0, 90) degrees");
  const double target = options.tolerance * surface.network().diagonal();
  const double angleLimit = options.angle * std::numbers::pi / 180;
  constexpr int kProbe = 8, kMaxResolution = 4096, kMaxPasses = 8, kMaxGrowth = 4;
  constexpr double kMargin = 0.92; // aim a little below the limits, so that most faces meet them at the first estimate
  const int faces = surface.faceCount();
  std::vector<int> resolution(static_cast<std::size_t>(faces), kProbe);
  // Faces whose angle stopped falling as their resolution grew: judged by
  // the deviation alone from then on.
  std::vector<char> angleUnreachable(static_cast<std::size_t>(faces), 0);
  // Whether face f misses the limits, the angle not asked where `excused`.
  auto misses = [&](const FaceAccuracy &a, int f, const std::vector<char> &excused) {
    return a.deviation[f] > target || (angleLimit > 0 && !excused[f] && a.angle[f] > angleLimit);
  };
  auto missesAny = [&](const FaceAccuracy &a, const std::vector<char> &excused) {
    for (int f = 0; f < faces; ++f)
      if (misses(a, f, excused)) return true;
    return false;
  };
  auto missed = [&](const FaceAccuracy &a, int f) { return misses(a, f, angleUnreachable); };
  TessellationOptions pass = options;
  pass.progress = nullptr; // several passes: no single fraction to report
  Mesh mesh;
  std::vector<std::array<Vec2, 3>> domains;
  FaceAccuracy accuracy;
  int passes = 0;
  bool memoryLimited = false;
  {
    const Layout probe = toleranceLayout(surface, resolution);
    if (!layoutFits(probe)) {
      const std::string shortfall = memoryShortfall(kToleranceBytesPerVertex * probe.vertexCount);
      throw InputError("", "tolerance",
                       "even the first pass (resolution " + std::to_string(kProbe) + " everywhere) " +
                           (shortfall.empty() ? "needs more vertices than a mesh's 32-bit indices can number" : shortfall));
    }
  }
  std::vector<int> previousResolution = resolution;
  std::vector<double> previousAngle(static_cast<std::size_t>(faces), 0.0);
  for (;;) {
    const Layout layout = toleranceLayout(surface, resolution);
    tessellateInto(surface, pass, layout, nullptr, mesh, &domains);
    accuracy = measureAccuracy(surface, mesh, domains, firstInteriorVertex(layout));
    ++passes;
    // A face refined by a quarter or more whose angle fell by less than a
    // tenth (the law asks a fifth) will not reach the limit by refinement.
    if (angleLimit > 0 && passes > 1)
      for (int f = 0; f < faces; ++f)
        if (accuracy.angle[f] > angleLimit && resolution[f] >= 1.25 * previousResolution[f] &&
            accuracy.angle[f] > 0.9 * previousAngle[f])
          angleUnreachable[f] = 1;
    if (memoryLimited) break;
    std::vector<int> next = resolution;
    for (int f = 0; f < faces; ++f) {
      const bool miss = missed(accuracy, f);
      if (passes > 1 && !miss) continue;
      double factor = std::sqrt(accuracy.deviation[f] / (kMargin * target));
      if (angleLimit > 0 && !angleUnreachable[f]) factor = std::max(factor, accuracy.angle[f] / (kMargin * angleLimit));
      int wanted = static_cast<int>(std::ceil(resolution[f] * std::min(factor, double(kMaxGrowth))));
      if (miss) wanted = std::max(wanted, resolution[f] + 1);
      next[f] = std::clamp(wanted, 1, kMaxResolution);
    }
    if (next == resolution || passes == kMaxPasses) break;
    if (!layoutFits(toleranceLayout(surface, next))) {
      // The largest share of every face's growth that fits (coarsened faces
      // keep their coarsening); nothing fits: the mesh in hand.
      memoryLimited = true;
      auto scaled = [&](double share) {
        std::vector<int> r = resolution;
        for (int f = 0; f < faces; ++f)
          r[f] = next[f] <= resolution[f] ? next[f]
                                          : resolution[f] + static_cast<int>(share * (next[f] - resolution[f]));
        return r;
      };
      double low = 0, high = 1;
      for (int step = 0; step < 20; ++step) {
        const double middle = 0.5 * (low + high);
        (layoutFits(toleranceLayout(surface, scaled(middle))) ? low : high) = middle;
      }
      next = scaled(low);
      if (next == resolution) break;
    }
    previousResolution = resolution, previousAngle = accuracy.angle;
    resolution = std::move(next);
  }
  // Trimming: a face that meets the limits with room to spare tries one
  // resolution less where the same laws predict it still meets them; the
  // faces that then miss go back (their segments with them: a finer
  // segment only brings the neighbours' boundary rows closer).
  auto predictedToMeet = [&](int f, int coarser) {
    const double ratio = static_cast<double>(resolution[f]) / coarser;
    return accuracy.deviation[f] * ratio * ratio <= target &&
           (angleLimit == 0 || angleUnreachable[f] || accuracy.angle[f] * ratio <= angleLimit);
  };
  for (int trim = 0; trim < 2 && passes < kMaxPasses + 2 && !memoryLimited; ++trim) {
    const bool met = std::all_of(accuracy.deviation.begin(), accuracy.deviation.end(),
                                 [&](double d) { return d <= target; });
    if (!met) break;
    std::vector<int> trimmed = resolution;
    for (int f = 0; f < faces; ++f)
      if (resolution[f] > 1 && predictedToMeet(f, resolution[f] - 1)) trimmed[f] = resolution[f] - 1;
    if (trimmed == resolution) break;
    Mesh candidate;
    std::vector<std::array<Vec2, 3>> candidateDomains;
    const Layout layout = toleranceLayout(surface, trimmed);
    tessellateInto(surface, pass, layout, nullptr, candidate, &candidateDomains);
    FaceAccuracy candidateAccuracy = measureAccuracy(surface, candidate, candidateDomains, firstInteriorVertex(layout));
    ++passes;
    bool reverted = false;
    for (int f = 0; f < faces; ++f)
      if (missed(candidateAccuracy, f)) trimmed[f] = resolution[f], reverted = true;
    resolution = trimmed;
    if (!reverted) {
      mesh = std::move(candidate), domains = std::move(candidateDomains), accuracy = std::move(candidateAccuracy);
      continue;
    }
    // The accepted resolutions, tessellated and measured once more.
    const Layout accepted = toleranceLayout(surface, resolution);
    tessellateInto(surface, pass, accepted, nullptr, mesh, &domains);
    accuracy = measureAccuracy(surface, mesh, domains, firstInteriorVertex(accepted));
    ++passes;
  }
  if (report) {
    TessellationReport &r = *report;
    r = {};
    r.diagonal = surface.network().diagonal();
    r.deviation = *std::max_element(accuracy.deviation.begin(), accuracy.deviation.end()) / r.diagonal;
    r.angle = *std::max_element(accuracy.angle.begin(), accuracy.angle.end()) * 180 / std::numbers::pi;
    r.triangles = mesh.triangles.size();
    r.minResolution = *std::min_element(resolution.begin(), resolution.end());
    r.maxResolution = *std::max_element(resolution.begin(), resolution.end());
    r.passes = passes;
    r.memoryLimited = memoryLimited;
    for (int f = 0; f < faces; ++f)
      if (angleUnreachable[f]) r.angleUnreachableFaces.push_back(f);
    r.met = !missesAny(accuracy, angleUnreachable);
    // The uniform comparison: the smallest uniform resolution whose mesh,
    // measured the same way, meets the same limits — bisection between one
    // and the largest face resolution, grown by quarters until it meets
    // them. The angle is not asked of the faces above, nor of those whose
    // angle does not fall as the uniform resolution grows (the same rule: a
    // fold near a corner that only a finer sampling than this mesh's
    // reaches). None (0) when no uniform mesh of at most 32 times this
    // mesh's vertices or 2²³ vertices, whichever is more (and within the
    // memory), meets them: unbounded, such a fold sent the search to the
    // memory's limit.
    const double reach = std::max(32 * static_cast<double>(mesh.positions.size()), 0x1p23);
    std::vector<char> exempt = angleUnreachable;
    enum class Uniform { Meets, Misses, TooLarge };
    auto measureUniform = [&](int uniform, FaceAccuracy *measured) {
      const Layout layout = makeLayout(surface, uniform);
      if (layout.vertexCount > reach || !layoutFits(layout)) return Uniform::TooLarge;
      Mesh m;
      std::vector<std::array<Vec2, 3>> d;
      tessellateInto(surface, pass, layout, nullptr, m, &d);
      FaceAccuracy a = measureAccuracy(surface, m, d, firstInteriorVertex(layout));
      const bool meets = !missesAny(a, exempt);
      if (measured) *measured = std::move(a);
      return meets ? Uniform::Meets : Uniform::Misses;
    };
    int high = r.maxResolution;
    FaceAccuracy last;
    Uniform at = measureUniform(high, &last);
    while (at == Uniform::Misses && high < kMaxResolution) {
      const int grown = std::min(kMaxResolution, high + std::max(1, high / 4));
      FaceAccuracy now;
      at = measureUniform(grown, &now);
      if (at == Uniform::TooLarge) break;
      if (angleLimit > 0 && grown >= 1.25 * high)
        for (int f = 0; f < faces; ++f)
          if (now.deviation[f] <= target && now.angle[f] > angleLimit && now.angle[f] > 0.9 * last.angle[f]) exempt[f] = 1;
      if (at == Uniform::Misses && !missesAny(now, exempt)) at = Uniform::Meets; // with the faces just exempted
      high = grown, last = std::move(now);
    }
    if (at == Uniform::Meets) {
      int low = 0; // does not meet (resolution 0 makes no mesh)
      while (high - low > 1) {
        const int middle = (low + high) / 2;
        (middle >= 1 && measureUniform(middle, nullptr) == Uniform::Meets ? high : low) = middle;
      }
      r.uniformResolution = high;
      r.uniformTriangles = uniformTriangles(surface, high);
    }
  }
  return mesh;
}

} // namespace

Mesh tessellate(const Surface &surface, const TessellationOptions &options) {
  if (options.tolerance > 0) return tessellateToTolerance(surface, options, nullptr);
  checkResolution(surface, options.resolution);
  Mesh mesh;
  tessellateInto(surface, options, makeLayout(surface, options.resolution), nullptr, mesh);
  return mesh;
}

void tessellate(const Surface &surface, const TessellationOptions &options, Mesh &mesh) {
  if (options.tolerance > 0) {
    mesh = tessellateToTolerance(surface, options, nullptr);
    return;
  }
  checkResolution(surface, options.resolution);
  tessellateInto(surface, options, makeLayout(surface, options.resolution), nullptr, mesh);
}

Mesh tessellate(const Surface &surface, const TessellationOptions &options, TessellationReport &report) {
  if (options.tolerance > 0) return tessellateToTolerance(surface, options, &report);
  checkResolution(surface, options.resolution);
  Mesh mesh;
  std::vector<std::array<Vec2, 3>> domains;
  const Layout layout = makeLayout(surface, options.resolution);
  tessellateInto(surface, options, layout, nullptr, mesh, &domains);
  const FaceAccuracy accuracy = measureAccuracy(surface, mesh, domains, firstInteriorVertex(layout));
  report = {};
  report.diagonal = surface.network().diagonal();
  report.deviation = *std::max_element(accuracy.deviation.begin(), accuracy.deviation.end()) / report.diagonal;
  report.angle = *std::max_element(accuracy.angle.begin(), accuracy.angle.end()) * 180 / std::numbers::pi;
  report.triangles = report.uniformTriangles = mesh.triangles.size();
  report.minResolution = report.maxResolution = report.uniformResolution = options.resolution;
  report.passes = 1;
  return mesh;
}

void retessellateFaces(const Surface &surface, std::span<const int> faces, Mesh &mesh,
                       const TessellationOptions &options) {
  std::vector<char> only(static_cast<std::size_t>(surface.faceCount()), 0);
  for (int f : faces) {
    if (f < 0 || f >= surface.faceCount()) throw InputError("", "face " + std::to_string(f), "no such face");
    only[f] = 1;
  }
  if (options.tolerance > 0)
    throw InputError("", "tolerance", "a mesh made to a tolerance is tessellated afresh after an edit, not updated");
  checkResolution(surface, options.resolution);
  tessellateInto(surface, options, makeLayout(surface, options.resolution), &only, mesh);
}

} // namespace v1
} // namespace curvenet
