// Surface evaluation: positions and jets of a built surface at domain
// points, pointwise and in batches (the batches through each patch's plan
// kernels), and second derivatives by differences of the exact first ones.
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "bezier/bezier_surface.hpp"
#include "curvenet/error.hpp"
#include "curvenet/surface.hpp"
#include "patches/patch.hpp"
#include "patches/surface_impl.hpp"
#include "plans/face_errors.hpp"

namespace curvenet {
inline namespace v1 {

double SurfacePoint2::normalCurvature(const Vec3 &direction) const {
  // Least-squares domain direction (a, b) with a du + b dv ≈ direction.
  const double g11 = dot(du, du), g12 = dot(du, dv), g22 = dot(dv, dv);
  const double r1 = dot(du, direction), r2 = dot(dv, direction);
  const double det = g11 * g22 - g12 * g12;
  const double a = (g22 * r1 - g12 * r2) / det, b = (g11 * r2 - g12 * r1) / det;
  const Vec3 x = du * a + dv * b;
  const double second = dot(normal, duu * (a * a) + duv * (2 * a * b) + dvv * (b * b));
  return second / dot(x, x);
}

void Surface::evaluatePositions(int face, std::span<const Vec2> uv, std::span<Vec3> out) const {
  CURVENET_CHECK(out.size() >= uv.size(), "evaluatePositions: output shorter than the input");
  if (impl_->bezier) {
    for (std::size_t k = 0; k < uv.size(); ++k) out[k] = evaluate(face, uv[k]).point;
    return;
  }
  const Patch &patch = *impl_->patches.at(face);
  constexpr std::size_t kChunk = 1024;
  thread_local std::vector<double> scratch;
  scratch.resize(2 * kChunk);
  double *u = scratch.data(), *v = u + kChunk;
  for (std::size_t first = 0; first < uv.size(); first += kChunk) {
    const std::size_t m = std::min(kChunk, uv.size() - first);
    for (std::size_t k = 0; k < m; ++k) u[k] = uv[first + k].x, v[k] = uv[first + k].y;
    // The kernel writes the points, the model's origin added. The face's
    // ribbon tables are built on its first batch: their errors name the face.
    const PositionSink sink = PositionSink::interleaved(out.data() + first, impl_->origin);
    namingFace(face, [&] { patch.evaluatePositions(m, u, v, sink); });
  }
}

void Surface::evaluate(int face, std::span<const Vec2> uv, std::span<SurfacePoint> out) const {
  CURVENET_CHECK(out.size() >= uv.size(), "evaluate: output shorter than the input");
  constexpr std::size_t kSmallestBatch = 32, kChunk = 1024;
  if (impl_->bezier || uv.size() < kSmallestBatch) {
    for (std::size_t k = 0; k < uv.size(); ++k) out[k] = evaluate(face, uv[k]);
    return;
  }
  const Patch &patch = *impl_->patches.at(face);
  thread_local std::vector<double> coordinates;
  thread_local std::vector<DualVec3> jets;
  coordinates.resize(2 * kChunk), jets.resize(kChunk);
  double *u = coordinates.data(), *v = u + kChunk;
  for (std::size_t first = 0; first < uv.size(); first += kChunk) {
    const std::size_t m = std::min(kChunk, uv.size() - first);
    for (std::size_t k = 0; k < m; ++k) u[k] = uv[first + k].x, v[k] = uv[first + k].y;
    // Whole vectors (Patch::evaluateJets): the last point repeated.
    const std::size_t padded = (m + 7) / 8 * 8;
    std::fill(u + m, u + padded, u[m - 1]), std::fill(v + m, v + padded, v[m - 1]);
    namingFace(face, [&] { patch.evaluateJets(padded, u, v, jets.data()); }); // tables built here name the face
    for (std::size_t k = 0; k < m; ++k) {
      const DualVec3 &r = jets[k];
      const Vec3 normal = cross(r.du, r.dv);
      // Parallel derivatives (straight-angle corners) or a point the
      // batched formula cannot take: the pointwise evaluation decides.
      const double size = squaredNorm(normal);
      if (!(size > 1e-24 * squaredNorm(r.du) * squaredNorm(r.dv)) || !isFinite(r.v) || !std::isfinite(size)) {
        out[first + k] = evaluate(face, uv[first + k]);
        continue;
      }
      out[first + k] = {r.v + impl_->origin, r.du, r.dv, normalized(normal)};
    }
  }
}

SurfacePoint Surface::evaluate(int face, const Vec2 &uv) const {
  if (impl_->bezier) {
    // Square domain → (u, v) ∈ [0, 1]² (see the header); d(u,v)/d(x,y) = 1/width.
    const Vec2 c0 = squareDomain().corner(0);
    const double width = squareDomain().corner(1).x - c0.x;
    const double u = std::clamp((uv.x - c0.x) / width, 0.0, 1.0), v = std::clamp((uv.y - c0.y) / width, 0.0, 1.0);
    const bezier::QuinticPatch::Point p = bezier::evaluateBezierFace(*impl_->bezier, face, u, v);
    Vec3 normal = cross(p.du, p.dv);
    // Degenerate only at a straight-angle corner of a Coons patch: the limit from inside.
    if (squaredNorm(normal) <= 1e-24 * squaredNorm(p.du) * squaredNorm(p.dv) || squaredNorm(normal) == 0) {
      const auto inside = bezier::evaluateBezierFace(*impl_->bezier, face, 0.5 + (u - 0.5) * (1 - 1e-7),
                                                     0.5 + (v - 0.5) * (1 - 1e-7));
      normal = cross(inside.du, inside.dv);
    }
    return {p.point + impl_->origin, p.du / width, p.dv / width, normalized(normal)};
  }
  const Patch &patch = *impl_->patches.at(face);
  const DualVec3 r = patch.evaluate(uv.x, uv.y);
  Vec3 normal = cross(r.du, r.dv);
  // Parallel derivatives happen only at straight-angle corners; the normal
  // there is the limit from inside the domain.
  if (squaredNorm(normal) <= 1e-24 * squaredNorm(r.du) * squaredNorm(r.dv)) {
    const DualVec3 inside = patch.evaluate(uv.x * (1 - 1e-7), uv.y * (1 - 1e-7));
    normal = cross(inside.du, inside.dv);
  }
  return {r.v + impl_->origin, r.du, r.dv, normalized(normal)};
}

SurfacePoint2 Surface::evaluateSecondOrder(int face, const Vec2 &uv, double step) const {
  if (!(step >= 1e-8 && step <= 1e-2)) throw InputError("", "step", "must lie in [1e-8, 1e-2]");
  if (faceOptions(face).scheme == Scheme::GregoryG2) {
    // Exact: hyper-dual evaluation.
    const Dual2Vec3 r = impl_->patches.at(face)->evaluateSecondOrder(uv.x, uv.y);
    SurfacePoint2 p;
    static_cast<SurfacePoint &>(p) = evaluate(face, uv);
    p.duu = r.duu, p.duv = r.duv, p.dvv = r.dvv;
    return p;
  }
  // Every scheme's domain is the regular n-gon (the Bézier schemes' too).
  const RegularDomain domain(domainSides(face));
  const int n = domain.sides();
  auto inside = [&](const Vec2 &p) {
    for (int i = 0; i < n; ++i)
      if (domain.perpendicularDistance(i, p.x, p.y).v < -1e-12) return false;
    return true;
  };
  // Two orthonormal directions: along and across the nearest side.
  int nearest = 0;
  double best = INFINITY;
  for (int i = 0; i < n; ++i) {
    const double d = domain.perpendicularDistance(i, uv.x, uv.y).v;
    if (d < best) best = d, nearest = i;
  }
  const Vec2 edge = domain.corner(nearest + 1) - domain.corner(nearest);
  const Vec2 along = edge / norm(edge), across{-along.y, along.x};
  // d/dw of the exact first derivatives along direction w, fourth order.
  auto derivativeAlong = [&](const Vec2 &w, Vec3 &dSu, Vec3 &dSv) {
    const double h = step;
    auto at = [&](double x) { return evaluate(face, {uv.x + w.x * x, uv.y + w.y * x}); };
    if (inside(uv + w * (2 * h)) && inside(uv - w * (2 * h))) {
      const SurfacePoint m2 = at(-2 * h), m1 = at(-h), p1 = at(h), p2 = at(2 * h);
      dSu = (m2.du - m1.du * 8.0 + p1.du * 8.0 - p2.du) / (12 * h);
      dSv = (m2.dv - m1.dv * 8.0 + p1.dv * 8.0 - p2.dv) / (12 * h);
      return;
    }
    const double sign = inside(uv + w * (4 * h)) ? 1.0 : -1.0;
    constexpr double weights[5] = {-25, 48, -36, 16, -3};
    dSu = {}, dSv = {};
    for (int k = 0; k < 5; ++k) {
      const SurfacePoint r = at(sign * k * h);
      dSu += r.du * weights[k];
      dSv += r.dv * weights[k];
    }
    dSu = dSu * (sign / (12 * h));
    dSv = dSv * (sign / (12 * h));
  };
  Vec3 aSu, aSv, cSu, cSv;
  derivativeAlong(along, aSu, aSv);
  derivativeAlong(across, cSu, cSv);
  // ∂_w S_u = w_x S_uu + w_y S_uv and ∂_w S_v = w_x S_uv + w_y S_vv for the
  // orthonormal pair (along, across); S_uv from both rows, averaged.
  SurfacePoint2 p;
  static_cast<SurfacePoint &>(p) = evaluate(face, uv);
  p.duu = aSu * along.x + cSu * across.x;
  p.dvv = aSv * along.y + cSv * across.y;
  p.duv = (aSu * along.y + cSu * across.y + aSv * along.x + cSv * across.x) * 0.5;
  return p;
}

} // namespace v1
} // namespace curvenet
