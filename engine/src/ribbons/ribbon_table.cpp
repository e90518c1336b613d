#include "ribbons/ribbon_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

// Refinement targets relative to the ribbon's size (the largest coordinate
// of P, T, C at the breakpoints): far below the 1e-12 agreement the plans
// promise with pointwise evaluation.
constexpr double kValueTolerance = 1e-13;
constexpr double kSlopeTolerance = 1e-10;
// Bisection depth below a breakpoint interval: 2⁻¹⁰ of it. An interval that
// still misses there holds a kink that is not a listed breakpoint (the table
// keeps what it has), or the exact functions are at fault (below).
constexpr int kMaxDepth = 10;
// Beyond it an interval is split further, up to kDeepestDepth, only while
// bisection still works: its error fell by kConvergence or more from its
// parent's (a smooth function's quintic Hermite error falls by 2⁵ … 2⁶ per
// halving). Functions whose high derivatives grow fast near a side's end
// need a level or two more; a derivative that disagrees with its values, or
// rounding, does not converge and stops at kMaxDepth.
constexpr int kDeepestDepth = 16;
constexpr double kConvergence = 8;
// A kink off the breakpoints leaves an interval or two at the depth limit;
// more than this many means the table cannot reach its tolerances, and
// building stops with an error rather than a table that quietly misses them
// (strict: whatever the size of the gap).
constexpr std::size_t kMaxUnresolved = 8;
// Intervals at most this wide (those whose one-sided stencil steps are an
// eighth of the interval, so that the slopes are known at nine evenly spaced
// parameters) take the value difference f(b) − f(a) from those slopes by
// Boole's rule instead of from the two values: the difference of two values
// of size |f| carries an error of ε|f| against a difference of only h|f'|,
// which on the narrow breakpoint intervals of sketch-fitted curves (a knot
// within 2e-6 of a curve end or of a fence knot: h ~ 1e-6) is 1e-10 of the
// slope, the tolerance itself, and grows as bisection narrows the interval.
// The quadrature carries ε relative to the difference (its truncation error,
// h·(h/8)⁶·f⁽⁷⁾/472, is far below it on such intervals), and the check at the
// interval's middle still compares the result with the exact value there.
constexpr double kWidestQuadratureInterval = 8 * 0x1p-13;
// What the unresolved intervals' slopes may miss the values by (their
// integral against the values' difference, relative to the slopes' size)
// before the message calls it a defect: a wrong factor misses by its own
// size, rounding by ε over the interval's relative width.
constexpr double kDisagreement = 1e-3;
// Where a quintic Hermite interpolant's error peaks: t³(1 − t)³ at ½, its
// derivative at ½ − 1/√20.
constexpr double kValueCheck = 0.5;
constexpr double kSlopeCheck = 0.27639320225002106;
// Parameters per interval: two end nodes of five (the end and four steps of
// the one-sided second-derivative stencil), then the two check points.
constexpr int kPerInterval = 12;

struct Interval {
  double a, b;
  int depth;
  double parentMiss = INFINITY; ///< the parent interval's error over the tolerance
};

/// Degree-5 polynomial in local t with its t-derivative.
/// Rows of `stride` doubles (t⁰ … t⁵), the first `dims` of each used.
inline void polynomial(const double *c, int stride, int dims, double t, double *value, double *dt) {
  for (int d = 0; d < dims; ++d) {
    const double c0 = c[d], c1 = c[stride + d], c2 = c[2 * stride + d], c3 = c[3 * stride + d],
                 c4 = c[4 * stride + d], c5 = c[5 * stride + d];
    value[d] = ((((c5 * t + c4) * t + c3) * t + c2) * t + c1) * t + c0;
    if (dt) dt[d] = (((5 * c5 * t + 4 * c4) * t + 3 * c3) * t + 2 * c2) * t + c1;
  }
}

/// x with `digits` significant digits ("3.1e-05"): std::to_string's fixed
/// six decimals would print a small gap as 0.000000.
std::string shortNumber(double x, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", digits, x);
  return text;
}

