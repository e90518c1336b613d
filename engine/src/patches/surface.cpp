// Surface::build — edge data shared by faces, then one patch per face.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <span>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "parallel/fork_join.hpp"

#include "analysis/vertex_curvature.hpp"
#include "analysis/vertex_frames.hpp"
#include "bezier/bezier_surface.hpp"
#include "curvenet/error.hpp"
#include "curvenet/surface.hpp"
#include "patches/corner_grid.hpp"
#include "patches/crossing.hpp"
#include "patches/patch.hpp"
#include "patches/surface_impl.hpp"
#include "plans/face_errors.hpp"
#include "plans/plan.hpp"

namespace curvenet {
inline namespace v1 {


namespace {
// A loop corner whose two tangents are closer than this to a straight line
// carries no cross direction (the ribbon follows the fence there); closer
// than this to folding back it is a cusp, which no patch can span.
constexpr double kStraightAngle = 1e-2; // radians
constexpr double kCuspAngle = 1e-3;     // radians
// Intervals of the transversal-curvature samples along a segment.
constexpr int kCurvatureIntervals = 16;
// Direct edge curvature: a curve's disagreement with the blended end tensors
// up to this many times the ends' transversal curvature moves κ_D as the
// constrained refit does; from 3 times that, not at all (buildEdgeCurvature).
constexpr double kSpikeFrom = 1.0;
// Directions (angles from the curve tangent) in which G¹ patches are measured
// for master–slave and averaging; ω0 = 0 carries the constraint.
constexpr std::array<double, 5> kMeasureAngles = {std::numbers::pi / 6, std::numbers::pi / 3, std::numbers::pi / 2,
                                                  2 * std::numbers::pi / 3, 5 * std::numbers::pi / 6};

/// Constrained fit ([SV14] App. A) of normal curvatures measured at the
/// kMeasureAngles from the tangent, keeping the curve's own curvature k0 at
/// ω0 = 0; returns the fitted normal curvature across the curve (ω = π/2).
double constrainedTransversal(const std::array<double, 5> &measured, double k0) {
  const CurvatureFit fit = fitCurvatureConstrained(kMeasureAngles, measured, 0.0, k0);
  return fit.tensor.normalCurvature(std::numbers::pi / 2);
}
} // namespace

/// A loop far from convex (a concave corner, a strongly bent side) can make
/// the map from the regular n-gon fold over itself: the surface normal
/// du × dv turns over inside the patch. Detected on the n-fold fan grid of
/// the tessellator at 8 rows: two neighbouring samples whose normals point
/// into opposite half-spaces. A smooth patch cannot turn its normal by 90°
/// between samples this close unless it folds, so no well-formed patch is
/// reported. The interior of each centre–side triangle and the centre are
/// the samples of the cached evaluation plan at resolution 8 (geometry-free,
/// shared by every face and build: no sweepline root solve per face). The
/// first row and the spokes are evaluated point by point, inset a little:
/// from the sides, so that straight-angle corners with vanishing derivatives
/// are avoided, and from the spokes, where the quintic Hermite sweep of a
/// triangle has its known fold along the bisector near the corner
/// (surface.hpp, Sweepline), which the interpolants there barely weigh.
struct NonFinitePatch {};

constexpr int kFoldRows = 8;

bool patchFolds(const Patch &patch, int rows = kFoldRows) {
  const RegularDomain &domain = patch.domain();
  const int n = domain.sides();
  auto normalOf = [](const DualVec3 &r) {
    const Vec3 normal = cross(r.du, r.dv);
    if (!std::isfinite(r.v.x + r.v.y + r.v.z + normal.x + normal.y + normal.z)) throw NonFinitePatch{};
    return normal;
  };
  const std::shared_ptr<const EvaluationPlan> plan = evaluationPlan(planKey(patch.options(), n, rows));
  std::vector<DualVec3> planned(plan->size());
  patch.evaluatePlanned(*plan, 0, plan->size(), planned.data());
  std::vector<Vec3> normals(planned.size());
  for (std::size_t k = 0; k < planned.size(); ++k) normals[k] = normalOf(planned[k]);
  // The plan's sample order (plan.hpp): centre, spokes corner-major at levels
  // 1 … rows − 1 (not used here), then each centre–side triangle's interior
  // row by row.
  std::size_t interior = 1 + static_cast<std::size_t>(n) * (rows - 1);
  // The first row and the spokes, inset, all in one batch.
  std::vector<double> us, vs;
  auto inset = [&](int i, int k, int j) {
    const double shrink = 1.0 - (k + 0.02) / rows;
    const Vec2 a = domain.corner(i) * shrink, b = domain.corner(i + 1) * shrink;
    return a + (b - a) * ((j + 0.02) / (rows - k + 0.04));
  };
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < rows; ++k)
      for (int j = 0; j <= rows - k; ++j)
        if (k == 0 || j == 0 || j == rows - k) {
          const Vec2 uv = inset(i, k, j);
          us.push_back(uv.x), vs.push_back(uv.y);
        }
  std::vector<DualVec3> edge(us.size());
  patch.evaluateBatch(us.size(), us.data(), vs.data(), edge.data());
  std::size_t next = 0;
  for (int i = 0; i < n; ++i) {
    std::vector<std::vector<Vec3>> grid(rows + 1);
    for (int k = 0; k < rows; ++k) {
      const int m = rows - k;
      for (int j = 0; j <= m; ++j)
        grid[k].push_back(k == 0 || j == 0 || j == m ? normalOf(edge[next++]) : normals[interior++]);
    }
    grid[rows].push_back(normals[0]);
    for (int k = 0; k <= rows; ++k)
      for (size_t j = 0; j < grid[k].size(); ++j) {
        if (j + 1 < grid[k].size() && dot(grid[k][j], grid[k][j + 1]) <= 0) return true;
        if (k < rows && j < grid[k + 1].size() && dot(grid[k][j], grid[k + 1][j]) <= 0) return true;
      }
  }
  return false;
}

/// The corners of the patch whose neighbourhood folds on the corner grid
/// (patches/corner_grid.hpp): the normal turned over closer to the corner
/// than the fold grid's first row, which patchFolds cannot see.
std::vector<int> foldedCorners(const Patch &patch) {
  const RegularDomain &domain = patch.domain();
  std::vector<int> corners;
  std::array<double, CornerGrid::kSize> us, vs;
  std::array<DualVec3, CornerGrid::kSize> at;
  std::array<Vec3, CornerGrid::kSize> normals;
  for (int k = 0; k < domain.sides(); ++k) {
    for (int i = 0; i < CornerGrid::kRings; ++i)
      for (int j = 0; j < CornerGrid::kRays; ++j) {
        const Vec2 uv = CornerGrid::point(domain.corner(k), domain.corner(k - 1), domain.corner(k + 1), i, j);
        us[CornerGrid::index(i, j)] = uv.x, vs[CornerGrid::index(i, j)] = uv.y;
      }
    patch.evaluateBatch(CornerGrid::kSize, us.data(), vs.data(), at.data());
    for (std::size_t s = 0; s < CornerGrid::kSize; ++s) normals[s] = cross(at[s].du, at[s].dv);
    if (CornerGrid::folds(normals)) corners.push_back(k);
  }
  return corners;
}

/// True when the patch's normal du × dv points along each side's fence
/// normal at eight points just inside the side (what a patch meeting its
/// fences with the loop's orientation does, folded inside or not). A patch
/// turned over as a whole, or along a side, does not.
bool facesItsFences(const Patch &patch) {
  const RegularDomain &domain = patch.domain();
  const double inset = 1.0 - 0.02 / kFoldRows;
  for (int i = 0; i < domain.sides(); ++i)
    for (int j = 0; j < 8; ++j) {
      const double s = (j + 0.5) / 8;
      const Vec2 uv = domain.pointOnSide(i, s) * inset;
      const DualVec3 r = patch.evaluate(uv.x, uv.y);
      const LinearRibbon &ribbon = patch.ribbon(i);
      const Vec3 fenceNormal = cross(ribbon.curve().derivatives(s)[1], ribbon.fenceDirection(s));
      if (!(dot(cross(r.du, r.dv), fenceNormal) > 0)) return false;
    }
  return true;
}

// Surface::Impl: patches/surface_impl.hpp.

const bezier::BezierSurfaceData *SurfaceAccess::bezierData(const Surface &surface) {
  return surface.impl_->bezier.get();
}

const Patch *SurfaceAccess::patch(const Surface &surface, int face) {
  return surface.impl_->bezier ? nullptr : surface.impl_->patches.at(face).get();
}

std::optional<Vec3> SurfaceAccess::selfCrossing(const Surface &surface, int face) {
  const std::vector<std::optional<Vec3>> &crossings = surface.impl_->selfCrossings;
  if (surface.impl_->bezier || !crossings.at(face)) return std::nullopt;
  return *crossings[face] + surface.impl_->origin;
}

std::shared_ptr<const Patch> SurfaceAccess::sharedPatch(const Surface &surface, int face) {
  return surface.impl_->patches.at(face);
}

std::shared_ptr<const NormalFence> SurfaceAccess::sharedFence(const Surface &surface, int segment) {
  return surface.impl_->fences.at(segment);
}

const RegularDomain &squareDomain() {
  static const RegularDomain domain(4);
  return domain;
}

namespace {
using Impl = Surface::Impl;

/// Runs body(k) for every k in [0, count), in parallel over TBB (one item
/// per task: a fence or a face costs 0.1–2 ms, far above the task overhead).
/// Items write disjoint results, so the output does not depend on the thread
/// count; an exception is rethrown for the lowest failing index, so the
/// error reported does not depend on scheduling either.
template <class Body>
void forEachItem(std::size_t count, Body &&body) {
  std::vector<std::exception_ptr> errors(count);
  auto one = [&](std::size_t k) {
    try {
      body(k);
    } catch (...) {
      errors[k] = std::current_exception();
    }
  };
  if (count < 2) {
    for (std::size_t k = 0; k < count; ++k) one(k);
  } else {
    parallel::parallelFor(tbb::blocked_range<std::size_t>(0, count, 1), [&](const tbb::blocked_range<std::size_t> &r) {
      for (std::size_t k = r.begin(); k < r.end(); ++k) one(k);
    });
  }
  for (const std::exception_ptr &e : errors)
    if (e) std::rethrow_exception(e);
}

std::vector<int> allIndices(std::size_t count) {
  std::vector<int> all(count);
  for (std::size_t k = 0; k < count; ++k) all[k] = static_cast<int>(k);
  return all;
}

/// A model far from the origin (a 1e6 offset on a unit-size part) would
/// lose its low digits in every difference the patches take: it is built
/// translated to its bounding-box centre (Surface::origin). A mesh reference
/// cannot be moved cheaply, so it keeps the world frame.
bool needsOriginShift(const Network &network) {
  const bool meshReference = network.reference() && network.reference()->kind == ReferenceSurface::Kind::Mesh;
  return norm(network.bounds().center()) > 4 * network.diagonal() && !meshReference;
}

// ---- Master surfaces given from outside ([SV14] Sec. 5.1) ----------------

/// The master surface segment `seg` names (nullptr for none).
const BSplineSurface *masterSurfaceOf(const Network &network, const Segment &seg) {
  return seg.masterSurface < 0 ? nullptr : &network.description().surfaces[size_t(seg.masterSurface)];
}

/// The master surface of the first segment at vertex v that names one
/// (nullptr for none): a vertex at the end of a master edge takes that
/// surface's curvature, so that the fences of its other edges meet the
/// master's (N' = −S(P') with the master's shape operator S).
const BSplineSurface *vertexMasterSurface(const Network &network, int v) {
  for (int e : network.vertices()[size_t(v)].segments)
    if (const BSplineSurface *master = masterSurfaceOf(network, network.segments()[size_t(e)])) return master;
  return nullptr;
}

/// The master's frame at its closest point to p.
SurfaceFrame masterFrame(const BSplineSurface &master, const Vec3 &p) {
  const SurfaceProjection foot = master.closestPoint(p);
  return master.frame(foot.u, foot.v);
}

// ---- end of master surfaces --------------------------------------------------

/// Vertex frames and curvatures of the listed vertices.
void buildVertexData(Impl &impl, std::span<const int> vertices) {
  const Network &network = impl.network;
  updateVertexFrames(network, vertices, impl.frames);
  impl.fitted.resize(network.vertices().size());
  impl.curvatures.resize(network.vertices().size());
  const bool referenceCurvature =
      impl.options.scheme == Scheme::GregoryG2 && impl.options.edgeCurvature == EdgeCurvature::Reference;
  for (int v : vertices) {
    // Vertex normals stay the curves' common tangent plane even with reference
    // fences: every patch corner reproduces that plane, so a fence that met a
    // different normal there would break G¹ (see NormalFence::fromNormalField).
    impl.fitted[v] = fitVertexCurvature(network, impl.frames, v);
    const Vec3 &position = network.vertices()[v].position;
    if (const BSplineSurface *master = vertexMasterSurface(network, v))
      impl.curvatures[v] = vertexCurvatureFromReference(masterFrame(*master, position), impl.fitted[v].normal,
                                                        impl.fitted[v].xAxis);
    else if (referenceCurvature)
      impl.curvatures[v] = vertexCurvatureFromReference(network.reference()->closest(position), impl.fitted[v].normal,
                                                        impl.fitted[v].xAxis);
    else
      impl.curvatures[v] = impl.fitted[v];
  }
}

bool keptG1(const Impl &impl, int face) { return face >= 0 && !impl.keptG1.empty() && impl.keptG1[face]; }

/// The side (0 or 1) of a segment whose face is kept as its G¹ patch while
/// the other is not; -1 otherwise (MasterFaces::KeptG1).
int keptSide(const Impl &impl, const Segment &seg) {
  const bool first = keptG1(impl, seg.faces[0]), second = keptG1(impl, seg.faces[1]);
  return first == second ? -1 : first ? 0 : 1;
}

/// The master faces a gregory-g2 surface keeps as G¹ patches (empty when none).
std::vector<char> keptG1Faces(const Network &network, const SurfaceOptions &options) {
  std::vector<char> kept;
  if (options.scheme != Scheme::GregoryG2 || options.masterFaces != MasterFaces::KeptG1) return kept;
  for (const Segment &seg : network.segments())
    if (seg.masterFace >= 0) {
      kept.resize(network.faces().size(), 0);
      kept[seg.masterFace] = 1;
    }
  return kept;
}

/// The normal fence of segment e for the face on `side` (both faces share
/// it unless the segment is a crease: see fenceEndNormal).
std::shared_ptr<const NormalFence> buildFence(const Impl &impl, int e, int side = 0) {
  const Segment &seg = impl.network.segments()[e];
  const Vec3 n0 = fenceEndNormal(impl.network, impl.frames, e, false, side);
  const Vec3 n1 = fenceEndNormal(impl.network, impl.frames, e, true, side);
  // A master surface's normal at the closest point of each fence sample:
  // every face along the edge then shares the master's tangent planes.
  if (const BSplineSurface *master = masterSurfaceOf(impl.network, seg))
    return std::make_shared<const NormalFence>(NormalFence::fromNormalField(
        seg.curve, [master](const Vec3 &p) { return masterFrame(*master, p).normal; }, n0, n1));
  // An edge of a kept G¹ face keeps that patch's fence: the G² face across
  // it then shares its tangent planes along the whole edge.
  if (keptG1(impl, seg.faces[0]) || keptG1(impl, seg.faces[1])) return SurfaceAccess::sharedFence(*impl.g1, e);
  const auto &given = impl.network.description().curveNormals;
  if (seg.sourceCurve >= 0 && seg.sourceCurve < static_cast<int>(given.size()) && !given[seg.sourceCurve].empty()) {
    // Normals sampled along the curve, turned to the side the faces' loops give.
    const CurveNormals &normals = given[seg.sourceCurve];
    return std::make_shared<const NormalFence>(NormalFence::fromNormalsAlong(
        seg.curve,
        [&normals, &seg, side = n0](double u) {
          const Vec3 n = normals.at(seg.sourceFrom + (seg.sourceTo - seg.sourceFrom) * u);
          return dot(n, side) < 0 ? -n : n;
        },
        n0, n1));
  }
  if (impl.referenceFences) {
    // The reference surface's normal, turned to the side the faces' loops give.
    const ReferenceSurface &reference = *impl.network.reference();
    return std::make_shared<const NormalFence>(NormalFence::fromNormalField(
        seg.curve,
        [&reference, side = n0](const Vec3 &p) {
          const Vec3 n = reference.closest(p).normal;
          return dot(n, side) < 0 ? -n : n;
        },
        n0, n1));
  }
  if (impl.options.scheme == Scheme::GregoryG2) {
    // Rotation rates about the tangent that make N' = −S(P') at both ends,
    // S the end vertex's shape operator; none at a crease vertex, whose one
    // tensor is fitted to the curves of both sides of the crease in a plane
    // that is neither side's. There it said nothing of either side's
    // surface: on bathtub.obj's rim a wall's fence took 11.5 rad per unit
    // length from it and turned a quarter turn mid-edge, into the rim's
    // plane, and the wall's patch curled under the rim through its
    // neighbour there.
    auto rate = [&](int vertex, const Vec3 &tangent, const Vec3 &normal) {
      if (impl.frames[vertex].crease) return 0.0;
      return -dot(impl.curvatures[vertex].shape(tangent), cross(tangent, normal));
    };
    const double rate0 = rate(seg.start, normalized(seg.curve.derivatives(0.0)[1]), n0);
    const double rate1 = rate(seg.end, normalized(seg.curve.derivatives(1.0)[1]), n1);
    return std::make_shared<const NormalFence>(NormalFence::curvatureCompatible(seg.curve, n0, n1, rate0, rate1));
  }
  return std::make_shared<const NormalFence>(seg.curve, n0, n1);
}

/// True when gregory-g2 measures segment `seg`'s transversal curvature on the
/// G¹ patches (named master, connection curve, master–slave, averaging).
bool measuredOnG1(const Segment &seg, EdgeCurvature source) {
  if (seg.masterSurface >= 0) return false; // the master surface's own curvature
  return seg.masterFace >= 0 || seg.connection || source == EdgeCurvature::MasterSlave ||
         source == EdgeCurvature::Averaging;
}

/// gregory-g2: the transversal curvature κ_D of segment e, sampled at
/// kCurvatureIntervals + 1 parameters and interpolated.
std::shared_ptr<const TransversalCurvature> buildEdgeCurvature(const Impl &impl, int e) {
  const Network &network = impl.network;
  const SurfaceOptions &options = impl.options;
  const Segment &seg = network.segments()[e];
  const NormalFence &fence = *impl.fences[e];
  const Surface *g1 = impl.g1.get();
  // The master face's side of the edge: named ([SV14] Sec. 5.1), or
  // faces[0] for MasterSlave; -1 averages both (Averaging).
  // Connection curves: both sides, averaged (-1), like named masters
  // independent of the source chosen for the other edges.
  // An edge between a kept G¹ face and a G² face takes the kept patch's
  // curvature, as if it named that face.
  const int kept = keptSide(impl, seg);
  const BSplineSurface *masterSurface = masterSurfaceOf(network, seg);
  const bool namedMaster = seg.masterFace >= 0 || seg.connection || kept >= 0 || masterSurface;
  const int masterSide = seg.masterFace >= 0                                   ? (seg.faces[0] == seg.masterFace ? 0 : 1)
                         : kept >= 0                                           ? kept
                         : seg.connection                                      ? -1
                         : options.edgeCurvature == EdgeCurvature::MasterSlave ? 0
                                                                               : -1;
  const bool direct = !namedMaster && options.edgeCurvature == EdgeCurvature::Direct;
  // Direct: the vertex tensors' normal curvatures across the edge (in the
  // fence direction N × t) and along it at both ends, blended in arc
  // length. The arc lengths to the samples are summed interval by interval
  // (each quadrature short, none repeated).
  std::array<double, 2> endTransversal{}, endAlong{};
  std::array<double, kCurvatureIntervals + 1> arc{};
  if (direct) {
    for (int end = 0; end < 2; ++end) {
      const VertexCurvature &vc = impl.curvatures[end == 0 ? seg.start : seg.end];
      const Vec3 t = normalized(seg.curve.derivatives(end)[1]), b = cross(fence.normal(end), t);
      endTransversal[end] = dot(vc.shape(b), b);
      endAlong[end] = dot(vc.shape(t), t);
    }
    for (int j = 1; j <= kCurvatureIntervals; ++j)
      arc[j] = arc[j - 1] + seg.curve.arcLength(double(j - 1) / kCurvatureIntervals, double(j) / kCurvatureIntervals);
  }
  const double length = arc.back() > 0 ? arc.back() : 1.0;
  std::vector<double> samples(kCurvatureIntervals + 1);
  for (int j = 0; j <= kCurvatureIntervals; ++j) {
    const double u = double(j) / kCurvatureIntervals;
    const auto c = seg.curve.derivatives(u);
    Vec3 n, dn;
    fence.normalAndDerivative(u, c, n, dn);
    const Vec3 t = normalized(c[1]), d = cross(n, t);
    double kappa = 0;
    if (masterSurface) {
      // The master's second fundamental form in the fence direction, at
      // the closest point (ends included: the end vertices carry the
      // master's tensor too, so the two agree there).
      const SurfaceFrame frame = masterFrame(*masterSurface, c[0]);
      kappa = (dot(frame.normal, n) < 0 ? -1.0 : 1.0) * frame.normalCurvature(d);
    } else if (!namedMaster && options.edgeCurvature == EdgeCurvature::Reference) {
      const SurfaceFrame frame = network.reference()->closest(c[0]);
      kappa = (dot(frame.normal, n) < 0 ? -1.0 : 1.0) * frame.normalCurvature(d);
    } else if (j == 0 || j == kCurvatureIntervals) {
      kappa = impl.curvatures[j == 0 ? seg.start : seg.end].normalCurvature(d);
    } else if (direct) {
      // The blend of the end tensors across the edge, w2, and along it, w1.
      // Refitting the blended tensor with the constraint κ(0) = k0 (as the
      // measured sources do, over their five directions) moves κ_D by
      // −(k0 − w1)/3: a third of the curve's disagreement with the blend,
      // turned across the edge. Where that disagreement is of the size of
      // the transversal curvatures themselves it is the surface's own
      // variation, and the shift is kept (saddle-nodes: up to 0.6 of the
      // ends' |κ_D|; without it 1.64 % instead of 1.44 %). Where it is many
      // times larger it is a spike of the curve's own curvature near a node
      // (a sketch stroke's fit; bathtub's rim: 28×), which the shift turned
      // into transversal curvatures 10–15 times the ends' and folded 18
      // faces: from 1× to 3× of the ends' max |κ_D| it is faded out.
      const double x = arc[j] / length;
      const double across = (1 - x) * endTransversal[0] + x * endTransversal[1];
      const double disagreement = dot(c[2], n) / dot(c[1], c[1]) - ((1 - x) * endAlong[0] + x * endAlong[1]);
      const double scale = std::max({std::abs(endTransversal[0]), std::abs(endTransversal[1]), 1 / network.diagonal()});
      const double fade = std::clamp((std::abs(disagreement) / scale - kSpikeFrom) / (2 * kSpikeFrom), 0.0, 1.0);
      kappa = across - disagreement / 3 * (1 - fade * fade * (3 - 2 * fade));
    } else {
      CURVENET_CHECK(g1 != nullptr, "segment " + std::to_string(e) + " needs the G¹ surface");
      std::array<double, 5> measured{};
      double curveCurvature = 0;
      int count = 0;
      for (int side = 0; side < 2; ++side) {
        const int face = seg.faces[side];
        if (face < 0 || (masterSide >= 0 && side != masterSide)) continue;
        const SurfacePoint2 p = g1->evaluateSecondOrder(face, g1->domainPointOnSegment(face, e, u));
        const double sign = dot(p.normal, n) < 0 ? -1.0 : 1.0;
        const Vec3 normal = p.normal * sign, b = normalized(cross(normal, t));
        for (size_t k = 0; k < kMeasureAngles.size(); ++k)
          measured[k] += sign * p.normalCurvature(t * std::cos(kMeasureAngles[k]) + b * std::sin(kMeasureAngles[k]));
        curveCurvature += dot(c[2], normal) / dot(c[1], c[1]);
        ++count;
      }
      for (double &m : measured) m /= count;
      kappa = constrainedTransversal(measured, curveCurvature / count);
    }
    samples[j] = kappa;
  }
  return std::make_shared<const TransversalCurvature>(samples);
}

/// One face's patch, its domain sides and whether it folds.
struct FaceBuild {
  std::shared_ptr<const Patch> patch;
  std::vector<Impl::DomainSide> sides;
  bool folded = false;
  std::optional<Vec3> selfCrossing; ///< patchSelfCrossing of `patch`
  PatchLattice lattice;             ///< its 24-row lattice (patchSelfCrossing), when built here
  bool clearOfOthers = true;        ///< whether `patch` passed buildFace's clearOfOthers, when given
};

/// Whether a face's patch, given its 24-row lattice, crosses no other face
/// (separateCrossingFaces).
using ClearOfOthers = std::function<bool(const PatchLattice &)>;

/// A variant of a patch (unfoldedVariant) with what its checks found.
struct PatchVariant {
  std::shared_ptr<const Patch> patch;
  PatchLattice lattice; ///< its 24-row lattice
  std::optional<Vec3> selfCrossing;
};

/// The fence face f sees along segment e.
const NormalFence *fenceOf(const Impl &impl, int e, int f) {
  const bool second = impl.network.segments()[e].faces[1] == f && impl.creaseFences[e];
  return second ? impl.creaseFences[e].get() : impl.fences[e].get();
}

/// The first of these variants of a patch that folds as built (with the
/// corner shares its ribbons ask for), inside or at a corner, that does not
/// fold (docs/surfaces.md, Folds): the asked shares with the two-ribbon
/// blend alone (μ = 1) at the corners `foldingCorners` (foldedCorners),
/// then eq. 17's corners alone (μ = 0 everywhere), the two-ribbon blend at every corner (μ = 1), then
/// both again with the ribbons' cross-derivatives at three quarters and at
/// half their length. `build(scale, shares)` makes one: the end targets
/// scaled (they take the neighbouring curves' parameter speed, whatever the
/// face's extent across: a planar half disc with a wavy rim reached past
/// its diameter) and the corners' shares set. Each variant keeps the
/// scheme's continuity across the sides: T stays in its fence's tangent
/// plane, a parabolic ribbon's C is II(T, T) N of the scaled T (the same
/// second fundamental form), and both corner forms meet each ribbon to the
/// scheme's order on its own side whatever the two ribbons' disagreement at
/// the corner. A variant is taken when `accepts` it and it folds neither on
/// the fold grid nor on one of kFineFoldRows rows (box.obj's triangles with
/// the blend pass the first and fold near their centre on the second; at
/// 3/4 length they pass both) nor at a corner, and does not pass through
/// itself (patchSelfCrossing); failing that, when the patch folds on the
/// fold grid (`foldsInside`), the first variant that passes the fold grid;
/// else none. With `clearOfOthers`, only variants whose lattice it passes
/// (the one lattice made for both that check and patchSelfCrossing's).
/// Three times the fold grid, below Patch::kTableResolution: no ribbon
/// tables are built for a variant.
constexpr int kFineFoldRows = 3 * kFoldRows;
static_assert(kFineFoldRows < Patch::kTableResolution);
template <class Build, class Accepts, class Folds>
std::optional<PatchVariant> unfoldedVariant(const Patch &patch, bool foldsInside, std::span<const int> foldingCorners,
                                            const Build &build, const Accepts &accepts, const Folds &folds,
                                            const ClearOfOthers *clearOfOthers) {
  const std::vector<double> &asked = patch.blendShares();
  const int n = patch.domain().sides();
  std::vector<std::pair<double, std::vector<double>>> variants;
  std::vector<double> blended = asked;
  for (const int k : foldingCorners) blended[k] = 1;
  variants.push_back({1.0, std::move(blended)});
  for (const double scale : {1.0, 0.75, 0.5})
    for (const double share : {0.0, 1.0}) variants.push_back({scale, std::vector<double>(n, share)});
  std::optional<PatchVariant> coarse;
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const auto &[scale, shares] = variants[v];
    // The patch itself, or a variant already tried.
    const bool tried = std::find(variants.begin(), variants.begin() + v, variants[v]) != variants.begin() + v;
    if ((scale == 1.0 && shares == asked) || tried) continue;
    std::shared_ptr<const Patch> candidate = build(scale, shares);
    if (folds(*candidate, kFoldRows) || !accepts(*candidate)) continue;
    const bool unfolded = !folds(*candidate, kFineFoldRows) && foldedCorners(*candidate).empty();
    if (!unfolded && (coarse || !foldsInside)) continue; // neither taken nor the fallback
    PatchVariant variant{std::move(candidate), {}, {}};
    variant.selfCrossing = patchSelfCrossing(*variant.patch, variant.lattice);
    if (clearOfOthers && !(*clearOfOthers)(variant.lattice)) continue;
    if (unfolded && !variant.selfCrossing) return variant;
    if (!coarse && foldsInside) coarse = std::move(variant);
  }
  return coarse;
}

/// Face f's patch as its ribbons ask, or the first variant that does not
/// fold or pass through itself (unfoldedVariant). With `clearOfOthers`, a
/// patch it refuses (one passing through a neighbour, separateCrossingFaces)
/// takes a variant too, and variants must pass it.
FaceBuild buildFace(const Impl &impl, int f, const ClearOfOthers *clearOfOthers = nullptr) {
  const Face &face = impl.network.faces()[f];
  const bool g2 = impl.options.scheme == Scheme::GregoryG2;
  FaceBuild result;
  if (keptG1(impl, f)) {
    // The G¹ surface's own patch, shared.
    const Surface &g1 = *impl.g1;
    result.patch = SurfaceAccess::sharedPatch(g1, f);
    for (int i = 0; i < g1.domainSides(f); ++i) result.sides.push_back(g1.domainSideRange(f, i));
    result.folded = std::binary_search(g1.foldedFaces().begin(), g1.foldedFaces().end(), f);
    if (const std::optional<Vec3> x = SurfaceAccess::selfCrossing(g1, f)) result.selfCrossing = *x - g1.origin();
    return result;
  }
  std::vector<Impl::DomainSide> &sides = result.sides;
  for (int k = 0; k < face.sideCount(); ++k) {
    if (face.sideCount() == 2) {
      // Split at the segment break nearest the middle, so that the new
      // corner is a vertex both neighbours already share; else the middle.
      double split = 0.5;
      for (double b : face.sides[k].breaks)
        if (std::abs(b - 0.5) < std::abs(split - 0.5) || split == 0.5) split = b;
      sides.push_back({k, 0.0, split});
      sides.push_back({k, split, 1.0});
    } else {
      sides.push_back({k, 0.0, 1.0});
    }
  }
  std::vector<LinearRibbon> ribbons;
  for (const Impl::DomainSide &ds : sides) {
    const FaceSide &side = face.sides[ds.faceSide];
    const double width = ds.sTo - ds.sFrom;
    BSplineCurve curve = width == 1.0 ? side.curve : side.curve.restricted(ds.sFrom, ds.sTo).reparameterized(0, 1);
    // Segments of this side, as ranges of the ribbon's own parameter.
    std::vector<LinearRibbon::Piece> pieces;
    for (size_t j = 0; j < side.segments.size(); ++j) {
      const double b0 = j == 0 ? 0.0 : side.breaks[j - 1];
      const double b1 = j + 1 == side.segments.size() ? 1.0 : side.breaks[j];
      if (b1 <= ds.sFrom || b0 >= ds.sTo) continue;
      pieces.push_back({fenceOf(impl, side.segments[j], f), (b0 - ds.sFrom) / width, (b1 - ds.sFrom) / width,
                        side.segmentReversed[j], side.segments[j]});
    }
    ribbons.emplace_back(std::move(curve), std::move(pieces));
  }
  // End conditions need the neighbouring sides' tangents (docs/design.md §3).
  const int n = static_cast<int>(ribbons.size());
  std::vector<Vec3> startTargets, endTargets;
  for (int i = 0; i < n; ++i) {
    const LinearRibbon &prev = ribbons[(i + n - 1) % n], &next = ribbons[(i + 1) % n];
    LinearRibbon &ribbon = ribbons[i];
    const Vec3 startTangent = ribbon.curve().derivatives(0.0)[1], endTangent = ribbon.curve().derivatives(1.0)[1];
    const Vec3 prevTangent = prev.curve().derivatives(1.0)[1], nextTangent = next.curve().derivatives(0.0)[1];
    const double startTurn = angleBetween(startTangent, prevTangent);
    const double endTurn = angleBetween(endTangent, nextTangent);
    if (std::numbers::pi - startTurn < kCuspAngle)
      throw InputError("", "face " + std::to_string(f),
                       "cusp at the start of side " + std::to_string(sides[i].faceSide) +
                           ": the two curves leave the corner in the same direction");
    const Vec3 startTarget = startTurn < kStraightAngle ? ribbon.fenceDirection(0.0) : -prevTangent;
    const Vec3 endTarget = endTurn < kStraightAngle ? ribbon.fenceDirection(1.0) : nextTangent;
    // gregory-g2: α, β by the quintic blend, so that the nine-term
    // correction patch meets compatible twists (see ScalarBlend).
    ribbon.setEndConditions(startTarget, endTarget,
                            g2 ? LinearRibbon::ScalarBlend::Quintic : LinearRibbon::ScalarBlend::Linear);
    startTargets.push_back(startTarget), endTargets.push_back(endTarget);
  }
  auto parabolicOf = [&](const LinearRibbon &ribbon) {
    std::vector<const TransversalCurvature *> curvatures;
    for (const LinearRibbon::Piece &piece : ribbon.pieces())
      curvatures.push_back(impl.edgeCurvatures[piece.segment].get());
    return ParabolicRibbon(ribbon, std::move(curvatures));
  };
  // gregory-g2's patch for given corner blend shares: parabolic ribbons
  // whose corner terms match (matchCornerTerms). A side whose corners both
  // take the two-ribbon blend alone meets no correction patch, which the
  // quintic blend of α, β (and the corner-term matching) is for: there it
  // takes the linear blend of the unit frame, as the G¹ ribbons do, whose
  // |T| stays within its end values.
  auto g2Patch = [&](std::vector<LinearRibbon> sideRibbons, std::vector<double> shares, double scale = 1.0) {
    std::vector<ParabolicRibbon> parabolic = matchCornerTerms(sideRibbons, parabolicOf);
    for (int i = 0; i < n; ++i)
      if (shares[i] == 1 && shares[(i + 1) % n] == 1) {
        sideRibbons[i].setEndConditions(startTargets[i] * scale, endTargets[i] * scale,
                                        LinearRibbon::ScalarBlend::Linear);
        parabolic[i] = parabolicOf(sideRibbons[i]);
      }
    return std::make_shared<const Patch>(std::move(sideRibbons), impl.options, std::move(parabolic), std::move(shares));
  };
  auto folds = [f](const Patch &patch, int rows = kFoldRows) {
    try {
      return patchFolds(patch, rows);
    } catch (const NonFinitePatch &) {
      // Degenerate input (e.g. coincident corners after the tolerance, a
      // collapsed side) that the topology checks let through: refuse it here
      // rather than hand out NaN points.
      throw InputError("", "face " + std::to_string(f),
                       "the patch cannot be evaluated (non-finite points inside the face): the loop is degenerate");
    }
  };
  const bool g1 = impl.options.scheme == Scheme::GregoryG1;
  std::vector<LinearRibbon> linear;
  std::vector<double> blendShares;
  if (g2) {
    std::vector<ParabolicRibbon> parabolic;
    for (const LinearRibbon &ribbon : ribbons) parabolic.push_back(parabolicOf(ribbon));
    blendShares = cornerBlendShares(ribbons, parabolic);
    result.patch = g2Patch(ribbons, blendShares);
  } else {
    if (g1) linear = ribbons;
    result.patch = std::make_shared<const Patch>(std::move(ribbons), impl.options);
  }
  result.folded = folds(*result.patch);
  if (!g1 && !g2) {
    result.selfCrossing = patchSelfCrossing(*result.patch, result.lattice);
    return result;
  }
  // The Gregory schemes' patch for given corner shares, its ribbons' end
  // targets scaled by `scale`.
  auto withShares = [&](std::vector<double> shares, double scale) -> std::shared_ptr<const Patch> {
    std::vector<LinearRibbon> scaled = g2 ? ribbons : linear;
    if (scale != 1.0)
      for (int i = 0; i < n; ++i)
        scaled[i].setEndConditions(startTargets[i] * scale, endTargets[i] * scale,
                                   g2 ? LinearRibbon::ScalarBlend::Quintic : LinearRibbon::ScalarBlend::Linear);
    if (g2) return g2Patch(std::move(scaled), std::move(shares), scale);
    return std::make_shared<const Patch>(std::move(scaled), impl.options, std::vector<ParabolicRibbon>{},
                                         std::move(shares));
  };
  // gregory-g2 wants each side's normal to face its fence (a face turned
  // over along a side meets its neighbour's normals there and passes the
  // fold grid).
  auto accepts = [&](const Patch &patch) { return !g2 || facesItsFences(patch); };
  // A face that folds with the shares its ribbons ask for is built again
  // (unfoldedVariant): first with the two-ribbon blend alone at the corners
  // that fold below the fold grid (foldedCorners; docs/surfaces.md, Corner
  // folds: on the public sketches eq. 17's corner interpolant turned the
  // normal over within 2e-3 of the diagonal of corners whose two curves
  // leave in nearly one direction, the blend at none), then with uniform
  // shares and shorter cross-derivatives. So is a face that passes through
  // itself without folding.
  const std::vector<int> foldingCorners = foldedCorners(*result.patch);
  result.selfCrossing = patchSelfCrossing(*result.patch, result.lattice);
  result.clearOfOthers = !clearOfOthers || (*clearOfOthers)(result.lattice);
  if (result.folded || !foldingCorners.empty() || result.selfCrossing || !result.clearOfOthers) {
    auto build = [&](double scale, const std::vector<double> &shares) { return withShares(shares, scale); };
    if (std::optional<PatchVariant> variant =
            unfoldedVariant(*result.patch, result.folded, foldingCorners, build, accepts, folds, clearOfOthers)) {
      result.patch = std::move(variant->patch);
      result.lattice = std::move(variant->lattice);
      result.selfCrossing = variant->selfCrossing;
      result.folded = false;
      result.clearOfOthers = true;
    }
  }
  return result;
}

/// The fences of the listed segments, in parallel.
void buildEdges(Impl &impl, std::span<const int> fenceSegments) {
  impl.fences.resize(impl.network.segments().size());
  impl.creaseFences.resize(impl.network.segments().size());
  forEachItem(fenceSegments.size(), [&](std::size_t k) {
    const int e = fenceSegments[k];
    impl.fences[e] = buildFence(impl, e);
    impl.creaseFences[e] = isCreaseSegment(impl.network, impl.frames, e) ? buildFence(impl, e, 1) : nullptr;
  });
}

/// gregory-g2: the edge curvatures of the listed segments, in parallel.
void buildEdgeCurvatures(Impl &impl, std::span<const int> segments) {
  impl.edgeCurvatures.resize(impl.network.segments().size());
  forEachItem(segments.size(),
              [&](std::size_t k) { impl.edgeCurvatures[segments[k]] = buildEdgeCurvature(impl, segments[k]); });
}

/// How far a lattice's normals turn from their mean: the least cosine
/// between the two (1 for a plane).
double leastAlignment(const PatchLattice &lattice) {
  Vec3 sum{0, 0, 0};
  for (const Vec3 &n : lattice.normals) sum += n;
  const Vec3 mean = normalized(sum);
  double least = 1;
  for (const Vec3 &n : lattice.normals) least = std::min(least, dot(n, mean));
  return least;
}

/// Whether two faces share a vertex: they meet there or along a curve.
class SharedVertices {
public:
  explicit SharedVertices(const Network &network) : vertices_(network.faces().size()) {
    for (std::size_t f = 0; f < vertices_.size(); ++f) {
      for (const FaceSide &side : network.faces()[f].sides)
        for (const int e : side.segments) {
          const Segment &segment = network.segments()[static_cast<std::size_t>(e)];
          vertices_[f].push_back(segment.start), vertices_[f].push_back(segment.end);
        }
      std::sort(vertices_[f].begin(), vertices_[f].end());
    }
  }
  bool operator()(int a, int b) const {
    const auto &x = vertices_[static_cast<std::size_t>(a)], &y = vertices_[static_cast<std::size_t>(b)];
    for (std::size_t i = 0, j = 0; i < x.size() && j < y.size();) {
      if (x[i] == y[j]) return true;
      x[i] < y[j] ? ++i : ++j;
    }
    return false;
  }

private:
  std::vector<std::vector<int>> vertices_;
};

/// Faces whose patches pass through each other (docs/surfaces.md,
/// Intersections), built again. A pair of the listed faces' and their
/// neighbours' 12-row lattices that cross (forEachLatticeCrossing; faces
/// sharing a vertex are not counted where both triangles touch their
/// boundaries), found again at 48 rows, gives one of its two faces the
/// first variant (buildFace, unfoldedVariant) whose lattice crosses no other
/// face's: the face whose normals turn further from their mean first (the
/// one curling over the other), else the other. On doghead.obj under
/// gregory-g2 the ear stalks' faces 11 and 35, whose patches with the
/// two-ribbon blend at every corner curl through faces 10 and 34, take
/// eq. 17's corners. Faces kept from the G¹ surface and composite-ribbon
/// patches have no variants. `searched` holds every face's 12-row lattice:
/// the faces not built here keep theirs, the built ones' are made here.
void separateCrossingFaces(const Impl &impl, std::span<const int> faces, std::vector<FaceBuild> &built,
                           std::vector<std::shared_ptr<const PatchLattice>> &searched) {
  if (impl.options.scheme != Scheme::GregoryG1 && impl.options.scheme != Scheme::GregoryG2) return;
  const int count = static_cast<int>(impl.network.faces().size());
  std::vector<int> builtIndex(static_cast<std::size_t>(count), -1);
  for (std::size_t k = 0; k < faces.size(); ++k) builtIndex[static_cast<std::size_t>(faces[k])] = static_cast<int>(k);
  auto patchOf = [&](int f) -> const Patch * {
    const int k = builtIndex[static_cast<std::size_t>(f)];
    return k >= 0 ? built[static_cast<std::size_t>(k)].patch.get() : impl.patches[static_cast<std::size_t>(f)].get();
  };
  // Every face's lattice at 12 rows for the search over all faces (the same
  // search at 24 rows took about as long as the rest of doghead.obj's G¹
  // build): the built faces' every other point of the build's 24-row one,
  // the others' kept from their build.
  searched.resize(static_cast<std::size_t>(count));
  auto coarseOf = [&](int f, const Patch &patch) {
    const int k = builtIndex[static_cast<std::size_t>(f)];
    const PatchLattice *ofBuild = k >= 0 ? &built[static_cast<std::size_t>(k)].lattice : nullptr;
    return std::make_shared<const PatchLattice>(ofBuild && ofBuild->rows == 24 ? halved(*ofBuild) : patchLattice(patch, 12));
  };
  forEachItem(static_cast<std::size_t>(count), [&](std::size_t f) {
    const Patch *patch = patchOf(static_cast<int>(f));
    if (!patch) searched[f] = nullptr;
    else if (builtIndex[f] >= 0 || !searched[f]) searched[f] = coarseOf(static_cast<int>(f), *patch);
  });
  std::vector<const PatchLattice *> coarseLattices(static_cast<std::size_t>(count));
  for (std::size_t f = 0; f < searched.size(); ++f) coarseLattices[f] = searched[f].get();
  // Each face's lattice at 24 rows, for the variant search: the build's, or
  // made when first needed (a partial rebuild makes none for faces far
  // from a crossing).
  std::vector<PatchLattice> own(static_cast<std::size_t>(count));
  std::vector<const PatchLattice *> lattices(static_cast<std::size_t>(count), nullptr);
  for (std::size_t k = 0; k < faces.size(); ++k)
    if (!built[k].lattice.triangles.empty()) lattices[static_cast<std::size_t>(faces[k])] = &built[k].lattice;
  auto latticeOf = [&](int f) -> const PatchLattice & {
    const auto F = static_cast<std::size_t>(f);
    if (!lattices[F]) own[F] = patchLattice(*patchOf(f), 24), lattices[F] = &own[F];
    return *lattices[F];
  };
  const SharedVertices touching(impl.network);
  std::vector<std::pair<int, int>> pairs;
  // Pair by pair of faces whose boxes meet, one of them built here, over
  // the triangles within both boxes (where any crossing lies): one search
  // over every face's triangles spent most of its time on neighbouring
  // triangles of one face.
  for (int a = 0; a < count; ++a)
    for (int b = a + 1; b < count; ++b) {
      const PatchLattice *A = coarseLattices[static_cast<std::size_t>(a)], *B = coarseLattices[static_cast<std::size_t>(b)];
      if (!A || !B || !A->box.meets(B->box) ||
          (builtIndex[static_cast<std::size_t>(a)] < 0 && builtIndex[static_cast<std::size_t>(b)] < 0))
        continue;
      const BoundingBox both = A->box.intersection(B->box);
      const PatchLattice *two[2] = {A, B};
      bool crossing = false;
      forEachLatticeCrossing(two, [&](int, int) { return touching(a, b); }, [&](int, int, const Vec3 &) { crossing = true; },
                             &both);
      if (crossing) pairs.push_back({a, b});
    }
  // Whether a lattice of face f crosses no other face's (at 24 rows).
  auto crossesNone = [&](int f, const PatchLattice &lattice) {
    std::vector<const PatchLattice *> near{&lattice};
    std::vector<int> faceOf{f};
    for (int g = 0; g < count; ++g)
      if (g != f && coarseLattices[static_cast<std::size_t>(g)] &&
          lattice.box.meets(coarseLattices[static_cast<std::size_t>(g)]->box))
        near.push_back(&latticeOf(g)), faceOf.push_back(g);
    // Only the neighbours' triangles that may meet this lattice's box: a
    // large network's faces would otherwise make every variant's search
    // as large as the whole surface's.
    bool crosses = false;
    forEachLatticeCrossing(
        near, [&](int a, int b) { return touching(faceOf[static_cast<std::size_t>(a)], faceOf[static_cast<std::size_t>(b)]); },
        [&](int a, int, const Vec3 &) { crosses = crosses || a == 0; }, &lattice.box);
    return !crosses;
  };
  for (const auto &pair : pairs) {
    const int a = pair.first, b = pair.second; // named, not bound: clang 14 captures no structured bindings
    // Found again at 48 rows (a coarse lattice's chords can cross where the
    // patches do not), and not yet taken apart by an earlier pair's variant.
    const PatchLattice fineA = patchLattice(*patchOf(a), 48), fineB = patchLattice(*patchOf(b), 48);
    const PatchLattice *fine[2] = {&fineA, &fineB};
    bool confirmed = false;
    forEachLatticeCrossing(fine, [&](int, int) { return touching(a, b); }, [&](int, int, const Vec3 &) { confirmed = true; });
    if (!confirmed) continue;
    std::vector<int> candidates;
    for (const int f : {a, b})
      if (builtIndex[static_cast<std::size_t>(f)] >= 0 && !keptG1(impl, f)) candidates.push_back(f);
    std::sort(candidates.begin(), candidates.end(), [&](int x, int y) {
      return leastAlignment(latticeOf(x)) < leastAlignment(latticeOf(y));
    });
    // A variant of face f crossing no other face, or nullopt.
    auto variantOf = [&](int f) -> std::optional<FaceBuild> {
      const ClearOfOthers clear = [&](const PatchLattice &lattice) { return crossesNone(f, lattice); };
      FaceBuild rebuilt = buildFace(impl, f, &clear);
      if (rebuilt.lattice.triangles.empty() || !rebuilt.clearOfOthers) return std::nullopt;
      return rebuilt;
    };
    auto take = [&](int f, FaceBuild &&rebuilt) {
      FaceBuild &slot = built[static_cast<std::size_t>(builtIndex[static_cast<std::size_t>(f)])];
      slot = std::move(rebuilt);
      lattices[static_cast<std::size_t>(f)] = &slot.lattice;
      searched[static_cast<std::size_t>(f)] = coarseOf(f, *slot.patch);
      coarseLattices[static_cast<std::size_t>(f)] = searched[static_cast<std::size_t>(f)].get();
    };
    for (const int f : candidates)
      if (std::optional<FaceBuild> rebuilt = variantOf(f)) {
        take(f, std::move(*rebuilt));
        break;
      }
  }
}

/// The patches of the listed faces, in parallel, faces passing through each
/// other built again; the folded list updated.
void buildFaces(Impl &impl, std::span<const int> faces) {
  const std::size_t count = impl.network.faces().size();
  impl.patches.resize(count);
  impl.domainSides.resize(count);
  std::vector<FaceBuild> built(faces.size());
  forEachItem(faces.size(), [&](std::size_t k) { built[k] = buildFace(impl, faces[k]); });
  std::vector<std::shared_ptr<const PatchLattice>> searched = impl.crossingLattices;
  separateCrossingFaces(impl, faces, built, searched);
  impl.crossingLattices = std::move(searched);
  std::vector<char> folded(count, 0);
  for (int f : impl.folded) folded[f] = 1;
  impl.selfCrossings.resize(count);
  for (std::size_t k = 0; k < faces.size(); ++k) {
    impl.selfCrossings[faces[k]] = built[k].selfCrossing;
    impl.patches[faces[k]] = std::move(built[k].patch);
    impl.domainSides[faces[k]] = std::move(built[k].sides);
    folded[faces[k]] = built[k].folded;
  }
  impl.folded.clear();
  for (std::size_t f = 0; f < count; ++f)
    if (folded[f]) impl.folded.push_back(static_cast<int>(f));
}

bool needsG1Surface(const Network &network, const SurfaceOptions &options) {
  return options.scheme == Scheme::GregoryG2 &&
         std::any_of(network.segments().begin(), network.segments().end(),
                     [&](const Segment &seg) { return measuredOnG1(seg, options.edgeCurvature); });
}

SurfaceOptions g1Options(const SurfaceOptions &options) {
  return {Scheme::GregoryG1, Sweepline::Radial, options.fenceNormals};
}

bool sameCurve(const BSplineCurve &a, const BSplineCurve &b) {
  return a.degree() == b.degree() && a.knots() == b.knots() && a.controlPoints() == b.controlPoints() &&
         a.weights() == b.weights();
}

bool sameMasterSurfaces(const std::vector<BSplineSurface> &a, const std::vector<BSplineSurface> &b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const BSplineSurface &x, const BSplineSurface &y) {
    return x.degreeU() == y.degreeU() && x.degreeV() == y.degreeV() && x.knotsU() == y.knotsU() &&
           x.knotsV() == y.knotsV() && x.controlPoints() == y.controlPoints() && x.weights() == y.weights();
  });
}

