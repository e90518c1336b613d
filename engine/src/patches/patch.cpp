#include "patches/patch.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

namespace {


/// Linear ribbon R(s, d) = P(s) + d T(s) at Dual parameters, from its jet at s.
DualVec3 ribbonAt(const RibbonJet &j, Dual s, Dual d) {
  return DualVec3::along(j.P, j.dP, s) + d * DualVec3::along(j.T, j.dT, s);
}

/// The number types the Composite Ribbon formula runs on: Dual (value and
/// gradient, for tessellation) and double (positions alone, three times
/// cheaper). The formula is written once over these.
template <class T> struct Numbers;
template <> struct Numbers<Dual> {
  using Point = DualVec3;
  static Point along(const Vec3 &c, const Vec3 &dc, Dual x) { return DualVec3::along(c, dc, x); }
  static Point constant(const Vec3 &c) { return DualVec3::constant(c); }
  static double value(Dual x) { return x.v; }
  static bool isZero(Dual x) { return x.isZero(); }
};
template <> struct Numbers<double> {
  using Point = Vec3;
  static Point along(const Vec3 &c, const Vec3 &, double) { return c; }
  static Point constant(const Vec3 &c) { return c; }
  static double value(double x) { return x; }
  static bool isZero(double x) { return x == 0; }
};

/// W = (x a + y b) / (x + y) over either number type; the corner limit
/// (x = y = 0) is finite but irrelevant, because the caller multiplies W by a
/// vanishing factor.
template <class T>
[[gnu::always_inline]] inline typename Numbers<T>::Point rationalTermOf(const Vec3 &a, const Vec3 &b, T x, T y) {
  const T sum = x + y;
  if (Numbers<T>::value(sum) == 0) return Numbers<T>::constant((a + b) * 0.5);
  // b + x / (x + y) · (a − b): one division and one scaled vector.
  return Numbers<T>::constant(b) + (x / sum) * (a - b);
}

/// gregoryCorrection over either number type.
template <class T>
[[gnu::always_inline]] inline typename Numbers<T>::Point gregoryCorrectionOf(const CornerData &c, T s, T t, T gs,
                                                                             T gt) {
  const T s2 = s * s, t2 = t * t;
  typename Numbers<T>::Point q = Numbers<T>::constant(c.a00);
  q += gs * rationalTermOf(c.a10, c.b10, s, t2);
  q += gt * rationalTermOf(c.a01, c.b01, s2, t);
  q += (gs * gt) * rationalTermOf(c.a11, c.b11, s, t);
  return q;
}

/// Parabolic ribbon R(s, d) = P(s) + d T(s) + ½ d² C(s) at Dual parameters.
DualVec3 ribbonAt(const ParabolicJet &j, Dual s, Dual d) {
  return DualVec3::along(j.P, j.dP, s) + d * DualVec3::along(j.T, j.dT, s) +
         (Dual(0.5) * d * d) * DualVec3::along(j.C, j.dC, s);
}

/// How far from its corner each ribbon's expansion there may be trusted:
/// ½ |ΔC| within this fraction of |T| (ParabolicRibbon::cornerTaylorReach).
/// Measured with the corner blend shares (gregory-g2): 0.5 takes
/// saddle-nodes from 4 folded faces to 1, its X-skews by 1° and 5° from 2
/// and 3 to 1 and 2, the public sketches from 115 to 49 (doghead 23 → 12,
/// its diagonal 1.54 → 1.01×; iron 21 → 4), and moves torus-mixed's
/// deviation 0.80 → 0.85 % and no other built-in's. Without the blend
/// shares 0.3 also cost torus-mixed 0.89 % and 0.1 sphere-dodecahedron
/// 0.27 → 0.47 %.
constexpr double kCornerTaylorTolerance = 0.5;
/// A reach is never taken below this, so that d keeps a range at every side.
constexpr double kMinimumReach = 0.05;
/// Sweep parameters this close to 0 or 1 are taken as the side's end (a
/// few ulps of 1; see Patch::evaluateSecondOrder).
constexpr double kSweepEndSnap = 1e-15;

/// A sweep parameter within kSweepEndSnap of 0 or 1 moved onto that end,
/// its derivatives kept.
template <class N> N snappedToSweepEnd(N s) {
  if (std::abs(s.v) <= kSweepEndSnap) s.v = 0;
  else if (std::abs(s.v - 1) <= kSweepEndSnap) s.v = 1;
  return s;
}

/// The cross parameter of a ribbon whose reach is r: d ↦ r tanh(d / r) — odd,
/// so its first two derivatives at d = 0 are 1 and 0 and the ribbon's P, T, C
/// on the side (its G² data) are what they were, while d never exceeds r.
/// r ≥ 1 leaves d as it is (bit for bit).
Dual limitedCross(Dual d, double reach) {
  if (reach >= 1) return d;
  const double th = std::tanh(d.v / reach);
  return d.apply(reach * th, 1 - th * th);
}
Dual2 limitedCross(Dual2 d, double reach) {
  if (reach >= 1) return d;
  const double th = std::tanh(d.v / reach), slope = 1 - th * th;
  return d.apply(reach * th, slope, -2 * th * slope / reach);
}

Dual2Vec3 rationalTerm2(const Vec3 &a, const Vec3 &b, Dual2 x, Dual2 y) {
  const Dual2 sum = x + y;
  if (sum.v == 0) return Dual2Vec3::constant((a + b) * 0.5);
  return (x / sum) * a + (y / sum) * b;
}

Dual2Vec3 ribbonAt2(const SideEndData &j, Dual2 s, Dual2 d) {
  return Dual2Vec3::along(j.P, j.dP, j.ddP, s) + d * Dual2Vec3::along(j.T, j.dT, j.ddT, s) +
         (Dual2(0.5) * d * d) * Dual2Vec3::along(j.C, j.dC, j.ddC, s);
}

/// μ (λ R_{i−1} + (1 − λ) R_i), λ = t³ / (s³ + t³), of a G² corner in
/// (s, t) (kernels::GregorySamples::blendShare): λ − 0 = O(t³) on t = 0
/// and 1 − λ = O(s³) on s = 0, so each ribbon is met to second order on its
/// side, and every value is a convex combination of the two ribbons'.
/// At the corner itself (0/0, or within underflow of it) the ribbons'
/// mean, as the correction patch's limit there.
/// G¹ (`order` 2): λ = t² / (s² + t²), which meets each ribbon to first order.
template <class N, class P> P sideBlendOf(const P &previous, const P &own, N s, N t, double mu, int order = 3) {
  if (mu == 0) return P{};
  const N sm = order == 3 ? s * s * s : s * s, tm = order == 3 ? t * t * t : t * t, sum = sm + tm;
  if (!(sum.v > 1e-250)) return N(0.5 * mu) * (previous + own); // as the kernels: sum² would underflow
  const N lambda = tm / sum;
  return N(mu) * (lambda * previous + (N(1.0) - lambda) * own);
}

/// How far the nine-term correction patch of a corner can carry its two
/// ribbons' disagreement into the interior: Σ |a_pq − b_pq| / (p! q!) · 2^−(p+q),
/// the bound of its rational part Σ s^p t^q / (p! q!) (W_pq − b_pq) at
/// s = t = ½, where the corner's reach ends.
double cornerDisagreement(const CornerData2 &c) {
  constexpr double inverseFactorial[3] = {1.0, 1.0, 0.5};
  double sum = 0;
  for (int p = 0; p <= 2; ++p)
    for (int q = 0; q <= 2; ++q)
      if (p || q) sum += norm(c.a[p][q] - c.b[p][q]) * inverseFactorial[p] * inverseFactorial[q] * std::ldexp(1.0, -(p + q));
  return sum;
}

/// The diagonal of the bounding box of the patch's boundary curves.
double boundaryDiagonal(const std::vector<LinearRibbon> &ribbons) {
  Vec3 low{INFINITY, INFINITY, INFINITY}, high = -low;
  for (const LinearRibbon &ribbon : ribbons)
    for (int k = 0; k <= 16; ++k) {
      const Vec3 p = ribbon.at(k / 16.0).P;
      low = {std::min(low.x, p.x), std::min(low.y, p.y), std::min(low.z, p.z)};
      high = {std::max(high.x, p.x), std::max(high.y, p.y), std::max(high.z, p.z)};
    }
  return norm(high - low);
}

/// gregoryCorrection2 in hyper-dual arithmetic.
Dual2Vec3 gregoryCorrection2Second(const CornerData2 &c, Dual2 s, Dual2 t) {
  const Dual2 sp[4] = {1.0, s, s * s, s * s * s}, tp[4] = {1.0, t, t * t, t * t * t};
  constexpr double inverseFactorial[3] = {1.0, 1.0, 0.5};
  Dual2Vec3 q = Dual2Vec3::constant(c.a[0][0]);
  for (int p = 0; p <= 2; ++p)
    for (int r = 0; r <= 2; ++r) {
      if (p == 0 && r == 0) continue;
      const Dual2 weight = sp[p] * tp[r] * Dual2(inverseFactorial[p] * inverseFactorial[r]);
      q += weight * rationalTerm2(c.a[p][r], c.b[p][r], sp[3 - p], tp[3 - r]);
    }
  return q;
}

CornerData2 cornerData2(const SideEndData &end, const SideEndData &start) {
  // a from R_{i-1}(1 - t, s): d/ds -> d/dd, d/dt -> -d/dsigma; b from R_i(s, t).
  CornerData2 corner;
  corner.a[0][0] = start.P;
  corner.a[1][0] = end.T, corner.a[2][0] = end.C;
  corner.a[0][1] = -end.dP, corner.a[1][1] = -end.dT, corner.a[2][1] = -end.dC;
  corner.a[0][2] = end.ddP, corner.a[1][2] = end.ddT, corner.a[2][2] = end.ddC;
  corner.b[1][0] = start.dP, corner.b[2][0] = start.ddP;
  corner.b[0][1] = start.T, corner.b[1][1] = start.dT, corner.b[2][1] = start.ddT;
  corner.b[0][2] = start.C, corner.b[1][2] = start.dC, corner.b[2][2] = start.ddC;
  return corner;
}

} // namespace