/// Σ weight[k] · slope_k of coordinate d over the interval's nine evenly
/// spaced parameters a + k h / 8: the samples' layout (kPerInterval) puts
/// k = 0 … 4 at 0 … 4 and k = 8, 7, 6, 5 at 5 … 8.
inline double weightedSlopes(const double *slopes, std::size_t dims, std::size_t d, const double (&weight)[9]) {
  constexpr int sample[9] = {0, 1, 2, 3, 4, 8, 7, 6, 5};
  double sum = 0;
  for (int k = 0; k < 9; ++k) sum += weight[k] * slopes[static_cast<std::size_t>(sample[k]) * dims + d];
  return sum;
}

/// f(b) − f(a) of coordinate d by composite Boole's rule over those slopes.
inline double booleDifference(const double *slopes, std::size_t dims, std::size_t d, double h) {
  constexpr double weight[9] = {7, 32, 12, 32, 14, 32, 12, 32, 7};
  return h / 180 * weightedSlopes(slopes, dims, d, weight);
}

/// The same difference by composite Simpson's rule on the same samples: its
/// distance from Boole's estimates the quadrature error.
inline double simpsonDifference(const double *slopes, std::size_t dims, std::size_t d, double h) {
  constexpr double weight[9] = {1, 4, 2, 4, 2, 4, 2, 4, 1};
  return h / 24 * weightedSlopes(slopes, dims, d, weight);
}

/// The parameters where the table's first intervals meet: 0, the breaks in
/// (0, 1) in order (none within 1e-12 of another or of an end), 1.
std::vector<double> tableEdges(std::vector<double> breaks) {
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> edges{0.0};
  for (double b : breaks)
    if (b > 1e-12 && b < 1 - 1e-12 && b - edges.back() > 1e-12) edges.push_back(b);
  edges.push_back(1.0);
  return edges;
}

/// The one-sided stencil's step on an interval of width h.
double stencilStep(double h) { return std::min(0x1p-13, h / 8); }

/// The kPerInterval parameters at which interval [a, b] is sampled: the
/// ends one ulp inside (on a segment break the exact ribbon takes the piece
/// of the side it is asked from) with four stencil steps each, then the
/// two check points.
void intervalParameters(double a, double b, double *p) {
  const double h = b - a, step = stencilStep(h);
  p[0] = std::nextafter(a, b), p[5] = std::nextafter(b, a);
  for (int k = 1; k <= 4; ++k) p[k] = a + k * step, p[5 + k] = b - k * step;
  p[10] = a + kValueCheck * h, p[11] = a + kSlopeCheck * h;
}

/// One interval's samples: `dims` values and slopes per parameter, in the
/// order intervalParameters lays them out.
struct IntervalSamples {
  const double *values, *slopes;
  std::size_t dims;
  double value(int point, std::size_t d) const { return values[static_cast<std::size_t>(point) * dims + d]; }
  double slope(int point, std::size_t d) const { return slopes[static_cast<std::size_t>(point) * dims + d]; }
};

/// The quintic Hermite interpolant of one interval of width h in local
/// t ∈ [0, 1]: 6 rows of `dims` coefficients (t⁰ … t⁵).
std::vector<double> quinticHermite(const IntervalSamples &x, double h) {
  const std::size_t D = x.dims;
  const double step = stencilStep(h);
  std::vector<double> c(6 * D);
  for (std::size_t d = 0; d < D; ++d) {
    // Second derivatives by fourth-order one-sided differences of the
    // exact first ones, the stencil inside the interval.
    constexpr double w[5] = {-25, 48, -36, 16, -3};
    double second0 = 0, second1 = 0;
    for (int k = 0; k < 5; ++k) second0 += w[k] * x.slope(k, d), second1 += w[k] * x.slope(5 + k, d);
    second0 /= 12 * step, second1 /= -12 * step;
    const double f0 = x.value(0, d), m0 = h * x.slope(0, d), m1 = h * x.slope(5, d);
    const double k0 = h * h * second0, k1 = h * h * second1;
    const double df = h <= kWidestQuadratureInterval ? booleDifference(x.slopes, D, d, h) : x.value(5, d) - f0;
    c[d] = f0;
    c[D + d] = m0;
    c[2 * D + d] = 0.5 * k0;
    c[3 * D + d] = 10 * df - 6 * m0 - 4 * m1 - 0.5 * (3 * k0 - k1);
    c[4 * D + d] = -15 * df + 8 * m0 + 7 * m1 + 0.5 * (3 * k0 - 2 * k1);
    c[5 * D + d] = 6 * df - 3 * m0 - 3 * m1 - 0.5 * (k0 - k1);
  }
  return c;
}

