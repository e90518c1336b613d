// Sweepline roots at arbitrary domain points of curvenet/kernels/kernels.hpp
// (hermiteSweepRoots, hermiteSweepRootsRobust): the side frame's quartic,
// the certified Newton solver and the robust derivative-cascade solver it
// falls back to. Written once over a Highway descriptor D (CappedTag<double,
// 1> the width-1 scalar reference); compiled once per target
// (foreach_target), dispatched at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sweep.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

#include "division-inl.h"
#include "loops-inl.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "curvenet/kernels/kernels.hpp"
#include "dispatch.hpp"

// Argument bundles, shared by every target's instance (defined once).
#ifndef CURVENET_SWEEP_ARGS
#define CURVENET_SWEEP_ARGS
namespace curvenet::kernels_impl {
namespace ck = curvenet::kernels;
struct SweepArgs {
  ck::SweepFrame frame;
  const double *x, *y;
  double *s, *d;
};

struct SweepGradientArgs {
  ck::SweepFrame frame;
  double ex, ey;
  const double *x, *y, *s;
  double *du, *dv;
};
} // namespace curvenet::kernels_impl
#endif

HWY_BEFORE_NAMESPACE();
namespace curvenet {
namespace kernels_impl {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace ck = curvenet::kernels;

/// Polynomial p(s) = Σ c_j s^j of degree ≤ 4, Horner.
template <class V> HWY_INLINE V horner(const V (&c)[5], V s) {
  return hn::MulAdd(hn::MulAdd(hn::MulAdd(hn::MulAdd(c[4], s, c[3]), s, c[2]), s, c[1]), s, c[0]);
}

/// p(s) = Σ c_j s^j of degree ≤ 3 (c[4] unread), Horner.
template <class V> HWY_INLINE V cubicHorner(const V (&c)[5], V s) {
  return hn::MulAdd(hn::MulAdd(hn::MulAdd(c[3], s, c[2]), s, c[1]), s, c[0]);
}

/// Root of p on [lo, hi] where p changes sign there (mask `found`), by
/// bisection to the last bit of [0, 1]; `lo` elsewhere.
template <class D, class V> HWY_INLINE V bisect(D d, const V (&p)[5], V lo, V hi, int iterations, decltype(hn::Lt(lo, lo)) &found) {
  const auto zero = hn::Zero(d);
  V flo = horner(p, lo);
  const V fhi = horner(p, hi);
  found = hn::AndNot(hn::Eq(flo, zero), hn::Xor(hn::Lt(flo, zero), hn::Lt(fhi, zero)));
  V a = lo, b = hi;
  const auto half = hn::Set(d, 0.5);
  for (int it = 0; it < iterations; ++it) {
    const V mid = hn::Mul(half, hn::Add(a, b));
    const V fm = horner(p, mid);
    const auto keepSign = hn::Not(hn::Xor(hn::Lt(fm, zero), hn::Lt(flo, zero)));
    a = hn::IfThenElse(keepSign, mid, a);
    flo = hn::IfThenElse(keepSign, fm, flo);
    b = hn::IfThenElse(keepSign, b, mid);
  }
  return hn::IfThenElse(found, hn::Mul(half, hn::Add(a, b)), lo);
}

/// F(s) = (x − s) w_y(s) − y w_x(s) of a side frame at points (x, y): its
/// power-basis coefficients and what both solvers need besides.
template <class D, class V = hn::Vec<D>> struct SweepQuartic {
  V cx, cy, bx, by;
  V F[5];
  HWY_INLINE SweepQuartic(D d, const ck::SweepFrame &f, V x, V y) {
    const V ax = hn::Set(d, f.ax), ay = hn::Set(d, f.ay);
    bx = hn::Set(d, f.bx), by = hn::Set(d, f.by);
    cx = hn::Sub(ax, bx), cy = hn::Sub(ay, by);
    // w(s) = b + c H(s) because H(1 − s) = 1 − H(s) for the cubic Hermite, so
    // F(s) = (A0 + A1 s) + (B0 + B1 s) H(s) with the coefficients below.
    const V A0 = hn::Sub(hn::Mul(x, by), hn::Mul(y, bx)), A1 = hn::Neg(by);
    const V B0 = hn::Sub(hn::Mul(x, cy), hn::Mul(y, cx)), B1 = hn::Neg(cy);
    F[0] = hn::Add(A0, B0), F[1] = hn::Add(A1, B1), F[2] = hn::Mul(hn::Set(d, -3.0), B0);
    F[3] = hn::Sub(hn::Add(B0, B0), hn::Mul(hn::Set(d, 3.0), B1)), F[4] = hn::Add(B1, B1);
  }
  /// The distance parameter d of root s: (x, y) = (s, 0) + d w(s); also
  /// w(s) and w'(s) for the orientation test.
  HWY_INLINE V distance(D d, V x, V y, V s, V &wx, V &wy, V &sx, V &sy) const {
    const V one = hn::Set(d, 1.0), two = hn::Set(d, 2.0), six = hn::Set(d, 6.0);
    // H(s) = 2s³ − 3s² + 1, H'(s) = 6s² − 6s
    const V H = hn::MulAdd(hn::Mul(s, s), hn::MulAdd(two, s, hn::Set(d, -3.0)), one);
    const V dH = hn::Mul(six, hn::Mul(s, hn::Sub(s, one)));
    wx = hn::MulAdd(cx, H, bx), wy = hn::MulAdd(cy, H, by);
    sx = hn::Mul(cx, dH), sy = hn::Mul(cy, dH);
    // One division: the larger component's quotient.
    const auto alongX = hn::Gt(hn::Abs(wx), hn::Abs(wy));
    return hn::Div(hn::IfThenElse(alongX, hn::Sub(x, s), y), hn::IfThenElse(alongX, wx, wy));
  }
};

/// The radial parameter of (x, y): where the line from the apex (or, for
/// parallel neighbours, along a) through the point meets the side. As a
/// start for Newton (Estimate) its quotient may be newtonQuotient's.
template <bool Estimate = false, class D, class V = hn::Vec<D>> HWY_INLINE V sweepRadial(D d, const ck::SweepFrame &f, V x, V y) {
  if (f.parallel) return hn::Sub(x, hn::Mul(y, hn::Set(d, f.ax / f.ay)));
  const V px = hn::Set(d, f.apexX), py = hn::Set(d, f.apexY);
  const V a = hn::Mul(py, hn::Sub(x, px)), b = hn::Sub(y, py);
  return hn::Sub(px, Estimate ? newtonQuotient<1>(d, a, b) : hn::Div(a, b));
}

/// The frame's factor of sweepEndTolerance, 1e-13 (|a| + |b|): computed once
/// per call of a solver, not per vector (two scalar square roots).
HWY_INLINE double sweepEndScale(const ck::SweepFrame &f) {
  // Plain square roots: the frame's vectors are of domain size (no overflow
  // to guard against), and std::hypot cost 5% of a batch here.
  return 1e-13 * (std::sqrt(f.ax * f.ax + f.ay * f.ay) + std::sqrt(f.bx * f.bx + f.by * f.by));
}

/// |F| at an end of [0, 1] below which the robust solver takes that end as a
/// root: a point on a neighbouring side may show no sign change after
/// rounding. endScale: sweepEndScale of the frame.
template <class D, class V = hn::Vec<D>> HWY_INLINE V sweepEndTolerance(D d, double endScale, V x, V y) {
  return hn::Mul(hn::Set(d, endScale), hn::Add(hn::Set(d, 1.0), hn::Add(hn::Abs(x), hn::Abs(y))));
}

/// Robust solver: isolates every root on [0, 1] by the derivative cascade,
/// bisects each, then applies the selection rule. About 230 polynomial
/// evaluations per point; the fast path's fallback.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void sweepRobust(D d, const ck::SweepFrame &f, double endScale, V x, V y, V &best, V &bestD) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const SweepQuartic<D> q(d, f, x, y);
  const V(&F)[5] = q.F;
  const V F1[5] = {F[1], hn::Add(F[2], F[2]), hn::Mul(hn::Set(d, 3.0), F[3]), hn::Mul(hn::Set(d, 4.0), F[4]), zero};
  const V F2[5] = {F1[1], hn::Add(F1[2], F1[2]), hn::Mul(hn::Set(d, 3.0), F1[3]), zero, zero};
  // Derivative cascade: the root of F''' (linear) splits [0, 1] where F'' is
  // monotone, F'' roots where F' is, F' roots where F is; each monotone
  // piece holds at most one root.
  const auto hasCubic = hn::Gt(hn::Abs(F2[2]), hn::Set(d, 1e-300));
  const V r3 = hn::IfThenElse(hasCubic, hn::Min(one, hn::Max(zero, hn::Div(hn::Neg(F2[1]), hn::Add(F2[2], F2[2])))),
                              zero);
  decltype(hn::Lt(x, x)) found;
  const V r2a = bisect(d, F2, zero, r3, 40, found);
  const V r2b = bisect(d, F2, r3, one, 40, found);
  // With no root a piece returns its start, so the breakpoints stay sorted.
  const V r1a = bisect(d, F1, zero, r2a, 40, found);
  const V r1b = bisect(d, F1, r2a, r2b, 40, found);
  const V r1c = bisect(d, F1, r2b, one, 40, found);
  const V bp[5] = {zero, r1a, r1b, r1c, one};

