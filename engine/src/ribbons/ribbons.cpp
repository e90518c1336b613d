#include "ribbons/ribbons.hpp"

#include <algorithm>
#include <cmath>

#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

namespace {
// Fence samples per segment. The double-reflection frame is fourth-order
// accurate in the step; 64 steps keep it far below any visible twist, and the
// cubic interpolant through them is smooth for the ribbon derivatives.
constexpr int kFenceSteps = 64;

Vec3 rotateAbout(const Vec3 &v, const Vec3 &axis, double angle) {
  // Rodrigues' formula for a unit axis.
  return v * std::cos(angle) + cross(axis, v) * std::sin(angle) + axis * (dot(axis, v) * (1 - std::cos(angle)));
}

Vec3 projectOut(const Vec3 &v, const Vec3 &unitDirection) { return v - unitDirection * dot(v, unitDirection); }
} // namespace

NormalFence::NormalFence(const BSplineCurve &segment, const Vec3 &startNormal, const Vec3 &endNormal)
    : curve_(segment) {
  std::vector<double> params(kFenceSteps + 1);
  std::vector<Vec3> points(kFenceSteps + 1), tangents(kFenceSteps + 1), normals(kFenceSteps + 1);
  std::vector<double> arc(kFenceSteps + 1, 0.0);
  for (int k = 0; k <= kFenceSteps; ++k) {
    params[k] = double(k) / kFenceSteps;
    const auto d = segment.derivatives(params[k]);
    points[k] = d[0];
    tangents[k] = normalized(d[1]);
    if (k > 0) arc[k] = arc[k - 1] + norm(points[k] - points[k - 1]);
  }
  // Rotation-minimizing frame by double reflection [WJZL08].
  normals[0] = normalized(projectOut(startNormal, tangents[0]));
  for (int k = 0; k < kFenceSteps; ++k) {
    const Vec3 v1 = points[k + 1] - points[k];
    const double c1 = dot(v1, v1);
    Vec3 r = normals[k], t = tangents[k];
    if (c1 > 0) {
      r = r - v1 * (2 / c1 * dot(v1, r));
      t = t - v1 * (2 / c1 * dot(v1, t));
    }
    const Vec3 v2 = tangents[k + 1] - t;
    const double c2 = dot(v2, v2);
    if (c2 > 0) r = r - v2 * (2 / c2 * dot(v2, r));
    normals[k + 1] = normalized(projectOut(r, tangents[k + 1]));
  }
  // The remaining rotation to the end normal, spread along the arc length.
  const Vec3 target = normalized(projectOut(endNormal, tangents.back()));
  const double angle =
      std::atan2(dot(cross(normals.back(), target), tangents.back()), dot(normals.back(), target));
  const double length = arc.back() > 0 ? arc.back() : 1.0;
  for (int k = 0; k <= kFenceSteps; ++k) normals[k] = rotateAbout(normals[k], tangents[k], angle * arc[k] / length);
  normals.back() = target;
  smoothNormal_ = BSplineCurve::interpolate(3, params, normals);
}

Vec3 NormalFence::normal(double u) const {
  Vec3 n, dn;
  normalAndDerivative(u, n, dn);
  return n;
}

void NormalFence::normalAndDerivative(double u, Vec3 &n, Vec3 &dn) const {
  // N = m / |m| with m = Ñ − (Ñ·t) t: the interpolant with its tangential
  // part removed, so N ⊥ P' holds exactly; derivatives by the chain rule.
  const auto c = curve_.derivatives(u);
  const auto f = smoothNormal_.derivatives(u);
  const double speed = norm(c[1]);
  const Vec3 t = c[1] / speed;
  const Vec3 dt = projectOut(c[2], t) / speed;
  const double ft = dot(f[0], t);
  const Vec3 m = f[0] - t * ft;
  const Vec3 dm = f[1] - t * (dot(f[1], t) + dot(f[0], dt)) - dt * ft;
  const double length = norm(m);
  n = m / length;
  dn = projectOut(dm, n) / length;
}

LinearRibbon::LinearRibbon(BSplineCurve curve, std::vector<Piece> pieces)
    : curve_(std::move(curve)), pieces_(std::move(pieces)) {
  CURVENET_CHECK(!pieces_.empty());
}

void LinearRibbon::fence(double s, Vec3 &n, Vec3 &dn) const {
  auto piece = std::find_if(pieces_.begin(), pieces_.end(), [s](const Piece &p) { return s <= p.sTo; });
  if (piece == pieces_.end()) piece = pieces_.end() - 1;
  const double scale = 1.0 / (piece->sTo - piece->sFrom);
  const double local = std::clamp((s - piece->sFrom) * scale, 0.0, 1.0);
  piece->fence->normalAndDerivative(piece->reversed ? 1 - local : local, n, dn);
  dn = dn * (piece->reversed ? -scale : scale);
}

Vec3 LinearRibbon::fenceDirection(double s) const {
  Vec3 n, dn;
  fence(s, n, dn);
  return cross(n, curve_.derivatives(s)[1]);
}

void LinearRibbon::setEndConditions(const Vec3 &startTarget, const Vec3 &endTarget) {
  // T = αD + βP' with D ⊥ P': the components of the target along D and P'
  // (a target slightly out of the tangent plane is projected onto it).
  auto solve = [&](double s, const Vec3 &target, double &alpha, double &beta) {
    const Vec3 d = fenceDirection(s), dp = curve_.derivatives(s)[1];
    alpha = dot(target, d) / dot(d, d);
    beta = dot(target, dp) / dot(dp, dp);
  };
  solve(0.0, startTarget, alpha0_, beta0_);
  solve(1.0, endTarget, alpha1_, beta1_);
}

RibbonJet LinearRibbon::at(double s) const {
  const auto c = curve_.derivatives(s);
  Vec3 n, dn;
  fence(s, n, dn);
  const Vec3 D = cross(n, c[1]);
  const Vec3 dD = cross(dn, c[1]) + cross(n, c[2]);
  const double alpha = alpha0_ + (alpha1_ - alpha0_) * s, beta = beta0_ + (beta1_ - beta0_) * s;
  const double dAlpha = alpha1_ - alpha0_, dBeta = beta1_ - beta0_;
  return {c[0], c[1], D * alpha + c[1] * beta, D * dAlpha + dD * alpha + c[1] * dBeta + c[2] * beta};
}

} // namespace v1
} // namespace curvenet