/// How far the interpolant c misses the exact samples at the two check
/// points: in value (both points) and in slope (d/ds, the slope point).
struct Miss {
  double value = 0, slope = 0;
};
Miss checkMiss(const std::vector<double> &c, const IntervalSamples &x, double h) {
  const int dims = static_cast<int>(x.dims);
  std::array<double, RibbonTable::kMaxDims> value{}, slope{};
  Miss miss;
  polynomial(c.data(), dims, dims, kValueCheck, value.data(), nullptr);
  for (std::size_t d = 0; d < x.dims; ++d) miss.value = std::max(miss.value, std::abs(value[d] - x.value(10, d)));
  polynomial(c.data(), dims, dims, kSlopeCheck, value.data(), slope.data());
  for (std::size_t d = 0; d < x.dims; ++d) {
    miss.value = std::max(miss.value, std::abs(value[d] - x.value(11, d)));
    miss.slope = std::max(miss.slope, std::abs(slope[d] / h - x.slope(11, d)));
  }
  return miss;
}

/// How far the slopes' integral over an interval misses the values'
/// difference, relative to the slopes' size (a defect: of the order of 1);
/// 0 where the miss is within ten times the quadrature's own error
/// (Boole's rule against Simpson's on the same samples): a ribbon too steep
/// for the interval, not a defect.
double slopeValueDisagreement(const IntervalSamples &x, double h) {
  double worst = 0;
  for (std::size_t d = 0; d < x.dims; ++d) {
    const double difference = x.value(5, d) - x.value(0, d), integral = booleDifference(x.slopes, x.dims, d, h);
    const double quadratureError = std::abs(integral - simpsonDifference(x.slopes, x.dims, d, h));
    double steepest = 0;
    for (int k = 0; k < 10; ++k) steepest = std::max(steepest, std::abs(x.slope(k, d)));
    const double gap = std::abs(integral - difference);
    if (gap > 10 * quadratureError) worst = std::max(worst, gap / (h * steepest + 1e-300));
  }
  return worst;
}

/// The intervals that stayed short of the tolerances at the depth limit.
struct Unresolved {
  std::size_t count = 0;
  Interval worst{0, 0, 0};
  double valueGap = 0, slopeGap = 0; ///< on the worst, absolute
  double disagreement = 0;           ///< on the worst (slopeValueDisagreement)
  void add(const Interval &interval, const Miss &miss, const IntervalSamples &x) {
    ++count;
    if (miss.value + miss.slope <= valueGap + slopeGap) return;
    worst = interval, valueGap = miss.value, slopeGap = miss.slope;
    disagreement = slopeValueDisagreement(x, interval.b - interval.a);
  }
};

/// Strict: any more than a stray kink's intervals short of the tolerances
/// stop the build. Derivatives that disagree with the values are a defect
/// of the engine; a ribbon that only varies too fast for the table is the
/// input's (its parameterization), said as such.
void throwIfUnresolved(const Unresolved &u, double scale) {
  if (u.count <= kMaxUnresolved) return;
  const std::string missed =
      "ribbon table: " + std::to_string(u.count) + " intervals miss the tolerance at the depth limit (worst on [" +
      shortNumber(u.worst.a, 9) + ", " + shortNumber(u.worst.b, 9) + "]: value gap " +
      shortNumber(u.valueGap / scale, 3) + ", slope gap " + shortNumber(u.slopeGap / scale, 3) +
      " of the ribbon's size); ";
  if (u.disagreement > kDisagreement)
    throw InternalError(missed + "the exact derivatives disagree with the values (their integral misses the "
                                 "values' difference by " + shortNumber(u.disagreement, 3) + " of the slopes' size)");
  throw InputError({}, {},
                   missed + "the ribbon's derivatives grow too fast there for the table (derivatives and values "
                            "agree to " + shortNumber(u.disagreement, 3) + "): a parameterization far from "
                            "uniform, such as extreme weights or crowded knots");
}

/// An interval of the finished table with its interpolant (quinticHermite).
struct FittedInterval {
  double a, b;
  std::vector<double> coefficients;
};

