// B-spline curves (curvenet/curve.hpp): evaluation, knot insertion, arc length,
// projection and interpolation. Algorithm numbers refer to Piegl & Tiller,
// "The NURBS Book" (2nd ed.).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "curvenet/curve.hpp"
#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

constexpr int kMaxOrder = BSplineCurve::maxDegree + 1;

[[noreturn]] void fail(const std::string &reason) { throw InputError("", "curve", reason); }

// A control point in homogeneous form (w·P, w); rational algorithms (knot
// insertion, derivatives) are linear in these coordinates.
struct Homogeneous {
  Vec3 p;
  double w = 1;
};

// Nonzero basis functions and their derivatives up to order `n` at t in span
// `span` (Algorithm A2.3). ders[k][j] = d^k N_{span-p+j,p}(t)/dt^k. Fixed-size
// scratch keeps evaluation free of heap allocation.
void basisDerivatives(int span, double t, int p, int n, std::span<const double> U,
                      std::array<std::array<double, kMaxOrder>, 4> &ders) {
  // Uninitialized on purpose: the algorithm (Piegl–Tiller A2.3) reads only the
  // entries it has written, and zeroing 16×16 doubles per call dominated ribbon evaluation.
  std::array<std::array<double, kMaxOrder>, kMaxOrder> ndu;
  std::array<double, kMaxOrder> left{}, right{};
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - U[span + 1 - j];
    right[j] = U[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r]; // lower triangle: knot differences
      double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (int j = 0; j <= p; ++j) ders[0][j] = ndu[j][p];
  std::array<std::array<double, kMaxOrder>, 2> a{};
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= n; ++k) {
      double d = 0.0;
      int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      int j1 = rk >= -1 ? 1 : -rk;
      int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k][r] = d;
      std::swap(s1, s2);
    }
  }
  int factor = p;
  for (int k = 1; k <= n; ++k) {
    for (int j = 0; j <= p; ++j) ders[k][j] *= factor;
    factor *= (p - k);
  }
}

