// The embedding facade (curvenet/curvenet.hpp): a Model over the public
// Network / Surface / tessellate API. Exceptions from the layers below are
// caught here, at the API edge, and turned into Status values.
#include "curvenet/curvenet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <unordered_map>

#include <tbb/blocked_range.h>

#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "parallel/fork_join.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

Status failure(StatusCode code, std::string element, std::string message) {
  return {code, {}, std::move(element), std::move(message)};
}

/// Runs `body` and maps what it throws to a Status; R is Status or Result<T>,
/// both constructible from a failed Status.
template <class R, class Body>
R guarded(Body &&body) noexcept {
  try {
    return body();
  } catch (const InputError &e) {
    return Status{StatusCode::InvalidInput, e.file(), e.element(), e.reason()};
  } catch (const InternalError &e) {
    return failure(StatusCode::Internal, {}, e.what());
  } catch (const std::bad_alloc &) {
    return failure(StatusCode::OutOfMemory, {}, "out of memory");
  } catch (const std::exception &e) {
    return failure(StatusCode::Internal, {}, e.what());
  } catch (...) {
    return failure(StatusCode::Internal, {}, "unknown exception");
  }
}

bool sameOptions(const SurfaceOptions &a, const SurfaceOptions &b) {
  return a.scheme == b.scheme && a.sweepline == b.sweepline && a.fenceNormals == b.fenceNormals &&
         a.edgeCurvature == b.edgeCurvature && a.masterFaces == b.masterFaces;
}

std::string faceName(int face) { return "face " + std::to_string(face); }

/// The corners of a face's domain polygon, counter-clockwise, for the
/// inside test; n ≤ 8 sides.
struct DomainPolygon {
  std::array<Vec2, 9> corners{};
  std::array<double, 8> tolerance{}; ///< −1e-9 |edge| per side, precomputed
  int sides = 0;

  DomainPolygon(const Surface &surface, int face) : sides(surface.domainSides(face)) {
    for (int i = 0; i <= sides; ++i) corners[i] = surface.domainCorner(face, i);
    for (int i = 0; i < sides; ++i) tolerance[i] = -1e-9 * norm(corners[i + 1] - corners[i]);
  }
  /// Inside or on the boundary, with a tolerance of 1e-9 of the circumradius
  /// so that points computed on a side (e.g. by interpolating corners) pass.
  bool contains(const Vec2 &p) const {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
    for (int i = 0; i < sides; ++i)
      if (cross(corners[i + 1] - corners[i], p - corners[i]) < tolerance[i]) return false;
    return true;
  }
};

template <class Point>
Point nanPoint() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Vec3 v{nan, nan, nan};
  if constexpr (std::is_same_v<Point, Vec3>) {
    return v;
  } else {
    Point p;
    p.point = p.du = p.dv = p.normal = v;
    if constexpr (std::is_same_v<Point, SurfacePoint2>) p.duu = p.duv = p.dvv = v;
    return p;
  }
}

} // namespace

const char *versionString() { return CURVENET_VERSION_STRING; }

const char *statusCodeName(StatusCode code) {
  switch (code) {
  case StatusCode::Ok: return "ok";
  case StatusCode::InvalidArgument: return "invalid-argument";
  case StatusCode::InvalidInput: return "invalid-input";
  case StatusCode::OutOfDomain: return "out-of-domain";
  case StatusCode::BufferTooSmall: return "buffer-too-small";
  case StatusCode::NoMesh: return "no-mesh";
  case StatusCode::Internal: return "internal";
  case StatusCode::OutOfMemory: return "out-of-memory";
  }
  return "unknown";
}

std::string Status::toString() const {
  if (ok()) return "ok";
  std::string s;
  if (!file.empty()) s += file + ": ";
  if (!element.empty()) s += element + ": ";
  return s + message;
}

Result<BSplineCurve> makeCurve(int degree, std::vector<double> knots, std::vector<Vec3> controlPoints,
                               std::vector<double> weights) {
  return guarded<Result<BSplineCurve>>([&]() -> Result<BSplineCurve> {
    return BSplineCurve(degree, std::move(knots), std::move(controlPoints), std::move(weights));
  });
}