/// Same vertices, segments, faces and their incidences (and master
/// surfaces): what an edit of curve geometry keeps (see
/// Surface::rebuildAfterEdit).
bool sameTopology(const Network &a, const Network &b) {
  if (!sameMasterSurfaces(a.description().surfaces, b.description().surfaces)) return false;
  if (a.vertices().size() != b.vertices().size() || a.segments().size() != b.segments().size() ||
      a.faces().size() != b.faces().size() || a.reference().has_value() != b.reference().has_value())
    return false;
  for (std::size_t v = 0; v < a.vertices().size(); ++v)
    if (a.vertices()[v].segments != b.vertices()[v].segments) return false;
  for (std::size_t e = 0; e < a.segments().size(); ++e) {
    const Segment &x = a.segments()[e], &y = b.segments()[e];
    if (x.start != y.start || x.end != y.end || x.faces != y.faces || x.masterFace != y.masterFace ||
        x.masterSurface != y.masterSurface || x.connection != y.connection)
      return false;
  }
  for (std::size_t f = 0; f < a.faces().size(); ++f) {
    const Face &x = a.faces()[f], &y = b.faces()[f];
    if (x.sideCount() != y.sideCount()) return false;
    for (int k = 0; k < x.sideCount(); ++k) {
      const FaceSide &p = x.sides[k], &q = y.sides[k];
      if (p.segments != q.segments || p.segmentReversed != q.segmentReversed || p.startVertex != q.startVertex ||
          p.endVertex != q.endVertex)
        return false;
    }
  }
  return true;
}