// Span index for knot vector U of a clamped curve with `count` control points:
// U[span] <= t < U[span+1], the last non-empty span for t at the domain end.
/// Derivatives of C = A / w from the homogeneous ones, by the Leibniz rule on
/// A = w·C (Piegl–Tiller eq. 4.8): C^(k) = (A^(k) − Σ_{i=1..k} binom(k,i) w^(i) C^(k−i)) / w.
std::array<Vec3, 4> rationalDerivatives(const std::array<Vec3, 4> &A, const double *W) {
  static constexpr int binom[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
  std::array<Vec3, 4> C{};
  for (int k = 0; k <= 3; ++k) {
    Vec3 v = A[k];
    for (int i = 1; i <= k; ++i) v -= (binom[k][i] * W[i]) * C[k - i];
    C[k] = v / W[0];
  }
  return C;
}

int spanOf(std::span<const double> U, int p, int count, double t) {
  // NaN compares false with everything and would walk past the last span:
  // keep it in range (the caller's result is NaN anyway).
  if (std::isnan(t)) t = U[p];
  if (t >= U[count]) {
    int s = count - 1;
    while (s > p && U[s] >= U[s + 1]) --s;
    return s;
  }
  if (t <= U[p]) {
    int s = p;
    while (s < count - 1 && U[s + 1] <= U[p]) ++s;
    return s;
  }
  // upper_bound over [p+1, count] finds the first knot > t.
  auto it = std::upper_bound(U.begin() + p + 1, U.begin() + count + 1, t);
  return static_cast<int>(it - U.begin()) - 1;
}

// The Taylor coefficients at x of the polynomial f(x) = Σ_j c[j] x^j of degree
// P, up to order M: out[k] = f^(k)(x) / k!, by repeated synthetic division
// (Horner's scheme applied M + 1 times, O(P M) operations per component).
// Dim = 3 for polynomial curves, 4 (with the weight) for rational ones.
template <int P, int Dim, int M>
inline void taylorAt(const std::array<double, 4> *c, double x, double (&out)[M + 1][4]) {
  double b[P + 1][Dim];
  for (int j = 0; j <= P; ++j)
    for (int d = 0; d < Dim; ++d) b[j][d] = c[j][d];
  for (int k = 0; k <= M; ++k) {
    if (k > P) {
      for (int d = 0; d < Dim; ++d) out[k][d] = 0.0;
      continue;
    }
    for (int j = P - 1; j >= k; --j)
      for (int d = 0; d < Dim; ++d) b[j][d] += x * b[j + 1][d];
    for (int d = 0; d < Dim; ++d) out[k][d] = b[k][d];
  }
}

template <int M>
void taylorAt(int p, bool rational, const std::array<double, 4> *c, double x, double (&out)[M + 1][4]) {
#define CURVENET_TAYLOR_CASE(P)                                                                                \
  case P:                                                                                                      \
    return rational ? taylorAt<P, 4, M>(c, x, out) : taylorAt<P, 3, M>(c, x, out);
  switch (p) {
    CURVENET_TAYLOR_CASE(1)
    CURVENET_TAYLOR_CASE(2)
    CURVENET_TAYLOR_CASE(3)
    CURVENET_TAYLOR_CASE(4)
    CURVENET_TAYLOR_CASE(5)
    CURVENET_TAYLOR_CASE(6)
    CURVENET_TAYLOR_CASE(7)
    CURVENET_TAYLOR_CASE(8)
    CURVENET_TAYLOR_CASE(9)
    CURVENET_TAYLOR_CASE(10)
  default:
    __builtin_unreachable(); // callers use the Taylor form only up to fastDegree
  }
#undef CURVENET_TAYLOR_CASE
}
static_assert(BSplineCurve::fastDegree == 10, "taylorAt has one case per degree up to fastDegree");

// Boehm insertion of knot u once into (U, P) in homogeneous form (Algorithm A5.1, r = 1).
void insertKnot(int p, std::vector<double> &U, std::vector<Homogeneous> &P, double u) {
  int count = static_cast<int>(P.size());
  int k = spanOf(U, p, count, u);
  std::vector<Homogeneous> Q(count + 1);
  for (int i = 0; i <= k - p; ++i) Q[i] = P[i];
  for (int i = k; i < count; ++i) Q[i + 1] = P[i];
  for (int i = k - p + 1; i <= k; ++i) {
    double alpha = (u - U[i]) / (U[i + p] - U[i]);
    Q[i].p = alpha * P[i].p + (1.0 - alpha) * P[i - 1].p;
    Q[i].w = alpha * P[i].w + (1.0 - alpha) * P[i - 1].w;
  }
  U.insert(U.begin() + k + 1, u);
  P = std::move(Q);
}

// 16-point Gauss–Legendre nodes/weights on [-1, 1] (positive half).
constexpr std::array<double, 8> kGaussX = {0.0950125098376374401853193, 0.2816035507792589132304605,
                                           0.4580167776572273863424194, 0.6178762444026437484466718,
                                           0.7554044083550030338951012, 0.8656312023878317438804679,
                                           0.9445750230732325760779884, 0.9894009349916499325961542};
constexpr std::array<double, 8> kGaussW = {0.1894506104550684962853967, 0.1826034150449235888667637,
                                           0.1691565193950025381893121, 0.1495959888165767320815017,
                                           0.1246289712555338720524763, 0.0951585116824927848099251,
                                           0.0622535239386478928628438, 0.0271524594117540948517806};

} // namespace