/// The table's intervals in order of s: the intervals between `edges`,
/// bisected (all pending intervals sampled in one call of `exact` per
/// round) until each interpolant meets the tolerances or refinement stops
/// (kMaxDepth, kDeepestDepth). The largest misses accepted, relative to
/// the ribbon's size, go to valueError and slopeError.
std::vector<FittedInterval> fitIntervals(std::size_t dims, const std::vector<double> &edges,
                                         const RibbonTable::Exact &exact, double &valueError, double &slopeError) {
  std::vector<Interval> pending;
  for (std::size_t j = 0; j + 1 < edges.size(); ++j) pending.push_back({edges[j], edges[j + 1], 0});
  std::vector<FittedInterval> fitted;
  std::vector<double> params, values, slopes;
  double scale = -1;
  Unresolved unresolved;
  while (!pending.empty()) {
    params.resize(pending.size() * kPerInterval);
    for (std::size_t j = 0; j < pending.size(); ++j)
      intervalParameters(pending[j].a, pending[j].b, params.data() + j * kPerInterval);
    values.resize(params.size() * dims), slopes.resize(params.size() * dims);
    exact(params, values.data(), slopes.data());
    if (scale < 0) {
      scale = 0;
      for (double v : values) scale = std::max(scale, std::abs(v));
      if (!(scale > 0)) scale = 1;
    }
    std::vector<Interval> next;
    for (std::size_t j = 0; j < pending.size(); ++j) {
      const auto [a, b, depth, parentMiss] = pending[j];
      const double h = b - a;
      const IntervalSamples x{values.data() + j * kPerInterval * dims, slopes.data() + j * kPerInterval * dims, dims};
      std::vector<double> c = quinticHermite(x, h);
      const Miss miss = checkMiss(c, x, h);
      const bool good = miss.value <= kValueTolerance * scale && miss.slope <= kSlopeTolerance * scale;
      const double over = std::max(miss.value / (kValueTolerance * scale), miss.slope / (kSlopeTolerance * scale));
      const bool converging = depth < kDeepestDepth && over * kConvergence < parentMiss;
      if (!good && (depth < kMaxDepth || converging)) {
        const double mid = 0.5 * (a + b);
        next.push_back({a, mid, depth + 1, over});
        next.push_back({mid, b, depth + 1, over});
        continue;
      }
      if (!good) unresolved.add(pending[j], miss, x);
      valueError = std::max(valueError, miss.value / scale);
      slopeError = std::max(slopeError, miss.slope / scale);
      fitted.push_back({a, b, std::move(c)});
    }
    pending = std::move(next);
  }
  throwIfUnresolved(unresolved, scale);
  std::sort(fitted.begin(), fitted.end(), [](const FittedInterval &x, const FittedInterval &y) { return x.a < y.a; });
  return fitted;
}

} // namespace

RibbonTable::RibbonTable(int dims, std::vector<double> breaks, const Exact &exact)
    // Rows of a multiple of 4 (kernels::PolynomialTable), a lone last
    // coordinate as a tail: nine (G² P, T, C) are rows of 8 and one tail.
    : dims_(dims), paddedDims_(dims % 4 == 1 ? dims - 1 : (dims + 3) / 4 * 4) {
  CURVENET_CHECK(dims >= 1 && dims <= kMaxDims, "ribbon table: " + std::to_string(dims) + " coordinates");
  const std::vector<double> edges = tableEdges(std::move(breaks));
  for (const FittedInterval &x : fitIntervals(static_cast<std::size_t>(dims), edges, exact, valueError_, slopeError_))
    appendInterval(x.a, x.b, x.coefficients.data());
  buildLookup();
  buildTailByInterval();
}

void RibbonTable::buildTailByInterval() {
  const kernels::PolynomialTable layout = view();
  const std::size_t intervals = starts_.size(), block = layout.blockSize();
  for (int e = 0; e < layout.tailDims(); ++e)
    for (int r = 0; r < 6; ++r)
      for (std::size_t j = 0; j < intervals; ++j)
        tailByInterval_.push_back(coefficients_[j * block + 6 * static_cast<std::size_t>(paddedDims_) + 8 * e + r]);
}

