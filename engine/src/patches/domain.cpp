#include "patches/domain.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

namespace {
// Direction of a domain vector in side i's frame (side length 1).
Vec2 inFrame(const Vec2 &e, const Vec2 &d) {
  const double l2 = dot(e, e);
  return {dot(d, e) / l2, cross(e, d) / l2};
}
} // namespace

RegularDomain::RegularDomain(int sides) : n_(sides) {
  CURVENET_CHECK(sides >= 3, "domain needs at least 3 sides, got " + std::to_string(sides));
  // Corner 0 at angle −π/2 − π/n puts side 0 horizontal at the bottom.
  const double start = -std::numbers::pi / 2 - std::numbers::pi / n_;
  for (int i = 0; i < n_; ++i) {
    const double a = start + 2 * std::numbers::pi * i / n_;
    corners_.push_back({std::cos(a), std::sin(a)});
  }
  for (int i = 0; i < n_; ++i) {
    const Vec2 e = corner(i + 1) - corner(i);
    sideAxes_.push_back({corner(i), e / dot(e, e)});
  }
  if (n_ == 3) inverseHeight_ = 1 / perpendicularDistance(0, Dual(corner(2).x), Dual(corner(2).y)).v;
  // Every side sees its neighbours alike (the polygon is regular): one frame
  // serves all sides, as the plans' rotations assume.
  const Vec2 e = corner(1) - corner(0);
  a_ = inFrame(e, corner(-1) - corner(0)), b_ = inFrame(e, corner(2) - corner(1));
  frame_ = {a_.x, a_.y, b_.x, b_.y};
  const double det = cross(a_, b_);
  if (std::abs(det) < 1e-12) {
    frame_.parallel = true;
  } else {
    const double alpha = cross(Vec2{1, 0}, b_) / det;
    frame_.apexX = a_.x * alpha, frame_.apexY = a_.y * alpha;
  }
}

Vec2 RegularDomain::pointOnSide(int i, double s) const { return corner(i) + (corner(i + 1) - corner(i)) * s; }

namespace {
/// The Hermite weight of eq. 20 and its first two derivatives: cubic
/// H(s) = 2s³ − 3s² + 1, or the quintic 1 − 10s³ + 15s⁴ − 6s⁵ of the footnote.
std::array<double, 3> hermiteWeight(double s, bool quintic) {
  if (quintic)
    return {1 - s * s * s * (10 - 15 * s + 6 * s * s), -30 * s * s * (1 - s) * (1 - s),
            -60 * s * (1 - s) * (1 - 2 * s)};
  return {2 * s * s * s - 3 * s * s + 1, 6 * s * s - 6 * s, 12 * s - 6};
}
} // namespace

Dual RegularDomain::radialSideParameter(int i, Dual u, Dual v) const {
  Dual x, y;
  sideFrame(i, u, v, x, y);
  return radialSideParameter(sweepFrame(i), x, y);
}

namespace {
/// |F| at an end of [0, 1] within which that end counts as a root (a point on
/// a neighbouring side may show no sign change after rounding); the kernels'
/// solvers use the same bound.
double sweepEndTolerance(double x, double y, const Vec2 &a, const Vec2 &b) {
  return 1e-13 * (1 + std::abs(x) + std::abs(y)) * (norm(a) + norm(b));
}
} // namespace

bool RegularDomain::rootAtSweepEnd(double x, double y) const {
  // Points on sides i ± 1, whose root is an end of [0, 1] (F within the end
  // tolerance there), are the kernel's uncertifiable cases, which its robust
  // solver would take: the grid solver settles them for a fraction of that.
  const double tolerance = sweepEndTolerance(x, y, a_, b_);
  return std::abs(x * a_.y - y * a_.x) <= tolerance || std::abs((x - 1) * b_.y - y * b_.x) <= tolerance; // F(0), F(1)
}

Dual RegularDomain::triangleSweep(int i, Dual u, Dual v) const {
  return triangleSideParameter(perpendicularDistance(i - 1, u, v), perpendicularDistance(i + 1, u, v),
                               perpendicularDistance(i, u, v));
}

