// Mean and Gaussian curvature from the exact first derivatives (see
// curvenet/curvature.hpp for the difference scheme and its error).
#include "curvenet/curvature.hpp"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "curvenet/error.hpp"
#include "parallel/fork_join.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

/// How far (λ ∈ [0, 1]) uv must move towards the domain centre for every
/// side to be at least `margin` away. The domain polygon is convex and
/// contains the origin, so distances to the sides grow linearly along that
/// path and one λ serves all sides.
double inwardShift(const Surface &surface, int face, const Vec2 &uv, double margin) {
  const int n = surface.domainSides(face);
  double lambda = 0;
  for (int i = 0; i < n; ++i) {
    const Vec2 c0 = surface.domainCorner(face, i), c1 = surface.domainCorner(face, i + 1);
    const Vec2 e = c1 - c0;
    const Vec2 inward = Vec2{-e.y, e.x} / norm(e); // corners run counter-clockwise
    const double d = dot(uv - c0, inward), apothem = dot(-c0, inward);
    if (d < margin) lambda = std::max(lambda, (margin - d) / (apothem - d));
  }
  return std::min(lambda, 1.0);
}

/// The central-difference estimate at a point whose stencil lies in the domain.
CurvatureSample centralEstimate(const Surface &surface, int face, const Vec2 &c, double h) {
  const SurfacePoint p = surface.evaluate(face, c);
  const SurfacePoint up = surface.evaluate(face, c + Vec2{h, 0}), um = surface.evaluate(face, c - Vec2{h, 0});
  const SurfacePoint vp = surface.evaluate(face, c + Vec2{0, h}), vm = surface.evaluate(face, c - Vec2{0, h});
  const double inv = 1.0 / (2 * h);
  const Vec3 puu = (up.du - um.du) * inv, pvv = (vp.dv - vm.dv) * inv;
  // P_uv from both mixed differences: their average cancels the asymmetric part of the error.
  const Vec3 puv = ((up.dv - um.dv) + (vp.du - vm.du)) * (0.5 * inv);

  const double E = dot(p.du, p.du), F = dot(p.du, p.dv), G = dot(p.dv, p.dv);
  const double L = dot(p.normal, puu), M = dot(p.normal, puv), N = dot(p.normal, pvv);
  const double det = E * G - F * F;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!(det > 0)) return {nan, nan, nan, nan, {}};
  CurvatureSample s;
  s.mean = (E * N - 2 * F * M + G * L) / (2 * det);
  s.gauss = (L * N - M * M) / det;
  const double root = std::sqrt(std::max(0.0, s.mean * s.mean - s.gauss));
  s.k1 = s.mean + root;
  s.k2 = s.mean - root;
  // Eigenvector of the shape operator I⁻¹ II for κ1: (II − κ1 I) w = 0; of
  // the two equivalent row forms take the better conditioned one.
  const Vec2 w1{M - s.k1 * F, -(L - s.k1 * E)}, w2{N - s.k1 * G, -(M - s.k1 * F)};
  const Vec2 w = dot(w1, w1) >= dot(w2, w2) ? w1 : w2;
  s.direction1 = normalized(dot(w, w) > 0 ? p.du * w.x + p.dv * w.y : p.du);
  return s;
}

CurvatureSample withPrincipal(CurvatureSample s) {
  const double root = std::sqrt(std::max(0.0, s.mean * s.mean - s.gauss));
  s.k1 = s.mean + root;
  s.k2 = s.mean - root;
  return s;
}

} // namespace

CurvatureSample surfaceCurvature(const Surface &surface, int face, const Vec2 &uv, const CurvatureOptions &options) {
  const double h = options.step;
  if (!(h > 0 && h <= 0.1)) throw InputError("", "curvature step", "must lie in (0, 0.1]");
  if (face < 0 || face >= surface.faceCount())
    throw InputError("", "face " + std::to_string(face), "no such face in the surface");
  // A hair more than h keeps rounding from putting a stencil point outside.
  const double margin = h * (1 + 1e-9);
  const double lambda1 = inwardShift(surface, face, uv, margin);
  if (lambda1 == 0) return centralEstimate(surface, face, uv, h);
  const double lambda2 = inwardShift(surface, face, uv, 2 * margin);
  const CurvatureSample a = centralEstimate(surface, face, uv * (1 - lambda1), h);
  if (!(lambda2 > lambda1)) return a;
  const CurvatureSample b = centralEstimate(surface, face, uv * (1 - lambda2), h);
  // Linear extrapolation in λ back to λ = 0 (the point itself).
  const double t = lambda1 / (lambda2 - lambda1);
  CurvatureSample s = a;
  s.mean = a.mean - t * (b.mean - a.mean);
  s.gauss = a.gauss - t * (b.gauss - a.gauss);
  return withPrincipal(s);
}

std::vector<CurvatureSample> meshCurvature(const Surface &surface, const Mesh &mesh, const CurvatureOptions &options) {
  if (mesh.domainPoints.size() != mesh.positions.size())
    throw InputError("", "mesh", "has no domain points (tessellate with recordDomainPoints set)");
  std::optional<tbb::global_control> limit;
  if (options.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, options.threads);
  std::vector<CurvatureSample> out(mesh.positions.size());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Each vertex is independent and written once: the result does not depend on threads.
  parallel::parallelFor(tbb::blocked_range<std::size_t>(0, out.size(), 256), [&](const auto &range) {
    for (std::size_t v = range.begin(); v != range.end(); ++v) {
      const MeshDomainPoint &d = mesh.domainPoints[v];
      out[v] = d.face < 0 ? CurvatureSample{nan, nan, nan, nan, {}} : surfaceCurvature(surface, d.face, d.uv, options);
    }
  });
  return out;
}

} // namespace v1
} // namespace curvenet