std::vector<int> sortedUnique(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

/// Faces using any of the segments.
std::vector<int> facesOf(const Network &network, std::span<const int> segments) {
  std::vector<int> faces;
  for (int e : segments)
    for (int f : network.segments()[e].faces)
      if (f >= 0) faces.push_back(f);
  return sortedUnique(std::move(faces));
}

/// The description with every point moved by `offset` (curves, masters, the reference surface).
NetworkDescription translated(NetworkDescription description, const Vec3 &offset) {
  for (BSplineCurve &curve : description.curves) {
    std::vector<Vec3> points = curve.controlPoints();
    for (Vec3 &p : points) p += offset;
    curve = BSplineCurve(curve.degree(), curve.knots(), std::move(points), curve.weights());
  }
  if (description.reference) description.reference->center += offset;
  for (BSplineSurface &master : description.surfaces) {
    std::vector<Vec3> points = master.controlPoints();
    for (Vec3 &p : points) p += offset;
    master = BSplineSurface(master.degreeU(), master.degreeV(), master.knotsU(), master.knotsV(), master.countU(),
                            master.countV(), std::move(points), master.weights());
  }
  return description;
}
} // namespace

Surface Surface::build(const Network &network, const SurfaceOptions &options) {
  // A model far from the origin is built translated to its bounding-box
  // centre, and points are translated back on the way out. First of all
  // stages: the vertex repair's curvatures (second derivatives at the ends
  // of split curves) lose digits with the coordinates' size too, and a
  // sketch 4 diagonals from the origin was repaired at two more vertices
  // than the same sketch at it.
  if (needsOriginShift(network)) {
    const Vec3 centre = network.bounds().center();
    Surface surface = build(Network::build(translated(network.description(), -centre)), options);
    // The surface was made here and is not shared yet: completing it is safe.
    const auto impl = std::const_pointer_cast<Impl>(surface.impl_);
    // Its network is the repaired one where the repair moved curves.
    impl->network = impl->repairMoves.empty()
                        ? network
                        : Network::build(translated(impl->network.description(), centre), network.name());
    impl->origin = centre;
    return surface;
  }
  // Vertex repair (curvenet/analysis.hpp) is the stage before all others:
  // the surface is built on, and reports, the repaired network.
  // Fans the repair left alone are reported even when nothing moved.
  if (options.curves == CurveHandling::Repaired)
    if (RepairResult repair = repairNetwork(network, repairOptionsFor(options.scheme));
        repair.changed() || !repair.skipped.empty()) {
      SurfaceOptions kept = options;
      kept.curves = CurveHandling::Kept;
      Surface surface = build(repair.changed() ? Network::build(repair.network, network.name()) : network, kept);
      const auto impl = std::const_pointer_cast<Impl>(surface.impl_); // not shared yet
      impl->options.curves = CurveHandling::Repaired;
      impl->repairMoves = std::move(repair.moves);
      impl->repairSkipped = std::move(repair.skipped);
      return surface;
    }
  const bool g2 = options.scheme == Scheme::GregoryG2;
  const auto &reference = network.reference();
  if (g2 && options.sweepline == Sweepline::Radial)
    throw InputError("", "options", "gregory-g2 needs a Hermite sweepline (the radial sweep is not G²)");
  if (options.fenceNormals == FenceNormals::Reference && !reference)
    throw InputError("", "options", "fence normals from the reference surface, but the network has none");
  if (g2 && options.edgeCurvature == EdgeCurvature::Reference && !reference)
    throw InputError("", "options", "edge curvature from the reference surface, but the network has none");

  auto impl = std::make_shared<Impl>();
  impl->network = network;
  impl->options = options;
  impl->referenceFences =
      options.fenceNormals == FenceNormals::Reference || (options.fenceNormals == FenceNormals::Auto && reference);
  const std::vector<int> vertices = allIndices(network.vertices().size());
  if (options.scheme == Scheme::BezierG1 || options.scheme == Scheme::CoonsC0) {
    impl->frames = computeVertexFrames(network);
    impl->bezier = std::make_shared<const bezier::BezierSurfaceData>(
        bezier::buildBezierSurface(network, options.scheme == Scheme::BezierG1));
    for (size_t f = 0; f < network.faces().size(); ++f)
      impl->domainSides.push_back({{0, 0.0, 1.0}, {1, 0.0, 1.0}, {2, 0.0, 1.0}, {3, 0.0, 1.0}});
    Surface surface;
    surface.impl_ = std::move(impl);
    return surface;
  }
  buildVertexData(*impl, vertices);
  const std::vector<int> segments = allIndices(network.segments().size());
  if (g2) {
    // Edges with an explicit master ([SV14] Sec. 5.1) take its curvature
    // whatever the source elsewhere, so they need the G¹ patches too.
    // Connection curves (Sec. 5.2) always average the two G¹ patches. Kept
    // master faces are those patches, with their fences.
    if (needsG1Surface(network, options))
      impl->g1 = std::make_shared<const Surface>(Surface::build(network, g1Options(options)));
    impl->keptG1 = keptG1Faces(network, options);
  }
  buildEdges(*impl, segments);
  if (g2) buildEdgeCurvatures(*impl, segments);
  buildFaces(*impl, allIndices(network.faces().size()));
  Surface surface;
  surface.impl_ = std::move(impl);
  return surface;
}