BSplineCurve::BSplineCurve(int degree, std::vector<double> knots, std::vector<Vec3> controlPoints,
                           std::vector<double> weights)
    : degree_(degree), knots_(std::move(knots)), points_(std::move(controlPoints)), weights_(std::move(weights)) {
  if (degree_ < 1 || degree_ > maxDegree)
    fail("degree " + std::to_string(degree_) + " outside [1, " + std::to_string(maxDegree) + "]");
  if (points_.size() < static_cast<size_t>(degree_) + 1)
    fail("needs at least degree + 1 = " + std::to_string(degree_ + 1) + " control points, got " +
         std::to_string(points_.size()));
  if (knots_.size() != points_.size() + degree_ + 1)
    fail("knot count " + std::to_string(knots_.size()) + " != control points + degree + 1 = " +
         std::to_string(points_.size() + degree_ + 1));
  if (!weights_.empty() && weights_.size() != points_.size())
    fail("weight count " + std::to_string(weights_.size()) + " != control point count " +
         std::to_string(points_.size()));
  for (double k : knots_)
    if (!std::isfinite(k)) fail("non-finite knot");
  for (const Vec3 &q : points_)
    if (!isFinite(q)) fail("non-finite control point");
  for (double w : weights_)
    if (!std::isfinite(w) || !(w > 0)) fail("weights must be finite and positive");
  for (size_t i = 1; i < knots_.size(); ++i)
    if (knots_[i] < knots_[i - 1]) fail("knots decrease at index " + std::to_string(i));
  const size_t last = knots_.size() - 1;
  for (int i = 1; i <= degree_; ++i)
    if (knots_[i] != knots_[0] || knots_[last - i] != knots_[last])
      fail("knot vector is not clamped (end knots need multiplicity degree + 1)");
  if (!(domainEnd() > domainStart())) fail("zero-length parameter domain");
  // Interior multiplicity above the degree would disconnect the curve.
  for (size_t i = degree_ + 1, run = 1; i + degree_ + 1 < knots_.size(); ++i) {
    run = knots_[i] == knots_[i - 1] ? run + 1 : 1;
    if (run > static_cast<size_t>(degree_)) fail("interior knot multiplicity exceeds the degree");
  }
  buildSpans();
}

void BSplineCurve::buildSpans() {
  const int p = degree_, count = static_cast<int>(points_.size());
  const std::vector<double> &U = knots_;
  breaks_.clear();
  taylor_.clear();
  breaks_.push_back(domainStart());
  for (int k = p; k < count; ++k)
    if (U[k + 1] > U[k]) breaks_.push_back(U[k + 1]);
  if (p > fastDegree) return;
  taylor_.reserve(2 * (breaks_.size() - 1) * (p + 1));
  // Homogeneous control points (w·P, w); for polynomial curves w = 1 exactly.
  auto homogeneous = [&](int i) {
    const double w = weights_.empty() ? 1.0 : weights_[i];
    const Vec3 q = weights_.empty() ? points_[i] : w * points_[i];
    return std::array<double, 4>{q.x, q.y, q.z, w};
  };
  // Per span s = [a, b]: e_k = C^(k)(a) / k! and C^(k)(b) / k!, homogeneous.
  // C^(k) is the degree p − k B-spline on the derivative control points
  // (Algorithm A3.3), evaluated at the span ends by de Boor's algorithm.
  // Derivative control points are scaled differences of neighbouring control
  // points, so each e_k carries rounding relative to the k-th derivative's own
  // size, not to the coordinates: a curve far from the origin with many short
  // spans keeps its third derivative as accurately as A2.3 does. At a
  // clamped end every de Boor α is exactly 0 or 1, so e_0 there is the end
  // control point bit for bit.
  for (int s = p; s < count; ++s) {
    if (!(U[s + 1] > U[s])) continue;
    const double ends[2] = {U[s], U[s + 1]};
    std::array<std::array<std::array<double, 4>, kMaxOrder>, kMaxOrder> Q; // Q[k][j], j = 0..p−k
    for (int j = 0; j <= p; ++j) Q[0][j] = homogeneous(s - p + j);
    for (int k = 1; k <= p; ++k)
      for (int j = 0; j <= p - k; ++j) {
        const double scale = (p - k + 1) / (U[s + j + 1] - U[s - p + j + k]);
        for (int c = 0; c < 4; ++c) Q[k][j][c] = scale * (Q[k - 1][j + 1][c] - Q[k - 1][j][c]);
      }
    const std::size_t start = taylor_.size();
    taylor_.resize(start + 2 * (p + 1));
    for (int end = 0; end < 2; ++end) {
      const double t = ends[end];
      double factorial = 1;
      for (int k = 0; k <= p; ++k) {
        if (k > 1) factorial *= k;
        const int q = p - k;
        std::array<std::array<double, 4>, kMaxOrder> d = Q[k];
        for (int r = 1; r <= q; ++r)
          for (int j = q; j >= r; --j) {
            const int g = s - q + j;
            const double alpha = (t - U[g]) / (U[g + q + 1 - r] - U[g]);
            for (int c = 0; c < 4; ++c) d[j][c] = (1 - alpha) * d[j - 1][c] + alpha * d[j][c];
          }
        for (int c = 0; c < 4; ++c) taylor_[start + end * (p + 1) + k][c] = d[q][c] / factorial;
      }
    }
  }
}