void RibbonTable::appendInterval(double a, double b, const double *coefficients) {
  starts_.push_back(a);
  ends_.push_back(b);
  inverseWidths_.push_back(1 / (b - a));
  const int rowDims = std::min(dims_, paddedDims_);
  for (int row = 0; row < 6; ++row) {
    const double *from = coefficients + row * dims_;
    coefficients_.insert(coefficients_.end(), from, from + rowDims);
    coefficients_.insert(coefficients_.end(), static_cast<std::size_t>(paddedDims_ - rowDims), 0.0);
  }
  for (int d = rowDims; d < dims_; ++d) {
    for (int row = 0; row < 6; ++row) coefficients_.push_back(coefficients[row * dims_ + d]);
    coefficients_.insert(coefficients_.end(), 2, 0.0);
  }
}

void RibbonTable::buildLookup() {
  // Lookup grid: cell c holds the first interval reaching c / cells. Cells
  // no wider than half the narrowest interval (up to 2¹⁶ of them) keep the
  // forward search to a step or two.
  double narrowest = 1;
  for (std::size_t j = 0; j < starts_.size(); ++j) narrowest = std::min(narrowest, ends_[j] - starts_[j]);
  cells_ = 1;
  while (cells_ < 4 * starts_.size() || (cells_ < (1u << 16) && 1.0 / static_cast<double>(cells_) > 0.5 * narrowest))
    cells_ *= 2;
  cellFirst_.resize(cells_);
  std::uint32_t i = 0;
  for (std::size_t cell = 0; cell < cells_; ++cell) {
    const double from = static_cast<double>(cell) / static_cast<double>(cells_);
    while (i + 1 < ends_.size() && ends_[i] < from) ++i;
    cellFirst_[cell] = i;
  }
  // The most forward moves any parameter of a cell needs: to the interval
  // holding the cell's end.
  steps_ = 0;
  for (std::size_t cell = 0; cell < cells_; ++cell) {
    const double to = static_cast<double>(cell + 1) / static_cast<double>(cells_);
    std::uint32_t j = cellFirst_[cell];
    while (j + 1 < ends_.size() && ends_[j] < to) ++j;
    steps_ = std::max(steps_, static_cast<int>(j - cellFirst_[cell]));
  }
  if (steps_ <= 1) {
    cellFirstEnd_.resize(cells_);
    for (std::size_t cell = 0; cell < cells_; ++cell)
      cellFirstEnd_[cell] = cellFirst_[cell] + 1 < ends_.size() ? ends_[cellFirst_[cell]] : INFINITY;
  }
}

void RibbonTable::evaluate(double s, double *values, double *slopes) const {
  const std::uint32_t i = interval(s);
  const double t = (s - starts_[i]) * inverseWidths_[i];
  const kernels::PolynomialTable layout = view();
  const int rowDims = layout.rowDims();
  const double *c = coefficients_.data() + i * layout.blockSize();
  polynomial(c, paddedDims_, rowDims, t, values, slopes);
  for (int d = rowDims; d < dims_; ++d)
    polynomial(c + 6 * paddedDims_ + 8 * (d - rowDims), 1, 1, t, values + d, slopes ? slopes + d : nullptr);
  if (slopes)
    for (int d = 0; d < dims_; ++d) slopes[d] *= inverseWidths_[i];
}

void RibbonTable::evaluate(std::size_t count, const double *s, double *const *values, double *const *slopes) const {
  kernels::evaluateTable(count, view(), s, values, slopes);
}

kernels::PolynomialTable RibbonTable::view() const {
  kernels::PolynomialTable t;
  t.dims = dims_, t.paddedDims = paddedDims_, t.steps = steps_;
  t.intervals = starts_.size(), t.cells = cells_;
  t.starts = starts_.data(), t.ends = ends_.data(), t.inverseWidths = inverseWidths_.data();
  t.coefficients = coefficients_.data(), t.cellFirst = cellFirst_.data();
  t.cellFirstEnd = cellFirstEnd_.empty() ? nullptr : cellFirstEnd_.data();
  t.tailByInterval = tailByInterval_.empty() ? nullptr : tailByInterval_.data();
  return t;
}

std::size_t RibbonTable::memory() const {
  return (starts_.size() * 3 + coefficients_.size() + cellFirstEnd_.size() + tailByInterval_.size()) * sizeof(double) +
         cellFirst_.size() * sizeof(std::uint32_t);
}

} // namespace v1
} // namespace curvenet
