#include "ribbons/ribbons.hpp"

#include <algorithm>
#include <cmath>
#include <array>

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

// Second-order Taylor jets of univariate functions (value, d/du, d²/du²),
// enough to differentiate the fence normal N = m/|m| twice by the chain rule.
// Forced inline: they run per ribbon sample of every G² evaluation, and as
// out-of-line calls returning structs they cost more than their arithmetic.
struct ScalarJet {
  double v, d, dd;
};
struct VectorJet {
  Vec3 v, d, dd;
};
[[gnu::always_inline]] inline ScalarJet dot(const VectorJet &a, const VectorJet &b) {
  return {curvenet::dot(a.v, b.v), curvenet::dot(a.d, b.v) + curvenet::dot(a.v, b.d),
          curvenet::dot(a.dd, b.v) + 2 * curvenet::dot(a.d, b.d) + curvenet::dot(a.v, b.dd)};
}
[[gnu::always_inline]] inline VectorJet operator*(const VectorJet &a, const ScalarJet &s) {
  return {a.v * s.v, a.d * s.v + a.v * s.d, a.dd * s.v + a.d * (2 * s.d) + a.v * s.dd};
}
[[gnu::always_inline]] inline VectorJet operator-(const VectorJet &a, const VectorJet &b) { return {a.v - b.v, a.d - b.d, a.dd - b.dd}; }
/// x^(−1/2) for x > 0.
[[gnu::always_inline]] inline ScalarJet inverseSqrt(const ScalarJet &x) {
  const double g = 1 / std::sqrt(x.v), g3 = g * g * g, g5 = g3 * g * g;
  return {g, -0.5 * g3 * x.d, 0.75 * g5 * x.d * x.d - 0.5 * g3 * x.dd};
}
[[gnu::always_inline]] inline VectorJet normalizedJet(const VectorJet &a) { return a * inverseSqrt(dot(a, a)); }

/// ½ x² (1 − x)^k with its first two derivatives at x ∈ [0, 1]: second
/// derivative 1 at x = 0, value and slope 0 there, flat to order k − 1 at x = 1.
/// The powers by multiplication: std::pow with an integer exponent is a
/// libm call, three per basis (a quarter of the ribbon tables' build under
/// the sanitizers; a few per cent in Release).
ScalarJet endCurvatureBasis(double x, int k) {
  const double y = 1 - x;
  double p = 1; // y^(k − 2), k ≥ 2
  for (int i = 2; i < k; ++i) p *= y;
  const double r = p * y * y, dr = -k * (p * y), ddr = k * (k - 1) * p;
  return {0.5 * x * x * r, x * r + 0.5 * x * x * dr, r + 2 * x * dr + 0.5 * x * x * ddr};
}
/// The basis of the end at s = 0 (end 0) or s = 1 (end 1) as a function of s.
ScalarJet endCurvatureBasisAt(double s, int end, int k) {
  if (end == 0) return endCurvatureBasis(s, k);
  const ScalarJet b = endCurvatureBasis(1 - s, k);
  return {b.v, -b.d, b.dd};
}
// Exponents of the basis. With (1 − x)³ for α, β too the ribbons' interior
// moves more: `pentagon` deviates 0.096 % instead of 0.089 %, and
// `sphere-dodecahedron` 0.330 % instead of 0.271 %; other exponents (4, 7
// for α, β; 4, 5 for Γ) change the built-ins' deviations by at most 6 %.
constexpr int kSlopeFlatness = 5;
constexpr int kTangentialFlatness = 3;

Vec3 tangentialPart(const Vec3 &v, const Vec3 &unitNormal) { return v - unitNormal * dot(v, unitNormal); }
} // namespace

NormalFence::NormalFence(const BSplineCurve &segment, const Vec3 &startNormal, const Vec3 &endNormal) {
  build(segment, startNormal, endNormal, false, 0, 0);
}

NormalFence NormalFence::curvatureCompatible(const BSplineCurve &segment, const Vec3 &startNormal,
                                             const Vec3 &endNormal, double startRate, double endRate) {
  NormalFence fence;
  fence.build(segment, startNormal, endNormal, true, startRate, endRate);
  return fence;
}