/// The smoothstep from 0 at `from` to 1 at `to`.
double smoothShare(double x, double from, double to) {
  const double r = std::clamp((x - from) / (to - from), 0.0, 1.0);
  return r * r * (3 - 2 * r);
}

std::vector<double> cornerBlendShares(const std::vector<LinearRibbon> &ribbons) {
  // The correction patch carries each ribbon's end twist T' over the face
  // (s t W11). Where T' at the end is not how T turns along the side, that
  // extrapolation is wrong: an end tangent turned by 3° bends the curve
  // within its first span, and T'(0) is 3–4 times T' 0.04 further on. The
  // measure: both end twists' departure from T's secant slope over a
  // quarter of the side, times s t = ¼ at the corner's reach, relative to
  // the face size. At most 0.17 on every built-in (saddle-nodes 0.15),
  // 0.28 with tangents turned by 1°, 0.32 on pocket3sided.lop (eq. 17 kept
  // there); from 0.59 (median) to 0.81 with tangents turned by 3°, where
  // the correction folded 9 of 12 faces.
  constexpr double kCorrectionAlone = 0.35, kBlendAlone = 0.55, kSecant = 0.25;
  const int n = static_cast<int>(ribbons.size());
  const double size = boundaryDiagonal(ribbons);
  std::vector<double> shares;
  for (int i = 0; i < n; ++i) {
    const LinearRibbon &own = ribbons[i], &previous = ribbons[(i + n - 1) % n];
    const RibbonJet start = own.at(0.0), end = previous.at(1.0);
    const double excess = norm(start.dT - (own.at(kSecant).T - start.T) / kSecant) +
                          norm(end.dT - (end.T - previous.at(1 - kSecant).T) / kSecant);
    shares.push_back(smoothShare(0.25 * excess / size, kCorrectionAlone, kBlendAlone));
  }
  return shares;
}

