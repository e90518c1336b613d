// Kernels of curvenet/kernels/kernels.hpp, written once over a Highway
// descriptor D: ScalableTag<double> gives the full width of each compiled
// instruction set, CappedTag<double, 1> the width-1 scalar reference (also
// used for the tail of every batch). This file is compiled once per target
// (foreach_target); run-time dispatch picks the CPU's best.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "kernels.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

#include "loops-inl.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include "curvenet/kernels/kernels.hpp"
#include "dispatch.hpp"

// Argument bundles, shared by every target's instance (defined once).
#ifndef CURVENET_KERNELS_ARGS
#define CURVENET_KERNELS_ARGS
namespace curvenet {
namespace kernels_impl {
namespace ck = curvenet::kernels;
struct TableArgs {
  const ck::PolynomialTable *table;
  const double *s;
  double *const *values, *const *slopes;
};

struct GregoryArgs {
  const ck::GregorySamples *in;
  const ck::GregoryCorner *corners;
  double *const *out;
  const ck::GregoryCornerTerms *terms; ///< per corner, G² only
  double *interleaved;                 ///< when set: points here (plus offset) instead of out
  double offset[3];
};

struct GregoryJetArgs {
  const ck::GregoryJetSamples *in;
  const ck::GregoryCorner *corners;
  ck::DualVec3Span out;
  const ck::GregoryCornerTerms *terms; ///< per corner, G² only
};

struct CornerWeightArgs {
  const double *s, *sPrevious;
  double *weights;
  std::size_t stride;
};

struct SweepArgs {
  ck::SweepFrame frame;
  const double *x, *y;
  double *s, *d;
};
} // namespace kernels_impl
} // namespace curvenet
#endif

