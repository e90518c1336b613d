#include "ribbons/ribbon_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

// Refinement targets relative to the ribbon's size (the largest coordinate
// of P, T, C at the breakpoints): far below the 1e-12 agreement the plans
// promise with pointwise evaluation.
constexpr double kValueTolerance = 1e-13;
constexpr double kSlopeTolerance = 1e-10;
// Bisection depth below a breakpoint interval: 2⁻¹⁰ of it. Deeper would mean
// a kink that is not a listed breakpoint; the table then keeps what it has.
constexpr int kMaxDepth = 10;
// A kink off the breakpoints leaves an interval or two at the depth limit;
// more than this many means the exact functions' derivatives disagree with
// their values (a defect), and building stops with an error rather than a
// table that quietly misses its tolerance everywhere.
constexpr std::size_t kMaxUnresolved = 8;
// ... and a gap this large (relative to the ribbon's size) is such a defect:
// a wrong factor or sign in a derivative misses by the derivative's own size.
// Smaller gaps keep the table (bounded: 2^kMaxDepth intervals per breakpoint
// interval) with its measured error. Curves fitted to sketches can carry
// knots within 2e-6 of a curve end or of a fence knot; on those breakpoint
// intervals, about 1e-6 wide, the tables miss the 1e-10 slope tolerance by up
// to 5e-5 (the exact functions are consistent there: finite differences agree
// to 1e-7), and they stay usable, to that accuracy.
constexpr double kDefectGap = 1e-3;
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

} // namespace