std::vector<double> cornerBlendShares(const std::vector<LinearRibbon> &ribbons,
                                      const std::vector<ParabolicRibbon> &parabolic) {
  // The disagreement bound relative to the face's size: at most 0.62 on
  // every built-in but saddle-nodes (0.48 torus-mixed, 0.026 on the sphere),
  // which keep eq. 17 exactly; from 1.16 on pocket3sided.lop and 2.9 on the
  // sphere with end tangents turned by 1°, where the correction patch folds.
  constexpr double kCorrectionAlone = 0.75, kBlendAlone = 1.0;
  const int n = static_cast<int>(parabolic.size());
  const double size = boundaryDiagonal(ribbons);
  std::vector<double> shares;
  for (int i = 0; i < n; ++i) {
    const CornerData2 corner = cornerData2(parabolic[(i + n - 1) % n].end(), parabolic[i].start());
    shares.push_back(smoothShare(cornerDisagreement(corner) / size, kCorrectionAlone, kBlendAlone));
  }
  return shares;
}

DualVec3 gregoryCorrection2(const CornerData2 &c, Dual s, Dual t) {
  const Dual sp[4] = {1.0, s, s * s, s * s * s}, tp[4] = {1.0, t, t * t, t * t * t};
  constexpr double inverseFactorial[3] = {1.0, 1.0, 0.5};
  DualVec3 q = DualVec3::constant(c.a[0][0]);
  for (int p = 0; p <= 2; ++p)
    for (int r = 0; r <= 2; ++r) {
      if (p == 0 && r == 0) continue;
      const Dual weight = sp[p] * tp[r] * Dual(inverseFactorial[p] * inverseFactorial[r]);
      q += weight * rationalTermOf(c.a[p][r], c.b[p][r], sp[3 - p], tp[3 - r]);
    }
  return q;
}

DualVec3 gregoryCorrection2(const kernels::GregoryCornerTerms &terms, const CornerData2 &c, Dual s, Dual t) {
  const double sv = s.v, tv = t.v;
  const double sp[4] = {1.0, sv, sv * sv, sv * sv * sv}, tp[4] = {1.0, tv, tv * tv, tv * tv * tv};
  // The eight denominators s^{3−p} + t^{3−r} with one division (prefix
  // products); at or within underflow of the corner, the reference form.
  double inverse[8], prefix[8];
  int j = 0;
  for (int p = 0; p <= 2; ++p)
    for (int r = 0; r <= 2; ++r)
      if (p || r) inverse[j] = sp[3 - p] + tp[3 - r], prefix[j] = j ? prefix[j - 1] * inverse[j] : inverse[j], ++j;
  if (!(prefix[7] > 1e-250)) return gregoryCorrection2(c, s, t);
  double all = 1 / prefix[7];
  for (j = 7; j > 0; --j) {
    const double mine = all * prefix[j - 1];
    all *= inverse[j];
    inverse[j] = mine;
  }
  inverse[0] = all;
  // Q and its partials ∂/∂s, ∂/∂t: the biquadratic part by Horner, then the
  // rational terms ρ_j = s³ t^r / den_j (see kernels::GregoryCornerTerms):
  //   ∂ρ/∂s = s² t^r (3 t^{3−r} + p s^{3−p}) / den², ∂ρ/∂t = s³ t^{r−1} (r s^{3−p} + (2r − 3) t^{3−r}) / den².
  double q[3], qs[3], qt[3];
  for (int c3 = 0; c3 < 3; ++c3) {
    double h[3], dh[3];
    for (int p = 0; p <= 2; ++p) {
      const double *row[3] = {terms.taylor[p][0], terms.taylor[p][1], terms.taylor[p][2]};
      h[p] = row[0][c3] + tv * (row[1][c3] + tv * row[2][c3]);
      dh[p] = row[1][c3] + 2 * tv * row[2][c3];
    }
    q[c3] = h[0] + sv * (h[1] + sv * h[2]);
    qs[c3] = h[1] + 2 * sv * h[2];
    qt[c3] = dh[0] + sv * (dh[1] + sv * dh[2]);
  }
  j = 0;
  for (int p = 0; p <= 2; ++p)
    for (int r = 0; r <= 2; ++r) {
      if (!p && !r) continue;
      const double x = sp[3 - p], y = tp[3 - r], i1 = inverse[j], i2 = i1 * i1;
      const double rho = sp[3] * tp[r] * i1;
      const double rhoS = sp[2] * tp[r] * (3 * y + p * x) * i2;
      const double rhoT = r ? sp[3] * tp[r - 1] * (r * x + (2 * r - 3) * y) * i2 : -3 * sp[3] * tp[2] * i2;
      for (int c3 = 0; c3 < 3; ++c3) {
        const double w = terms.rational[j][c3];
        q[c3] += rho * w, qs[c3] += rhoS * w, qt[c3] += rhoT * w;
      }
      ++j;
    }
  // The chain rule through s(u, v) and t(u, v).
  const Vec3 value{q[0], q[1], q[2]}, bySide{qs[0], qs[1], qs[2]}, across{qt[0], qt[1], qt[2]};
  return {value, bySide * s.du + across * t.du, bySide * s.dv + across * t.dv};
}