HWY_BEFORE_NAMESPACE();
namespace curvenet {
namespace kernels_impl {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace ck = curvenet::kernels;

/// The interval of s (see PolynomialTable): its grid cell's first, then at
/// most `steps` forward moves, branch-free (the grid is fine enough).
HWY_INLINE std::size_t tableInterval(const ck::PolynomialTable &tb, double s) {
  // Out of [0, 1] (or NaN) clamps to the end cells before any conversion.
  const double scaled = s * static_cast<double>(tb.cells);
  const std::size_t cell = !(scaled > 0) ? 0
                           : scaled < static_cast<double>(tb.cells) ? static_cast<std::size_t>(scaled)
                                                                    : tb.cells - 1;
  std::size_t j = tb.cellFirst[cell];
  // One step at most: the first interval's end is stored with the cell.
  if (tb.cellFirstEnd) return j + (tb.cellFirstEnd[cell] < s);
  for (int q = 0; q < tb.steps; ++q) j += (j + 1 < tb.intervals) & (tb.ends[j] < s);
  return j;
}

/// One sample's coordinates x .. x + lanes − 1 (value, and d/ds when
/// Slopes) over D, whose lanes run across the coordinates; c points at the
/// sample's interval, t is its local parameter.
template <bool Slopes, class D, class V = hn::Vec<D>>
HWY_INLINE void tablePolynomial(D d, const double *c, std::size_t row, V t, V inverseWidth, V &value, V &slope) {
  const V c0 = hn::LoadU(d, c), c1 = hn::LoadU(d, c + row), c2 = hn::LoadU(d, c + 2 * row);
  const V c3 = hn::LoadU(d, c + 3 * row), c4 = hn::LoadU(d, c + 4 * row), c5 = hn::LoadU(d, c + 5 * row);
  value = hn::MulAdd(hn::MulAdd(hn::MulAdd(hn::MulAdd(hn::MulAdd(c5, t, c4), t, c3), t, c2), t, c1), t, c0);
  if constexpr (Slopes) {
    const V dv = hn::MulAdd(hn::MulAdd(hn::MulAdd(hn::MulAdd(hn::Mul(hn::Set(d, 5.0), c5), t, hn::Mul(hn::Set(d, 4.0), c4)),
                                                  t, hn::Mul(hn::Set(d, 3.0), c3)),
                                       t, hn::Add(c2, c2)),
                            t, c1);
    slope = hn::Mul(dv, inverseWidth);
  }
}

/// The intervals of s[k .. end) into interval, local (the local parameter)
/// and, when Inverse, inverse (the interval's 1 / width), `end − k` ≤ 64.
/// Apart from the polynomials, the lookups' chains of dependent loads
/// overlap with one another instead of stalling the polynomial work behind
/// each sample's lookup; out of line, with the table's arrays in locals, the
/// loop keeps everything in registers. With cellFirstEnd, the cells four at
/// a time (tableInterval's clamping: NaN and s ≤ 0 to the first cell, s ≥ 1
/// to the last), then one read per cell; else through tableInterval.
template <bool Inverse, class D>
HWY_NOINLINE void tableLookups(D d, const ck::PolynomialTable &tb, const double *HWY_RESTRICT s, std::size_t k,
                               std::size_t end, std::size_t *HWY_RESTRICT interval, double *HWY_RESTRICT local,
                               double *HWY_RESTRICT inverse) {
  using V = hn::Vec<D>;
  const double *HWY_RESTRICT starts = tb.starts, *HWY_RESTRICT inverseWidths = tb.inverseWidths;
  std::size_t q = k;
  if (tb.cellFirstEnd) {
    const std::uint32_t *HWY_RESTRICT first = tb.cellFirst;
    const double *HWY_RESTRICT firstEnd = tb.cellFirstEnd;
    HWY_ALIGN std::int64_t cellOf[64];
    const hn::RebindToSigned<D> di;
    const V scale = hn::Set(d, static_cast<double>(tb.cells)), last = hn::Set(d, static_cast<double>(tb.cells - 1));
    std::size_t vectorEnd = k;
    for (; vectorEnd + 4 <= end; vectorEnd += 4) {
      const V scaled = hn::Mul(hn::LoadU(d, s + vectorEnd), scale);
      const V cell = hn::Min(hn::IfThenElseZero(hn::Gt(scaled, hn::Zero(d)), scaled), last);
      hn::Store(hn::ConvertTo(di, cell), di, cellOf + (vectorEnd - k));
    }
    for (; q < vectorEnd; ++q) {
      const double x = s[q];
      const auto cell = static_cast<std::size_t>(cellOf[q - k]);
      const std::size_t j = first[cell] + (firstEnd[cell] < x);
      const double w = inverseWidths[j];
      interval[q - k] = j, local[q - k] = (x - starts[j]) * w;
      if constexpr (Inverse) inverse[q - k] = w;
    }
  }
  for (; q < end; ++q) {
    const double x = s[q];
    const std::size_t j = tableInterval(tb, x);
    const double w = inverseWidths[j];
    interval[q - k] = j, local[q - k] = (x - starts[j]) * w;
    if constexpr (Inverse) inverse[q - k] = w;
  }
}

#if HWY_TARGET != HWY_SCALAR
/// The 4 × 4 transpose: r[q][c] → column c = (r[0][c], …, r[3][c]), for
/// the first kUsed columns.
template <std::size_t kUsed = 4, class D, class V = hn::Vec<D>>
HWY_INLINE void transpose4(D d, const V (&r)[4], V (&column)[4]) {
  const V t0 = hn::InterleaveLower(d, r[0], r[1]), t1 = hn::InterleaveUpper(d, r[0], r[1]);
  const V t2 = hn::InterleaveLower(d, r[2], r[3]), t3 = hn::InterleaveUpper(d, r[2], r[3]);
  column[0] = hn::ConcatLowerLower(d, t2, t0);
  if constexpr (kUsed > 1) column[1] = hn::ConcatLowerLower(d, t3, t1);
  if constexpr (kUsed > 2) column[2] = hn::ConcatUpperUpper(d, t2, t0);
  if constexpr (kUsed > 3) column[3] = hn::ConcatUpperUpper(d, t3, t1);
}

/// Four samples' four-coordinate vectors r[q] stored as the coordinates'
/// four-sample vectors out[x + c][k .. k + 4), c < kUsed.
template <std::size_t kUsed, class D, class V = hn::Vec<D>>
HWY_INLINE void transposeStore(D d, const V (&r)[4], double *const *out, std::size_t x, std::size_t k) {
  V column[4];
  transpose4<kUsed>(d, r, column);
  for (std::size_t c = 0; c < kUsed; ++c) hn::StoreU(column[c], d, out[x + c] + k);
}

/// One tail coordinate (see PolynomialTable) of four samples, its lanes
/// across the samples: each sample's eight doubles at c[q] (t⁰ … t⁵, two
/// zeros) transposed into the six coefficients' four-sample vectors, then
/// one polynomial for the four samples at their local parameters t.
template <bool Slopes, class D, class V = hn::Vec<D>>
HWY_INLINE void tailPolynomial(D d, const double *const (&c)[4], V t, V inverseWidth, V &value, V &slope) {
  const V low[4] = {hn::LoadU(d, c[0]), hn::LoadU(d, c[1]), hn::LoadU(d, c[2]), hn::LoadU(d, c[3])};
  const V high[4] = {hn::LoadU(d, c[0] + 4), hn::LoadU(d, c[1] + 4), hn::LoadU(d, c[2] + 4), hn::LoadU(d, c[3] + 4)};
  V k[4], k45[4];
  transpose4(d, low, k);
  transpose4<2>(d, high, k45);
  value = hn::MulAdd(hn::MulAdd(hn::MulAdd(hn::MulAdd(hn::MulAdd(k45[1], t, k45[0]), t, k[3]), t, k[2]), t, k[1]), t, k[0]);
  if constexpr (Slopes) {
    const V dv = hn::MulAdd(hn::MulAdd(hn::MulAdd(hn::MulAdd(hn::Mul(hn::Set(d, 5.0), k45[1]), t, hn::Mul(hn::Set(d, 4.0), k45[0])),
                                                  t, hn::Mul(hn::Set(d, 3.0), k[3])),
                                       t, hn::Add(k[2], k[2])),
                            t, k[1]);
    slope = hn::Mul(dv, inverseWidth);
  }
}

/// RibbonTable evaluation of four samples at a time over D with four lanes:
/// the row coordinates with the lanes across the coordinates, the four
/// samples transposed in registers so that the structure-of-arrays outputs
/// are written as whole vectors; the tail coordinates with the lanes across
/// the samples. The layout known at compile time (kRow > 0: the engine's
/// tables, 6 row coordinates in rows of 8 for G¹ ribbons P, T; 8 and a tail
/// of 1 for G² P, T, C) unrolls every loop and keeps the output pointers in
/// registers; kRow = 0 reads it from the table. Returns the samples done (a
/// multiple of four); the rest is the caller's.
template <bool Slopes, std::size_t kRowDims, std::size_t kRow, std::size_t kTail, class D>
HWY_INLINE std::size_t evaluateTableFours(D d, std::size_t count, const TableArgs &a) {
  using V = hn::Vec<D>;
  const ck::PolynomialTable &tb = *a.table;
  const std::size_t rowDims = kRow ? kRowDims : static_cast<std::size_t>(tb.rowDims());
  const std::size_t row = kRow ? kRow : static_cast<std::size_t>(tb.paddedDims);
  const std::size_t tail = kRow ? kTail : static_cast<std::size_t>(tb.tailDims());
  const std::size_t dims = rowDims + tail, block = 6 * row + 8 * tail;
  constexpr std::size_t kOut = kRow ? kRowDims + kTail : ck::PolynomialTable::kMaxDims;
  double *values[kOut], *slopes[kOut];
  for (std::size_t x = 0; x < dims; ++x) values[x] = a.values[x], slopes[x] = Slopes ? a.slopes[x] : nullptr;
  constexpr std::size_t kChunk = 64;
  HWY_ALIGN std::size_t interval[kChunk];
  HWY_ALIGN double local[kChunk], inverse[kChunk];
  std::size_t k = 0;
  for (std::size_t chunkStart = 0; chunkStart + 4 <= count; chunkStart += kChunk) {
    const std::size_t chunkEnd = std::min(count, chunkStart + kChunk);
    tableLookups<Slopes>(d, tb, a.s, chunkStart, chunkEnd, interval, local, inverse);
    for (k = chunkStart; k + 4 <= chunkEnd; k += 4) {
      const double *c[4];
      V t[4], w[4];
      for (std::size_t q = 0; q < 4; ++q) {
        c[q] = tb.coefficients + interval[k - chunkStart + q] * block;
        t[q] = hn::Set(d, local[k - chunkStart + q]);
        w[q] = Slopes ? hn::Set(d, inverse[k - chunkStart + q]) : hn::Zero(d); // inverse: only with slopes
      }
      auto chunk = [&](std::size_t x, auto used) {
        V value[4], slope[4];
        for (int q = 0; q < 4; ++q) tablePolynomial<Slopes>(d, c[q] + x, row, t[q], w[q], value[q], slope[q]);
        transposeStore<decltype(used)::value>(d, value, values, x, k);
        if constexpr (Slopes) transposeStore<decltype(used)::value>(d, slope, slopes, x, k);
      };
      if constexpr (kRow > 0) {
        [&]<std::size_t... X>(std::index_sequence<X...>) {
          (chunk(4 * X, std::integral_constant<std::size_t, std::min<std::size_t>(4, kRowDims - 4 * X)>()), ...);
        }(std::make_index_sequence<(kRowDims + 3) / 4>());
      } else {
        for (std::size_t x = 0; x < rowDims; x += 4) {
          switch (rowDims - x) {
          case 1: chunk(x, std::integral_constant<std::size_t, 1>()); break;
          case 2: chunk(x, std::integral_constant<std::size_t, 2>()); break;
          case 3: chunk(x, std::integral_constant<std::size_t, 3>()); break;
          default: chunk(x, std::integral_constant<std::size_t, 4>()); break;
          }
        }
      }
      if (tail) {
        const V ts = hn::Load(d, local + (k - chunkStart));
        const V ws = Slopes ? hn::Load(d, inverse + (k - chunkStart)) : hn::Zero(d);
        for (std::size_t e = 0; e < tail; ++e) {
          const std::size_t offset = 6 * row + 8 * e;
          const double *const at[4] = {c[0] + offset, c[1] + offset, c[2] + offset, c[3] + offset};
          V value, slope;
          tailPolynomial<Slopes>(d, at, ts, ws, value, slope);
          hn::StoreU(value, d, values[rowDims + e] + k);
          if constexpr (Slopes) hn::StoreU(slope, d, slopes[rowDims + e] + k);
        }
      }
    }
    if (chunkEnd == count) break;
  }
  return k;
}

#endif

/// RibbonTable evaluation over D, a tag whose lanes run across the
/// coordinates of one sample: four samples at a time when D has four lanes
/// (evaluateTableFours), the rest one at a time (the row coordinates a
/// vector at a time, the tail ones alone).
template <bool Slopes, class D> HWY_INLINE void evaluateTableWith(D d, std::size_t count, const TableArgs &a) {
  using V = hn::Vec<D>;
  const ck::PolynomialTable &tb = *a.table;
  const std::size_t lanes = hn::Lanes(d), rowDims = static_cast<std::size_t>(tb.rowDims());
  const std::size_t row = static_cast<std::size_t>(tb.paddedDims), tail = static_cast<std::size_t>(tb.tailDims());
  const std::size_t block = tb.blockSize();
  std::size_t k = 0;
#if HWY_TARGET != HWY_SCALAR
  if constexpr (hn::MaxLanes(D()) == 4) {
    if (lanes == 4) {
      if (rowDims == 8 && row == 8 && tail == 1) k = evaluateTableFours<Slopes, 8, 8, 1>(d, count, a);
      else if (rowDims == 6 && row == 8 && tail == 0) k = evaluateTableFours<Slopes, 6, 8, 0>(d, count, a);
      else k = evaluateTableFours<Slopes, 0, 0, 0>(d, count, a);
    }
  }
#endif
  const hn::CappedTag<double, 1> one;
  HWY_ALIGN double value[ck::PolynomialTable::kMaxDims], slope[ck::PolynomialTable::kMaxDims];
  for (; k < count; ++k) {
    const double s = a.s[k];
    const std::size_t j = tableInterval(tb, s);
    const double *c = tb.coefficients + j * block;
    const V t = hn::Set(d, (s - tb.starts[j]) * tb.inverseWidths[j]), w = hn::Set(d, tb.inverseWidths[j]);
    for (std::size_t x = 0; x < rowDims; x += lanes) {
      V v, sl;
      tablePolynomial<Slopes>(d, c + x, row, t, w, v, sl);
      hn::Store(v, d, value + x);
      if constexpr (Slopes) hn::Store(sl, d, slope + x);
    }
    for (std::size_t e = 0; e < tail; ++e) {
      hn::Vec<decltype(one)> v, sl;
      tablePolynomial<Slopes>(one, c + 6 * row + 8 * e, 1, hn::Set(one, hn::GetLane(t)), hn::Set(one, hn::GetLane(w)), v,
                              sl);
      value[rowDims + e] = hn::GetLane(v);
      if constexpr (Slopes) slope[rowDims + e] = hn::GetLane(sl);
    }
    for (std::size_t x = 0; x < rowDims + tail; ++x) a.values[x][k] = value[x];
    if constexpr (Slopes)
      for (std::size_t x = 0; x < rowDims + tail; ++x) a.slopes[x][k] = slope[x];
  }
}

void EvaluateTable(std::size_t count, const TableArgs &args, bool reference) {
  auto run = [&](auto tag) {
    if (args.slopes) evaluateTableWith<true>(tag, count, args);
    else evaluateTableWith<false>(tag, count, args);
  };
  if (reference) run(hn::CappedTag<double, 1>());
  else run(hn::CappedTag<double, 4>());
}

/// In-place reciprocals of m positive values with one division (batch
/// inversion: prefix products, one reciprocal, back substitution). Lanes
/// whose product underflows take m divisions instead.
template <int M, class D, class V> HWY_INLINE void reciprocals(D d, V (&x)[M]) {
  V prefix[M];
  prefix[0] = x[0];
  for (int j = 1; j < M; ++j) prefix[j] = hn::Mul(prefix[j - 1], x[j]);
  if (HWY_UNLIKELY(!hn::AllFalse(d, hn::Not(hn::Gt(prefix[M - 1], hn::Set(d, 1e-250)))))) {
    // Near a corner (or at it, where x = 0 and the caller's factor vanishes).
    const V tiny = hn::Set(d, 1e-300), one = hn::Set(d, 1.0);
    for (int j = 0; j < M; ++j) x[j] = hn::Div(one, hn::Max(x[j], tiny));
    return;
  }
  V inverse = hn::Div(hn::Set(d, 1.0), prefix[M - 1]);
  for (int j = M - 1; j > 0; --j) {
    const V mine = hn::Mul(inverse, prefix[j - 1]);
    inverse = hn::Mul(inverse, x[j]);
    x[j] = mine;
  }
  x[0] = inverse;
}

/// reciprocals for eight values with the products taken as a tree (pairs,
/// quads, all): the same multiplications, but a dependency chain of depth 3
/// on each side of the division instead of 7, so that the corners of a
/// sample overlap in the pipeline.
/// With `numerator`: numerator / x for each (the same operations, the
/// numerator taken into the one division).
template <class D, class V> HWY_INLINE void reciprocals(D d, V (&x)[8], V numerator) {
  const V pair[4] = {hn::Mul(x[0], x[1]), hn::Mul(x[2], x[3]), hn::Mul(x[4], x[5]), hn::Mul(x[6], x[7])};
  const V quad[2] = {hn::Mul(pair[0], pair[1]), hn::Mul(pair[2], pair[3])};
  const V all = hn::Mul(quad[0], quad[1]);
  if (HWY_UNLIKELY(!hn::AllFalse(d, hn::Not(hn::Gt(all, hn::Set(d, 1e-250)))))) {
    const V tiny = hn::Set(d, 1e-300);
    for (V &v : x) v = hn::Div(numerator, hn::Max(v, tiny));
    return;
  }
  const V inverse = hn::Div(numerator, all);
  const V quadInverse[2] = {hn::Mul(inverse, quad[1]), hn::Mul(inverse, quad[0])};
  V pairInverse[4];
  for (int q = 0; q < 2; ++q)
    pairInverse[2 * q] = hn::Mul(quadInverse[q], pair[2 * q + 1]), pairInverse[2 * q + 1] = hn::Mul(quadInverse[q], pair[2 * q]);
  for (int p = 0; p < 4; ++p) {
    const V first = x[2 * p];
    x[2 * p] = hn::Mul(pairInverse[p], x[2 * p + 1]);
    x[2 * p + 1] = hn::Mul(pairInverse[p], first);
  }
}

/// Powers 1, s, s², s³ and 1, t, t², t³, and the reciprocals of the eight
/// denominators s^{3−p} + t^{3−r} of the G² correction patch, (p, r) ≠ (0, 0)
/// row by row.
/// With OverS3, s³ / (s^{3−p} + t^{3−r}) instead of the reciprocals (s³
/// the batch inversion's numerator, at no extra cost).
template <bool OverS3 = false, class D, class V>
HWY_INLINE void g2CornerWeights(D d, V s, V t, V (&sp)[4], V (&tp)[4], V (&den)[8]) {
  const V one = hn::Set(d, 1.0), s2 = hn::Mul(s, s), t2 = hn::Mul(t, t);
  sp[0] = one, sp[1] = s, sp[2] = s2, sp[3] = hn::Mul(s2, s);
  tp[0] = one, tp[1] = t, tp[2] = t2, tp[3] = hn::Mul(t2, t);
  int j = 0;
  for (int p = 0; p <= 2; ++p)
    for (int r = 0; r <= 2; ++r)
      if (p || r) den[j++] = hn::Add(sp[3 - p], tp[3 - r]);
  reciprocals(d, den, OverS3 ? sp[3] : one);
}

/// gregoryCornerWeights' eight weights s³ t^r / (s^{3−p} + t^{3−r}): they
/// cost what the reciprocals did.
template <class D, class V> HWY_INLINE void g2RationalWeights(D d, V s, V t, V (&w)[8]) {
  V sp[4], tp[4];
  g2CornerWeights<true>(d, s, t, sp, tp, w);
  int j = 0;
  for (int p = 0; p <= 2; ++p)
    for (int r = 0; r <= 2; ++r) {
      if (!p && !r) continue;
      if (r) w[j] = hn::Mul(tp[r], w[j]);
      ++j;
    }
}

/// The two-ribbon blend's weight λ = t^m / (s^m + t^m) of R_{i−1} at a
/// corner (GregorySamples::blendShare; m = 3 for G², 2 for G¹), ½ at the
/// corner itself; with the partials ∂λ/∂s = −m s^{m−1} t^m / (s^m + t^m)²,
/// ∂λ/∂t = m t^{m−1} s^m / (s^m + t^m)² (0 there). "At the corner" is
/// s^m + t^m ≤ 1e-250, where the squared denominator would underflow.
template <int M, class D, class V>
HWY_INLINE V sideBlendWeight(D d, V s, V t, V *bySide = nullptr, V *across = nullptr) {
  static_assert(M == 2 || M == 3);
  const V sLow = M == 3 ? hn::Mul(s, s) : s, tLow = M == 3 ? hn::Mul(t, t) : t; // s^{m−1}, t^{m−1}
  const V sm = hn::Mul(sLow, s), tm = hn::Mul(tLow, t);
  const V sum = hn::Add(sm, tm);
  const auto atCorner = hn::Not(hn::Gt(sum, hn::Set(d, 1e-250)));
  const V inverse = hn::Div(hn::Set(d, 1.0), hn::Max(sum, hn::Set(d, 1e-250)));
  if (bySide) {
    const V m = hn::Set(d, double(M)), inverse2 = hn::Mul(inverse, inverse);
    *bySide = hn::IfThenZeroElse(atCorner, hn::Neg(hn::Mul(hn::Mul(m, hn::Mul(sLow, tm)), inverse2)));
    *across = hn::IfThenZeroElse(atCorner, hn::Mul(hn::Mul(m, hn::Mul(tLow, sm)), inverse2));
  }
  return hn::IfThenElse(atCorner, hn::Set(d, 0.5), hn::Mul(tm, inverse));
}

template <bool Parabolic, class D> HWY_INLINE void gregoryBody(D d, std::size_t k, const GregoryArgs &a) {
  using V = hn::Vec<D>;
  const ck::GregorySamples &in = *a.in;
  const int n = in.sides;
  const V one = hn::Set(d, 1.0), half = hn::Set(d, 0.5);
  V side[ck::GregorySamples::kMaxSides], blend[ck::GregorySamples::kMaxSides];
  for (int i = 0; i < n; ++i) side[i] = hn::LoadU(d, in.s[i] + k), blend[i] = hn::LoadU(d, in.blend[i] + k);
  // Corner i's weights of its two ribbons: B_i for both in eq. 17; with a
  // blend share μ, B_i (1 − μ (1 − λ)) for R_{i−1} and B_i (1 − μ λ) for R_i.
  V previousWeight[ck::GregorySamples::kMaxSides], ownWeight[ck::GregorySamples::kMaxSides];
  for (int i = 0; i < n; ++i) {
    previousWeight[i] = ownWeight[i] = blend[i];
    const double mu = in.blendShare[i];
    if (mu == 0) continue;
    const V lambda = sideBlendWeight<Parabolic ? 3 : 2>(d, side[i], hn::Sub(one, side[i == 0 ? n - 1 : i - 1]));
    const V muLambda = hn::Mul(hn::Set(d, mu), lambda);
    ownWeight[i] = hn::NegMulAdd(blend[i], muLambda, blend[i]);
    previousWeight[i] = hn::Mul(blend[i], hn::Add(hn::Set(d, 1.0 - mu), muLambda));
  }
  V acc[3] = {hn::Zero(d), hn::Zero(d), hn::Zero(d)};
  // The ribbon terms gathered per ribbon: R_i enters corner i at δ = t_i =
  // 1 − s_{i−1} with weight B_i and corner i + 1 at δ = s_{i+1} with weight
  // B_{i+1}, so its share is (B_i + B_{i+1}) P_i + (B_i t_i + B_{i+1} s_{i+1}) T_i
  // [+ ½ (B_i t_i² + B_{i+1} s_{i+1}²) C_i]: each ribbon value is read once.
  // (The weights there are ownWeight[i] and previousWeight[i + 1].)
  for (int i = 0; i < n; ++i) {
    const int prev = i == 0 ? n - 1 : i - 1, next = i + 1 == n ? 0 : i + 1;
    const V t = hn::Sub(one, side[prev]);
    const V atCorner = hn::Mul(ownWeight[i], t), atNext = hn::Mul(previousWeight[next], side[next]);
    const V wP = hn::Add(ownWeight[i], previousWeight[next]), wT = hn::Add(atCorner, atNext);
    V wC = hn::Zero(d);
    if constexpr (Parabolic) wC = hn::Mul(half, hn::MulAdd(atCorner, t, hn::Mul(atNext, side[next])));
    for (int c = 0; c < 3; ++c) {
      acc[c] = hn::MulAdd(wP, hn::LoadU(d, in.P[i][c] + k), acc[c]);
      acc[c] = hn::MulAdd(wT, hn::LoadU(d, in.T[i][c] + k), acc[c]);
      if constexpr (Parabolic) acc[c] = hn::MulAdd(wC, hn::LoadU(d, in.C[i][c] + k), acc[c]);
    }
  }
  // − Σ B_i (1 − μ_i) Q_i(s_i, t_i).
  for (int i = 0; i < n; ++i) {
    if (in.blendShare[i] == 1) continue;
    const int prev = i == 0 ? n - 1 : i - 1;
    const V s = side[i], t = hn::Sub(one, side[prev]);
    const double(*vec)[3] = a.corners[i].v;
    V q[3];
    if constexpr (Parabolic) {
      // Q in the form of GregoryCornerTerms (a00 is in taylor[0][0]): the
      // polynomial in Horner form, then the rational terms.
      V w[8];
      if (in.weights[i]) {
        for (int j = 0; j < 8; ++j) w[j] = hn::LoadU(d, in.weights[i] + j * in.weightStride + k);
      } else {
        g2RationalWeights(d, s, t, w);
      }
      const ck::GregoryCornerTerms &terms = a.terms[i];
      for (int c = 0; c < 3; ++c) {
        V h[3];
        for (int p = 0; p <= 2; ++p)
          h[p] = hn::MulAdd(t, hn::MulAdd(t, hn::Set(d, terms.taylor[p][2][c]), hn::Set(d, terms.taylor[p][1][c])),
                            hn::Set(d, terms.taylor[p][0][c]));
        q[c] = hn::MulAdd(s, hn::MulAdd(s, h[2], h[1]), h[0]);
      }
      for (int j = 0; j < 8; ++j)
        for (int c = 0; c < 3; ++c) q[c] = hn::MulAdd(w[j], hn::Set(d, terms.rational[j][c]), q[c]);
    } else {
      // a00 + Σ f (wa a + wb b), wa = x / (x + y), wb = 1 − wa.
      for (int c = 0; c < 3; ++c) q[c] = hn::Set(d, vec[0][c]);
      auto add = [&](V f, V wa, int slot) {
        const V fa = hn::Mul(f, wa), fb = hn::Sub(f, fa);
        for (int c = 0; c < 3; ++c)
          q[c] = hn::MulAdd(fa, hn::Set(d, vec[slot][c]), hn::MulAdd(fb, hn::Set(d, vec[slot + 1][c]), q[c]));
      };
      const V s2 = hn::Mul(s, s), t2 = hn::Mul(t, t);
      V den[3] = {hn::Add(s, t2), hn::Add(s2, t), hn::Add(s, t)};
      reciprocals(d, den);
      add(s, hn::Mul(s, den[0]), 1);
      add(t, hn::Mul(s2, den[1]), 3);
      add(hn::Mul(s, t), hn::Mul(s, den[2]), 5);
    }
    const V correctionWeight = hn::Mul(blend[i], hn::Set(d, 1.0 - in.blendShare[i]));
    for (int c = 0; c < 3; ++c) acc[c] = hn::NegMulAdd(correctionWeight, q[c], acc[c]);
  }
  if (a.interleaved) {
    hn::StoreInterleaved3(hn::Add(acc[0], hn::Set(d, a.offset[0])), hn::Add(acc[1], hn::Set(d, a.offset[1])),
                          hn::Add(acc[2], hn::Set(d, a.offset[2])), d, a.interleaved + 3 * k);
    return;
  }
  for (int c = 0; c < 3; ++c) hn::StoreU(acc[c], d, a.out[c] + k);
}

/// A value with its two domain partials, in registers.
template <class V> struct DualV {
  V v, u, w; // value, ∂/∂u, ∂/∂v
};

template <bool Parabolic, class D> HWY_INLINE void gregoryJetBody(D d, std::size_t k, const GregoryJetArgs &a) {
  using V = hn::Vec<D>;
  const ck::GregoryJetSamples &in = *a.in;
  const ck::GregorySamples &val = in.values;
  const int n = val.sides;
  const V one = hn::Set(d, 1.0), half = hn::Set(d, 0.5);
  V acc[3][3]; // [value, du, dv][x, y, z]
  for (auto &row : acc)
    for (V &x : row) x = hn::Zero(d);
  auto load = [&](const double *p) { return hn::LoadU(d, p + k); };
  for (int i = 0; i < n; ++i) {
    const int prev = i == 0 ? n - 1 : i - 1;
    const DualV<V> s{load(val.s[i]), load(in.sDu[i]), load(in.sDv[i])};
    const DualV<V> sp{load(val.s[prev]), load(in.sDu[prev]), load(in.sDv[prev])};
    const DualV<V> t{hn::Sub(one, sp.v), hn::Neg(sp.u), hn::Neg(sp.w)};
    const DualV<V> blend{load(val.blend[i]), load(in.blendDu[i]), load(in.blendDv[i])};
    // I = R_{i−1}(σ = s_{i−1}, δ = s) + R_i(σ = s, δ = t) − Q; for R(σ, δ):
    // value P + δT [+ ½δ²C], ∂ = σ' (P' + δT' [+ ½δ²C']) + δ' (T [+ δC]).
    V term[3][3];
    const V hs2 = hn::Mul(half, hn::Mul(s.v, s.v)), ht2 = hn::Mul(half, hn::Mul(t.v, t.v));
    // G² blend share μ (GregorySamples::blendShare): the ribbons' weights
    // 1 − μ (1 − λ) and 1 − μ λ with their partials ±μ ∂λ.
    const double mu = val.blendShare[i];
    DualV<V> previousShare{one, hn::Zero(d), hn::Zero(d)}, ownShare = previousShare;
    if (mu != 0) {
      V lambdaS, lambdaT;
      const V lambda = sideBlendWeight<Parabolic ? 3 : 2>(d, s.v, t.v, &lambdaS, &lambdaT), m = hn::Set(d, mu);
      const V lambdaU = hn::MulAdd(lambdaS, s.u, hn::Mul(lambdaT, t.u));
      const V lambdaW = hn::MulAdd(lambdaS, s.w, hn::Mul(lambdaT, t.w));
      previousShare = {hn::MulAdd(m, lambda, hn::Set(d, 1.0 - mu)), hn::Mul(m, lambdaU), hn::Mul(m, lambdaW)};
      ownShare = {hn::NegMulAdd(m, lambda, one), hn::Neg(previousShare.u), hn::Neg(previousShare.w)};
    }
    for (int c = 0; c < 3; ++c) {
      V lv = hn::MulAdd(s.v, load(val.T[prev][c]), load(val.P[prev][c]));
      V lslope = hn::MulAdd(s.v, load(in.dT[prev][c]), load(in.dP[prev][c]));
      V lacross = load(val.T[prev][c]);
      V rv = hn::MulAdd(t.v, load(val.T[i][c]), load(val.P[i][c]));
      V rslope = hn::MulAdd(t.v, load(in.dT[i][c]), load(in.dP[i][c]));
      V racross = load(val.T[i][c]);
      if constexpr (Parabolic) {
        const V lc = load(val.C[prev][c]), rc = load(val.C[i][c]);
        lv = hn::MulAdd(hs2, lc, lv), rv = hn::MulAdd(ht2, rc, rv);
        lslope = hn::MulAdd(hs2, load(in.dC[prev][c]), lslope), rslope = hn::MulAdd(ht2, load(in.dC[i][c]), rslope);
        lacross = hn::MulAdd(s.v, lc, lacross), racross = hn::MulAdd(t.v, rc, racross);
      }
      if (mu != 0) {
        // (1 − μ (1 − λ)) R_{i−1} + (1 − μ λ) R_i with the product rule.
        const V lu = hn::MulAdd(sp.u, lslope, hn::Mul(s.u, lacross)), lw = hn::MulAdd(sp.w, lslope, hn::Mul(s.w, lacross));
        const V ru = hn::MulAdd(s.u, rslope, hn::Mul(t.u, racross)), rw = hn::MulAdd(s.w, rslope, hn::Mul(t.w, racross));
        const V gap = hn::Sub(lv, rv);
        term[0][c] = hn::MulAdd(previousShare.v, lv, hn::Mul(ownShare.v, rv));
        term[1][c] = hn::MulAdd(previousShare.v, lu, hn::MulAdd(ownShare.v, ru, hn::Mul(previousShare.u, gap)));
        term[2][c] = hn::MulAdd(previousShare.v, lw, hn::MulAdd(ownShare.v, rw, hn::Mul(previousShare.w, gap)));
        continue;
      }
      term[0][c] = hn::Add(lv, rv);
      term[1][c] = hn::MulAdd(sp.u, lslope, hn::MulAdd(s.u, lacross, hn::MulAdd(s.u, rslope, hn::Mul(t.u, racross))));
      term[2][c] = hn::MulAdd(sp.w, lslope, hn::MulAdd(s.w, lacross, hn::MulAdd(s.w, rslope, hn::Mul(t.w, racross))));
    }
    const V zero = hn::Zero(d);
    if (mu == 1) {
      // The two-ribbon blend alone: no correction patch.
    } else if constexpr (Parabolic) {
      // Q in the form of GregoryCornerTerms with its partials in s and t:
      // Q = Σ s^p t^r taylor[p][r] + Σ_j ρ_j rational[j], ρ_j = s³ t^r / (s^{3−p} + t^{3−r}),
      //   ∂ρ/∂s = s² t^r (3 t^{3−r} + p s^{3−p}) / den²,
      //   ∂ρ/∂t = s³ t^{r−1} (r s^{3−p} + (2r − 3) t^{3−r}) / den²  (r = 0: −3 s³ t² / den²),
      // then the chain rule through s and t once per corner, not per term.
      V sp3[4], tp3[4], inv[8];
      g2CornerWeights(d, s.v, t.v, sp3, tp3, inv);
      const ck::GregoryCornerTerms &terms = a.terms[i];
      V q[3][3]; // [value, ∂/∂s, ∂/∂t][x, y, z]
      const V two = hn::Set(d, 2.0);
      for (int c = 0; c < 3; ++c) {
        V h[3], dh[3];
        for (int p = 0; p <= 2; ++p) {
          const V t0 = hn::Set(d, terms.taylor[p][0][c]), t1 = hn::Set(d, terms.taylor[p][1][c]);
          const V t2 = hn::Set(d, terms.taylor[p][2][c]);
          h[p] = hn::MulAdd(t.v, hn::MulAdd(t.v, t2, t1), t0);
          dh[p] = hn::MulAdd(hn::Mul(two, t.v), t2, t1);
        }
        q[0][c] = hn::MulAdd(s.v, hn::MulAdd(s.v, h[2], h[1]), h[0]);
        q[1][c] = hn::MulAdd(hn::Mul(two, s.v), h[2], h[1]);
        q[2][c] = hn::MulAdd(s.v, hn::MulAdd(s.v, dh[2], dh[1]), dh[0]);
      }
      // s^2 t^r and s^3 t^r for r = 0, 1, 2, shared by the rows p.
      const V s2t[3] = {sp3[2], hn::Mul(sp3[2], tp3[1]), hn::Mul(sp3[2], tp3[2])};
      const V s3t[3] = {sp3[3], hn::Mul(sp3[3], tp3[1]), hn::Mul(sp3[3], tp3[2])};
      int j = 0;
      for (int p = 0; p <= 2; ++p)
        for (int r = 0; r <= 2; ++r) {
          if (!p && !r) continue;
          const V x = sp3[3 - p], y = tp3[3 - r], i1 = inv[j], i2 = hn::Mul(i1, i1);
          const V rho = hn::Mul(s3t[r], i1);
          const V rhoS = hn::Mul(hn::Mul(s2t[r], hn::MulAdd(hn::Set(d, p), x, hn::Mul(hn::Set(d, 3.0), y))), i2);
          const V rhoT =
              r ? hn::Mul(hn::Mul(s3t[r - 1], hn::MulAdd(hn::Set(d, r), x, hn::Mul(hn::Set(d, 2 * r - 3), y))), i2)
                : hn::Mul(hn::Mul(hn::Set(d, -3.0), hn::Mul(sp3[3], tp3[2])), i2);
          for (int c = 0; c < 3; ++c) {
            const V R = hn::Set(d, terms.rational[j][c]);
            q[0][c] = hn::MulAdd(rho, R, q[0][c]);
            q[1][c] = hn::MulAdd(rhoS, R, q[1][c]);
            q[2][c] = hn::MulAdd(rhoT, R, q[2][c]);
          }
          ++j;
        }
      if (mu != 0) {
        const V keep = hn::Set(d, 1.0 - mu);
        for (auto &row : q)
          for (V &x : row) x = hn::Mul(keep, x);
      }
      for (int c = 0; c < 3; ++c) {
        term[0][c] = hn::Sub(term[0][c], q[0][c]);
        term[1][c] = hn::NegMulAdd(q[1][c], s.u, hn::NegMulAdd(q[2][c], t.u, term[1][c]));
        term[2][c] = hn::NegMulAdd(q[1][c], s.w, hn::NegMulAdd(q[2][c], t.w, term[2][c]));
      }
    } else {
      // − f W(a, b; x, y) with W = wa a + (1 − wa) b, wa = x / (x + y), x = x(s),
      // y = y(t): fs, ft the partials of f, xs = dx/ds, yt = dy/dt, r = 1/(x + y).
      const double(*vec)[3] = a.corners[i].v;
      auto subtract = [&](V f, V fs, V ft, V x, V xs, V y, V yt, V r, int slot) {
        const V wa = hn::Mul(x, r), r2 = hn::Mul(r, r);
        const V A = hn::Mul(hn::Mul(xs, y), r2), B = hn::Mul(hn::Mul(x, yt), r2);
        const V waU = hn::NegMulAdd(B, t.u, hn::Mul(A, s.u)), waV = hn::NegMulAdd(B, t.w, hn::Mul(A, s.w));
        const V fU = hn::MulAdd(ft, t.u, hn::Mul(fs, s.u)), fV = hn::MulAdd(ft, t.w, hn::Mul(fs, s.w));
        const V fa = hn::Mul(f, wa);
        const V faU = hn::MulAdd(fU, wa, hn::Mul(f, waU)), faV = hn::MulAdd(fV, wa, hn::Mul(f, waV));
        const V fb = hn::Sub(f, fa), fbU = hn::Sub(fU, faU), fbV = hn::Sub(fV, faV);
        for (int c = 0; c < 3; ++c) {
          const V va = hn::Set(d, vec[slot][c]), vb = hn::Set(d, vec[slot + 1][c]);
          term[0][c] = hn::NegMulAdd(fa, va, hn::NegMulAdd(fb, vb, term[0][c]));
          term[1][c] = hn::NegMulAdd(faU, va, hn::NegMulAdd(fbU, vb, term[1][c]));
          term[2][c] = hn::NegMulAdd(faV, va, hn::NegMulAdd(fbV, vb, term[2][c]));
        }
      };
      // With a blend share μ, (1 − μ) Q: every f and its partials scaled.
      const V keep = hn::Set(d, 1.0 - mu);
      for (int c = 0; c < 3; ++c) term[0][c] = hn::NegMulAdd(keep, hn::Set(d, vec[0][c]), term[0][c]);
      const V s2 = hn::Mul(s.v, s.v), t2 = hn::Mul(t.v, t.v), two = hn::Set(d, 2.0);
      V den[3] = {hn::Add(s.v, t2), hn::Add(s2, t.v), hn::Add(s.v, t.v)};
      reciprocals(d, den);
      // s W(a10, b10; s, t²), t W(a01, b01; s², t), s t W(a11, b11; s, t).
      const V st = hn::Mul(s.v, t.v), kt = hn::Mul(keep, t.v), ks = hn::Mul(keep, s.v);
      subtract(ks, keep, zero, s.v, one, t2, hn::Mul(two, t.v), den[0], 1);
      subtract(kt, zero, keep, s2, hn::Mul(two, s.v), t.v, one, den[1], 3);
      subtract(hn::Mul(keep, st), kt, ks, s.v, one, t.v, one, den[2], 5);
    }
    for (int c = 0; c < 3; ++c) {
      acc[0][c] = hn::MulAdd(blend.v, term[0][c], acc[0][c]);
      acc[1][c] = hn::MulAdd(blend.u, term[0][c], hn::MulAdd(blend.v, term[1][c], acc[1][c]));
      acc[2][c] = hn::MulAdd(blend.w, term[0][c], hn::MulAdd(blend.v, term[2][c], acc[2][c]));
    }
  }
  for (int c = 0; c < 3; ++c) {
    hn::StoreU(acc[0][c], d, a.out.v[c] + k);
    hn::StoreU(acc[1][c], d, a.out.du[c] + k);
    hn::StoreU(acc[2][c], d, a.out.dv[c] + k);
  }
}

void GregoryJets(std::size_t count, const GregoryJetArgs &args, bool reference) {
  auto run = [&](auto tag) {
    if (args.in->values.parabolic)
      forEachVector(tag, count, [&](auto d, std::size_t k) { gregoryJetBody<true>(d, k, args); });
    else forEachVector(tag, count, [&](auto d, std::size_t k) { gregoryJetBody<false>(d, k, args); });
  };
  if (reference) run(hn::CappedTag<double, 1>());
  else run(hn::ScalableTag<double>());
}

void GregoryPositions(std::size_t count, const GregoryArgs &args, bool reference) {
  auto run = [&](auto tag) {
    if (args.in->parabolic) forEachVector(tag, count, [&](auto d, std::size_t k) { gregoryBody<true>(d, k, args); });
    else forEachVector(tag, count, [&](auto d, std::size_t k) { gregoryBody<false>(d, k, args); });
  };
  if (reference) run(hn::CappedTag<double, 1>());
  else run(hn::ScalableTag<double>());
}

/// The weights of samples [k, end) in vectors of d's width (a loop of its
/// own with its pointers in registers: the stores cannot alias them).
template <class D>
HWY_NOINLINE std::size_t cornerWeightsLoop(D d, std::size_t k, std::size_t end, const double *HWY_RESTRICT s,
                                           const double *HWY_RESTRICT sPrevious, double *HWY_RESTRICT weights,
                                           std::size_t stride) {
  using V = hn::Vec<D>;
  const std::size_t lanes = hn::Lanes(d);
  const V one = hn::Set(d, 1.0);
  for (; k + lanes <= end; k += lanes) {
    // t as gregoryBody takes it, so that the weights are the same numbers.
    const V sv = hn::LoadU(d, s + k), t = hn::Sub(one, hn::LoadU(d, sPrevious + k));
    V w[8];
    g2RationalWeights(d, sv, t, w);
    for (int j = 0; j < 8; ++j) hn::StoreU(w[j], d, weights + j * stride + k);
  }
  return k;
}

void GregoryCornerWeights(std::size_t count, const CornerWeightArgs &args, bool reference) {
  std::size_t k = 0;
  if (!reference) k = cornerWeightsLoop(hn::ScalableTag<double>(), 0, count, args.s, args.sPrevious, args.weights, args.stride);
  cornerWeightsLoop(hn::CappedTag<double, 1>(), k, count, args.s, args.sPrevious, args.weights, args.stride);
}

/// Polynomial p(s) = Σ c_j s^j of degree ≤ 4, Horner.
template <class V> HWY_INLINE V horner(const V (&c)[5], V s) {
  return hn::MulAdd(hn::MulAdd(hn::MulAdd(hn::MulAdd(c[4], s, c[3]), s, c[2]), s, c[1]), s, c[0]);
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
    return hn::IfThenElse(hn::Gt(hn::Abs(wx), hn::Abs(wy)), hn::Div(hn::Sub(x, s), wx), hn::Div(y, wy));
  }
};

/// The radial parameter of (x, y): where the line from the apex (or, for
/// parallel neighbours, along a) through the point meets the side.
template <class D, class V = hn::Vec<D>> HWY_INLINE V sweepRadial(D d, const ck::SweepFrame &f, V x, V y) {
  if (f.parallel) return hn::Sub(x, hn::Mul(y, hn::Set(d, f.ax / f.ay)));
  const V px = hn::Set(d, f.apexX), py = hn::Set(d, f.apexY);
  return hn::Sub(px, hn::Div(hn::Mul(py, hn::Sub(x, px)), hn::Sub(y, py)));
}

/// |F| at an end of [0, 1] below which the robust solver takes that end as a
/// root: a point on a neighbouring side may show no sign change after rounding.
template <class D, class V = hn::Vec<D>> HWY_INLINE V sweepEndTolerance(D d, const ck::SweepFrame &f, V x, V y) {
  // Plain square roots: the frame's vectors are of domain size (no overflow
  // to guard against), and std::hypot cost 5% of a batch here.
  const double abNorm = std::sqrt(f.ax * f.ax + f.ay * f.ay) + std::sqrt(f.bx * f.bx + f.by * f.by);
  return hn::Mul(hn::Set(d, 1e-13 * abNorm), hn::Add(hn::Set(d, 1.0), hn::Add(hn::Abs(x), hn::Abs(y))));
}

/// Robust solver: isolates every root on [0, 1] by the derivative cascade,
/// bisects each, then applies the selection rule. About 230 polynomial
/// evaluations per point; the fast path's fallback.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void sweepRobust(D d, const ck::SweepFrame &f, V x, V y, V &best, V &bestD) {
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
  const V tolerance = sweepEndTolerance(d, f, x, y);
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

/// Fast solver: safeguarded Newton from the radial parameter, then a
/// certificate that the root found is the one the robust solver selects.
/// Returns the lanes that hold it (s, dist written); the others need the
/// robust solver. About 15 polynomial evaluations and 7 divisions per point.
///
/// Certificate, per lane:
///  * Newton converged: a step |Δs| ≤ 1e-15 inside the bracket of F's sign
///    change (steps leaving it are replaced by bisection; the lane's iterate
///    freezes once converged, so the result does not depend on the other
///    lanes of the vector);
///  * the root r is the only one on [0, 1]: F(s) = (s − r) G(s) + F(r) with
///    the cubic G from synthetic division. If G's Bernstein coefficients on
///    [0, ½] and [½, 1] share a sign, |G| is bounded below on each half by
///    them (a Bernstein polynomial is a convex combination of its
///    coefficients); with the distance from r to each half this bounds
///    |s − r| |G(s)| away from F(r) plus rounding, so every sign change of
///    the computed F lies within 1e-13 of r: one root, the one the robust
///    solver isolates;
///  * neither end of [0, 1] passes the robust solver's end tolerance (else
///    that end would be a second candidate);
///  * d ≥ −1e-9 with a margin: the unique root is then the selection.
template <class D, class V = hn::Vec<D>>
HWY_INLINE auto sweepFast(D d, const ck::SweepFrame &f, V x, V y, V &s, V &dist) -> decltype(hn::Lt(x, x)) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const SweepQuartic<D> q(d, f, x, y);
  const V(&F)[5] = q.F;
  const V F1[5] = {F[1], hn::Add(F[2], F[2]), hn::Mul(hn::Set(d, 3.0), F[3]), hn::Mul(hn::Set(d, 4.0), F[4]), zero};
  constexpr int kIterations = 16;
  const V stepLimit = hn::Set(d, 1e-15), half = hn::Set(d, 0.5);
  // The radial sweep is the Hermite sweep's first-order approximation: few
  // steps. The bracket [lo, hi] keeps the sign change of F (a certified
  // lane has one: F(0) and F(1) differ in sign when the root is unique and
  // away from the ends); a Newton step leaving it is replaced by bisection.
  V r = hn::Min(one, hn::Max(zero, sweepRadial(d, f, x, y)));
  r = hn::IfThenElse(hn::Eq(r, r), r, half); // the apex itself: no radial direction
  V lo = zero, hi = one;
  const auto negativeAtZero = hn::Lt(F[0], zero);
  auto converged = hn::Lt(zero, zero);
  for (int it = 0; it < kIterations; ++it) {
    const V value = horner(F, r);
    const auto belowLo = hn::Not(hn::Xor(hn::Lt(value, zero), negativeAtZero));
    lo = hn::IfThenElse(belowLo, r, lo);
    hi = hn::IfThenElse(belowLo, hi, r);
    const V step = hn::Div(value, horner(F1, r));
    const V newton = hn::Sub(r, step);
    const auto inside = hn::And(hn::Ge(newton, lo), hn::Le(newton, hi));
    r = hn::IfThenElse(converged, r, hn::IfThenElse(inside, newton, hn::Mul(half, hn::Add(lo, hi))));
    converged = hn::Or(converged, hn::And(inside, hn::Le(hn::Abs(step), stepLimit)));
    if (hn::AllTrue(d, converged)) break;
  }
  // Deflation F = (s − r) G + F(r) and G's Bernstein coefficients on [0, 1].
  const V g3 = F[4], g2 = hn::MulAdd(r, g3, F[3]), g1 = hn::MulAdd(r, g2, F[2]), g0 = hn::MulAdd(r, g1, F[1]);
  const V third = hn::Set(d, 1.0 / 3.0);
  const V b1 = hn::MulAdd(third, g1, g0), b2 = hn::MulAdd(third, hn::Add(g1, hn::Add(g1, g2)), g0);
  const V b3 = hn::Add(hn::Add(g0, g1), hn::Add(g2, g3));
  // One de Casteljau split at ½ tightens the hull (the control points of the
  // halves are convex combinations of these): it certifies most triangle
  // points whose quotient dips towards zero without a root.
  const V l1 = hn::Mul(half, hn::Add(g0, b1)), c = hn::Mul(half, hn::Add(b1, b2)), r2 = hn::Mul(half, hn::Add(b2, b3));
  const V l2 = hn::Mul(half, hn::Add(l1, c)), r1 = hn::Mul(half, hn::Add(c, r2)), mid = hn::Mul(half, hn::Add(l2, r1));
  const V lowLeft = hn::Min(hn::Min(g0, l1), hn::Min(l2, mid)), lowRight = hn::Min(hn::Min(mid, r1), hn::Min(r2, b3));
  const V highLeft = hn::Max(hn::Max(g0, l1), hn::Max(l2, mid)), highRight = hn::Max(hn::Max(mid, r1), hn::Max(r2, b3));
  const auto positive = hn::Gt(hn::Min(lowLeft, lowRight), zero), negative = hn::Lt(hn::Max(highLeft, highRight), zero);
  // |G| ≥ m on each half (with G's sign).
  const V mLeft = hn::IfThenElse(positive, lowLeft, hn::Neg(highLeft));
  const V mRight = hn::IfThenElse(positive, lowRight, hn::Neg(highRight));
  V scale = hn::Abs(F[0]);
  for (int j = 1; j < 5; ++j) scale = hn::Add(scale, hn::Abs(F[j]));
  // Another sign change of the computed F at s needs |s − r| |G(s)| ≤ E =
  // |F(r)| + 8 ε Σ|F_j| (Horner's error bound). On a half at distance δ from
  // r, |s − r| ≥ max(δ, ρ) for the s farther than ρ = 1e-13 from r: so if
  // m max(δ, ρ) > E on both halves, every root lies within ρ of r. The floor
  // on m keeps it far above the rounding of G's coefficients.
  const V E = hn::MulAdd(hn::Set(d, 8 * 2.220446049250313e-16), scale, hn::Abs(horner(F, r)));
  const V rho = hn::Set(d, 1e-13), floor = hn::Mul(hn::Set(d, 1e-10), scale);
  const V reachLeft = hn::Max(hn::Sub(r, half), rho), reachRight = hn::Max(hn::Sub(half, r), rho);
  const auto unique = hn::And(hn::Or(positive, negative),
                              hn::And(hn::And(hn::Gt(hn::Mul(mLeft, reachLeft), E), hn::Gt(hn::Mul(mRight, reachRight), E)),
                                      hn::And(hn::Gt(mLeft, floor), hn::Gt(mRight, floor))));
  const V tolerance = sweepEndTolerance(d, f, x, y);
  const auto endsClear = hn::And(hn::Gt(hn::Abs(F[0]), tolerance), hn::Gt(hn::Abs(horner(F, one)), tolerance));
  V wx, wy, sx, sy;
  dist = q.distance(d, x, y, r, wx, wy, sx, sy);
  s = r;
  return hn::And(hn::And(converged, unique), hn::And(endsClear, hn::Ge(dist, hn::Set(d, -0.999e-9))));
}

