// A side's ribbon functions as a piecewise quintic Hermite table in the side
// parameter s, for evaluation at many parameters (docs/design.md §4).
//
// Exact ribbon evaluation costs a B-spline, a fence interpolant, a
// normalization and the α, β blend per parameter (G²: also the transversal
// curvature and the second fundamental form) — about 150 ns per side and
// sample, most of a plan-based tessellation. The functions themselves are
// smooth between known breakpoints (segment breaks, curve knots, fence and
// curvature interpolant knots), so between those breakpoints a quintic
// Hermite interpolant of the exact values and first derivatives (second
// derivatives by one-sided differences of the exact first ones) reproduces
// them to the last digits: the table is refined by bisection until the
// interpolant agrees with the exact functions to 1e-13 of the ribbon's size
// in value and 1e-10 in slope at the interior points where a quintic
// Hermite's error peaks. Evaluation is then a lookup and one degree-5
// polynomial per coordinate.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "curvenet/kernels/kernels.hpp"

namespace curvenet {
inline namespace v1 {

class RibbonTable {
public:
  /// Exact functions: for every parameter s[k], `dims` values into
  /// values[k·dims + c] and their s-derivatives into slopes[k·dims + c].
  using Exact = std::function<void(std::span<const double> s, double *values, double *slopes)>;

  RibbonTable() = default;
  /// Tabulates `exact` (dims ≤ kMaxDims coordinates) on [0, 1]; `breaks` are
  /// the parameters in (0, 1) where its derivatives may jump. Cost: about a
  /// dozen exact evaluations per table interval (typically 64–300 intervals).
  RibbonTable(int dims, std::vector<double> breaks, const Exact &exact);

  static constexpr int kMaxDims = 9;
  static_assert(kMaxDims <= kernels::PolynomialTable::kMaxDims, "the table kernel's limit");
  int dims() const { return dims_; }
  std::size_t intervals() const { return starts_.size(); }
  /// Largest differences to the exact functions seen at the check points.
  double valueError() const { return valueError_; }
  double slopeError() const { return slopeError_; }

  /// Values at s ∈ [0, 1] (on a break: the interval to its left, as
  /// LinearRibbon::pieceAt), and, when slopes is not null, d/ds.
  void evaluate(double s, double *values, double *slopes) const;
  /// The same for s[0 .. count) into structure-of-arrays outputs:
  /// values[c][k] (and slopes[c][k] when slopes is not null), through the
  /// SIMD kernel kernels::evaluateTable.
  void evaluate(std::size_t count, const double *s, double *const *values, double *const *slopes) const;
  /// The storage as the kernels see it.
  kernels::PolynomialTable view() const;

  std::size_t memory() const;

private:
  /// Appends interval [a, b] with its 6 rows of dims_ coefficients
  /// (t⁰ … t⁵) in the kernel's layout (coefficients_).
  void appendInterval(double a, double b, const double *coefficients);
  /// The lookup grid over the intervals (cells_, cellFirst_, steps_,
  /// cellFirstEnd_).
  void buildLookup();
  /// The tail coordinates' coefficients again, interval after interval
  /// (tailByInterval_), from coefficients_.
  void buildTailByInterval();
  std::uint32_t interval(double s) const {
    const double scaled = s * static_cast<double>(cells_); // NaN or out of [0, 1]: the end cells
    const std::size_t cell = !(scaled > 0) ? 0
                             : scaled < static_cast<double>(cells_) ? static_cast<std::size_t>(scaled)
                                                                    : cells_ - 1;
    std::uint32_t i = cellFirst_[cell];
    for (int q = 0; q < steps_; ++q)
      i += static_cast<std::uint32_t>(i + 1 < starts_.size()) & static_cast<std::uint32_t>(ends_[i] < s);
    return i;
  }

  int dims_ = 0, paddedDims_ = 0;
  std::vector<double> starts_, ends_, inverseWidths_;
  /// Per interval: 6 rows of paddedDims_ (t⁰ … t⁵ in local t ∈ [0, 1]),
  /// then the tail coordinates (kernels::PolynomialTable); on a cache line,
  /// so that the kernel's four-double loads never straddle two.
  kernels::AlignedVector<double> coefficients_;
  /// The tail coordinates' coefficients interval after interval
  /// (kernels::PolynomialTable::tailByInterval).
  std::vector<double> tailByInterval_;
  std::vector<std::uint32_t> cellFirst_;
  std::vector<double> cellFirstEnd_; ///< when steps_ ≤ 1: see kernels::PolynomialTable
  std::size_t cells_ = 0;
  int steps_ = 0; ///< forward moves from a cell's first interval (see interval())
  double valueError_ = 0, slopeError_ = 0;
};

} // namespace v1
} // namespace curvenet