  // Candidate rule of the scalar solver: d ≥ 0, orientation-preserving
  // preferred, nearest the radial parameter.
  const V radial = sweepRadial(d, f, x, y);
  best = hn::Set(d, -1.0), bestD = zero;
  V bestScore = hn::Set(d, INFINITY);
  const V two = hn::Set(d, 2.0);
  auto consider = [&](V s, decltype(found) valid) {
    V wx, wy, sx, sy;
    const V dist = q.distance(d, x, y, s, wx, wy, sx, sy);
    const V jac = hn::Sub(hn::Mul(hn::MulAdd(dist, sx, one), wy), hn::Mul(hn::Mul(dist, sy), wx));
    const V penalty = hn::IfThenElse(hn::Gt(jac, hn::Set(d, 1e-9)), zero, two);
    const V score = hn::Add(hn::Abs(hn::Sub(s, radial)), penalty);
    const auto take = hn::And(hn::And(valid, hn::Ge(dist, hn::Set(d, -1e-9))), hn::Lt(score, bestScore));
    best = hn::IfThenElse(take, s, best);
    bestD = hn::IfThenElse(take, dist, bestD);
    bestScore = hn::IfThenElse(take, score, bestScore);
  };
  const V tolerance = sweepEndTolerance(d, endScale, x, y);
  consider(zero, hn::Le(hn::Abs(horner(F, zero)), tolerance));
  consider(one, hn::Le(hn::Abs(horner(F, one)), tolerance));
  for (int j = 0; j < 4; ++j) {
    const V root = bisect(d, F, bp[j], bp[j + 1], 56, found);
    consider(root, found);
  }
  const auto none = hn::Lt(best, zero);
  if (!hn::AllFalse(d, none)) {
    // Outside the domain: the nearest base point, as the scalar solver does.
    const V s = hn::Min(one, hn::Max(zero, x));
    V wx, wy, sx, sy;
    const V dist = q.distance(d, x, y, s, wx, wy, sx, sy);
    best = hn::IfThenElse(none, s, best);
    bestD = hn::IfThenElse(none, dist, bestD);
  }
}

/// A mask over the lanes of D (one per point).
template <class D, class V = hn::Vec<D>> using SweepMask = decltype(hn::Lt(V(), V()));

/// sweepFast's Newton iteration for G vectors of points at once, their F
/// and F' given: r the iterates, `converged` per lane. The vectors' chains
/// of dependent operations (a Horner evaluation and a division per step)
/// overlap in the pipeline instead of each waiting for the previous one's
/// latency; a lane freezes once converged, so its result does not depend on
/// the other lanes nor on G.
template <int G, class D, class V = hn::Vec<D>>
HWY_INLINE void sweepNewton(D d, const ck::SweepFrame &f, const V (&x)[G], const V (&y)[G], const V (&F)[G][5],
                            const V (&F1)[G][5], V (&r)[G], SweepMask<D> (&converged)[G]) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  constexpr int kIterations = 16;
  // Four plain steps: after them one guarded step certifies almost every
  // lane at arbitrary points of the pentagon and of cagd86.lop, where after
  // three a lane of the four vectors mostly needed a second (a guarded step
  // costs about three plain ones). Batch positions 3-6 % faster than with
  // three on Zen 4 (engine_bench BatchPositions, alternating runs); three
  // had measured best on the kernel's own grid of points on Intel.
  constexpr int kPlainSteps = 4;
  const V stepLimit = hn::Set(d, 1e-15), half = hn::Set(d, 0.5);
  // The radial sweep is the Hermite sweep's first-order approximation: few
  // steps. The bracket [lo, hi] keeps the sign change of F (a certified
  // lane has one: F(0) and F(1) differ in sign when the root is unique and
  // away from the ends); a Newton step leaving it is replaced by bisection.
  V lo[G], hi[G], start[G];
  SweepMask<D> negativeAtZero[G];
  for (int g = 0; g < G; ++g) {
    r[g] = hn::Min(one, hn::Max(zero, sweepRadial<true>(d, f, x[g], y[g])));
    r[g] = hn::IfThenElse(hn::Eq(r[g], r[g]), r[g], half); // the apex itself: no radial direction
    start[g] = r[g];
    lo[g] = zero, hi[g] = one;
    negativeAtZero[g] = hn::Lt(F[g][0], zero);
    converged[g] = hn::Lt(zero, zero);
  }
  // Plain Newton steps first: from the radial parameter they stay in [0, 1]
  // on almost every point, and a step without the bracket's bookkeeping
  // costs a third of a guarded one. Their count is fixed, so a lane's
  // iterate does not depend on the other lanes. A lane they leave outside
  // [0, 1] (or not a number, where F' vanished) starts the guarded steps
  // from the radial parameter instead; the guarded steps and the
  // certificate decide either way.
  for (int it = 0; it < kPlainSteps; ++it)
    for (int g = 0; g < G; ++g) r[g] = hn::Sub(r[g], newtonQuotient<1>(d, horner(F[g], r[g]), cubicHorner(F1[g], r[g])));
  for (int g = 0; g < G; ++g) {
    const auto inside = hn::And(hn::Ge(r[g], zero), hn::Le(r[g], one));
    r[g] = hn::IfThenElse(inside, r[g], start[g]);
  }
  for (int it = 0; it < kIterations; ++it) {
    bool all = true;
    for (int g = 0; g < G; ++g) {
      const V value = horner(F[g], r[g]);
      const auto belowLo = hn::Not(hn::Xor(hn::Lt(value, zero), negativeAtZero[g]));
      lo[g] = hn::IfThenElse(belowLo, r[g], lo[g]);
      hi[g] = hn::IfThenElse(belowLo, hi[g], r[g]);
      const V step = newtonQuotient<2>(d, value, cubicHorner(F1[g], r[g]));
      const V newton = hn::Sub(r[g], step);
      const auto inside = hn::And(hn::Ge(newton, lo[g]), hn::Le(newton, hi[g]));
      r[g] = hn::IfThenElse(converged[g], r[g], hn::IfThenElse(inside, newton, hn::Mul(half, hn::Add(lo[g], hi[g]))));
      converged[g] = hn::Or(converged[g], hn::And(inside, hn::Le(hn::Abs(step), stepLimit)));
      all = all && hn::AllTrue(d, converged[g]);
    }
    if (all) break;
  }
}