template <class D> HWY_INLINE void sweepRobustBody(D d, std::size_t k, const SweepArgs &a) {
  hn::Vec<D> s, dist;
  sweepRobust(d, a.frame, hn::LoadU(d, a.x + k), hn::LoadU(d, a.y + k), s, dist);
  hn::StoreU(s, d, a.s + k);
  hn::StoreU(dist, d, a.d + k);
}

/// The fast solver over [0, count) in chunks; the lanes it cannot certify are
/// gathered per chunk and solved by the robust solver at full width, so its
/// cost scales with the failing points, not with the vectors they fall in.
/// Returns the number of such points.
template <class D> HWY_INLINE std::size_t sweepFastThenRobust(D d, std::size_t count, const SweepArgs &a) {
  constexpr std::size_t kChunk = 256;
  double fx[kChunk], fy[kChunk], fs[kChunk], fd[kChunk];
  std::size_t index[kChunk];
  std::size_t total = 0;
  const std::size_t lanes = hn::Lanes(d);
  for (std::size_t begin = 0; begin < count; begin += kChunk) {
    const std::size_t end = std::min(count, begin + kChunk);
    std::size_t failed = 0;
    auto body = [&](auto dd, std::size_t k) {
      using V = hn::Vec<decltype(dd)>;
      V s, dist;
      const auto ok = sweepFast(dd, a.frame, hn::LoadU(dd, a.x + k), hn::LoadU(dd, a.y + k), s, dist);
      hn::StoreU(s, dd, a.s + k);
      hn::StoreU(dist, dd, a.d + k);
      if (HWY_UNLIKELY(!hn::AllTrue(dd, ok))) {
        std::uint8_t bits[16] = {};
        hn::StoreMaskBits(dd, hn::Not(ok), bits);
        for (std::size_t j = 0; j < hn::Lanes(dd); ++j)
          if ((bits[j >> 3] >> (j & 7)) & 1) index[failed] = k + j, fx[failed] = a.x[k + j], fy[failed++] = a.y[k + j];
      }
    };
    std::size_t k = begin;
    for (; k + lanes <= end; k += lanes) body(d, k);
    for (; k < end; ++k) body(hn::CappedTag<double, 1>(), k);
    if (failed == 0) continue;
    const SweepArgs gathered{a.frame, fx, fy, fs, fd};
    forEachVector(d, failed, [&](auto dd, std::size_t j) { sweepRobustBody(dd, j, gathered); });
    for (std::size_t j = 0; j < failed; ++j) a.s[index[j]] = fs[j], a.d[index[j]] = fd[j];
    total += failed;
  }
  return total;
}