Dual2 RegularDomain::triangleSweep2(int i, Dual2 u, Dual2 v) const {
  return triangleSideParameter(perpendicularDistance2(i - 1, u, v), perpendicularDistance2(i + 1, u, v),
                               perpendicularDistance2(i, u, v));
}

RegularDomain::SweepParameters RegularDomain::hermiteSweep(int i, Dual u, Dual v, bool quintic) const {
  // Triangles: the cubic sweep in closed form (triangleSideParameter), d the
  // distance from the side in units of the height. The quintic keeps eq. 20
  // by the grid solver, whose sweeplines cross near the opposite corner
  // (see Sweepline): there a point lies on several of them and the two
  // solvers' selection can part at rounding level.
  if (sides() == 3 && !quintic) return {triangleSweep(i, u, v), perpendicularDistance(i, u, v) * inverseHeight_};
  if (quintic || sides() == 3) return hermiteSweepByGrid(i, u, v, quintic);
  Dual x, y;
  sideFrame(i, u, v, x, y);
  if (rootAtSweepEnd(x.v, y.v)) return hermiteSweepByGrid(i, u, v);
  double root, distance;
  kernels::hermiteSweepRoots(1, sweepFrame(i), &x.v, &y.v, &root, &distance, kernels::kScalarReference);
  return hermiteSweepFromRoot(i, u, v, root);
}

void RegularDomain::hermiteSweepSides(Dual u, Dual v, bool quintic, std::span<Dual> s) const {
  solveHermiteSweepSides(u, v, quintic, s);
  if (const int j = cornerAt(u.v, v.v); j >= 0) s[j].v = 0, s[wrap(j - 1)].v = 1;
}

void RegularDomain::solveHermiteSweepSides(Dual u, Dual v, bool quintic, std::span<Dual> s) const {
  constexpr int kMaxBatch = 16;
  if (quintic || n_ == 3 || n_ > kMaxBatch) {
    for (int i = 0; i < n_; ++i) s[i] = hermiteSweep(i, u, v, quintic).s;
    return;
  }
  // The sides hermiteSweep would give the kernel, gathered; the end-root
  // cases to the grid solver as there.
  static const std::size_t lanes = kernels::bestWidth().lanes;
  std::array<double, kMaxBatch> x, y, root, distance;
  std::array<int, kMaxBatch> side;
  std::size_t count = 0;
  for (int i = 0; i < n_; ++i) {
    Dual fx, fy;
    sideFrame(i, u, v, fx, fy);
    if (rootAtSweepEnd(fx.v, fy.v)) {
      s[i] = hermiteSweepByGrid(i, u, v).s;
      continue;
    }
    x[count] = fx.v, y[count] = fy.v, side[count++] = i;
  }
  if (count == 0) return;
  // Whole vectors: the lanes past the sides repeat the first side's point.
  std::size_t padded = std::min<std::size_t>((count + lanes - 1) / lanes * lanes, kMaxBatch);
  if (padded < count) padded = count;
  for (std::size_t k = count; k < padded; ++k) x[k] = x[0], y[k] = y[0];
  kernels::hermiteSweepRoots(padded, frame_, x.data(), y.data(), root.data(), distance.data());
  for (std::size_t k = 0; k < count; ++k) s[side[k]] = hermiteSweepFromRoot(side[k], u, v, root[k]).s;
}