SurfaceEdit Surface::rebuildAfterEdit(const Network &edited) const {
  const Impl &old = *impl_;
  // A model built translated (see build) is rebuilt whole, translated first
  // and repaired there.
  if (old.origin != Vec3{} || needsOriginShift(edited))
    return {build(edited, old.options), allIndices(edited.faces().size()), false};
  // The vertex repair first, as in build: the repaired edit differs from this
  // surface's (repaired) network near the edit only, so the rebuild below
  // stays partial; repairing it again changes nothing.
  RepairResult repair;
  if (old.options.curves == CurveHandling::Repaired) {
    repair = repairNetwork(edited, repairOptionsFor(old.options.scheme));
    if (repair.changed()) {
      SurfaceEdit result = rebuildAfterEdit(Network::build(repair.network, edited.name()));
      const auto impl = std::const_pointer_cast<Impl>(result.surface.impl_); // not shared yet
      impl->repairMoves = std::move(repair.moves);
      impl->repairSkipped = std::move(repair.skipped);
      return result;
    }
  }
  // Kept G¹ master faces: a full build (their fences and patches come from
  // the G¹ surface, which an edit rebuilds in part by itself).
  const bool partial = !old.bezier && old.keptG1.empty() && sameTopology(old.network, edited);
  if (!partial) return {build(edited, old.options), allIndices(edited.faces().size()), false};

  // What the edit touched: segments whose curve changed (and those of face
  // sides whose curve changed, which carry the same source-curve range).
  std::vector<int> changed;
  for (std::size_t e = 0; e < edited.segments().size(); ++e)
    if (!sameCurve(old.network.segments()[e].curve, edited.segments()[e].curve)) changed.push_back(static_cast<int>(e));
  for (std::size_t f = 0; f < edited.faces().size(); ++f)
    for (int k = 0; k < edited.faces()[f].sideCount(); ++k)
      if (!sameCurve(old.network.faces()[f].sides[k].curve, edited.faces()[f].sides[k].curve))
        for (int e : edited.faces()[f].sides[k].segments) changed.push_back(e);
  changed = sortedUnique(std::move(changed));

  auto impl = std::make_shared<Impl>(old);
  impl->repairMoves.clear(); // the caller (above) sets the moves of this edit's repair
  impl->repairSkipped = std::move(repair.skipped);
  impl->network = edited;
  // The frames and curvatures of the changed segments' end vertices (every
  // curve at a vertex enters its tangent plane and curvature fit); then the
  // fences of every segment at those vertices (their end normals and rates).
  std::vector<int> vertices;
  for (int e : changed) vertices.push_back(edited.segments()[e].start), vertices.push_back(edited.segments()[e].end);
  vertices = sortedUnique(std::move(vertices));
  buildVertexData(*impl, vertices);
  std::vector<int> fenceSegments = changed;
  for (int v : vertices)
    fenceSegments.insert(fenceSegments.end(), edited.vertices()[v].segments.begin(), edited.vertices()[v].segments.end());
  fenceSegments = sortedUnique(std::move(fenceSegments));
  buildEdges(*impl, fenceSegments);

  std::vector<int> curvatureSegments;
  if (old.options.scheme == Scheme::GregoryG2) {
    curvatureSegments = fenceSegments;
    if (old.g1) {
      // A segment measured on the G¹ patches changes with any of its faces'
      // G¹ patches, which change with their own fences.
      SurfaceEdit g1 = old.g1->rebuildAfterEdit(edited);
      impl->g1 = std::make_shared<const Surface>(std::move(g1.surface));
      for (int f : g1.changedFaces)
        for (const FaceSide &side : edited.faces()[f].sides)
          for (int e : side.segments)
            if (measuredOnG1(edited.segments()[e], old.options.edgeCurvature)) curvatureSegments.push_back(e);
      curvatureSegments = sortedUnique(std::move(curvatureSegments));
    }
    buildEdgeCurvatures(*impl, curvatureSegments);
  }

  std::vector<int> touched = fenceSegments;
  touched.insert(touched.end(), curvatureSegments.begin(), curvatureSegments.end());
  std::vector<int> faces = facesOf(edited, sortedUnique(std::move(touched)));
  buildFaces(*impl, faces);
  Surface surface;
  surface.impl_ = std::move(impl);
  return {std::move(surface), std::move(faces), true};
}