std::size_t SweepRoots(std::size_t count, const SweepArgs &args, bool reference) {
  if (reference) return sweepFastThenRobust(hn::CappedTag<double, 1>(), count, args);
  return sweepFastThenRobust(hn::ScalableTag<double>(), count, args);
}

void SweepRootsRobust(std::size_t count, const SweepArgs &args, bool reference) {
  auto body = [&](auto d, std::size_t k) { sweepRobustBody(d, k, args); };
  if (reference) forEachVector(hn::CappedTag<double, 1>(), count, body);
  else forEachVector(hn::ScalableTag<double>(), count, body);
}

std::size_t Lanes() { return hn::Lanes(hn::ScalableTag<double>()); }

} // namespace HWY_NAMESPACE
} // namespace kernels_impl
} // namespace curvenet
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <hwy/targets.h>

namespace curvenet {
namespace kernels_impl {
HWY_EXPORT(SweepRoots);
HWY_EXPORT(SweepRootsRobust);
HWY_EXPORT(GregoryPositions);
HWY_EXPORT(GregoryJets);
HWY_EXPORT(GregoryCornerWeights);
HWY_EXPORT(EvaluateTable);
HWY_EXPORT(Lanes);

/// Index into the dispatch tables: the best target, the baseline for the
/// scalar reference (its width-1 instance), or the one requested
/// (dispatch.hpp: the other kernel sources dispatch through it too).
std::size_t tableIndex(std::int64_t width, bool &reference) {
  reference = width == kernels::kScalarReference;
  if (width == kernels::kBestWidth || reference) {
    // Resolve the CPU's choice (the first dynamic call initializes it); the
    // reference is that target's width-1 instance.
    (void)HWY_DYNAMIC_DISPATCH(Lanes)();
    return hwy::GetChosenTarget().GetIndex();
  }
  const std::int64_t mask = HWY_CHOSEN_TARGET_SHIFT(width) | HWY_CHOSEN_TARGET_MASK_SCALAR;
  return hwy::Num0BitsBelowLS1Bit_Nonzero64(static_cast<std::uint64_t>(mask & HWY_CHOSEN_TARGET_MASK_TARGETS));
}
} // namespace kernels_impl

inline namespace v1 {
namespace kernels {
using namespace curvenet::kernels_impl;

std::vector<Width> availableWidths() {
  std::vector<Width> widths{{kScalarReference, "scalar", 1}};
  for (std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    bool reference;
    const std::size_t lanes = HWY_DISPATCH_TABLE(Lanes)[tableIndex(target, reference)]();
    widths.push_back({target, hwy::TargetName(target), lanes});
  }
  return widths;
}

Width bestWidth() {
  bool reference;
  const std::size_t index = tableIndex(kBestWidth, reference);
  for (const Width &w : availableWidths()) {
    bool r;
    if (w.id != kScalarReference && tableIndex(w.id, r) == index) return w;
  }
  return availableWidths().back();
}

void gregoryJets(std::size_t count, const GregoryJetSamples &samples, const GregoryCorner *corners, DualVec3Span out,
                 std::int64_t width, const GregoryCornerTerms *terms) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  std::array<GregoryCornerTerms, GregorySamples::kMaxSides> computed;
  if (samples.values.parabolic && !terms) {
    for (int i = 0; i < samples.values.sides; ++i) computed[i] = gregoryCornerTerms(corners[i]);
    terms = computed.data();
  }
  HWY_DISPATCH_TABLE(GregoryJets)[index](count, {&samples, corners, out, terms}, reference);
}

void evaluateTable(std::size_t count, const PolynomialTable &table, const double *s, double *const *values,
                   double *const *slopes, std::int64_t width) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  HWY_DISPATCH_TABLE(EvaluateTable)[index](count, {&table, s, values, slopes}, reference);
}

GregoryCornerTerms gregoryCornerTerms(const GregoryCorner &corner) {
  const auto &v = corner.v;
  GregoryCornerTerms q{};
  int slot = 1, j = 0;
  for (int c = 0; c < 3; ++c) q.taylor[0][0][c] = v[0][c];
  for (int p = 0; p <= 2; ++p)
    for (int r = 0; r <= 2; ++r) {
      if (!p && !r) continue;
      const double factorial = (p == 2 ? 0.5 : 1.0) * (r == 2 ? 0.5 : 1.0);
      for (int c = 0; c < 3; ++c)
        q.taylor[p][r][c] = factorial * v[slot + 1][c], q.rational[j][c] = factorial * (v[slot][c] - v[slot + 1][c]);
      slot += 2, ++j;
    }
  return q;
}

void gregoryCornerWeights(std::size_t count, const double *s, const double *sPrevious, double *weights,
                          std::size_t stride, std::int64_t width) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  HWY_DISPATCH_TABLE(GregoryCornerWeights)[index](count, {s, sPrevious, weights, stride}, reference);
}