DualVec3 gregoryCorrection(const CornerData &c, Dual s, Dual t, Dual gs, Dual gt) {
  return gregoryCorrectionOf(c, s, t, gs, gt);
}

DualVec3 gregoryCorrection(const CornerData &c, Dual s, Dual t) {
  const double sv = s.v, tv = t.v;
  const double d1 = sv + tv * tv, d2 = sv * sv + tv, d3 = sv + tv;
  const double product = d1 * d2 * d3;
  if (!(product > 1e-250)) return gregoryCorrectionOf(c, s, t, s, t); // at or within underflow of the corner
  const double inverse = 1 / product;
  const double i1 = d2 * d3 * inverse, i2 = d1 * d3 * inverse, i3 = d1 * d2 * inverse;
  // Q = a00 + s b10 + t b01 + s t b11 + f1 (a10 − b10) + f2 (a01 − b01) + f3 (a11 − b11) with
  // f1 = s² / (s + t²), f2 = s² t / (s² + t), f3 = s² t / (s + t), and their partials:
  const double s2 = sv * sv;
  const double f1 = s2 * i1, f1s = sv * (sv + 2 * tv * tv) * i1 * i1, f1t = -2 * s2 * tv * i1 * i1;
  const double f2 = s2 * tv * i2, f2s = 2 * sv * tv * tv * i2 * i2, f2t = s2 * s2 * i2 * i2;
  const double f3 = s2 * tv * i3, f3s = sv * tv * (sv + 2 * tv) * i3 * i3, f3t = s2 * sv * i3 * i3;
  const Vec3 r1 = c.a10 - c.b10, r2 = c.a01 - c.b01, r3 = c.a11 - c.b11;
  const Vec3 q = c.a00 + c.b10 * sv + c.b01 * tv + c.b11 * (sv * tv) + r1 * f1 + r2 * f2 + r3 * f3;
  const Vec3 qs = c.b10 + c.b11 * tv + r1 * f1s + r2 * f2s + r3 * f3s;
  const Vec3 qt = c.b01 + c.b11 * sv + r1 * f1t + r2 * f2t + r3 * f3t;
  return {q, qs * s.du + qt * t.du, qs * s.dv + qt * t.dv};
}

Patch::Patch(std::vector<LinearRibbon> ribbons, const SurfaceOptions &options, std::vector<ParabolicRibbon> parabolic,
             std::vector<double> blendShares)
    : tables_(std::make_shared<TableCache>()), domain_(static_cast<int>(ribbons.size())), ribbons_(std::move(ribbons)), parabolic_(std::move(parabolic)),
      options_(options) {
  CURVENET_CHECK(ribbons_.size() >= 3 && ribbons_.size() <= Patch::kMaxSides);
  if (options_.sweepline == Sweepline::Auto)
    options_.sweepline = options_.scheme == Scheme::GregoryG2 ? Sweepline::Hermite : Sweepline::Radial;
  CURVENET_CHECK(options_.scheme != Scheme::GregoryG2 || parabolic_.size() == ribbons_.size(),
                 "gregory-g2 needs one parabolic ribbon per side");
  std::vector<RibbonJet> starts, ends;
  for (const LinearRibbon &ribbon : ribbons_) starts.push_back(ribbon.at(0.0)), ends.push_back(ribbon.at(1.0));
  for (int i = 0; i < domain_.sides(); ++i) {
    const RibbonJet &start = starts[i], &end = ends[i];
    const RibbonJet &prevEnd = ends[domain_.wrap(i - 1)], &nextStart = starts[domain_.wrap(i + 1)];
    corners_.push_back({start.P, prevEnd.T, -prevEnd.dP, -prevEnd.dT, start.dP, start.T, start.dT});
    endCorners_.push_back({nextStart.P, nextStart.T, nextStart.dP, nextStart.dT, -end.dP, end.T, -end.dT});
    if (options_.scheme == Scheme::GregoryG2)
      corners2_.push_back(cornerData2(parabolic_[domain_.wrap(i - 1)].end(), parabolic_[i].start()));
  }
  for (int i = 0; i < domain_.sides(); ++i) {
    if (options_.scheme == Scheme::CompositeRibbon) {
      kernelCorners_.push_back(kernelCorner(corners_[i]));
      kernelEndCorners_.push_back(kernelCorner(endCorners_[i]));
      continue;
    }
    kernelCorners_.push_back(cornerVectors(i));
    if (options_.scheme == Scheme::GregoryG2) cornerTerms_.push_back(kernels::gregoryCornerTerms(kernelCorners_[i]));
  }
  if (options_.scheme == Scheme::GregoryG1) {
    blendShare_ = blendShares.empty() ? cornerBlendShares(ribbons_) : std::move(blendShares);
    CURVENET_CHECK(blendShare_.size() == ribbons_.size(), "one blend share per corner");
  }
  if (options_.scheme == Scheme::GregoryG2) {
    blendShare_ = blendShares.empty() ? cornerBlendShares(ribbons_, parabolic_) : std::move(blendShares);
    CURVENET_CHECK(blendShare_.size() == ribbons_.size(), "one blend share per corner");
    // Ribbon i's cross parameter is side i−1's parameter at corner i and side
    // i+1's at corner i+1, and there the correction patch extrapolates those
    // sides' expansions at their ends by as much: it saturates where the
    // first of the two stops being trusted.
    for (int i = 0; i < domain_.sides(); ++i) {
      const double before = parabolic_[domain_.wrap(i - 1)].cornerTaylorReach(false, kCornerTaylorTolerance);
      const double after = parabolic_[domain_.wrap(i + 1)].cornerTaylorReach(true, kCornerTaylorTolerance);
      crossReach_.push_back(std::max(std::min(before, after), kMinimumReach));
      reachLimited_ = reachLimited_ || crossReach_.back() < 1;
    }
  }
}