int BSplineCurve::fastSpan(double t, int hint) const {
  const int last = static_cast<int>(breaks_.size()) - 2;
  if (hint >= 0 && hint <= last && breaks_[hint] <= t && (hint == last || t < breaks_[hint + 1])) return hint;
  // First interior break > t; the span before it holds t.
  auto it = std::upper_bound(breaks_.begin() + 1, breaks_.begin() + last + 1, t);
  return static_cast<int>(it - breaks_.begin()) - 1;
}

std::array<Vec3, 4> BSplineCurve::fastDerivatives(double t, int span) const {
  const int p = degree_;
  const double a = breaks_[span], b = breaks_[span + 1];
  // Each half of the span is evaluated from the expansion at its own end.
  const bool fromStart = t - a <= b - t;
  const double x = fromStart ? t - a : t - b;
  const std::array<double, 4> *c = taylor_.data() + (2 * span + (fromStart ? 0 : 1)) * (p + 1);
  double jet[4][4];
  const bool rational = !weights_.empty();
  taylorAt<3>(p, rational, c, x, jet);
  // d^k/dt^k = k! × (k-th Taylor coefficient at t).
  constexpr double scale[4] = {1.0, 1.0, 2.0, 6.0};
  std::array<Vec3, 4> A;
  for (int k = 0; k < 4; ++k) A[k] = Vec3{jet[k][0], jet[k][1], jet[k][2]} * scale[k];
  if (!rational) return A;
  const double W[4] = {jet[0][3], jet[1][3] * scale[1], jet[2][3] * scale[2], jet[3][3] * scale[3]};
  return rationalDerivatives(A, W);
}

BSplineCurve BSplineCurve::bezier(std::vector<Vec3> controlPoints) {
  if (controlPoints.size() < 2) fail("a Bézier curve needs at least 2 control points");
  int p = static_cast<int>(controlPoints.size()) - 1;
  std::vector<double> U(2 * (p + 1), 0.0);
  std::fill(U.begin() + p + 1, U.end(), 1.0);
  return BSplineCurve(p, std::move(U), std::move(controlPoints));
}

int BSplineCurve::findSpan(double t) const {
  return spanOf(knots_, degree_, static_cast<int>(points_.size()), t);
}

Vec3 BSplineCurve::point(double t) const {
  t = std::clamp(t, domainStart(), domainEnd());
  if (!taylor_.empty()) {
    const int span = fastSpan(t, -1), p = degree_;
    const double a = breaks_[span], b = breaks_[span + 1];
    const bool fromStart = t - a <= b - t;
    const double x = fromStart ? t - a : t - b;
    double jet[1][4];
    const bool rational = !weights_.empty();
    taylorAt<0>(p, rational, taylor_.data() + (2 * span + (fromStart ? 0 : 1)) * (p + 1), x, jet);
    const Vec3 A{jet[0][0], jet[0][1], jet[0][2]};
    return rational ? A / jet[0][3] : A;
  }
  const int p = degree_, span = findSpan(t);
  std::array<std::array<double, kMaxOrder>, 4> N;
  basisDerivatives(span, t, p, 0, knots_, N);
  Vec3 a;
  double w = 0;
  for (int j = 0; j <= p; ++j) {
    int i = span - p + j;
    double wi = weights_.empty() ? 1.0 : weights_[i];
    a += (N[0][j] * wi) * points_[i];
    w += N[0][j] * wi;
  }
  return a / w;
}

std::array<Vec3, 4> BSplineCurve::derivatives(double t) const {
  if (taylor_.empty()) return derivativesReference(t);
  t = std::clamp(t, domainStart(), domainEnd());
  return fastDerivatives(t, fastSpan(t, -1));
}