namespace {
void gregoryPositionsTo(std::size_t count, const GregorySamples &samples, const GregoryCorner *corners,
                        double *const *out, double *interleaved, const double *offset, std::int64_t width,
                        const GregoryCornerTerms *terms) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  std::array<GregoryCornerTerms, GregorySamples::kMaxSides> computed;
  if (samples.parabolic && !terms) {
    for (int i = 0; i < samples.sides; ++i) computed[i] = gregoryCornerTerms(corners[i]);
    terms = computed.data();
  }
  GregoryArgs args{&samples, corners, out, terms, interleaved, {0, 0, 0}};
  if (offset) args.offset[0] = offset[0], args.offset[1] = offset[1], args.offset[2] = offset[2];
  HWY_DISPATCH_TABLE(GregoryPositions)[index](count, args, reference);
}
} // namespace

void gregoryPositions(std::size_t count, const GregorySamples &samples, const GregoryCorner *corners,
                      double *const out[3], std::int64_t width, const GregoryCornerTerms *terms) {
  gregoryPositionsTo(count, samples, corners, out, nullptr, nullptr, width, terms);
}

void gregoryPositionsInterleaved(std::size_t count, const GregorySamples &samples, const GregoryCorner *corners,
                                 double *xyz, const double offset[3], std::int64_t width,
                                 const GregoryCornerTerms *terms) {
  gregoryPositionsTo(count, samples, corners, nullptr, xyz, offset, width, terms);
}

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

} // namespace kernels
} // namespace v1
} // namespace curvenet
#endif