RibbonTable::RibbonTable(int dims, std::vector<double> breaks, const Exact &exact)
    // Rows of a multiple of 4 (kernels::PolynomialTable), a lone last
    // coordinate as a tail: nine (G² P, T, C) are rows of 8 and one tail.
    : dims_(dims), paddedDims_(dims % 4 == 1 ? dims - 1 : (dims + 3) / 4 * 4) {
  CURVENET_CHECK(dims >= 1 && dims <= kMaxDims, "ribbon table: " + std::to_string(dims) + " coordinates");
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> edges{0.0};
  for (double b : breaks)
    if (b > 1e-12 && b < 1 - 1e-12 && b - edges.back() > 1e-12) edges.push_back(b);
  edges.push_back(1.0);

  std::vector<Interval> pending;
  for (std::size_t j = 0; j + 1 < edges.size(); ++j) pending.push_back({edges[j], edges[j + 1], 0});
  struct Accepted {
    double a, b;
    std::vector<double> coefficients;
  };
  std::vector<Accepted> accepted;
  std::vector<double> params, values, slopes;
  double scale = -1;
  std::size_t unresolved = 0;
  Interval worstUnresolved{0, 0, 0};
  double worstValueGap = 0, worstSlopeGap = 0;
  const std::size_t D = static_cast<std::size_t>(dims);
  while (!pending.empty()) {
    params.resize(pending.size() * kPerInterval);
    for (std::size_t j = 0; j < pending.size(); ++j) {
      const auto [a, b, depth] = pending[j];
      const double h = b - a, step = std::min(0x1p-13, h / 8);
      double *p = params.data() + j * kPerInterval;
      // The ends one ulp inside: on a segment break the exact ribbon takes
      // the piece of the side it is asked from.
      p[0] = std::nextafter(a, b), p[5] = std::nextafter(b, a);
      for (int k = 1; k <= 4; ++k) p[k] = a + k * step, p[5 + k] = b - k * step;
      p[10] = a + kValueCheck * h, p[11] = a + kSlopeCheck * h;
    }
    values.resize(params.size() * D), slopes.resize(params.size() * D);
    exact(params, values.data(), slopes.data());
    if (scale < 0) {
      scale = 0;
      for (double v : values) scale = std::max(scale, std::abs(v));
      if (!(scale > 0)) scale = 1;
    }
    std::vector<Interval> next;
    for (std::size_t j = 0; j < pending.size(); ++j) {
      const auto [a, b, depth] = pending[j];
      const double h = b - a, step = std::min(0x1p-13, h / 8);
      const double *v = values.data() + j * kPerInterval * D, *sl = slopes.data() + j * kPerInterval * D;
      auto at = [&](const double *base, int point, std::size_t d) { return base[static_cast<std::size_t>(point) * D + d]; };
      std::vector<double> c(6 * D);
      for (std::size_t d = 0; d < D; ++d) {
        // Second derivatives by fourth-order one-sided differences of the
        // exact first ones, the stencil inside the interval.
        constexpr double w[5] = {-25, 48, -36, 16, -3};
        double second0 = 0, second1 = 0;
        for (int k = 0; k < 5; ++k) second0 += w[k] * at(sl, k, d), second1 += w[k] * at(sl, 5 + k, d);
        second0 /= 12 * step, second1 /= -12 * step;
        const double f0 = at(v, 0, d), f1 = at(v, 5, d), m0 = h * at(sl, 0, d), m1 = h * at(sl, 5, d);
        const double k0 = h * h * second0, k1 = h * h * second1, df = f1 - f0;
        c[d] = f0;
        c[D + d] = m0;
        c[2 * D + d] = 0.5 * k0;
        c[3 * D + d] = 10 * df - 6 * m0 - 4 * m1 - 0.5 * (3 * k0 - k1);
        c[4 * D + d] = -15 * df + 8 * m0 + 7 * m1 + 0.5 * (3 * k0 - 2 * k1);
        c[5 * D + d] = 6 * df - 3 * m0 - 3 * m1 - 0.5 * (k0 - k1);
      }
      std::array<double, kMaxDims> value{}, slope{};
      double valueError = 0, slopeError = 0;
      polynomial(c.data(), dims, dims, kValueCheck, value.data(), nullptr);
      for (std::size_t d = 0; d < D; ++d) valueError = std::max(valueError, std::abs(value[d] - at(v, 10, d)));
      polynomial(c.data(), dims, dims, kSlopeCheck, value.data(), slope.data());
      for (std::size_t d = 0; d < D; ++d) {
        valueError = std::max(valueError, std::abs(value[d] - at(v, 11, d)));
        slopeError = std::max(slopeError, std::abs(slope[d] / h - at(sl, 11, d)));
      }
      const bool good = valueError <= kValueTolerance * scale && slopeError <= kSlopeTolerance * scale;
      if (!good && depth < kMaxDepth) {
        const double mid = 0.5 * (a + b);
        next.push_back({a, mid, depth + 1});
        next.push_back({mid, b, depth + 1});
        continue;
      }
      if (!good) {
        ++unresolved;
        if (valueError + slopeError > worstValueGap + worstSlopeGap)
          worstUnresolved = pending[j], worstValueGap = valueError, worstSlopeGap = slopeError;
      }
      valueError_ = std::max(valueError_, valueError / scale);
      slopeError_ = std::max(slopeError_, slopeError / scale);
      accepted.push_back({a, b, std::move(c)});
    }
    pending = std::move(next);
  }
  if (unresolved > kMaxUnresolved && std::max(worstValueGap, worstSlopeGap) > kDefectGap * scale)
    throw InternalError("ribbon table: " + std::to_string(unresolved) + " intervals miss the tolerance at the depth limit (worst on [" +
                        std::to_string(worstUnresolved.a) + ", " + std::to_string(worstUnresolved.b) + "]: value gap " +
                        std::to_string(worstValueGap / scale) + ", slope gap " + std::to_string(worstSlopeGap / scale) +
                        " of the ribbon's size); the exact derivatives disagree with the values");

  std::sort(accepted.begin(), accepted.end(), [](const Accepted &x, const Accepted &y) { return x.a < y.a; });
  for (const Accepted &x : accepted) {
    starts_.push_back(x.a);
    ends_.push_back(x.b);
    inverseWidths_.push_back(1 / (x.b - x.a));
    const int rowDims = std::min(dims_, paddedDims_);
    for (int row = 0; row < 6; ++row) {
      const auto from = x.coefficients.begin() + row * dims_;
      coefficients_.insert(coefficients_.end(), from, from + rowDims);
      coefficients_.insert(coefficients_.end(), static_cast<std::size_t>(paddedDims_ - rowDims), 0.0);
    }
    for (int d = rowDims; d < dims_; ++d) {
      for (int row = 0; row < 6; ++row) coefficients_.push_back(x.coefficients[row * dims_ + d]);
      coefficients_.insert(coefficients_.end(), 2, 0.0);
    }
  }
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
  return t;
}

std::size_t RibbonTable::memory() const {
  return (starts_.size() * 3 + coefficients_.size() + cellFirstEnd_.size()) * sizeof(double) +
         cellFirst_.size() * sizeof(std::uint32_t);
}

} // namespace v1
} // namespace curvenet