const Network &Surface::network() const { return impl_->network; }
const std::vector<RepairMove> &Surface::repairMoves() const { return impl_->repairMoves; }
const std::vector<std::string> &Surface::repairSkipped() const { return impl_->repairSkipped; }
Vec3 Surface::origin() const { return impl_->origin; }
const std::vector<int> &Surface::foldedFaces() const { return impl_->folded; }
const SurfaceOptions &Surface::options() const { return impl_->options; }
SurfaceOptions Surface::faceOptions(int face) const {
  if (face < 0 || face >= faceCount()) throw InputError("", "face " + std::to_string(face), "no such face");
  return keptG1(*impl_, face) ? g1Options(impl_->options) : impl_->options;
}
int Surface::faceCount() const {
  return static_cast<int>(impl_->bezier ? impl_->bezier->faces.size() : impl_->patches.size());
}
int Surface::domainSides(int face) const {
  return impl_->bezier ? 4 : impl_->patches.at(face)->domain().sides();
}
Vec2 Surface::domainCorner(int face, int corner) const {
  return impl_->bezier ? squareDomain().corner(corner) : impl_->patches.at(face)->domain().corner(corner);
}

Surface::DomainSideRange Surface::domainSideRange(int face, int domainSide) const {
  return impl_->domainSides.at(face).at(domainSide);
}

