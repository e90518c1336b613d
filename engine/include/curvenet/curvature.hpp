// curvenet/curvature.hpp — mean and Gaussian curvature of the patches themselves.
//
// The schemes give exact first derivatives only, so the second fundamental
// form is estimated by differentiating those exact first derivatives once,
// with second-order central differences on the face's domain:
//
//   P_uu ≈ (P_u(u+h, v) − P_u(u−h, v)) / 2h,   P_vv ≈ (P_v(u, v+h) − P_v(u, v−h)) / 2h,
//   P_uv ≈ ½ [(P_v(u+h, v) − P_v(u−h, v)) + (P_u(u, v+h) − P_u(u, v−h))] / 2h,
//
// truncation error O(h²), rounding error O(ε/h); with the default
// h = 1e-3 (domain polygons have unit circumradius) both stay below 1e-6
// relative. L, M, N = n · P_uu, n · P_uv, n · P_vv with the exact unit normal n,
// and E, F, G from the exact first derivatives.
//
// Sign convention as in reference.hpp: κ = II(t, t) with II = −dn · dP, so a
// sphere of radius r with outward normal has κ1 = κ2 = −1/r, mean curvature
// H = (κ1 + κ2)/2 = −1/r and Gaussian curvature K = κ1 κ2 = 1/r².
//
// Near the domain boundary the stencil would leave the polygon, where the
// patch is not defined: a point closer than h to a side is evaluated at two
// points moved towards the domain centre, until every side is h away and
// until it is 2h away, and the values are extrapolated linearly back to the
// point. The boundary error still falls only linearly with h (measured on
// the built-ins: 1e-3 relative at h = 1e-3), because the patches' second
// derivatives vary fastest right next to their sides.
// Where the parameterization degenerates (the straight-angle corners of
// 2-sided faces and T-nodes, where P_u ∥ P_v) the curvature is not resolved
// by domain differences; values near such corners are unreliable.
//
// Thread-safety: pure functions of an immutable Surface; call from any thread.
// Cost: four Surface::evaluate calls per point (five with the normal).
#pragma once

#include <vector>

#include "curvenet/mesh.hpp"
#include "curvenet/surface.hpp"

namespace curvenet {
inline namespace v1 {

struct CurvatureOptions {
  /// Central-difference step in domain units, in (0, 0.1]. Halving it changes
  /// the built-ins' values by less than 1e-3 of their largest magnitude.
  double step = 1e-3;
  /// Worker threads for the mesh version: 0 = all cores, 1 = serial.
  int threads = 0;
};

/// Curvatures at one surface point, in the sign convention above. κ1 ≥ κ2;
/// direction1 is the unit principal direction of κ1 (any tangent at an
/// umbilic), so the normal curvature in a unit tangent t is
/// κ1 cos²φ + κ2 sin²φ with cos φ = t · direction1 (Euler's formula).
struct CurvatureSample {
  double mean = 0, gauss = 0, k1 = 0, k2 = 0;
  Vec3 direction1;
  /// Normal curvature in the tangent direction t (normalized here).
  double normalCurvature(const Vec3 &t) const {
    const Vec3 u = normalized(t);
    const double c = dot(u, direction1);
    return k1 * c * c + k2 * (1 - c * c);
  }
};

/// Curvature of face `face` at domain point uv (inside or on its polygon).
/// Throws InputError for a step outside (0, 0.1] or a face out of range.
CurvatureSample surfaceCurvature(const Surface &surface, int face, const Vec2 &uv, const CurvatureOptions &options = {});

/// Curvature at every vertex of a mesh made by tessellate() with
/// recordDomainPoints set (throws InputError otherwise). Vertices with no
/// face (MeshDomainPoint::face < 0) get NaN. Deterministic for any thread count.
std::vector<CurvatureSample> meshCurvature(const Surface &surface, const Mesh &mesh,
                                           const CurvatureOptions &options = {});

} // namespace v1
} // namespace curvenet