RegularDomain::SweepParameters RegularDomain::hermiteSweepByGrid(int i, Dual u, Dual v, bool quintic) const {
  Dual x, y;
  sideFrame(i, u, v, x, y);
  const Vec2 &a = a_, &b = b_;
  auto H = [quintic](double s) { return hermiteWeight(s, quintic); };
  // w(s) = a H(s) + b H(1 − s) and its derivative.
  auto w = [&](double s, Vec2 &value, Vec2 &slope) {
    const auto h0 = H(s), h1 = H(1 - s);
    value = a * h0[0] + b * h1[0];
    slope = a * h0[1] - b * h1[1];
  };
  // F(s) = (x − s) w_y(s) − y w_x(s) = 0: the point lies on the sweepline of s.
  const double px = x.v, py = y.v;
  auto F = [&](double s) {
    Vec2 val, slope;
    w(s, val, slope);
    return (px - s) * val.y - py * val.x;
  };
  // Bracket sign changes on a fine grid over [0, 1] and refine by bisection
  // (robust; the cached evaluation plans do this once per sample anyway).
  constexpr int kGrid = 64;
  // In a triangle the sweeplines of side i cross near the opposite corner
  // (see Sweepline in curvenet/surface.hpp), so a point there lies on several
  // sweeplines. Of the orientation-preserving roots with d ≥ 0 take the one
  // nearest the radial parameter, the sweep this one perturbs; elsewhere the
  // root is unique and the rule changes nothing.
  const double radial = radialSideParameter(i, Dual(u.v), Dual(v.v)).v;
  double best = -1, bestDistance = INFINITY;
  auto consider = [&](double s) {
    Vec2 val, slope;
    w(s, val, slope);
    const double d = std::abs(val.x) > std::abs(val.y) ? (px - s) / val.x : py / val.y;
    // Orientation of (s, d) ↦ (x, y) = (s, 0) + d w(s): beyond a fold the
    // root lies on the reversed sheet, which no valid sweep passes through.
    const double jacobian = (1 + d * slope.x) * val.y - d * slope.y * val.x;
    const double penalty = jacobian > 1e-9 ? 0.0 : 2.0; // reversed or folded: only if nothing else
    if (d >= -1e-9 && std::abs(s - radial) + penalty < bestDistance) bestDistance = std::abs(s - radial) + penalty, best = s;
  };
  double f0 = F(0.0);
  // A point on side i−1 or i+1 has its root exactly at an end of [0, 1],
  // where rounding may leave F a hair off zero with no sign change: accept
  // the ends within a rounding tolerance.
  const double tolerance = sweepEndTolerance(px, py, a, b);
  if (std::abs(f0) <= tolerance) consider(0.0);
  if (std::abs(F(1.0)) <= tolerance) consider(1.0);
  for (int k = 1; k <= kGrid; ++k) {
    const double s1 = double(k) / kGrid, f1 = F(s1);
    if (f1 == 0 && k < kGrid) consider(s1);
    else if ((f0 < 0) != (f1 < 0) && f0 != 0) {
      double lo = s1 - 1.0 / kGrid, hi = s1, flo = f0;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi), fm = F(mid);
        if ((fm < 0) == (flo < 0)) lo = mid, flo = fm;
        else hi = mid;
      }
      consider(0.5 * (lo + hi));
    }
    f0 = f1;
  }
  if (best < 0) best = std::clamp(px, 0.0, 1.0); // outside the domain: nearest base point
  return hermiteSweepFromRoot(i, u, v, best, quintic);
}

RegularDomain::SweepParameters RegularDomain::hermiteSweepFromRoot(int i, Dual u, Dual v, double best,
                                                                   bool quintic) const {
  Dual x, y;
  sideFrame(i, u, v, x, y);
  const Vec2 &a = a_, &b = b_;
  auto H = [quintic](double s) { return hermiteWeight(s, quintic); };
  const double px = x.v, py = y.v;
  // Implicit differentiation of F(s; x, y) = 0.
  const auto h0 = H(best), h1 = H(1 - best);
  const Vec2 val = a * h0[0] + b * h1[0], slope = a * h0[1] - b * h1[1];
  const double Fs = -val.y + (px - best) * slope.y - py * slope.x;
  const double sx = Fs != 0 ? -val.y / Fs : 0, sy = Fs != 0 ? val.x / Fs : 0;
  Dual s{best, sx * x.du + sy * y.du, sx * x.dv + sy * y.dv};
  const Dual wx = s.apply(val.x, slope.x), wy = s.apply(val.y, slope.y);
  const Dual d = std::abs(val.x) > std::abs(val.y) ? (x - s) / wx : y / wy;
  return {s, d};
}

Dual2 RegularDomain::perpendicularDistance2(int i, Dual2 u, Dual2 v) const {
  const Vec2 p = corner(i), e = corner(i + 1) - corner(i);
  const double l2 = dot(e, e);
  return ((v - p.y) * e.x - (u - p.x) * e.y) * (1.0 / l2);
}