/// Fast solver: safeguarded Newton from the radial parameter, then a
/// certificate that the root found is the one the robust solver selects,
/// for G vectors of points (x, y) at once (sweepNewton). Sets ok to the
/// lanes that hold it (s, dist written); the others need the robust solver.
/// About 15 polynomial evaluations and 7 quotients per point, on AVX-512 all
/// but the distance's from refined reciprocal estimates (newtonQuotient).
///
/// Certificate, per lane:
///  * Newton converged: a step |Δs| ≤ 1e-15 inside the bracket of F's sign
///    change (steps leaving it are replaced by bisection; the lane's iterate
///    freezes once converged, so the result does not depend on the other
///    lanes of the vector);
///  * the root r is the only one on [0, 1]: F(s) = (s − r) G(s) + F(r) with
///    the cubic G from synthetic division. If G's Bernstein coefficients on
///    [0, 1] (or, failing that, on [0, ½] and [½, 1]) share a sign, |G| is
///    bounded below on each half by them (a Bernstein polynomial is a
///    convex combination of its coefficients); with the distance from r to
///    each half (at least ρ = 1e-13) this bounds
///    |s − r| |G(s)| away from F(r) plus rounding, so every sign change of
///    the computed F lies within 1e-13 of r: one root, the one the robust
///    solver isolates;
///  * neither end of [0, 1] passes the robust solver's end tolerance (else
///    that end would be a second candidate);
///  * d ≥ −1e-9 with a margin: the unique root is then the selection.
template <int G, class D, class V = hn::Vec<D>>
HWY_INLINE void sweepFast(D d, const ck::SweepFrame &f, double endScale, const V (&x)[G], const V (&y)[G], V (&s)[G],
                          V (&dist)[G], SweepMask<D> (&ok)[G]) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0), half = hn::Set(d, 0.5);
  V F[G][5], F1[G][5];
  for (int g = 0; g < G; ++g) {
    const SweepQuartic<D> q(d, f, x[g], y[g]);
    for (int j = 0; j < 5; ++j) F[g][j] = q.F[j];
    F1[g][0] = F[g][1], F1[g][1] = hn::Add(F[g][2], F[g][2]), F1[g][2] = hn::Mul(hn::Set(d, 3.0), F[g][3]);
    F1[g][3] = hn::Mul(hn::Set(d, 4.0), F[g][4]), F1[g][4] = zero;
  }
  V root[G];
  SweepMask<D> converged[G];
  sweepNewton<G>(d, f, x, y, F, F1, root, converged);
  for (int g = 0; g < G; ++g) {
    const V(&Fg)[5] = F[g];
    const V r = root[g];
    // Deflation F = (s − r) G + F(r) and G's Bernstein coefficients on [0, 1].
    const V g3 = Fg[4], g2 = hn::MulAdd(r, g3, Fg[3]), g1 = hn::MulAdd(r, g2, Fg[2]), g0 = hn::MulAdd(r, g1, Fg[1]);
    const V third = hn::Set(d, 1.0 / 3.0);
    const V b1 = hn::MulAdd(third, g1, g0), b2 = hn::MulAdd(third, hn::Add(g1, hn::Add(g1, g2)), g0);
    const V b3 = hn::Add(hn::Add(g0, g1), hn::Add(g2, g3));
    V scale = hn::Abs(Fg[0]);
    for (int j = 1; j < 5; ++j) scale = hn::Add(scale, hn::Abs(Fg[j]));
    // Another sign change of the computed F at s needs |s − r| |G(s)| ≤ E =
    // |F(r)| + 8 ε Σ|F_j| (Horner's error bound). On a half at distance δ from
    // r, |s − r| ≥ max(δ, ρ) for the s farther than ρ = 1e-13 from r: so if
    // m max(δ, ρ) > E on both halves, every root lies within ρ of r. The floor
    // on m keeps it far above the rounding of G's coefficients.
    const V E = hn::MulAdd(hn::Set(d, 8 * 2.220446049250313e-16), scale, hn::Abs(horner(Fg, r)));
    const V rho = hn::Set(d, 1e-13), floor = hn::Mul(hn::Set(d, 1e-10), scale);
    // |G| ≥ m on [0, 1] from the hull of all four coefficients, with ρ as the
    // distance on both halves: where that certifies every lane (nearly
    // always for n ≥ 4) the split below would too — its halves' control
    // points are convex combinations of these and their distances at least ρ
    // — so it is skipped with the same result.
    const V lowAll = hn::Min(hn::Min(g0, b1), hn::Min(b2, b3)), highAll = hn::Max(hn::Max(g0, b1), hn::Max(b2, b3));
    const auto positiveAll = hn::Gt(lowAll, zero);
    const V mAll = hn::IfThenElse(positiveAll, lowAll, hn::Neg(highAll));
    auto unique = hn::And(hn::Or(positiveAll, hn::Lt(highAll, zero)),
                          hn::And(hn::Gt(hn::Mul(mAll, rho), E), hn::Gt(mAll, floor)));
    if (HWY_UNLIKELY(!hn::AllTrue(d, unique))) {
      // One de Casteljau split at ½ tightens the hull (the control points of
      // the halves are convex combinations of these): it certifies most
      // triangle points whose quotient dips towards zero without a root.
      const V l1 = hn::Mul(half, hn::Add(g0, b1)), c = hn::Mul(half, hn::Add(b1, b2)), r2 = hn::Mul(half, hn::Add(b2, b3));
      const V l2 = hn::Mul(half, hn::Add(l1, c)), r1 = hn::Mul(half, hn::Add(c, r2)), mid = hn::Mul(half, hn::Add(l2, r1));
      const V lowLeft = hn::Min(hn::Min(g0, l1), hn::Min(l2, mid)), lowRight = hn::Min(hn::Min(mid, r1), hn::Min(r2, b3));
      const V highLeft = hn::Max(hn::Max(g0, l1), hn::Max(l2, mid)), highRight = hn::Max(hn::Max(mid, r1), hn::Max(r2, b3));
      const auto positive = hn::Gt(hn::Min(lowLeft, lowRight), zero), negative = hn::Lt(hn::Max(highLeft, highRight), zero);
      // |G| ≥ m on each half (with G's sign).
      const V mLeft = hn::IfThenElse(positive, lowLeft, hn::Neg(highLeft));
      const V mRight = hn::IfThenElse(positive, lowRight, hn::Neg(highRight));
      const V reachLeft = hn::Max(hn::Sub(r, half), rho), reachRight = hn::Max(hn::Sub(half, r), rho);
      unique = hn::And(hn::Or(positive, negative),
                       hn::And(hn::And(hn::Gt(hn::Mul(mLeft, reachLeft), E), hn::Gt(hn::Mul(mRight, reachRight), E)),
                               hn::And(hn::Gt(mLeft, floor), hn::Gt(mRight, floor))));
    }
    const V tolerance = sweepEndTolerance(d, endScale, x[g], y[g]);
    const auto endsClear = hn::And(hn::Gt(hn::Abs(Fg[0]), tolerance), hn::Gt(hn::Abs(horner(Fg, one)), tolerance));
    const SweepQuartic<D> q(d, f, x[g], y[g]);
    V wx, wy, sx, sy;
    dist[g] = q.distance(d, x[g], y[g], r, wx, wy, sx, sy);
    s[g] = r;
    ok[g] = hn::And(hn::And(converged[g], unique), hn::And(endsClear, hn::Ge(dist[g], hn::Set(d, -0.999e-9))));
  }
}