void BSplineCurve::derivatives(std::span<const double> t, std::span<std::array<Vec3, 4>> out) const {
  CURVENET_CHECK(out.size() >= t.size(), "derivatives: output shorter than the parameters");
  if (taylor_.empty()) {
    for (std::size_t k = 0; k < t.size(); ++k) out[k] = derivativesReference(t[k]);
    return;
  }
  int span = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double u = std::clamp(t[k], domainStart(), domainEnd());
    span = fastSpan(u, span);
    out[k] = fastDerivatives(u, span);
  }
}

std::array<Vec3, 4> BSplineCurve::derivativesReference(double t) const {
  t = std::clamp(t, domainStart(), domainEnd());
  const int p = degree_, span = findSpan(t), order = std::min(3, p);
  std::array<std::array<double, kMaxOrder>, 4> N;
  basisDerivatives(span, t, p, order, knots_, N);
  // Homogeneous derivatives A^(k) = Σ N_i^(k) w_i P_i and w^(k) = Σ N_i^(k) w_i.
  std::array<Vec3, 4> A{};
  std::array<double, 4> W{};
  for (int k = 0; k <= order; ++k)
    for (int j = 0; j <= p; ++j) {
      int i = span - p + j;
      double wi = weights_.empty() ? 1.0 : weights_[i];
      A[k] += (N[k][j] * wi) * points_[i];
      W[k] += N[k][j] * wi;
    }
  return rationalDerivatives(A, W.data());
}

BSplineCurve BSplineCurve::reversed() const {
  const double s = domainStart() + domainEnd();
  std::vector<double> U(knots_.rbegin(), knots_.rend());
  for (double &u : U) u = s - u;
  // Keep the end knots bit-identical to the original domain.
  for (int i = 0; i <= degree_; ++i) {
    U[i] = domainStart();
    U[U.size() - 1 - i] = domainEnd();
  }
  std::vector<Vec3> P(points_.rbegin(), points_.rend());
  std::vector<double> W(weights_.rbegin(), weights_.rend());
  return BSplineCurve(degree_, std::move(U), std::move(P), std::move(W));
}

BSplineCurve BSplineCurve::restricted(double from, double to) const {
  const double a = domainStart(), b = domainEnd();
  if (!(from < to)) fail("restriction needs from < to");
  if (from < a || to > b) fail("restriction range outside the curve domain");
  const int p = degree_;
  std::vector<double> U = knots_;
  std::vector<Homogeneous> P(points_.size());
  for (size_t i = 0; i < points_.size(); ++i) {
    double w = weights_.empty() ? 1.0 : weights_[i];
    P[i] = {w * points_[i], w};
  }
  // Snap the cut parameters to existing knots they equal up to rounding, so
  // no sliver spans appear.
  const double snap = 1e-13 * (b - a);
  for (double u : knots_) {
    if (std::abs(u - from) <= snap) from = u;
    if (std::abs(u - to) <= snap) to = u;
  }
  // Boehm insertion raises each cut to multiplicity p; the curve point there
  // is then a control point and the pieces separate.
  auto raise = [&](double u) {
    if (u == a || u == b) return;
    int mult = static_cast<int>(std::count(U.begin(), U.end(), u));
    for (int r = mult; r < p; ++r) insertKnot(p, U, P, u);
  };
  raise(from);
  raise(to);
  // Last index of `from`, first index of `to` in the refined knot vector.
  int lastFrom = static_cast<int>(std::upper_bound(U.begin(), U.end(), from) - U.begin()) - 1;
  int firstTo = static_cast<int>(std::lower_bound(U.begin(), U.end(), to) - U.begin());
  int first = lastFrom - p, last = firstTo - 1;
  std::vector<double> K;
  K.insert(K.end(), p + 1, from);
  K.insert(K.end(), U.begin() + lastFrom + 1, U.begin() + firstTo);
  K.insert(K.end(), p + 1, to);
  std::vector<Vec3> Q;
  std::vector<double> W;
  for (int i = first; i <= last; ++i) {
    Q.push_back(P[i].p / P[i].w);
    if (!weights_.empty()) W.push_back(P[i].w);
  }
  return BSplineCurve(p, std::move(K), std::move(Q), std::move(W));
}