void Patch::snapToCorner(double &u, double &v) const {
  // A point meant to be a corner but computed along a side (p_i + (p_{i+1} −
  // p_i)·1) misses it by a rounding error; there the blends of the far
  // corners are not exactly zero while their sweep parameters are singular
  // (the radial sweep of a triangle meets at the opposite corner). Snap to
  // the exact corner, where the far blends vanish identically.
  for (int i = 0; i < domain_.sides(); ++i) {
    const Vec2 &c = domain_.corner(i);
    if (std::abs(u - c.x) <= 1e-14 && std::abs(v - c.y) <= 1e-14) u = c.x, v = c.y;
  }
}

DualVec3 Patch::evaluate(double u, double v) const {
  snapToCorner(u, v);
  const Dual du = Dual::u(u), dv = Dual::vCoord(v);
  switch (options_.scheme) {
  case Scheme::CompositeRibbon: return compositeRibbon(du, dv);
  case Scheme::GregoryG2: return gregoryG2(du, dv);
  case Scheme::GregoryG1: break;
  case Scheme::BezierG1:
  case Scheme::CoonsC0: CURVENET_CHECK(false, "Bézier schemes have no transfinite patch"); break;
  }
  return gregory(du, dv);
}

// Gregory corner-based patch, [SV14] eqs. 16–18 with m = 2.
DualVec3 Patch::gregory(Dual u, Dual v) const {
  const int n = domain_.sides();
  std::array<Dual, Patch::kMaxSides> s, distance;
  std::array<RibbonJet, Patch::kMaxSides> jet;
  if (options_.sweepline != Sweepline::Radial)
    domain_.hermiteSweepSides(u, v, options_.sweepline == Sweepline::QuinticHermite, s);
  // With a share of the two-ribbon blend, λ = t² / (s² + t²) turns with the
  // direction from the corner: its gradient grows as 1 / r while the two
  // ribbons' gap shrinks as r². At a corner evaluated along a side, s and t
  // are rounding errors (1e-17) and so is the gap, which the gradient then
  // blows up (a normal 69° off at a doghead corner): a parameter within a
  // few ulps of a side's end is that end, as in gregoryG2From.
  const bool blended = std::any_of(blendShare_.begin(), blendShare_.end(), [](double mu) { return mu > 0; });
  for (int i = 0; i < n; ++i) {
    if (options_.sweepline == Sweepline::Radial) s[i] = domain_.radialSideParameter(i, u, v);
    if (blended && std::abs(s[i].v) <= kSweepEndSnap) s[i].v = 0;
    if (blended && std::abs(s[i].v - 1) <= kSweepEndSnap) s[i].v = 1;
    distance[i] = domain_.perpendicularDistance(i, u, v);
    jet[i] = ribbons_[i].at(ribbons_[i].snap(std::clamp(s[i].v, 0.0, 1.0)));
  }
  // Corner blends in product form (safe on the sides):
  // B_{i,i−1} = ∏_{j∉{i,i−1}} Δ_j² / Σ_k ∏_{j∉{k,k−1}} Δ_j².
  std::array<Dual, Patch::kMaxSides> squared, blend;
  for (int i = 0; i < n; ++i) squared[i] = distance[i] * distance[i];
  const Dual total = domain_.cornerProducts(squared, blend);
  DualVec3 result{};
  for (int i = 0; i < n; ++i) {
    const Dual b = blend[i] / total;
    if (b.isZero()) continue; // far corner: the interpolant may be undefined there
    const int prev = domain_.wrap(i - 1);
    const RibbonJet &left = jet[prev], &right = jet[i];
    // I_{i,i−1} = R_{i−1}(s_{i−1}, s_i) + R_i(s_i, 1 − s_{i−1}) − Q(s_i, 1 − s_{i−1}) (eq. 17),
    // its share μ taken from the two-ribbon blend (cornerBlendShares).
    const Dual si = s[i], ti = Dual(1.0) - s[prev];
    const DualVec3 previous = ribbonAt(left, s[prev], si), own = ribbonAt(right, si, ti);
    const double mu = blendShare_[i];
    DualVec3 interpolant = sideBlendOf(previous, own, si, ti, mu, 2);
    if (mu != 1) interpolant += Dual(1.0 - mu) * (previous + own - gregoryCorrection(corners_[i], si, ti));
    result += b * interpolant;
  }
  return result;
}