Result<BSplineSurface> makeSurface(int degreeU, int degreeV, std::vector<double> knotsU, std::vector<double> knotsV,
                                   int countU, int countV, std::vector<Vec3> controlPoints, std::vector<double> weights) {
  return guarded<Result<BSplineSurface>>([&]() -> Result<BSplineSurface> {
    return BSplineSurface(degreeU, degreeV, std::move(knotsU), std::move(knotsV), countU, countV,
                          std::move(controlPoints), std::move(weights));
  });
}

Result<BSplineCurve> makeBezier(std::vector<Vec3> controlPoints) {
  if (controlPoints.size() < 2)
    return failure(StatusCode::InvalidInput, "curve", "a Bézier curve needs at least 2 control points");
  return guarded<Result<BSplineCurve>>(
      [&]() -> Result<BSplineCurve> { return BSplineCurve::bezier(std::move(controlPoints)); });
}

// ---------------------------------------------------------------------------

struct Model::Impl {
  struct Group {
    SurfaceOptions options;
    Surface surface;
  };
  NetworkDescription description;
  Network network;
  std::vector<SurfaceOptions> faceOptions;
  std::vector<Group> groups;
  std::vector<int> faceGroup;
  /// The mesh copyMesh/mesh() hand out, and the whole-network tessellation
  /// it was cut from (kept so one-face calls reuse it).
  Mesh mesh;
  bool hasMesh = false;
  std::optional<Mesh> whole;
  TessellationOptions wholeOptions;

  /// Network and surfaces for `description` with `options` per face of the
  /// network, or one entry for every face (a fresh build: the network may
  /// have more faces than the description, where connection curves split a
  /// concave face). Groups of `reuse` (same network) whose options recur are
  /// kept, not rebuilt.
  static std::unique_ptr<Impl> assemble(NetworkDescription description, std::vector<SurfaceOptions> options,
                                        const Impl *reuse) {
    auto impl = std::make_unique<Impl>();
    impl->network = reuse ? reuse->network : Network::build(description);
    impl->description = std::move(description);
    const int faces = static_cast<int>(impl->network.faces().size());
    if (options.size() == 1) options.resize(static_cast<std::size_t>(faces), options.front());
    CURVENET_CHECK(static_cast<int>(options.size()) == faces, "options for every face");
    impl->faceOptions = std::move(options);
    for (int f = 0; f < faces; ++f) {
      const SurfaceOptions &o = impl->faceOptions[f];
      auto same = [&](const Group &g) { return sameOptions(g.options, o); };
      auto it = std::find_if(impl->groups.begin(), impl->groups.end(), same);
      if (it == impl->groups.end()) {
        const Group *old = nullptr;
        if (reuse)
          if (auto r = std::find_if(reuse->groups.begin(), reuse->groups.end(), same); r != reuse->groups.end())
            old = &*r;
        impl->groups.push_back({o, old ? old->surface : Surface::build(impl->network, o)});
        it = impl->groups.end() - 1;
      }
      impl->faceGroup.push_back(static_cast<int>(it - impl->groups.begin()));
    }
    if (faces == 0) impl->groups.push_back({SurfaceOptions{}, Surface::build(impl->network, {})});
    return impl;
  }

  /// The model after replacing its description by `description` (curves
  /// changed in shape): every group's surface rebuilt by
  /// Surface::rebuildAfterEdit, so that only the faces near the changed
  /// curves are rebuilt (a full build where the topology changed).
  static std::unique_ptr<Impl> edited(const Impl &old, NetworkDescription description) {
    auto impl = std::make_unique<Impl>();
    impl->network = Network::build(description);
    if (impl->network.faces().size() != old.faceGroup.size()) {
      // The edit changed how connection curves split a concave face: the
      // faces are numbered anew, so per-face options have nothing to follow.
      // With one option set for every face that is no obstacle (a full build).
      if (old.groups.size() == 1) return assemble(std::move(description), {old.groups[0].options}, nullptr);
      throw InputError({}, "faces",
                       "the edit changes how concave faces are split (" + std::to_string(old.faceGroup.size()) +
                           " faces before, " + std::to_string(impl->network.faces().size()) +
                           " after), so the per-face options no longer match the faces; set one option set for "
                           "every face before such an edit");
    }
    impl->description = std::move(description);
    impl->faceOptions = old.faceOptions;
    impl->faceGroup = old.faceGroup;
    std::vector<int> changed;
    bool partial = true;
    for (const Group &g : old.groups) {
      SurfaceEdit edit = g.surface.rebuildAfterEdit(impl->network);
      changed.insert(changed.end(), edit.changedFaces.begin(), edit.changedFaces.end());
      partial = partial && edit.partial;
      impl->groups.push_back({g.options, std::move(edit.surface)});
    }
    CURVENET_CHECK(static_cast<int>(impl->network.faces().size()) == static_cast<int>(impl->faceGroup.size()),
                   "an edit keeps the faces");
    std::sort(changed.begin(), changed.end());
    changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
    // One surface, same topology: the cached whole-network tessellation is
    // brought up to date on the changed faces only (plans reused), so the
    // next tessellate at that resolution costs a copy.
    // (A mesh made to a tolerance is made afresh: the edit may change the
    // resolutions it needs.)
    if (partial && old.whole && impl->groups.size() == 1 && !(old.wholeOptions.tolerance > 0)) {
      impl->whole = *old.whole;
      impl->wholeOptions = old.wholeOptions;
      retessellateFaces(impl->groups[0].surface, changed, *impl->whole, impl->wholeOptions);
    }
    impl->lastChangedFaces = std::move(changed);
    return impl;
  }