Dual2 RegularDomain::hermiteSweepSide2(int i, Dual2 u, Dual2 v, bool quintic) const {
  const Vec2 p = corner(i), e = corner(i + 1) - corner(i);
  const double l2 = dot(e, e);
  const Dual2 qx = u - p.x, qy = v - p.y;
  const Dual2 x = (qx * e.x + qy * e.y) * (1.0 / l2), y = (qy * e.x - qx * e.y) * (1.0 / l2);
  if (n_ == 3 && !quintic) return triangleSweep2(i, u, v);
  const Vec2 &a = a_, &b = b_;
  const double s0 = hermiteSweep(i, Dual(u.v), Dual(v.v), quintic).s.v;
  auto H = [quintic](double s) -> std::array<double, 3> {
    if (quintic)
      return {1 - s * s * s * (10 - 15 * s + 6 * s * s), -30 * s * s * (1 - s) * (1 - s),
              -60 * s * (1 - s) * (1 - 2 * s)};
    return {2 * s * s * s - 3 * s * s + 1, 6 * s * s - 6 * s, 12 * s - 6};
  };
  // F(s) = (x − s) w_y(s) − y w_x(s) with w = a H(s) + b H(1 − s), in jets.
  auto F = [&](Dual2 s) {
    const auto h0 = H(s.v), h1 = H(1 - s.v);
    const Dual2 hs = s.apply(h0[0], h0[1], h0[2]);
    const Dual2 hr = s.apply(h1[0], -h1[1], h1[2]); // H(1 − s) as a function of s
    const Dual2 wx = hs * a.x + hr * b.x, wy = hs * a.y + hr * b.y;
    return (x - s) * wy - y * wx;
  };
  const auto h0 = H(s0), h1 = H(1 - s0);
  const Vec2 val = a * h0[0] + b * h1[0], slope = a * h0[1] - b * h1[1];
  const double Fs = -val.y + (x.v - s0) * slope.y - y.v * slope.x;
  Dual2 s = s0;
  if (Fs == 0) return s;
  // Newton with the derivative frozen at the root: each step gains one order.
  for (int k = 0; k < 2; ++k) {
    Dual2 r = F(s);
    r.v = 0; // the value is the root already; keep it exact
    s = s - r * (1.0 / Fs);
  }
  return s;
}

Dual RegularDomain::linearSweepSideParameter(int i, Dual u, Dual v) const {
  Dual x, y;
  sideFrame(i, u, v, x, y);
  const Vec2 &a = a_, &b = b_;
  const Vec2 c = b - a;
  // (x, y) on the line from (s, 0) to a + s (1 + b − a): cross(E(s), X − A(s)) = 0,
  // i.e. (a_x y − a_y x) + s (a_y + c_x y − c_y x) + s² c_y = 0. In a regular
  // polygon the chord p_{i−1} p_{i+2} is parallel to side i, so c_y = 0.
  CURVENET_CHECK(std::abs(c.y) < 1e-9, "linear sweep expects a regular domain");
  return -(y * a.x - x * a.y) / (y * c.x + a.y);
}

void RegularDomain::wachspressDistances(Dual u, Dual v, std::span<Dual> distances) const {
  // Product form of the Wachspress weights: w_i ∏_j A_j = C_i ∏_{j ≠ i−1, i} A_j,
  // which stays finite on the sides where some A_j vanish ([VSR] Sec. 2.3).
  std::array<Dual, 16> area;
  for (int j = 0; j < n_; ++j) {
    // A_j = signed area of (p_j, q, p_{j+1}), positive inside.
    const Vec2 p = corner(j), e = corner(j + 1) - corner(j);
    area[j] = ((v - p.y) * e.x - (u - p.x) * e.y) * 0.5;
  }
  std::array<Dual, 16> weight;
  Dual total = 0.0;
  for (int i = 0; i < n_; ++i) {
    const double c = 0.5 * cross(corner(i) - corner(i - 1), corner(i + 1) - corner(i));
    Dual w = c;
    for (int j = 0; j < n_; ++j)
      if (j != wrap(i - 1) && j != i) w *= area[j];
    weight[i] = w;
    total += w;
  }
  CURVENET_CHECK(distances.size() >= static_cast<std::size_t>(n_), "wachspress: output shorter than the sides");
  for (int i = 0; i < n_; ++i) distances[i] = Dual(1.0) - (weight[i] + weight[wrap(i + 1)]) / total;
}

} // namespace v1
} // namespace curvenet