// The G² Gregory patch in hyper-dual arithmetic: the same formula as
// gregoryG2, with exact second derivatives of every constituent (C'' of the
// ribbons excepted, see ParabolicRibbon::secondOrder).
Dual2Vec3 Patch::evaluateSecondOrder(double uValue, double vValue) const {
  CURVENET_CHECK(options_.scheme == Scheme::GregoryG2, "second-order evaluation is gregory-g2 only");
  const Dual2 u = Dual2::u(uValue), v = Dual2::vCoord(vValue);
  const int n = domain_.sides();
  const bool quintic = options_.sweepline == Sweepline::QuinticHermite;
  std::array<Dual2, Patch::kMaxSides> s, cubed;
  std::array<SideEndData, Patch::kMaxSides> jet;
  for (int i = 0; i < n; ++i) {
    // On a side the two neighbouring sides' sweeps are 0 and 1 exactly, but
    // a point computed on it (corner + x · edge) and its root miss them by
    // an ulp or two, and near a corner the second derivatives are that
    // sensitive to the cross parameter: the rational terms of the
    // correction patch switch between their two ribbons' corner data over
    // a layer as thin as the cube of the distance to the corner (W₀₂ =
    // (s³ a + t b) / (s³ + t), t the cross parameter), so ∂²Q/∂t² moves
    // by (b − a) / s³ per unit of t. At 1 % of a side from a corner an ulp
    // of t gave curvature jumps of 5e-11 across seams that are G² in the
    // limit; taken as the side itself, the point gets that limit.
    s[i] = snappedToSweepEnd(domain_.hermiteSweepSide2(i, u, v, quintic));
    const Dual2 distance = domain_.perpendicularDistance2(i, u, v);
    cubed[i] = distance * distance * distance;
    const double side = ribbons_[i].snap(std::clamp(s[i].v, 0.0, 1.0));
    jet[i] = side == 0.0 ? parabolic_[i].start() : side == 1.0 ? parabolic_[i].end() : parabolic_[i].secondOrder(side);
  }
  std::array<Dual2, Patch::kMaxSides> blend;
  const Dual2 total = domain_.cornerProducts(cubed, blend);
  Dual2Vec3 result{};
  for (int i = 0; i < n; ++i) {
    const Dual2 b = blend[i] / total;
    if (b.isZero()) continue;
    const int prev = domain_.wrap(i - 1);
    // The cross parameters saturate at their ribbons' reach (limitedCross);
    // the two-ribbon blend keeps the sweep's own.
    const Dual2 si = s[i], ti = Dual2(1.0) - s[prev];
    const Dual2 sCross = limitedCross(si, crossReach_[prev]), tCross = limitedCross(ti, crossReach_[i]);
    const Dual2Vec3 previous = ribbonAt2(jet[prev], s[prev], sCross), own = ribbonAt2(jet[i], si, tCross);
    const double mu = blendShare_[i];
    Dual2Vec3 interpolant = sideBlendOf(previous, own, si, ti, mu);
    if (mu != 1)
      interpolant += Dual2(1.0 - mu) * (previous + own - gregoryCorrection2Second(corners2_[i], sCross, tCross));
    result += b * interpolant;
  }
  return result;
}

// G² Gregory patch, [SV14] eqs. 16–18 with m = 3, parabolic ribbons, the
// Hermite sweepline (eq. 20) and the nine-term correction patch (eq. 22).
DualVec3 Patch::gregoryG2(Dual u, Dual v) const {
  const int n = domain_.sides();
  const bool quintic = options_.sweepline == Sweepline::QuinticHermite;
  std::array<Dual, Patch::kMaxSides> s, cubed;
  std::array<ParabolicJet, Patch::kMaxSides> jet;
  domain_.hermiteSweepSides(u, v, quintic, s);
  for (int i = 0; i < n; ++i) {
    const Dual distance = domain_.perpendicularDistance(i, u, v);
    cubed[i] = distance * distance * distance;
    jet[i] = parabolic_[i].at(ribbons_[i].snap(std::clamp(s[i].v, 0.0, 1.0)));
  }
  // Corner blends in product form with m = 3 (eq. 18): their first and second
  // derivatives vanish on every side but the two at the corner.
  std::array<Dual, Patch::kMaxSides> blend;
  const Dual total = domain_.cornerProducts(cubed, blend);
  for (int i = 0; i < n; ++i) blend[i] = blend[i] / total;
  return gregoryG2From(s.data(), blend.data(), jet.data());
}

