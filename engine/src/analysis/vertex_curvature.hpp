// Surface curvature at the vertices of a network ([SV14] Sec. 2, App. A):
// the fit of curvenet/vertex_math.hpp applied to the curves at each vertex.
#pragma once

#include <span>
#include <vector>

#include "analysis/vertex_frames.hpp"
#include "curvenet/network.hpp"
#include "curvenet/vertex_math.hpp"

namespace curvenet {
inline namespace v1 {

/// A curvature tensor placed in a vertex's tangent plane. Normal curvatures
/// are signed with respect to `normal` (positive when bending towards it).
struct VertexCurvature {
  Vec3 normal, xAxis, yAxis; ///< right-handed: yAxis = normal × xAxis
  CurvatureTensor tensor;    ///< λ measured from xAxis towards yAxis
  FitBranch branch = FitBranch::Exact;
  int independentDirections = 0;
  double maxResidual = 0; ///< largest misfit of a curve's normal curvature, 1/length
  /// How many of the three Euler modes the curves left undetermined, taken
  /// from the curves' mean curvature instead (see fitBoundedCurvature); 0
  /// where the paper's fit stands.
  int regularizedModes = 0;

  /// Normal curvature in tangent direction v (projected into the plane).
  double normalCurvature(const Vec3 &v) const;
  /// Shape operator S(v) (II(v, w) = S(v)·w), for a tangent vector v.
  Vec3 shape(const Vec3 &v) const;
  /// The principal directions as 3D vectors.
  Vec3 direction1() const;
  Vec3 direction2() const { return cross(normal, direction1()); }
};

/// Sets fit's rmsResidual and maxResidual: the misfit of its tensor's normal
/// curvature in each direction omegas[i] to ks[i] (both 0 without curves).
void fillResiduals(CurvatureFit &fit, std::span<const double> omegas, std::span<const double> ks);

/// A vertex curvature fit that stays within what the curves show.
struct BoundedCurvatureFit {
  CurvatureFit fit;
  /// 0: fitCurvature's result unchanged. 1–3: that many modes of the Euler
  /// fit were replaced by the curves' mean curvature (3: the umbilic).
  int regularizedModes = 0;
};

/// The relative singular value below which an Euler mode counts as
/// undetermined: σ_min / σ_max of the design rows [1, cos 2ω, sin 2ω].
/// Three evenly spread curves give 0.71; an X skewed by 1° gives 0.025 and by
/// 5° 0.12; the vertices of the analytic built-ins with three or more
/// curves stay above 0.16 (saddle-nodes; torus-mixed 0.21, ellipsoid 0.32).
inline constexpr double kUndeterminedModeRatio = 0.1;

/// Two curves whose lines meet at less than asin of this (15°) are nearly
/// parallel: the n = 2 rules of [SV14] divide by sin² of that angle. The
/// built-ins' two-curve vertices meet at 36.9° or more.
inline constexpr double kNearlyParallelSine = 0.2588;

/// The bound a fitted principal curvature may reach at a vertex whose curves
/// have normal curvatures ks: max |k| plus twice their disagreement
/// max k − min k. Twice, because a true tensor sampled in a few directions
/// lies beyond its samples: the analytic built-ins reach max |k| + 1.37 ×
/// the disagreement at a three-valent ellipsoid vertex (κ2 = −1.793 from
/// curves of −1.106, −0.607, −1.106) and + 1.67 × at a saddle between two
/// curves (saddle-nodes); a near-X fit goes beyond it by orders of magnitude.
double principalCurvatureBound(std::span<const double> ks);

/// fitCurvature ([SV14] Sec. 2), kept where it is well conditioned: with
/// three or more curves every mode above kUndeterminedModeRatio and the
/// tensor within principalCurvatureBound; with two curves within the bound
/// or not nearly parallel (the paper's n = 2 rule is a choice of the free
/// mode, and the built-ins' surfaces rest on it). Otherwise —
/// directions in nearly opposite pairs (a near-X, whose sin 2ω column nearly
/// vanishes), clustered directions, two nearly parallel curves — the fit
/// κ(ω) = a + p cos 2ω + q sin 2ω is solved by truncated SVD about the
/// umbilic at the mean k: modes with σ/σ_max < kUndeterminedModeRatio keep
/// the umbilic's value, and further modes are dropped, smallest first, until
/// both principal curvatures are within the bound (all three dropped leave the
/// umbilic, which always is). Near an X this is the X's own fit (each pair's
/// mean along its line, no twist).
BoundedCurvatureFit fitBoundedCurvature(std::span<const double> omegas, std::span<const double> ks,
                                        const FitOptions &options);

/// The normal curvature `kappa` of curve `curve`'s end at vertex `vertex`,
/// or InputError naming both when it is not finite (a curve whose second
/// derivative overflows there: extreme weights or control points), before a
/// fit would refuse it naming only its position in a list.
double finiteNormalCurvature(double kappa, int vertex, int curve);

/// Fits (κ1, κ2, λ) at every vertex to the normal curvatures P''·N/|P'|² of
/// the segment ends there, by fitBoundedCurvature (fitCurvature, which picks
/// the n = 1, 2, 3, > 3 branch, wherever that is well conditioned). The x axis is the first outgoing tangent projected into the plane.
std::vector<VertexCurvature> fitVertexCurvatures(const Network &network, const std::vector<VertexFrame> &frames);
/// The same fit at vertex v alone (what fitVertexCurvatures gives for it).
VertexCurvature fitVertexCurvature(const Network &network, const std::vector<VertexFrame> &frames, int v);

/// The same tensor read off a reference surface frame, re-signed for `normal`
/// (which may point to the other side than the reference's normal).
VertexCurvature vertexCurvatureFromReference(const SurfaceFrame &frame, const Vec3 &normal, const Vec3 &xHint);

} // namespace v1
} // namespace curvenet