Vec2 Surface::domainPointOnFaceSide(int face, int side, double s) const {
  const auto &sides = impl_->domainSides.at(face);
  for (size_t i = 0; i < sides.size(); ++i) {
    const auto &ds = sides[i];
    if (ds.faceSide == side && s <= ds.sTo)
      return (impl_->bezier ? squareDomain() : impl_->patches[face]->domain()).pointOnSide(static_cast<int>(i), (s - ds.sFrom) / (ds.sTo - ds.sFrom));
  }
  throw InputError("", "face " + std::to_string(face), "no side " + std::to_string(side));
}

Vec2 Surface::domainPointOnSegment(int face, int segment, double u) const {
  const Face &f = impl_->network.faces().at(face);
  for (int k = 0; k < f.sideCount(); ++k) {
    const FaceSide &side = f.sides[k];
    for (size_t j = 0; j < side.segments.size(); ++j) {
      if (side.segments[j] != segment) continue;
      // Segment and side are affine images of the same source-curve range.
      const double b0 = j == 0 ? 0.0 : side.breaks[j - 1];
      const double b1 = j + 1 == side.segments.size() ? 1.0 : side.breaks[j];
      const double x = side.segmentReversed[j] ? 1 - u : u;
      return domainPointOnFaceSide(face, k, b0 + (b1 - b0) * x);
    }
  }
  throw InputError("", "face " + std::to_string(face), "does not use segment " + std::to_string(segment));
}