  /// Faces rebuilt by the last edit (Model::lastEditedFaces).
  std::vector<int> lastChangedFaces;

  const Surface &surfaceOf(int face) const { return groups[faceGroup[face]].surface; }
  bool validFace(int face) const { return face >= 0 && face < static_cast<int>(faceGroup.size()); }

  /// The whole-network mesh with every face evaluated by its own group. All
  /// groups share one vertex layout (it depends on the topology and the
  /// resolution only), so each vertex is taken from the group of the face
  /// the tessellator evaluated it in.
  Mesh tessellateWhole(TessellationOptions options) const {
    if (groups.size() == 1) return curvenet::tessellate(groups[0].surface, options);
    const bool wanted = options.recordDomainPoints;
    options.recordDomainPoints = true;
    std::vector<Mesh> meshes;
    for (const Group &g : groups) meshes.push_back(curvenet::tessellate(g.surface, options));
    Mesh merged = std::move(meshes[0]);
    for (size_t g = 1; g < meshes.size(); ++g)
      CURVENET_CHECK(meshes[g].positions.size() == merged.positions.size() &&
                         meshes[g].triangles == merged.triangles,
                     "every scheme tessellates a network with one vertex layout");
    for (size_t v = 0; v < merged.positions.size(); ++v) {
      const int f = merged.domainPoints[v].face;
      const int g = f < 0 ? 0 : faceGroup[f];
      if (g == 0) continue;
      merged.positions[v] = meshes[g].positions[v];
      merged.normals[v] = meshes[g].normals[v];
    }
    if (!wanted) merged.domainPoints.clear();
    return merged;
  }

  /// Face f's triangles of `whole`, with the vertices they use renumbered in
  /// order of first use.
  static Mesh cutFace(const Mesh &whole, int f) {
    Mesh out;
    std::unordered_map<std::uint32_t, std::uint32_t> local;
    auto vertex = [&](std::uint32_t v) {
      auto [it, inserted] = local.try_emplace(v, static_cast<std::uint32_t>(out.positions.size()));
      if (inserted) {
        out.positions.push_back(whole.positions[v]);
        if (!whole.normals.empty()) out.normals.push_back(whole.normals[v]);
        if (!whole.domainPoints.empty()) out.domainPoints.push_back(whole.domainPoints[v]);
      }
      return it->second;
    };
    for (std::uint32_t t = whole.faceTriangleStart[f]; t < whole.faceTriangleStart[f + 1]; ++t) {
      const auto &tri = whole.triangles[t];
      out.triangles.push_back({vertex(tri[0]), vertex(tri[1]), vertex(tri[2])});
    }
    out.faceTriangleStart = {0, static_cast<std::uint32_t>(out.triangles.size())};
    return out;
  }

  /// Applies `one` to every point of a batch, serially or over TBB by the
  /// batch policy; points outside the domain get NaN.
  template <class Point, class One>
  Status batch(int face, std::span<const Vec2> uv, std::span<Point> out, const BatchOptions &options,
               One &&one) const {
    return batchRanges(face, uv, out, options,
                       [&](const Surface &surface, const DomainPolygon &polygon, std::size_t begin, std::size_t end) {
                         for (std::size_t k = begin; k < end; ++k)
                           out[k] = polygon.contains(uv[k]) ? one(surface, uv[k]) : nanPoint<Point>();
                       });
  }