BSplineCurve BSplineCurve::reparameterized(double from, double to) const {
  if (!(from < to) || !std::isfinite(from) || !std::isfinite(to)) fail("reparameterization needs finite from < to");
  const double a = domainStart(), b = domainEnd(), scale = (to - from) / (b - a);
  std::vector<double> U = knots_;
  for (double &u : U) u = (u == a) ? from : (u == b) ? to : from + (u - a) * scale;
  return BSplineCurve(degree_, std::move(U), points_, weights_);
}

double BSplineCurve::arcLength(double a, double b) const {
  if (a > b) std::swap(a, b);
  a = std::max(a, domainStart());
  b = std::min(b, domainEnd());
  if (!(a < b)) return 0.0;
  auto speed = [this](double t) { return norm(derivatives(t)[1]); };
  // 16-point rule on [lo, hi].
  auto gauss = [&](double lo, double hi) {
    double m = 0.5 * (lo + hi), h = 0.5 * (hi - lo), s = 0;
    for (size_t i = 0; i < kGaussX.size(); ++i) s += kGaussW[i] * (speed(m - h * kGaussX[i]) + speed(m + h * kGaussX[i]));
    return s * h;
  };
  // Adaptive bisection with an absolute tolerance that halves with the
  // interval, so the total error stays below 1e-13 of the span's length.
  // Where the speed has a kink or a zero (a cusp inside a span) the halves
  // never agree to a relative 1e-13; the absolute split still terminates
  // after a few levels around the bad point, and a fixed budget of
  // subdivisions bounds the work for any input. The speed cannot be more
  // accurate than the rounding of control-point differences: a small curve
  // far from the origin (coordinates ~1e6, size ~1) sets a floor on the
  // tolerance, measured in the same units.
  int budget = 1 << 12;
  double magnitude = 0;
  for (const Vec3 &p : points_) magnitude = std::max({magnitude, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  auto adaptive = [&](auto &&self, double lo, double hi, double whole, double tolerance) -> double {
    double mid = 0.5 * (lo + hi);
    double left = gauss(lo, mid), right = gauss(mid, hi);
    if (--budget <= 0 || !(mid > lo && mid < hi) || std::abs(left + right - whole) <= tolerance) return left + right;
    return self(self, lo, mid, left, 0.5 * tolerance) + self(self, mid, hi, right, 0.5 * tolerance);
  };
  // Integrate span by span: the speed is smooth inside each knot span.
  double total = 0;
  double lo = a;
  for (size_t i = 0; i < knots_.size(); ++i) {
    double k = knots_[i];
    if (k <= lo) continue;
    double hi = std::min(k, b);
    const double whole = gauss(lo, hi);
    const double spanWidth = i > 0 && k > knots_[i - 1] ? k - knots_[i - 1] : 1.0;
    const double roundingFloor = 1e-15 * magnitude * degree_ * (hi - lo) / spanWidth;
    total += adaptive(adaptive, lo, hi, whole, std::max(1e-13 * std::abs(whole), roundingFloor));
    lo = hi;
    if (lo >= b) break;
  }
  return total;
}

double BSplineCurve::closestParameter(const Vec3 &q) const {
  const double a = domainStart(), b = domainEnd();
  auto dist2 = [&](double t) { return squaredNorm(point(t) - q); };
  // Global start: sample every knot span densely enough to isolate the basins
  // of the distance function (at most ~degree oscillations per span).
  double bestT = a, bestD = dist2(a);
  std::vector<double> candidates;
  const int perSpan = 4 * degree_ + 4;
  std::vector<std::pair<double, double>> samples;
  for (size_t i = degree_; i < points_.size(); ++i) {
    double lo = knots_[i], hi = knots_[i + 1];
    if (!(hi > lo) || lo < a || hi > b) continue;
    for (int s = 0; s < perSpan; ++s) {
      double t = lo + (hi - lo) * s / perSpan;
      samples.emplace_back(t, dist2(t));
    }
  }
  samples.emplace_back(b, dist2(b));
  // Local minima of the samples seed the Newton refinement.
  for (size_t i = 0; i < samples.size(); ++i) {
    bool leftOk = i == 0 || samples[i].second <= samples[i - 1].second;
    bool rightOk = i + 1 == samples.size() || samples[i].second <= samples[i + 1].second;
    if (leftOk && rightOk) candidates.push_back(samples[i].first);
    if (samples[i].second < bestD) bestD = samples[i].second, bestT = samples[i].first;
  }
  // Safeguarded Newton on f(t) = C'(t)·(C(t) − q): clamp to the domain and
  // halve steps that do not decrease the distance.
  for (double t : candidates) {
    double d = dist2(t);
    for (int it = 0; it < 50; ++it) {
      auto D = derivatives(t);
      Vec3 r = D[0] - q;
      double f = dot(D[1], r), fp = dot(D[2], r) + squaredNorm(D[1]);
      double step = fp > 0 ? -f / fp : -f / std::max(squaredNorm(D[1]), 1e-300);
      // Slack for rounding: near the minimum the distance is stationary.
      const double slack = 1e-12 * d;
      double tn = std::clamp(t + step, a, b), dn = dist2(tn);
      for (int h = 0; h < 30 && dn > d + slack; ++h) {
        tn = 0.5 * (t + tn);
        dn = dist2(tn);
      }
      if (dn > d + slack) break;
      bool done = std::abs(tn - t) <= 1e-15 * (b - a);
      t = tn, d = dn;
      if (done) break;
    }
    if (d < bestD) bestD = d, bestT = t;
  }
  return bestT;
}

BSplineCurve BSplineCurve::interpolate(int degree, std::span<const double> params, std::span<const Vec3> points) {
  const int count = static_cast<int>(points.size());
  if (degree < 1 || degree > maxDegree) fail("interpolation degree " + std::to_string(degree) + " out of range");
  if (params.size() != points.size())
    fail("interpolation has " + std::to_string(params.size()) + " parameters for " + std::to_string(count) +
         " points");
  if (count < degree + 1)
    fail("interpolation of degree " + std::to_string(degree) + " needs at least " + std::to_string(degree + 1) +
         " points, got " + std::to_string(count));
  for (int i = 0; i < count; ++i) {
    if (!std::isfinite(params[i]) || !isFinite(points[i])) fail("non-finite interpolation data");
    if (i > 0 && !(params[i] > params[i - 1])) fail("interpolation parameters must increase strictly");
  }
  // Knots by averaging (eq. 9.8): u_{j+p} = (1/p) Σ_{i=j}^{j+p-1} t_i, j = 1..n−p.
  // Schoenberg–Whitney holds, so the collocation matrix is nonsingular.
  const int p = degree, n = count - 1;
  std::vector<double> U(count + p + 1);
  for (int i = 0; i <= p; ++i) U[i] = params.front(), U[count + i] = params.back();
  for (int j = 1; j <= n - p; ++j) {
    double s = 0;
    for (int i = j; i < j + p; ++i) s += params[i];
    U[j + p] = s / p;
  }
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(count, count);
  std::array<std::array<double, kMaxOrder>, 4> N;
  for (int r = 0; r < count; ++r) {
    int span = spanOf(U, p, count, params[r]);
    basisDerivatives(span, params[r], p, 0, U, N);
    for (int j = 0; j <= p; ++j) A(r, span - p + j) = N[0][j];
  }
  Eigen::MatrixXd rhs(count, 3);
  for (int r = 0; r < count; ++r) rhs.row(r) << points[r].x, points[r].y, points[r].z;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
  Eigen::MatrixXd X = lu.solve(rhs);
  if (!X.allFinite()) fail("interpolation system is singular");
  std::vector<Vec3> P(count);
  for (int i = 0; i < count; ++i) P[i] = {X(i, 0), X(i, 1), X(i, 2)};
  // Clamped ends interpolate exactly: make them bit-identical to the data.
  P.front() = points.front();
  P.back() = points.back();
  return BSplineCurve(p, std::move(U), std::move(P));
}

} // namespace v1
} // namespace curvenet