NormalFence NormalFence::fromNormalField(const BSplineCurve &segment,
                                         const std::function<Vec3(const Vec3 &)> &normalAt, const Vec3 &startNormal,
                                         const Vec3 &endNormal) {
  return fromNormalsAlong(
      segment, [&](double u) { return normalAt(segment.derivatives(u)[0]); }, startNormal, endNormal);
}

NormalFence NormalFence::fromNormalsAlong(const BSplineCurve &segment, const std::function<Vec3(double)> &normalAt,
                                          const Vec3 &startNormal, const Vec3 &endNormal) {
  NormalFence fence;
  fence.curve_ = segment;
  std::vector<double> params(kFenceSteps + 1);
  std::vector<Vec3> normals(kFenceSteps + 1), tangents(kFenceSteps + 1);
  for (int k = 0; k <= kFenceSteps; ++k) {
    params[k] = double(k) / kFenceSteps;
    const auto d = segment.derivatives(params[k]);
    tangents[k] = normalized(d[1]);
    Vec3 n = normalized(projectOut(normalAt(params[k]), tangents[k]));
    // The field's orientation is the caller's; keep the samples continuous.
    if (k > 0 && dot(n, normals[k - 1]) < 0) n = -n;
    normals[k] = n;
  }
  // Signed angles about the tangent from the field to the vertex normals.
  auto angleTo = [](const Vec3 &from, const Vec3 &to, const Vec3 &axis) {
    const Vec3 target = normalized(projectOut(to, axis));
    return std::atan2(dot(cross(from, target), axis), dot(from, target));
  };
  const double start = angleTo(normals.front(), startNormal, tangents.front());
  const double end = angleTo(normals.back(), endNormal, tangents.back());
  for (int k = 0; k <= kFenceSteps; ++k)
    normals[k] = rotateAbout(normals[k], tangents[k], start + (end - start) * params[k]);
  fence.smoothNormal_ = BSplineCurve::interpolate(3, params, normals);
  return fence;
}