/// endScale: sweepEndScale(a.frame), taken once by the caller.
template <class D> HWY_INLINE void sweepRobustBody(D d, std::size_t k, const SweepArgs &a, double endScale) {
  hn::Vec<D> s, dist;
  sweepRobust(d, a.frame, endScale, hn::LoadU(d, a.x + k), hn::LoadU(d, a.y + k), s, dist);
  hn::StoreU(s, d, a.s + k);
  hn::StoreU(dist, d, a.d + k);
}

/// The fast solver over [0, count) in chunks, kGroup vectors at a time
/// (sweepFast); the lanes it cannot certify are gathered per chunk and
/// solved by the robust solver at full width, so its cost scales with the
/// failing points, not with the vectors they fall in. Returns the number of
/// such points.
template <class D> HWY_INLINE std::size_t sweepFastThenRobust(D d, std::size_t count, const SweepArgs &a) {
  constexpr std::size_t kChunk = 256;
  // Four vectors' Newton chains in flight: on AVX-512 the batch of positions
  // at arbitrary points took 24% less time than with one (two: 20%, eight:
  // no better than four).
  constexpr int kGroup = 4;
  double fx[kChunk], fy[kChunk], fs[kChunk], fd[kChunk];
  std::size_t index[kChunk];
  std::size_t total = 0;
  const std::size_t lanes = hn::Lanes(d);
  const double endScale = sweepEndScale(a.frame);
  for (std::size_t begin = 0; begin < count; begin += kChunk) {
    const std::size_t end = std::min(count, begin + kChunk);
    std::size_t failed = 0;
    auto group = [&]<int G>(auto dd, std::size_t k) {
      using DD = decltype(dd);
      using V = hn::Vec<DD>;
      const std::size_t width = hn::Lanes(dd);
      V x[G], y[G], s[G], dist[G];
      SweepMask<DD> ok[G];
      for (int g = 0; g < G; ++g) x[g] = hn::LoadU(dd, a.x + k + g * width), y[g] = hn::LoadU(dd, a.y + k + g * width);
      sweepFast<G>(dd, a.frame, endScale, x, y, s, dist, ok);
      for (int g = 0; g < G; ++g) {
        const std::size_t at = k + g * width;
        hn::StoreU(s[g], dd, a.s + at);
        hn::StoreU(dist[g], dd, a.d + at);
        if (HWY_UNLIKELY(!hn::AllTrue(dd, ok[g]))) {
          std::uint8_t bits[16] = {};
          hn::StoreMaskBits(dd, hn::Not(ok[g]), bits);
          for (std::size_t j = 0; j < width; ++j)
            if ((bits[j >> 3] >> (j & 7)) & 1) index[failed] = at + j, fx[failed] = a.x[at + j], fy[failed++] = a.y[at + j];
        }
      }
    };
    std::size_t k = begin;
    for (; k + kGroup * lanes <= end; k += kGroup * lanes) group.template operator()<kGroup>(d, k);
    for (; k + lanes <= end; k += lanes) group.template operator()<1>(d, k);
    for (; k < end; ++k) group.template operator()<1>(hn::CappedTag<double, 1>(), k);
    if (failed == 0) continue;
    const SweepArgs gathered{a.frame, fx, fy, fs, fd};
    forEachVector(d, failed, [&](auto dd, std::size_t j) { sweepRobustBody(dd, j, gathered, endScale); });
    for (std::size_t j = 0; j < failed; ++j) a.s[index[j]] = fs[j], a.d[index[j]] = fd[j];
    total += failed;
  }
  return total;
}