DualVec3 Patch::gregoryG2From(const Dual *s, const Dual *blend, const ParabolicJet *jet) const {
  const int n = domain_.sides();
  // At a corner the two-ribbon blend and the correction's rational terms
  // take their limits (s = t = 0) only when the sweep gives exactly 0 or 1:
  // every path's sweep does there (RegularDomain::cornerAt).
  DualVec3 result{};
  for (int i = 0; i < n; ++i) {
    const Dual b = blend[i];
    if (b.isZero()) continue; // far corner: the interpolant may be undefined there
    const int prev = domain_.wrap(i - 1);
    const Dual si = s[i], ti = Dual(1.0) - s[prev];
    // The cross parameters, each saturating at its ribbon's reach (the
    // correction patch takes the same ones, so that it still cancels what
    // the two ribbons share): s_i for R_{i−1}, t_i = 1 − s_{i−1} for R_i.
    // The two-ribbon blend keeps the sweep's own.
    const Dual sCross = limitedCross(si, crossReach_[prev]), tCross = limitedCross(ti, crossReach_[i]);
    // I_{i,i−1} = R_{i−1}(s_{i−1}, s_i) + R_i(s_i, 1 − s_{i−1}) − Q (eq. 17),
    // its share μ taken from the two-ribbon blend (cornerBlendShares).
    const DualVec3 previous = ribbonAt(jet[prev], s[prev], sCross), own = ribbonAt(jet[i], si, tCross);
    const double mu = blendShare_[i];
    DualVec3 interpolant = sideBlendOf(previous, own, si, ti, mu);
    if (mu != 1)
      interpolant += Dual(1.0 - mu) * (previous + own - gregoryCorrection2(cornerTerms_[i], corners2_[i], sCross, tCross));
    result += b * interpolant;
  }
  return result;
}

// Composite Ribbon patch, [VSR] Sec. 2.
void Patch::compositeParameters(Dual u, Dual v, Dual *s, Dual *d, Dual *blend) const {
  const int n = domain_.sides();
  domain_.wachspressDistances(u, v, std::span<Dual>(d, static_cast<std::size_t>(n)));
  for (int i = 0; i < n; ++i) s[i] = domain_.linearSweepSideParameter(i, u, v);
  // CR blends B_i = (D_{i,i−1} + D_{i,i+1}) / Σ_j D_{j,j−1}, D = ∏ d_j² over the others.
  std::array<Dual, Patch::kMaxSides> squared, cornerProduct;
  for (int i = 0; i < n; ++i) squared[i] = d[i] * d[i];
  const Dual total = domain_.cornerProducts(squared, cornerProduct); // cornerProduct[i] = D_{i,i−1}
  for (int i = 0; i < n; ++i) blend[i] = (cornerProduct[i] + cornerProduct[domain_.wrap(i + 1)]) / total;
}

DualVec3 Patch::compositeRibbon(Dual u, Dual v) const {
  std::array<Dual, Patch::kMaxSides> s, d, blend; // stack arrays: no allocation per point
  compositeParameters(u, v, s.data(), d.data(), blend.data());
  return compositeRibbonFrom(s.data(), d.data(), blend.data());
}

template <class T> auto Patch::compositeRibbonWith(const T *s, const T *d, const T *blends) const {
  using N = Numbers<T>;
  using Point = typename N::Point;
  const int n = domain_.sides();
  auto gamma = [](T x) { return x / (x * 2.0 + 1.0); };
  auto hermite0 = [](T x) { return x * x * (x * 2.0 - 3.0) + 1.0; }; // α0 = 2x³ − 3x² + 1
  // Ribbon with the γ reparameterization: R_i(s, d) = P_i(s) + γ(d) T_i(s).
  auto ribbon = [&](int i, T side, T dist) {
    const LinearRibbon &r = ribbons_[domain_.wrap(i)];
    const RibbonJet j = r.at(r.snap(std::clamp(N::value(side), 0.0, 1.0)));
    return N::along(j.P, j.dP, side) + gamma(dist) * N::along(j.T, j.dT, side);
  };
  Point result{};
  for (int i = 0; i < n; ++i) {
    const T blend = blends[i];
    if (N::isZero(blend)) continue;
    const int prev = domain_.wrap(i - 1), next = domain_.wrap(i + 1);
    const T si = s[i], di = d[i], one = 1.0;
    // Curved ribbon C_i (a Coons patch with three sides given):
    // C = R^l α0(s) + R α0(d) + R^r α1(s) − [Q^l α0(s) α0(d) + Q^r α1(s) α0(d)].
    const Point centre = ribbon(i, si, di);
    const Point leftRibbon = ribbon(prev, one - di, si);  // R_{i−1}(1 − d, s)
    const Point rightRibbon = ribbon(next, di, one - si); // R_{i+1}(d, 1 − s)
    // Left corner in (s, d), right corner in (σ = 1 − s, d): corners_, endCorners_.
    const T sigma = one - si;
    const Point leftCorrection = gregoryCorrectionOf(corners_[i], si, di, gamma(si), gamma(di));
    const Point rightCorrection = gregoryCorrectionOf(endCorners_[i], sigma, di, gamma(sigma), gamma(di));
    const T a0s = hermite0(si), a1s = one - a0s, a0d = hermite0(di);
    const Point curved = a0s * leftRibbon + a0d * centre + a1s * rightRibbon -
                         (a0s * a0d) * leftCorrection - (a1s * a0d) * rightCorrection;
    result += blend * curved;
  }
  return T(0.5) * result;
}

DualVec3 Patch::compositeRibbonFrom(const Dual *s, const Dual *d, const Dual *blends) const {
  return compositeRibbonWith(s, d, blends);
}

Vec3 Patch::compositeRibbonPoint(const double *s, const double *d, const double *blends) const {
  return compositeRibbonWith(s, d, blends);
}