void NormalFence::build(const BSplineCurve &segment, const Vec3 &startNormal, const Vec3 &endNormal, bool rates,
                        double startRate, double endRate) {
  curve_ = segment;
  std::vector<double> params(kFenceSteps + 1);
  std::vector<Vec3> points(kFenceSteps + 1), tangents(kFenceSteps + 1), normals(kFenceSteps + 1);
  std::vector<double> arc(kFenceSteps + 1, 0.0);
  for (int k = 0; k <= kFenceSteps; ++k) {
    params[k] = double(k) / kFenceSteps;
    const auto d = segment.derivatives(params[k]);
    points[k] = d[0];
    tangents[k] = normalized(d[1]);
    // Arc length exactly (the cubic angle profile below is in arc length).
    if (k > 0) arc[k] = arc[k - 1] + segment.arcLength(params[k - 1], params[k]);
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
  // The remaining rotation to the end normal, spread along the arc length:
  // linearly (G¹), or by the cubic Hermite that also meets the end rates (G²).
  const Vec3 target = normalized(projectOut(endNormal, tangents.back()));
  const double angle =
      std::atan2(dot(cross(normals.back(), target), tangents.back()), dot(normals.back(), target));
  const double length = arc.back() > 0 ? arc.back() : 1.0;
  for (int k = 0; k <= kFenceSteps; ++k) {
    const double x = arc[k] / length;
    double theta = angle * x;
    if (rates) {
      const double h01 = x * x * (3 - 2 * x), h10 = x * (1 - x) * (1 - x), h11 = x * x * (x - 1);
      theta = angle * h01 + length * (startRate * h10 + endRate * h11);
    }
    normals[k] = rotateAbout(normals[k], tangents[k], theta);
  }
  normals.back() = target;
  smoothNormal_ = BSplineCurve::interpolate(3, params, normals);
}

Vec3 NormalFence::normal(double u) const {
  Vec3 n, dn;
  normalAndDerivative(u, n, dn);
  return n;
}

void NormalFence::normalAndDerivative(double u, Vec3 &n, Vec3 &dn) const {
  normalAndDerivative(u, curve_.derivatives(u), n, dn);
}

void NormalFence::normalAndDerivative(double u, const std::array<Vec3, 4> &c, Vec3 &n, Vec3 &dn) const {
  // N = m / |m| with m = Ñ − (Ñ·t) t: the interpolant with its tangential
  // part removed, so N ⊥ P' holds exactly; derivatives by the chain rule.
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

void NormalFence::normalJet(double u, Vec3 &n, Vec3 &dn, Vec3 &ddn) const {
  normalJet(u, curve_.derivatives(u), n, dn, ddn);
}

void NormalFence::normalJet(double u, const std::array<Vec3, 4> &c, Vec3 &n, Vec3 &dn, Vec3 &ddn) const {
  const auto f = smoothNormal_.derivatives(u);
  const VectorJet t = normalizedJet({c[1], c[2], c[3]});
  const VectorJet fj{f[0], f[1], f[2]};
  const VectorJet result = normalizedJet(fj - t * dot(fj, t));
  n = result.v, dn = result.d, ddn = result.dd;
}

TransversalCurvature::TransversalCurvature(const std::vector<double> &samples) {
  CURVENET_CHECK(samples.size() >= 4, "need at least 4 curvature samples, got " + std::to_string(samples.size()));
  std::vector<double> params(samples.size());
  std::vector<Vec3> values(samples.size());
  for (size_t j = 0; j < samples.size(); ++j) {
    params[j] = double(j) / double(samples.size() - 1);
    values[j] = {samples[j], 0, 0};
  }
  spline_ = BSplineCurve::interpolate(3, params, values);
}

void TransversalCurvature::valueAndDerivative(double u, double &k, double &dk) const {
  const auto d = spline_.derivatives(u);
  k = d[0].x;
  dk = d[1].x;
}

LinearRibbon::LinearRibbon(BSplineCurve curve, std::vector<Piece> pieces)
    : curve_(std::move(curve)), pieces_(std::move(pieces)) {
  CURVENET_CHECK(!pieces_.empty());
}

int LinearRibbon::pieceAt(double s, double &local, double &dLocal) const {
  auto piece = std::find_if(pieces_.begin(), pieces_.end(), [s](const Piece &p) { return s <= p.sTo; });
  if (piece == pieces_.end()) piece = pieces_.end() - 1;
  const double scale = 1.0 / (piece->sTo - piece->sFrom);
  const double x = std::clamp((s - piece->sFrom) * scale, 0.0, 1.0);
  local = piece->reversed ? 1 - x : x;
  dLocal = piece->reversed ? -scale : scale;
  return static_cast<int>(piece - pieces_.begin());
}

void LinearRibbon::fence(double s, Vec3 &n, Vec3 &dn) const {
  double local, dLocal;
  const Piece &piece = pieces_[pieceAt(s, local, dLocal)];
  piece.fence->normalAndDerivative(local, n, dn);
  dn = dn * dLocal;
}

Vec3 LinearRibbon::fenceDirection(double s) const {
  Vec3 n, dn;
  fence(s, n, dn);
  return cross(n, curve_.derivatives(s)[1]);
}

void LinearRibbon::setEndConditions(const Vec3 &startTarget, const Vec3 &endTarget, ScalarBlend blend) {
  blend_ = blend;
  hasEndCurvatures_ = false; // set for the previous end conditions, if any
  // T = αD + βP' with D ⊥ P': the components of the target along D and P'
  // (a target slightly out of the tangent plane is projected onto it).
  auto solve = [&](double s, const Vec3 &target, double &alpha, double &beta) {
    const Vec3 d = fenceDirection(s), dp = curve_.derivatives(s)[1];
    alpha = dot(target, d) / dot(d, d);
    beta = dot(target, dp) / dot(dp, dp);
  };
  solve(0.0, startTarget, alpha0_, beta0_);
  solve(1.0, endTarget, alpha1_, beta1_);
  if (blend == ScalarBlend::Linear) {
    // Coefficients of the unit frame (D/|D|, P'/|P'|); |D| = |P'|.
    const double speed0 = norm(curve_.derivatives(0.0)[1]), speed1 = norm(curve_.derivatives(1.0)[1]);
    alpha0_ *= speed0, beta0_ *= speed0, alpha1_ *= speed1, beta1_ *= speed1;
  }
}

std::array<double, 3> LinearRibbon::profile(double s) const {
  if (blend_ == ScalarBlend::Quintic)
    return {s * s * s * (10 - 15 * s + 6 * s * s), 30 * s * s * (1 - s) * (1 - s), 60 * s * (1 - s) * (1 - 2 * s)};
  return {s, 1, 0};
}

LinearRibbon::Coefficients LinearRibbon::coefficients(double s, const std::array<Vec3, 4> &c) const {
  const auto h = profile(s);
  // Linear blend: the coefficients are those of the unit frame, so α, β of
  // D and P' carry the factor g = 1 / |P'| (see setEndConditions).
  double g = 1, dg = 0, ddg = 0;
  if (blend_ == ScalarBlend::Linear) {
    const double speed = norm(c[1]);
    const double dSpeed = dot(c[1], c[2]) / speed;
    const double ddSpeed = (dot(c[2], c[2]) + dot(c[1], c[3]) - dSpeed * dSpeed) / speed;
    g = 1 / speed;
    dg = -dSpeed * g * g;
    ddg = (2 * dSpeed * dSpeed * g - ddSpeed) * g * g;
  }
  auto scaled = [&](double from, double to, double &v, double &dv, double &ddv) {
    const double b = from + (to - from) * h[0], db = (to - from) * h[1], ddb = (to - from) * h[2];
    v = g * b;
    dv = dg * b + g * db;
    ddv = ddg * b + 2 * dg * db + g * ddb;
  };
  Coefficients k;
  scaled(alpha0_, alpha1_, k.alpha, k.dAlpha, k.ddAlpha);
  scaled(beta0_, beta1_, k.beta, k.dBeta, k.ddBeta);
  if (hasEndCurvatures_)
    for (int end = 0; end < 2; ++end) {
      const ScalarJet b = endCurvatureBasisAt(s, end, kSlopeFlatness);
      const EndCurvature &e = endCurvatures_[end];
      k.alpha += e.alpha * b.v, k.dAlpha += e.alpha * b.d, k.ddAlpha += e.alpha * b.dd;
      k.beta += e.beta * b.v, k.dBeta += e.beta * b.d, k.ddBeta += e.beta * b.dd;
    }
  return k;
}

void LinearRibbon::setEndCurvatures(const EndCurvature &start, const EndCurvature &end) {
  CURVENET_CHECK(blend_ == ScalarBlend::Quintic, "end curvatures of α, β need the quintic blend");
  endCurvatures_ = {start, end};
  hasEndCurvatures_ = true;
}

namespace {
/// The segment's derivatives with respect to its own parameter u from the
/// ribbon curve's with respect to s, where u is affine in s with du/ds =
/// dLocal: the side curve and the segment are the same piece of one source
/// curve (exact knot insertion), so only the chain rule separates them.
std::array<Vec3, 4> segmentJet(const std::array<Vec3, 4> &c, double dLocal) {
  const double r = 1 / dLocal;
  return {c[0], c[1] * r, c[2] * (r * r), c[3] * (r * r * r)};
}
} // namespace

RibbonJet LinearRibbon::at(double s) const { return jet(s, curve_.derivatives(s)); }

void LinearRibbon::at(std::span<const double> s, std::span<RibbonJet> out) const {
  CURVENET_CHECK(out.size() >= s.size(), "ribbon batch: output shorter than the parameters");
  thread_local std::vector<std::array<Vec3, 4>> curve;
  curve.resize(s.size());
  curve_.derivatives(s, curve);
  for (std::size_t k = 0; k < s.size(); ++k) out[k] = jet(s[k], curve[k]);
}

RibbonJet LinearRibbon::jet(double s, const std::array<Vec3, 4> &c) const {
  double local, dLocal;
  const Piece &piece = pieces_[pieceAt(s, local, dLocal)];
  Vec3 n, dn;
  piece.fence->normalAndDerivative(local, segmentJet(c, dLocal), n, dn);
  dn = dn * dLocal;
  const Vec3 D = cross(n, c[1]);
  const Vec3 dD = cross(dn, c[1]) + cross(n, c[2]);
  const Coefficients k = coefficients(s, c);
  return {c[0], c[1], D * k.alpha + c[1] * k.beta, D * k.dAlpha + dD * k.alpha + c[1] * k.dBeta + c[2] * k.beta};
}

LinearRibbon::SecondJet LinearRibbon::secondJet(double s) const { return secondJet(s, curve_.derivatives(s)); }

LinearRibbon::SecondJet LinearRibbon::secondJet(double s, const std::array<Vec3, 4> &c) const {
  SecondJet j;
  j.P = c[0], j.dP = c[1], j.ddP = c[2], j.dddP = c[3];
  double local, dLocal;
  const Piece &piece = pieces_[pieceAt(s, local, dLocal)];
  piece.fence->normalJet(local, segmentJet(c, dLocal), j.N, j.dN, j.ddN);
  j.dN = j.dN * dLocal;
  j.ddN = j.ddN * (dLocal * dLocal);
  j.D = cross(j.N, j.dP);
  j.dD = cross(j.dN, j.dP) + cross(j.N, j.ddP);
  const Vec3 ddD = cross(j.ddN, j.dP) + 2.0 * cross(j.dN, j.ddP) + cross(j.N, j.dddP);
  const Coefficients k = coefficients(s, c);
  j.alpha = k.alpha, j.beta = k.beta, j.dAlpha = k.dAlpha, j.dBeta = k.dBeta;
  const double ddAlpha = k.ddAlpha, ddBeta = k.ddBeta;
  j.T = j.D * j.alpha + j.dP * j.beta;
  j.dT = j.D * j.dAlpha + j.dD * j.alpha + j.dP * j.dBeta + j.ddP * j.beta;
  j.ddT = j.D * ddAlpha + j.dD * (2 * j.dAlpha) + ddD * j.alpha + j.dP * ddBeta + j.ddP * (2 * j.dBeta) +
          j.dddP * j.beta;
  return j;
}

ParabolicRibbon::ParabolicRibbon(LinearRibbon linear, std::vector<const TransversalCurvature *> curvatures)
    : linear_(std::move(linear)), curvatures_(std::move(curvatures)) {
  CURVENET_CHECK(curvatures_.size() == linear_.pieces().size());
  start_ = secondOrder(0.0);
  end_ = secondOrder(1.0);
}

ParabolicJet ParabolicRibbon::at(double s) const { return jet(s, linear_.curve().derivatives(s)); }

void ParabolicRibbon::at(std::span<const double> s, std::span<ParabolicJet> out) const {
  CURVENET_CHECK(out.size() >= s.size(), "ribbon batch: output shorter than the parameters");
  thread_local std::vector<std::array<Vec3, 4>> curve;
  curve.resize(s.size());
  linear_.curve().derivatives(s, curve);
  for (std::size_t k = 0; k < s.size(); ++k) out[k] = jet(s[k], curve[k]);
}

ParabolicJet ParabolicRibbon::jet(double s, const std::array<Vec3, 4> &c) const {
  const LinearRibbon::SecondJet j = linear_.secondJet(s, c);
  double local, dLocal;
  const int piece = linear_.pieceAt(s, local, dLocal);
  double kappa, dKappa;
  curvatures_[piece]->valueAndDerivative(local, kappa, dKappa);
  dKappa *= dLocal;
  // g = II(T, T) = α² |D|² κ_D − 2αβ N'·D + β² N·P'' and its s-derivative.
  const double a = j.alpha, da = j.dAlpha, b = j.beta, db = j.dBeta;
  const double dd = dot(j.D, j.D), ddd = 2 * dot(j.D, j.dD);
  const double e = dot(j.dN, j.D), de = dot(j.ddN, j.D) + dot(j.dN, j.dD);
  const double f = dot(j.N, j.ddP), df = dot(j.dN, j.ddP) + dot(j.N, j.dddP);
  const double g = a * a * dd * kappa - 2 * a * b * e + b * b * f;
  const double dg = 2 * a * da * dd * kappa + a * a * ddd * kappa + a * a * dd * dKappa - 2 * (da * b + a * db) * e -
                    2 * a * b * de + 2 * b * db * f + b * b * df;
  Vec3 C = j.N * g, dC = j.N * dg + j.dN * g;
  if (hasTangential_) {
    // + Γ − (Γ·N) N, tangential: C·N = g still.
    Vec3 gamma, dGamma;
    for (int end = 0; end < 2; ++end) {
      const ScalarJet basis = endCurvatureBasisAt(s, end, kTangentialFlatness);
      gamma += tangentialCurvatures_[end] * basis.v, dGamma += tangentialCurvatures_[end] * basis.d;
    }
    const double normal = dot(gamma, j.N), dNormal = dot(dGamma, j.N) + dot(gamma, j.dN);
    C += gamma - j.N * normal;
    dC += dGamma - j.N * dNormal - j.dN * normal;
  }
  return {j.P, j.dP, j.T, j.dT, C, dC};
}

void ParabolicRibbon::setEndTangentialCurvatures(const Vec3 &start, const Vec3 &end) {
  tangentialCurvatures_ = {start, end};
  hasTangential_ = true;
  start_ = secondOrder(0.0);
  end_ = secondOrder(1.0);
}

std::vector<ParabolicRibbon> matchCornerTerms(std::vector<LinearRibbon> &linear,
                                              const std::function<ParabolicRibbon(const LinearRibbon &)> &build) {
  const int n = static_cast<int>(linear.size());
  std::vector<ParabolicRibbon> parabolic;
  for (const LinearRibbon &ribbon : linear) parabolic.push_back(build(ribbon));
  // A tangential ΔT'' = Δα'' D + Δβ'' P' (D ⊥ P', both in the tangent plane).
  auto curvatureFor = [](const Vec3 &delta, const SideEndData &end, const Vec3 &normal) {
    const Vec3 D = cross(normal, end.dP);
    return LinearRibbon::EndCurvature{dot(delta, D) / dot(D, D), dot(delta, end.dP) / dot(end.dP, end.dP)};
  };
  std::vector<Vec3> startNormals(n), endNormals(n);
  for (int i = 0; i < n; ++i) startNormals[i] = linear[i].secondJet(0.0).N, endNormals[i] = linear[i].secondJet(1.0).N;
  std::vector<std::array<LinearRibbon::EndCurvature, 2>> curvatures(n);
  for (int i = 0; i < n; ++i) {
    const int prev = (i + n - 1) % n;
    const SideEndData &before = parabolic[prev].end(), &after = parabolic[i].start();
    const Vec3 &normal = startNormals[i], &normalBefore = endNormals[prev];
    // W₂₁ = ∂_s²∂_t: T_i''(0) against −C_{i−1}'(1).
    const Vec3 t21 = tangentialPart(after.ddT, normal), c21 = tangentialPart(-before.dC, normalBefore);
    curvatures[i][0] = curvatureFor(c21 - t21, after, normal);
    // W₁₂ = ∂_s∂_t²: T_{i−1}''(1) against C_i'(0).
    const Vec3 t12 = tangentialPart(before.ddT, normalBefore), c12 = tangentialPart(after.dC, normal);
    curvatures[prev][1] = curvatureFor(c12 - t12, before, normalBefore);
  }
  for (int i = 0; i < n; ++i) {
    linear[i].setEndCurvatures(curvatures[i][0], curvatures[i][1]);
    parabolic[i] = build(linear[i]);
  }
  // W₂₂ = ∂_s²∂_t²: C_{i−1}''(1) against C_i''(0); Γ'' enters C'' as itself
  // in the tangent plane.
  std::vector<std::array<Vec3, 2>> tangential(n);
  for (int i = 0; i < n; ++i) {
    const int prev = (i + n - 1) % n;
    const Vec3 mine = tangentialPart(parabolic[i].start().ddC, startNormals[i]);
    const Vec3 theirs = tangentialPart(parabolic[prev].end().ddC, endNormals[prev]);
    tangential[i][0] = (theirs - mine) * 0.5;
    tangential[prev][1] = (mine - theirs) * 0.5;
  }
  for (int i = 0; i < n; ++i) parabolic[i].setEndTangentialCurvatures(tangential[i][0], tangential[i][1]);
  return parabolic;
}

double ParabolicRibbon::crossCurvature(double s) const {
  // The curve d ↦ R(s, d) has R_d = T and R_dd = C: normal curvature C·N / |T|².
  const ParabolicJet j = at(s);
  return dot(j.C, linear_.secondJet(s).N) / dot(j.T, j.T);
}

SideEndData ParabolicRibbon::secondOrder(double s) const {
  const LinearRibbon::SecondJet j = linear_.secondJet(s);
  const ParabolicJet p = at(s);
  // C'' by fourth-order differences of the exact C': central inside, one-sided
  // near the ends (the third derivative of C would need that of the fence).
  constexpr double h = 1e-3;
  Vec3 ddC;
  if (s >= 4 * h && s <= 1 - 4 * h) {
    ddC = (at(s - 2 * h).dC - at(s - h).dC * 8.0 + at(s + h).dC * 8.0 - at(s + 2 * h).dC) / (12 * h);
  } else {
    const double sign = s < 0.5 ? 1.0 : -1.0;
    constexpr double weights[5] = {-25, 48, -36, 16, -3};
    for (int k = 0; k < 5; ++k) ddC += at(s + sign * k * h).dC * weights[k];
    ddC = ddC * (sign / (12 * h));
  }
  return {j.P, j.dP, j.ddP, j.T, j.dT, j.ddT, p.C, p.dC, ddC};
}

namespace {
/// Interior knots of c, mapped to [0, 1] over its domain.
void interiorKnots(const BSplineCurve &c, std::vector<double> &out) {
  const double a = c.domainStart(), b = c.domainEnd();
  for (double k : c.knots())
    if (k > a && k < b) out.push_back((k - a) / (b - a));
}
} // namespace

std::vector<double> NormalFence::breakpoints() const {
  std::vector<double> out;
  interiorKnots(curve_, out);
  interiorKnots(smoothNormal_, out);
  return out;
}

std::vector<double> NormalFence::interpolantBreakpoints() const {
  std::vector<double> out;
  interiorKnots(smoothNormal_, out);
  return out;
}

std::vector<double> TransversalCurvature::breakpoints() const {
  std::vector<double> out;
  interiorKnots(spline_, out);
  return out;
}

std::vector<double> LinearRibbon::breakpoints() const {
  std::vector<double> out;
  interiorKnots(curve_, out);
  for (const Piece &piece : pieces_) {
    if (piece.sTo < 1) out.push_back(piece.sTo);
    for (double u : piece.fence->interpolantBreakpoints())
      out.push_back(piece.sFrom + (piece.sTo - piece.sFrom) * (piece.reversed ? 1 - u : u));
  }
  return out;
}

double ParabolicRibbon::cornerTaylorReach(bool atStart, double tolerance) const {
  constexpr int kSteps = 20;
  const SideEndData &end = atStart ? start_ : end_;
  const double bound = tolerance * norm(end.T);
  for (int k = 1; k <= kSteps; ++k) {
    const double step = double(k) / kSteps, x = atStart ? step : -step;
    const Vec3 expanded = end.C + end.dC * x + end.ddC * (0.5 * x * x);
    if (0.5 * norm(expanded - at(atStart ? step : 1 - step).C) > bound) return double(k - 1) / kSteps;
  }
  return 1.0;
}

std::vector<double> ParabolicRibbon::breakpoints() const {
  std::vector<double> out = linear_.breakpoints();
  const auto &pieces = linear_.pieces();
  for (std::size_t j = 0; j < pieces.size(); ++j)
    for (double u : curvatures_[j]->breakpoints())
      out.push_back(pieces[j].sFrom + (pieces[j].sTo - pieces[j].sFrom) * (pieces[j].reversed ? 1 - u : u));
  return out;
}

} // namespace v1
} // namespace curvenet