template <class D> HWY_INLINE void sweepGradientBody(D d, std::size_t k, const SweepGradientArgs &a) {
  using V = hn::Vec<D>;
  const ck::SweepFrame &f = a.frame;
  const V one = hn::Set(d, 1.0), two = hn::Set(d, 2.0), three = hn::Set(d, 3.0), six = hn::Set(d, 6.0);
  const V r = hn::LoadU(d, a.s + k), x = hn::LoadU(d, a.x + k), y = hn::LoadU(d, a.y + k), q = hn::Sub(one, r);
  // w(s) = a H(s) + b H(1 − s) and w'(s), H(s) = 2s³ − 3s² + 1.
  const V r2 = hn::Mul(r, r), q2 = hn::Mul(q, q);
  const V h0 = hn::Add(hn::Sub(hn::Mul(two, hn::Mul(r2, r)), hn::Mul(three, r2)), one);
  const V h1 = hn::Add(hn::Sub(hn::Mul(two, hn::Mul(q2, q)), hn::Mul(three, q2)), one);
  const V d0 = hn::Sub(hn::Mul(six, r2), hn::Mul(six, r)), d1 = hn::Sub(hn::Mul(six, q2), hn::Mul(six, q));
  const V ax = hn::Set(d, f.ax), ay = hn::Set(d, f.ay), bx = hn::Set(d, f.bx), by = hn::Set(d, f.by);
  const V wx = hn::Add(hn::Mul(ax, h0), hn::Mul(bx, h1)), wy = hn::Add(hn::Mul(ay, h0), hn::Mul(by, h1));
  const V slopeX = hn::Sub(hn::Mul(ax, d0), hn::Mul(bx, d1)), slopeY = hn::Sub(hn::Mul(ay, d0), hn::Mul(by, d1));
  // F_s = −w_y + (x − s) w_y' − y w_x'.
  const V Fs = hn::Sub(hn::Add(hn::Neg(wy), hn::Mul(hn::Sub(x, r), slopeY)), hn::Mul(y, slopeX));
  const auto regular = hn::Ne(Fs, hn::Zero(d));
  const V inverse = hn::IfThenElseZero(regular, hn::Div(one, hn::IfThenElse(regular, Fs, one)));
  const V sx = hn::Mul(hn::Neg(wy), inverse), sy = hn::Mul(wx, inverse);
  const V ex = hn::Set(d, a.ex), ey = hn::Set(d, a.ey);
  hn::StoreU(hn::Sub(hn::Mul(sx, ex), hn::Mul(sy, ey)), d, a.du + k);
  hn::StoreU(hn::Add(hn::Mul(sx, ey), hn::Mul(sy, ex)), d, a.dv + k);
}