  /// The batch frame: argument checks, the serial/parallel split into
  /// ranges evaluated by range(surface, polygon, begin, end), and the
  /// out-of-domain status.
  template <class Point, class Range>
  Status batchRanges(int face, std::span<const Vec2> uv, std::span<Point> out, const BatchOptions &options,
                     Range &&range) const {
    if (!validFace(face)) return failure(StatusCode::InvalidArgument, faceName(face), "no such face");
    if (uv.size() != out.size())
      return failure(StatusCode::InvalidArgument, "output",
                     "holds " + std::to_string(out.size()) + " points for " + std::to_string(uv.size()) + " inputs");
    if (options.threads < 0) return failure(StatusCode::InvalidArgument, "threads", "must be ≥ 0");
    const Surface &surface = surfaceOf(face);
    const DomainPolygon polygon(surface, face);
    const std::size_t n = uv.size();
    const bool serial = options.threads == 1 || (options.threads == 0 && n < options.parallelThreshold);
    if (serial) {
      range(surface, polygon, 0, n);
    } else {
      // Fixed chunks of kChunk points, whatever the thread count: the batched
      // kernels work in blocks counted from the start of each call, so a point
      // meets the same block position (and lane) as in one serial call, and
      // the output is the same bits for any thread count. kChunk is a multiple
      // of every block size and keeps task overhead below 1%.
      constexpr std::size_t kChunk = 4096;
      const std::size_t chunks = (n + kChunk - 1) / kChunk;
      parallel::withThreads(options.threads, [&] {
        parallel::parallelFor(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t> &r) {
          for (std::size_t c = r.begin(); c != r.end(); ++c)
            range(surface, polygon, c * kChunk, std::min(n, (c + 1) * kChunk));
        });
      });
    }
    // Points outside the domain: NaN (whatever the range evaluation left
    // there) and the status.
    std::size_t outside = 0, first = n;
    for (std::size_t k = 0; k < n; ++k)
      if (!polygon.contains(uv[k])) {
        out[k] = nanPoint<Point>();
        ++outside;
        first = std::min(first, k);
      }
    if (outside)
      return failure(StatusCode::OutOfDomain, "point " + std::to_string(first),
                     std::to_string(outside) + " of " + std::to_string(n) + " points lie outside the domain of " +
                         faceName(face) + " (set to NaN)");
    return {};
  }
};