// Evaluation: patches/surface_evaluate.cpp.


Vec3 Surface::vertexNormal(int vertex) const { return impl_->frames.at(vertex).normal; }
double Surface::vertexResidualAngle(int vertex) const { return impl_->frames.at(vertex).residualAngle; }
bool Surface::isCreaseVertex(int vertex) const { return impl_->frames.at(vertex).crease; }
bool Surface::isCreaseSegment(int segment) const {
  if (segment < 0 || segment >= static_cast<int>(impl_->network.segments().size()))
    throw std::out_of_range("segment " + std::to_string(segment));
  return curvenet::isCreaseSegment(impl_->network, impl_->frames, segment);
}

VertexCurvatureInfo Surface::vertexCurvature(int vertex) const {
  const VertexCurvature &vc = impl_->curvatures.at(vertex);
  return {vc.tensor, vc.xAxis, vc.branch, vc.independentDirections, vc.maxResidual};
}

double Surface::transversalCurvature(int segment, double u) const {
  if (impl_->edgeCurvatures.empty()) return std::numeric_limits<double>::quiet_NaN();
  double k, dk;
  impl_->edgeCurvatures.at(segment)->valueAndDerivative(u, k, dk);
  return k;
}

Vec3 Surface::fenceNormal(int segment, double u) const { return impl_->fences.at(segment)->normal(u); }

} // namespace v1
} // namespace curvenet