void SweepGradients(std::size_t count, const SweepGradientArgs &args, bool reference) {
  auto body = [&](auto d, std::size_t k) { sweepGradientBody(d, k, args); };
  if (reference) forEachVector(hn::CappedTag<double, 1>(), count, body);
  else forEachVector(hn::ScalableTag<double>(), count, body);
}

std::size_t SweepRoots(std::size_t count, const SweepArgs &args, bool reference) {
  if (reference) return sweepFastThenRobust(hn::CappedTag<double, 1>(), count, args);
  return sweepFastThenRobust(hn::ScalableTag<double>(), count, args);
}

void SweepRootsRobust(std::size_t count, const SweepArgs &args, bool reference) {
  const double endScale = sweepEndScale(args.frame);
  auto body = [&](auto d, std::size_t k) { sweepRobustBody(d, k, args, endScale); };
  if (reference) forEachVector(hn::CappedTag<double, 1>(), count, body);
  else forEachVector(hn::ScalableTag<double>(), count, body);
}

} // namespace HWY_NAMESPACE
} // namespace kernels_impl
} // namespace curvenet
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace curvenet {
namespace kernels_impl {
HWY_EXPORT(SweepRoots);
HWY_EXPORT(SweepRootsRobust);
HWY_EXPORT(SweepGradients);
} // namespace kernels_impl

inline namespace v1 {
namespace kernels {
using namespace curvenet::kernels_impl;

std::size_t hermiteSweepRoots(std::size_t count, const SweepFrame &frame, const double *x, const double *y, double *s,
                              double *d, std::int64_t width) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  return HWY_DISPATCH_TABLE(SweepRoots)[index](count, {frame, x, y, s, d}, reference);
}

void hermiteSweepRootsRobust(std::size_t count, const SweepFrame &frame, const double *x, const double *y, double *s,
                             double *d, std::int64_t width) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  HWY_DISPATCH_TABLE(SweepRootsRobust)[index](count, {frame, x, y, s, d}, reference);
}

void hermiteSweepGradients(std::size_t count, const SweepFrame &frame, double ex, double ey, const double *x,
                           const double *y, const double *s, double *du, double *dv, std::int64_t width) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  HWY_DISPATCH_TABLE(SweepGradients)[index](count, {frame, ex, ey, x, y, s, du, dv}, reference);
}

} // namespace kernels
} // namespace v1
} // namespace curvenet
#endif