Model::Model(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Model::Model(Model &&) noexcept = default;
Model &Model::operator=(Model &&) noexcept = default;
Model::~Model() = default;

Result<Model> Model::build(NetworkDescription description, const SurfaceOptions &options) {
  return guarded<Result<Model>>([&]() -> Result<Model> {
    return Model(Impl::assemble(std::move(description), {options}, nullptr));
  });
}

Result<Model> Model::fromLoop(std::vector<BSplineCurve> curves, const SurfaceOptions &options) {
  NetworkDescription description;
  description.name = "loop";
  FaceDescription face;
  for (std::size_t k = 0; k < curves.size(); ++k)
    face.sides.push_back({static_cast<int>(k), curves[k].domainStart(), curves[k].domainEnd()});
  description.curves = std::move(curves);
  description.faces.push_back(std::move(face));
  return build(std::move(description), options);
}

Result<Model> Model::load(const std::string &input, const SurfaceOptions &options) {
  auto description = guarded<Result<NetworkDescription>>(
      [&]() -> Result<NetworkDescription> { return loadNetworkInput(input); });
  if (!description) return description.status();
  return build(std::move(description).value(), options);
}

int Model::faceCount() const { return static_cast<int>(impl_->faceGroup.size()); }
int Model::curveCount() const { return static_cast<int>(impl_->description.curves.size()); }

int Model::domainSides(int face) const {
  return impl_->validFace(face) ? impl_->surfaceOf(face).domainSides(face) : 0;
}

Result<Vec2> Model::domainCorner(int face, int corner) const {
  if (!impl_->validFace(face)) return failure(StatusCode::InvalidArgument, faceName(face), "no such face");
  const int n = domainSides(face);
  return impl_->surfaceOf(face).domainCorner(face, ((corner % n) + n) % n);
}

bool Model::hasExactSecondDerivatives(int face) const {
  return impl_->validFace(face) && impl_->surfaceOf(face).faceOptions(face).scheme == Scheme::GregoryG2;
}

const SurfaceOptions &Model::faceOptions(int face) const {
  return impl_->groups[impl_->validFace(face) ? impl_->faceGroup[face] : 0].options;
}

const std::vector<int> &Model::lastEditedFaces() const { return impl_->lastChangedFaces; }

int Model::surfaceCount() const { return static_cast<int>(impl_->groups.size()); }
const Network &Model::network() const { return impl_->network; }
const NetworkDescription &Model::description() const { return impl_->description; }
const Surface *Model::surface(int face) const {
  return impl_->validFace(face) ? &impl_->surfaceOf(face) : nullptr;
}

Result<ShapeReport> Model::shape(const ShapeOptions &options) const {
  return guarded<Result<ShapeReport>>([&]() -> Result<ShapeReport> {
    ShapeReport merged;
    merged.faces.resize(static_cast<std::size_t>(faceCount()));
    std::vector<const Surface *> measured;
    for (int f = 0; f < faceCount(); ++f) {
      const Surface *owner = surface(f);
      if (std::find(measured.begin(), measured.end(), owner) != measured.end()) continue;
      measured.push_back(owner);
      const ShapeReport part = measureShape(*owner, options);
      for (int g = 0; g < faceCount(); ++g)
        if (surface(g) == owner) merged.faces[static_cast<std::size_t>(g)] = part.faces[static_cast<std::size_t>(g)];
      for (const CornerFold &fold : part.cornerFolds)
        if (surface(fold.face) == owner) merged.cornerFolds.push_back(fold);
      for (const FaceIntersection &x : part.intersections)
        if (surface(x.faceA) == owner && surface(x.faceB) == owner) merged.intersections.push_back(x);
    }
    std::sort(merged.intersections.begin(), merged.intersections.end(),
              [](const FaceIntersection &a, const FaceIntersection &b) {
                return std::pair(a.faceA, a.faceB) < std::pair(b.faceA, b.faceB);
              });
    std::sort(merged.cornerFolds.begin(), merged.cornerFolds.end(), [](const CornerFold &a, const CornerFold &b) {
      return std::pair(a.face, a.corner) < std::pair(b.face, b.corner);
    });
    double weighted = 0, area = 0;
    for (const FaceShape &face : merged.faces) {
      if (face.folded) merged.foldedFaces.push_back(face.face);
      if (face.folded || face.foldsAtCorner || face.intersects || !(face.excursion <= kExcursionBound))
        merged.rejectedFaces.push_back(face.face);
      if (merged.worstExcursionFace < 0 || face.excursion > merged.maxExcursion)
        merged.maxExcursion = face.excursion, merged.worstExcursionFace = face.face;
      if (merged.worstFairnessFace < 0 || face.fairness > merged.maxFairness)
        merged.maxFairness = face.fairness, merged.worstFairnessFace = face.face;
      weighted += face.fairness * face.area;
      area += face.area;
    }
    merged.fairness = area > 0 ? weighted / area : 0.0;
    return merged;
  });
}

std::vector<const Surface *> Model::groupSurfaces() const {
  std::vector<const Surface *> seen;
  for (int f = 0; f < faceCount(); ++f)
    if (const Surface *owner = surface(f); std::find(seen.begin(), seen.end(), owner) == seen.end())
      seen.push_back(owner);
  return seen;
}

std::vector<RepairMove> Model::repairMoves() const {
  std::vector<RepairMove> moves;
  for (const Surface *owner : groupSurfaces())
    moves.insert(moves.end(), owner->repairMoves().begin(), owner->repairMoves().end());
  return moves;
}

std::vector<std::string> Model::repairSkipped() const {
  // Groups of different schemes repair the same vertices: a reason once.
  std::vector<std::string> skipped;
  for (const Surface *owner : groupSurfaces())
    for (const std::string &reason : owner->repairSkipped())
      if (std::find(skipped.begin(), skipped.end(), reason) == skipped.end()) skipped.push_back(reason);
  return skipped;
}

Status Model::setFaceOptions(int face, const SurfaceOptions &options) {
  if (face != allFaces && !impl_->validFace(face))
    return failure(StatusCode::InvalidArgument, faceName(face), "no such face");
  std::vector<SurfaceOptions> perFace = impl_->faceOptions;
  if (face == allFaces)
    std::fill(perFace.begin(), perFace.end(), options);
  else
    perFace[face] = options;
  return setFaceOptions(perFace);
}

Status Model::setFaceOptions(std::span<const SurfaceOptions> perFace) {
  if (static_cast<int>(perFace.size()) != faceCount())
    return failure(StatusCode::InvalidArgument, "options",
                   std::to_string(perFace.size()) + " option sets for " + std::to_string(faceCount()) + " faces");
  return guarded<Status>([&]() -> Status {
    impl_ = Impl::assemble(impl_->description, {perFace.begin(), perFace.end()}, impl_.get());
    return {};
  });
}

Result<SurfacePoint> Model::evaluate(int face, const Vec2 &uv) const {
  SurfacePoint out;
  const Status status = evaluate(face, std::span(&uv, 1), std::span(&out, 1), {.threads = 1});
  if (!status.ok()) return status;
  return out;
}

Status Model::evaluate(int face, std::span<const Vec2> uv, std::span<SurfacePoint> out,
                       const BatchOptions &options) const {
  return guarded<Status>([&] {
    return impl_->batchRanges(
        face, uv, out, options,
        [&](const Surface &surface, const DomainPolygon &, std::size_t begin, std::size_t end) {
          // Outside points are evaluated too (finite or not, never a fault)
          // and set to NaN by batchRanges.
          surface.evaluate(face, uv.subspan(begin, end - begin), out.subspan(begin, end - begin));
        });
  });
}

Status Model::evaluatePositions(int face, std::span<const Vec2> uv, std::span<Vec3> out,
                                const BatchOptions &options) const {
  return guarded<Status>([&] {
    return impl_->batchRanges(
        face, uv, out, options,
        [&](const Surface &surface, const DomainPolygon &, std::size_t begin, std::size_t end) {
          // Outside points are evaluated too (finite or not, never a fault)
          // and set to NaN by batchRanges.
          surface.evaluatePositions(face, uv.subspan(begin, end - begin), out.subspan(begin, end - begin));
        });
  });
}

Result<SurfacePoint2> Model::evaluateSecondOrder(int face, const Vec2 &uv, const BatchOptions &options) const {
  SurfacePoint2 out;
  BatchOptions serial = options;
  serial.threads = 1;
  const Status status = evaluateSecondOrder(face, std::span(&uv, 1), std::span(&out, 1), serial);
  if (!status.ok()) return status;
  return out;
}

Status Model::evaluateSecondOrder(int face, std::span<const Vec2> uv, std::span<SurfacePoint2> out,
                                  const BatchOptions &options) const {
  if (!(options.step >= 1e-8 && options.step <= 1e-2))
    return failure(StatusCode::InvalidArgument, "step", "must lie in [1e-8, 1e-2]");
  return guarded<Status>([&] {
    return impl_->batch(face, uv, out, options, [face, step = options.step](const Surface &s, const Vec2 &p) {
      return s.evaluateSecondOrder(face, p, step);
    });
  });
}

Result<MeshSize> Model::tessellate(const TessellationOptions &options, int face) {
  if (options.resolution < 1) return failure(StatusCode::InvalidArgument, "resolution", "must be at least 1");
  if (options.threads < 0) return failure(StatusCode::InvalidArgument, "threads", "must be ≥ 0");
  if (face != allFaces && !impl_->validFace(face))
    return failure(StatusCode::InvalidArgument, faceName(face), "no such face");
  const bool toTolerance = options.tolerance != 0 || options.angle != 0;
  if (toTolerance && !(options.tolerance > 0 && options.tolerance < 1))
    return failure(StatusCode::InvalidArgument, "tolerance", "must lie in (0, 1) (relative to the diagonal)");
  if (toTolerance && !(options.angle >= 0 && options.angle < 90))
    return failure(StatusCode::InvalidArgument, "angle", "must lie in [0, 90) degrees");
  if (toTolerance && impl_->groups.size() > 1)
    return failure(StatusCode::InvalidArgument, "tolerance",
                   "needs one option set for every face (each surface would choose its own resolutions)");
  return guarded<Result<MeshSize>>([&]() -> Result<MeshSize> {
    Impl &m = *impl_;
    // Refused before any work when it could not fit in memory, as the
    // command line does: the caller gets a status instead of the system's
    // out-of-memory killer. Per vertex: positions, normals and about two
    // triangles (72 B) for each surface's mesh, the merged whole mesh and
    // the kept copy, plus the tessellator's staging (~32 B).
    // (A tolerance's resolutions are known only once measured.)
    const double vertices = static_cast<double>(estimateMeshVertices(m.groups[0].surface, options.resolution));
    if (const std::string shortfall =
            memoryShortfall(vertices * (72.0 * static_cast<double>(m.groups.size() + 2) + 32));
        !toTolerance && !shortfall.empty())
      return failure(StatusCode::OutOfMemory, "resolution", std::to_string(options.resolution) + " " + shortfall);
    if (!m.whole || m.wholeOptions.resolution != options.resolution ||
        m.wholeOptions.recordDomainPoints != options.recordDomainPoints ||
        m.wholeOptions.tolerance != options.tolerance || m.wholeOptions.angle != options.angle) {
      m.whole.reset();
      m.hasMesh = false;
      m.whole = m.tessellateWhole(options);
      m.wholeOptions = options;
    }
    m.mesh = face == allFaces ? *m.whole : Impl::cutFace(*m.whole, face);
    m.hasMesh = true;
    return MeshSize{m.mesh.positions.size(), m.mesh.triangles.size()};
  });
}

const Mesh &Model::mesh() const { return impl_->mesh; }

Status Model::copyMesh(std::span<Vec3> positions, std::span<Vec3> normals,
                       std::span<std::array<std::uint32_t, 3>> triangles) const {
  const Mesh &m = impl_->mesh;
  if (!impl_->hasMesh) return failure(StatusCode::NoMesh, "mesh", "tessellate first");
  auto small = [](const char *what, std::size_t have, std::size_t need) {
    return failure(StatusCode::BufferTooSmall, what,
                   "holds " + std::to_string(have) + ", the mesh needs " + std::to_string(need));
  };
  if (positions.size() < m.positions.size()) return small("positions", positions.size(), m.positions.size());
  if (!normals.empty() && normals.size() < m.normals.size()) return small("normals", normals.size(), m.normals.size());
  if (triangles.size() < m.triangles.size()) return small("triangles", triangles.size(), m.triangles.size());
  std::copy(m.positions.begin(), m.positions.end(), positions.begin());
  if (!normals.empty()) std::copy(m.normals.begin(), m.normals.end(), normals.begin());
  std::copy(m.triangles.begin(), m.triangles.end(), triangles.begin());
  return {};
}

Status Model::writeMesh(const std::string &path) const {
  if (!impl_->hasMesh) return failure(StatusCode::NoMesh, "mesh", "tessellate first");
  return guarded<Status>([&]() -> Status {
    writeMeshFile(impl_->mesh, path);
    return {};
  });
}

Status Model::setCurve(int curve, BSplineCurve replacement) {
  if (curve < 0 || curve >= curveCount())
    return failure(StatusCode::InvalidArgument, "curve " + std::to_string(curve), "no such curve");
  return guarded<Status>([&]() -> Status {
    NetworkDescription description = impl_->description;
    description.curves[curve] = std::move(replacement);
    // Loops refer to curve parameters: keep them inside the new domain.
    for (std::size_t f = 0; f < description.faces.size(); ++f)
      for (std::size_t k = 0; k < description.faces[f].sides.size(); ++k) {
        const SideDescription &side = description.faces[f].sides[k];
        const BSplineCurve &c = description.curves[curve];
        if (side.curve == curve && (std::min(side.from, side.to) < c.domainStart() - 1e-12 ||
                                    std::max(side.from, side.to) > c.domainEnd() + 1e-12))
          return failure(StatusCode::InvalidInput, faceName(static_cast<int>(f)) + " side " + std::to_string(k),
                         "uses a parameter range outside the new curve's domain");
      }
    impl_ = Impl::edited(*impl_, std::move(description));
    return {};
  });
}

Status Model::setControlPoints(int curve, std::span<const Vec3> points) {
  if (curve < 0 || curve >= curveCount())
    return failure(StatusCode::InvalidArgument, "curve " + std::to_string(curve), "no such curve");
  const BSplineCurve &old = impl_->description.curves[curve];
  if (points.size() != old.controlPoints().size())
    return failure(StatusCode::InvalidArgument, "curve " + std::to_string(curve),
                   std::to_string(points.size()) + " control points for a curve with " +
                       std::to_string(old.controlPoints().size()));
  auto replacement = makeCurve(old.degree(), old.knots(), {points.begin(), points.end()}, old.weights());
  if (!replacement) {
    Status status = replacement.status();
    status.element = "curve " + std::to_string(curve);
    return status;
  }
  return setCurve(curve, std::move(replacement).value());
}

} // namespace v1
} // namespace curvenet