template <class T, class Emit>
void Patch::compositeRibbonBatch(std::size_t count, const T *const *s, const T *const *d, const T *const *blends,
                                 const Emit &emit) const {
  using N = Numbers<T>;
  constexpr bool slopes = !std::is_same_v<T, double>;
  // Blocks whose ribbon arrays (up to 36 per side) stay in the fast caches.
  constexpr std::size_t kBlock = 64;
  constexpr int kPerRibbon = slopes ? 12 : 6;   // P, T (and their slopes)
  constexpr int kArrays = 3 * kPerRibbon + 3;   // three ribbons and their parameters
  const int n = domain_.sides();
  const PatchTables &t = tables();
  thread_local std::vector<double> scratch, splits, outputs;
  scratch.resize(static_cast<std::size_t>(n) * kArrays * kBlock);
  if constexpr (slopes) splits.resize(static_cast<std::size_t>(n) * 9 * kBlock);
  outputs.resize(9 * kBlock);
  // Dual inputs split into arrays: which (s, d, blend), side, part (value, ∂u, ∂v).
  auto split = [&](int which, int i, int part) {
    return splits.data() + ((static_cast<std::size_t>(i) * 3 + which) * 3 + part) * kBlock;
  };
  for (std::size_t first = 0; first < count; first += kBlock) {
    const std::size_t m = std::min(kBlock, count - first);
    // Per side i, three ribbons as in compositeRibbonWith: R_i at s_i, R_{i−1}
    // at 1 − d_i, R_{i+1} at d_i, each through the table kernel.
    auto array = [&](int i, int j) { return scratch.data() + (static_cast<std::size_t>(i) * kArrays + j) * kBlock; };
    for (int i = 0; i < n; ++i) {
      const int ribbon[3] = {i, domain_.wrap(i - 1), domain_.wrap(i + 1)};
      for (int r = 0; r < 3; ++r) {
        double *at = array(i, kArrays - 3 + r);
        const LinearRibbon &line = ribbons_[ribbon[r]];
        for (std::size_t k = 0; k < m; ++k) {
          const double x = r == 0   ? N::value(s[i][first + k])
                           : r == 1 ? 1.0 - N::value(d[i][first + k])
                                    : N::value(d[i][first + k]);
          at[k] = line.snap(std::clamp(x, 0.0, 1.0));
        }
        double *values[6], *derivatives[6];
        for (int c = 0; c < 6; ++c)
          values[c] = array(i, kPerRibbon * r + c),
          derivatives[c] = slopes ? array(i, kPerRibbon * r + 6 + c) : nullptr;
        t.sides[ribbon[r]].evaluate(m, at, values, slopes ? derivatives : nullptr);
      }
    }
    // The CR formula over the block: kernels::compositeRibbon{Positions,Jets}
    // on structure-of-arrays inputs (a Dual batch split into its value and
    // partials).
    kernels::CompositeSamples in;
    in.sides = n;
    for (int i = 0; i < n; ++i) {
      const T *inputs[3] = {s[i] + first, d[i] + first, blends[i] + first};
      const double **targets[3] = {in.s[i], in.d[i], in.blend[i]};
      for (int which = 0; which < 3; ++which) {
        if constexpr (slopes) {
          for (int part = 0; part < 3; ++part) {
            double *column = split(which, i, part);
            for (std::size_t k = 0; k < m; ++k)
              column[k] = part == 0 ? inputs[which][k].v : part == 1 ? inputs[which][k].du : inputs[which][k].dv;
            targets[which][part] = column;
          }
        } else {
          targets[which][0] = inputs[which];
        }
      }
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          in.P[i][r][c] = array(i, kPerRibbon * r + c), in.T[i][r][c] = array(i, kPerRibbon * r + 3 + c);
          if constexpr (slopes)
            in.dP[i][r][c] = array(i, kPerRibbon * r + 6 + c), in.dT[i][r][c] = array(i, kPerRibbon * r + 9 + c);
        }
    }
    double *result[9];
    for (int j = 0; j < 9; ++j) result[j] = outputs.data() + static_cast<std::size_t>(j) * kBlock;
    if constexpr (slopes) {
      kernels::compositeRibbonJets(m, in, kernelCorners_.data(), kernelEndCorners_.data(),
                                   {{result[0], result[1], result[2]}, {result[3], result[4], result[5]},
                                    {result[6], result[7], result[8]}});
      for (std::size_t k = 0; k < m; ++k)
        emit(first + k, DualVec3{{result[0][k], result[1][k], result[2][k]},
                                 {result[3][k], result[4][k], result[5][k]},
                                 {result[6][k], result[7][k], result[8][k]}});
    } else {
      kernels::compositeRibbonPositions(m, in, kernelCorners_.data(), kernelEndCorners_.data(), result);
      for (std::size_t k = 0; k < m; ++k) emit(first + k, Vec3{result[0][k], result[1][k], result[2][k]});
    }
  }
}

void Patch::compositeRibbonPositions(std::size_t count, const double *const *s, const double *const *d,
                                     const double *const *blends, const PositionSink &out) const {
  compositeRibbonBatch(count, s, d, blends, [&](std::size_t k, const Vec3 &p) { out.set(k, p); });
}

void Patch::compositeRibbonJets(std::size_t count, const Dual *const *s, const Dual *const *d,
                                const Dual *const *blends, DualVec3 *out) const {
  compositeRibbonBatch(count, s, d, blends, [&](std::size_t k, const DualVec3 &p) { out[k] = p; });
}

} // namespace v1
} // namespace curvenet
