// Ribbon-table evaluation of curvenet/kernels/kernels.hpp (evaluateTable):
// each sample's interval looked up in the table's cell grid, then its
// degree-5 polynomials and their slopes. Written once over a Highway
// descriptor D (CappedTag<double, 1> the width-1 scalar reference);
// compiled once per target (foreach_target), dispatched at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "table.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "curvenet/kernels/kernels.hpp"
#include "dispatch.hpp"

// Argument bundles, shared by every target's instance (defined once).
#ifndef CURVENET_TABLE_ARGS
#define CURVENET_TABLE_ARGS
namespace curvenet::kernels_impl {
namespace ck = curvenet::kernels;
/// A vector of samples whose intervals are not known to lie in a window.
inline constexpr std::size_t kNoWindow = ~std::size_t{0};
struct TableArgs {
  const ck::PolynomialTable *table;
  const double *s;
  double *const *values, *const *slopes;
};
} // namespace curvenet::kernels_impl
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

/// p(t) = Σ c_j t^j (degree 5) by Horner and, when Slopes, dp/dt beside it:
/// the derivative's Horner runs on the value's partial sums (four
/// multiply-adds, no scaling of the coefficients by 5, 4, 3, 2). The value
/// is the same Horner either way, so values alone equal values with slopes.
template <bool Slopes, class V> HWY_INLINE void quintic(const V (&c)[6], V t, V &value, V &derivative) {
  V v = hn::MulAdd(c[5], t, c[4]), dv = c[5];
  for (int j = 3; j >= 0; --j) {
    if constexpr (Slopes) dv = hn::MulAdd(dv, t, v);
    v = hn::MulAdd(v, t, c[j]);
  }
  value = v;
  if constexpr (Slopes) derivative = dv;
}

/// One sample's coordinates x .. x + lanes − 1 (value, and d/ds when
/// Slopes) over D, whose lanes run across the coordinates; c points at the
/// sample's interval, t is its local parameter.
template <bool Slopes, class D, class V = hn::Vec<D>>
HWY_INLINE void tablePolynomial(D d, const double *c, std::size_t row, V t, V inverseWidth, V &value, V &slope) {
  const V coefficient[6] = {hn::LoadU(d, c),           hn::LoadU(d, c + row),     hn::LoadU(d, c + 2 * row),
                            hn::LoadU(d, c + 3 * row), hn::LoadU(d, c + 4 * row), hn::LoadU(d, c + 5 * row)};
  V dv;
  quintic<Slopes>(coefficient, t, value, dv);
  if constexpr (Slopes) slope = hn::Mul(dv, inverseWidth);
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
/// Whether s[q] and s[q + lanes − 1] lie within `lanes` intervals of average
/// width of each other: farther apart (or NaN), their vector misses any
/// window — a batch at random points, found for the cost of a subtraction.
HWY_INLINE bool closeTogether(const double *s, std::size_t q, std::size_t lanes, std::size_t intervals) {
  return std::abs(s[q + lanes - 1] - s[q]) * static_cast<double>(intervals) <= static_cast<double>(lanes);
}

/// tableLookups for samples that lie close together, as a plan's rows do:
/// a vector of samples at a time whose intervals all lie in the window of
/// `lanes` intervals from the first or last sample's, whichever is less
/// (or from the table's last but `lanes`). That interval j₀ through
/// tableInterval, then each sample's as j₀ plus the number of the
/// window's intervals ending before it, compared a whole vector at a time,
/// and the starts and widths permuted out of the window's. The interval is
/// the first whose end is not below s, which tableInterval finds when the
/// cell count is a power of two (every cell's start then exact). At the
/// first vector with a sample left of its window (NaN, s ≤ 0, samples not
/// in order) or right of it, or first and last samples too far apart, the
/// rest go through tableLookups (a batch at random points would try every
/// window in vain: 8–12 % slower so). A scalar lookup a sample was
/// about fourteen instructions with chains of dependent loads: a quarter of
/// G¹'s face interiors, a fifth of G²'s.
template <bool Inverse, class D>
HWY_NOINLINE void tableLookupsWindowed(D d, const ck::PolynomialTable &tb, const double *HWY_RESTRICT s, std::size_t k,
                                       std::size_t end, std::size_t *HWY_RESTRICT interval, double *HWY_RESTRICT local,
                                       double *HWY_RESTRICT inverse, std::size_t *HWY_RESTRICT windows) {
  using V = hn::Vec<D>;
  const hn::RebindToSigned<D> di;
  const std::size_t lanes = hn::Lanes(d), intervals = tb.intervals;
  // The table's arrays in locals: through tb, GCC reloaded them after every store.
  const double *HWY_RESTRICT ends = tb.ends, *HWY_RESTRICT starts = tb.starts,
               *HWY_RESTRICT inverseWidths = tb.inverseWidths;
  std::size_t q = k;
  for (; q + lanes <= end && intervals >= lanes; q += lanes) {
    if (!closeTogether(s, q, lanes, intervals)) break;
    const V x = hn::LoadU(d, s + q);
    // The rows run either way along a side: the window starts at the end
    // nearer s = 0, no further than `lanes` from the table's end.
    const std::size_t first = std::min(tableInterval(tb, std::min(s[q], s[q + lanes - 1])), intervals - lanes);
    const bool window = (first == 0 || hn::AllTrue(d, hn::Lt(hn::Set(d, ends[first - 1]), x))) &&
                        hn::AllFalse(d, hn::Lt(hn::Set(d, ends[first + lanes - 1]), x));
    if (!window) break; // the rest one at a time: samples at random would miss every window
    auto offset = hn::Zero(di);
    for (std::size_t r = 0; r + 1 < lanes; ++r)
      offset = hn::IfThenElse(hn::RebindMask(di, hn::Lt(hn::Set(d, ends[first + r]), x)), hn::Add(offset, hn::Set(di, 1)),
                              offset);
    const auto at = hn::IndicesFromVec(d, offset);
    const V w = hn::TableLookupLanes(hn::LoadU(d, inverseWidths + first), at);
    const V start = hn::TableLookupLanes(hn::LoadU(d, starts + first), at);
    hn::StoreU(hn::Add(offset, hn::Set(di, static_cast<std::int64_t>(first))), di,
               reinterpret_cast<std::int64_t *>(interval) + (q - k));
    hn::StoreU(hn::Mul(hn::Sub(x, start), w), d, local + (q - k));
    if constexpr (Inverse) hn::StoreU(w, d, inverse + (q - k));
    windows[(q - k) / lanes] = first;
  }
  for (std::size_t v = q; v + lanes <= end; v += lanes) windows[(v - k) / lanes] = kNoWindow;
  if (q < end) tableLookups<Inverse>(hn::CappedTag<double, 4>(), tb, s, q, end, interval + (q - k), local + (q - k), inverse + (q - k));
}

/// The lookups of s[k .. end) (see tableLookups), windowed where the
/// table's cells allow (tableLookupsWindowed); each vector's window start
/// into windows[v] (kNoWindow: none).
template <bool Inverse, class D>
HWY_INLINE void lookUp(D d, const ck::PolynomialTable &tb, const double *s, std::size_t k, std::size_t end,
                       std::size_t *interval, double *local, double *inverse, std::size_t *windows) {
  // The windows' first test here, in line: a batch at random points fails
  // it at once and goes straight to the scalar lookups.
  const std::size_t lanes = hn::Lanes(d);
  if (end - k >= lanes && closeTogether(s, k, lanes, tb.intervals) && (tb.cells & (tb.cells - 1)) == 0)
    return tableLookupsWindowed<Inverse>(d, tb, s, k, end, interval, local, inverse, windows);
  tableLookups<Inverse>(hn::CappedTag<double, 4>(), tb, s, k, end, interval, local, inverse);
  for (std::size_t v = 0; (v + 1) * lanes <= end - k; ++v) windows[v] = kNoWindow;
}

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
  const V coefficient[6] = {k[0], k[1], k[2], k[3], k45[0], k45[1]};
  V dv;
  quintic<Slopes>(coefficient, t, value, dv);
  if constexpr (Slopes) slope = hn::Mul(dv, inverseWidth);
}

/// The samples k … k + lanes − 1 of D when they share one interval, whose
/// coefficients start at c: the lanes run across the samples from the start
/// and every coefficient is a broadcast, so no transposes, which cost the
/// other blocks as many vector operations as their polynomials. The same
/// operations lane by lane as the transposing paths: the same bits.
template <bool Slopes, class D, class V = hn::Vec<D>>
HWY_INLINE void oneIntervalPolynomials(D d, const double *c, std::size_t row, std::size_t rowDims, std::size_t tail, V t,
                                       V inverseWidth, double *const *values, double *const *slopes, std::size_t k) {
  auto coordinate = [&](const double *at, std::size_t step, double *value, double *slope) {
    const V coefficient[6] = {hn::Set(d, at[0]),        hn::Set(d, at[step]),     hn::Set(d, at[2 * step]),
                              hn::Set(d, at[3 * step]), hn::Set(d, at[4 * step]), hn::Set(d, at[5 * step])};
    V v, dv;
    quintic<Slopes>(coefficient, t, v, dv);
    hn::StoreU(v, d, value + k);
    if constexpr (Slopes) hn::StoreU(hn::Mul(dv, inverseWidth), d, slope + k);
  };
  for (std::size_t x = 0; x < rowDims; ++x) coordinate(c + x, row, values[x], Slopes ? slopes[x] : nullptr);
  for (std::size_t e = 0; e < tail; ++e)
    coordinate(c + 6 * row + 8 * e, 1, values[rowDims + e], Slopes ? slopes[rowDims + e] : nullptr);
}

/// Whether the `lanes` intervals from `interval` on are all the same.
template <class D> HWY_INLINE bool oneInterval(D d, const std::size_t *interval) {
  const hn::Rebind<std::uint64_t, D> du;
  const auto *at = reinterpret_cast<const std::uint64_t *>(interval);
  return hn::AllTrue(du, hn::Eq(hn::Load(du, at), hn::Set(du, at[0])));
}

/// RibbonTable evaluation of four samples at a time over D with four lanes:
/// the row coordinates with the lanes across the coordinates, the four
/// samples transposed in registers so that the structure-of-arrays outputs
/// are written as whole vectors; the tail coordinates with the lanes across
/// the samples. The layout known at compile time (kRow > 0: the engine's
/// tables, 6 row coordinates in rows of 8 for G¹ ribbons P, T; 8 and a tail
/// of 1 for G² P, T, C) unrolls every loop and keeps the output pointers in
/// registers; kRow = 0 reads it from the table. Four samples in one interval
/// take oneIntervalPolynomials. Returns the samples done (a multiple of
/// four); the rest is the caller's.
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
  HWY_ALIGN std::size_t interval[kChunk], windows[kChunk / 4];
  HWY_ALIGN double local[kChunk], inverse[kChunk];
  std::size_t k = 0;
  for (std::size_t chunkStart = 0; chunkStart + 4 <= count; chunkStart += kChunk) {
    const std::size_t chunkEnd = std::min(count, chunkStart + kChunk);
    lookUp<Slopes>(d, tb, a.s, chunkStart, chunkEnd, interval, local, inverse, windows);
    for (k = chunkStart; k + 4 <= chunkEnd; k += 4) {
      const std::size_t first = k - chunkStart;
      if (oneInterval(d, interval + first)) {
        oneIntervalPolynomials<Slopes>(d, tb.coefficients + interval[first] * block, row, rowDims, tail,
                                       hn::Load(d, local + first), Slopes ? hn::Load(d, inverse + first) : hn::Zero(d),
                                       values, slopes, k);
        continue;
      }
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

#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
/// The 8 × 8 transpose on AVX-512: r[q] (sample q's eight coordinates) →
/// column[c] = (r[0][c], …, r[7][c]). Pairs of rows interleaved within each
/// 128-bit block, then a 4 × 4 transpose of the blocks: column 2b + p takes
/// block b of the interleaved rows p, 2 + p, 4 + p, 6 + p. Columns nobody
/// stores are dropped by the compiler.
template <class D, class V = hn::Vec<D>> HWY_INLINE void transpose8(D d, const V (&r)[8], V (&column)[8]) {
  V t[8];
  for (int i = 0; i < 4; ++i)
    t[2 * i] = hn::InterleaveLower(d, r[2 * i], r[2 * i + 1]), t[2 * i + 1] = hn::InterleaveUpper(d, r[2 * i], r[2 * i + 1]);
  for (int p = 0; p < 2; ++p) {
    const V a = t[p], b = t[2 + p], c = t[4 + p], e = t[6 + p];
    // Blocks (a0 b0 a2 b2), (a1 b1 a3 b3), (c0 e0 c2 e2), (c1 e1 c3 e3).
    const V x0 = hn::OddEvenBlocks(hn::SwapAdjacentBlocks(b), a), x1 = hn::OddEvenBlocks(b, hn::SwapAdjacentBlocks(a));
    const V y0 = hn::OddEvenBlocks(hn::SwapAdjacentBlocks(e), c), y1 = hn::OddEvenBlocks(e, hn::SwapAdjacentBlocks(c));
    column[p] = hn::ConcatLowerLower(d, y0, x0), column[2 + p] = hn::ConcatLowerLower(d, y1, x1);
    column[4 + p] = hn::ConcatUpperUpper(d, y0, x0), column[6 + p] = hn::ConcatUpperUpper(d, y1, x1);
  }
}

/// evaluateTableFours at eight lanes, for the engine's tables (rows of 8:
/// kRowDims = 8 with a tail of 1 for G² P, T, C; 6 and none for G¹ P, T):
/// per sample one vector per coefficient row instead of two, eight samples
/// transposed at a time, the tail's eight samples across the lanes. Half the
/// loads and multiply-adds of four lanes; the table took 57 % of the face
/// interiors' time at four. Eight samples in one interval take
/// oneIntervalPolynomials. Returns the samples done (a multiple of eight).
/// Its chunk loop (lookups, then a block at a time) is evaluateTableFours'
/// at eight: one loop over both with the mixed block as a callable measured
/// 3–4 % slower on the face interiors, so each keeps its own.
template <bool Slopes, std::size_t kRowDims, std::size_t kTail, class D>
HWY_INLINE std::size_t evaluateTableEights(D d, std::size_t count, const TableArgs &a) {
  using V = hn::Vec<D>;
  const ck::PolynomialTable &tb = *a.table;
  constexpr std::size_t kRow = 8, kBlock = 6 * kRow + 8 * kTail, kChunk = 64;
  double *values[kRowDims + kTail], *slopes[kRowDims + kTail];
  for (std::size_t x = 0; x < kRowDims + kTail; ++x) values[x] = a.values[x], slopes[x] = Slopes ? a.slopes[x] : nullptr;
  HWY_ALIGN std::size_t interval[kChunk], windows[kChunk / 4];
  HWY_ALIGN double local[kChunk], inverse[kChunk];
  std::size_t k = 0;
  for (std::size_t chunkStart = 0; chunkStart + 8 <= count; chunkStart += kChunk) {
    const std::size_t chunkEnd = std::min(count, chunkStart + kChunk);
    lookUp<Slopes>(d, tb, a.s, chunkStart, chunkEnd, interval, local, inverse, windows);
    for (k = chunkStart; k + 8 <= chunkEnd; k += 8) {
      const std::size_t first = k - chunkStart;
      if (oneInterval(d, interval + first)) {
        // On pentagon r256 three blocks in ten of a G² tessellation; the
        // others span two to eight intervals.
        oneIntervalPolynomials<Slopes>(d, tb.coefficients + interval[first] * kBlock, kRow, kRowDims, kTail,
                                       hn::Load(d, local + first), Slopes ? hn::Load(d, inverse + first) : hn::Zero(d),
                                       values, slopes, k);
        continue;
      }
      const double *c[8];
      V value[8], slope[8], column[8];
      for (std::size_t q = 0; q < 8; ++q) {
        const std::size_t at = k - chunkStart + q;
        c[q] = tb.coefficients + interval[at] * kBlock;
        const V w = Slopes ? hn::Set(d, inverse[at]) : hn::Zero(d); // inverse: only with slopes
        tablePolynomial<Slopes>(d, c[q], kRow, hn::Set(d, local[at]), w, value[q], slope[q]);
      }
      transpose8(d, value, column);
      for (std::size_t x = 0; x < kRowDims; ++x) hn::StoreU(column[x], d, values[x] + k);
      if constexpr (Slopes) {
        transpose8(d, slope, column);
        for (std::size_t x = 0; x < kRowDims; ++x) hn::StoreU(column[x], d, slopes[x] + k);
      }
      const std::size_t window = windows[(k - chunkStart) / 8];
      for (std::size_t e = 0; e < kTail; ++e) {
        V coefficient[6];
        if (tb.tailByInterval && window != kNoWindow) {
          // The eight samples' intervals lie in [window, window + 8): each
          // coefficient's vector permuted out of the window's.
          const hn::RebindToSigned<D> di;
          const auto at = hn::IndicesFromVec(
              d, hn::Sub(hn::Load(di, reinterpret_cast<const std::int64_t *>(interval) + (k - chunkStart)),
                         hn::Set(di, static_cast<std::int64_t>(window))));
          const double *from = tb.tailByInterval + 6 * e * tb.intervals + window;
          for (std::size_t r = 0; r < 6; ++r) coefficient[r] = hn::TableLookupLanes(hn::LoadU(d, from + r * tb.intervals), at);
        } else {
          // Each sample's eight doubles (t⁰ … t⁵, two zeros) → the six
          // coefficients' eight-sample vectors.
          V raw[8], column[8];
          for (std::size_t q = 0; q < 8; ++q) raw[q] = hn::LoadU(d, c[q] + 6 * kRow + 8 * e);
          transpose8(d, raw, column);
          for (std::size_t r = 0; r < 6; ++r) coefficient[r] = column[r];
        }
        V v, dv;
        quintic<Slopes>(coefficient, hn::Load(d, local + (k - chunkStart)), v, dv);
        hn::StoreU(v, d, values[kRowDims + e] + k);
        if constexpr (Slopes) hn::StoreU(hn::Mul(dv, hn::Load(d, inverse + (k - chunkStart))), d, slopes[kRowDims + e] + k);
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
  if (reference) return run(hn::CappedTag<double, 1>());
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
  // The engine's layouts at eight lanes, the rest of the samples at four;
  // every layout at four where the CPU splits 512-bit vectors (on Zen 4 the
  // G² face interiors ran 3-10 % and the tessellation 3-12 % faster so,
  // curvenet bench, alternating runs).
  const ck::PolynomialTable &tb = *args.table;
  const hn::CappedTag<double, 8> d8;
  std::size_t done = 0;
  const bool eightLanes = ck::eightLaneTables();
  if (eightLanes && tb.paddedDims == 8 && tb.rowDims() == 8 && tb.tailDims() == 1)
    done = args.slopes ? evaluateTableEights<true, 8, 1>(d8, count, args) : evaluateTableEights<false, 8, 1>(d8, count, args);
  else if (eightLanes && tb.paddedDims == 8 && tb.rowDims() == 6 && tb.tailDims() == 0)
    done = args.slopes ? evaluateTableEights<true, 6, 0>(d8, count, args) : evaluateTableEights<false, 6, 0>(d8, count, args);
  if (done > 0) {
    if (done == count) return;
    double *values[ck::PolynomialTable::kMaxDims], *slopes[ck::PolynomialTable::kMaxDims];
    for (int x = 0; x < tb.dims; ++x) values[x] = args.values[x] + done, slopes[x] = args.slopes ? args.slopes[x] + done : nullptr;
    const TableArgs rest{&tb, args.s + done, values, args.slopes ? slopes : nullptr};
    if (rest.slopes) evaluateTableWith<true>(hn::CappedTag<double, 4>(), count - done, rest);
    else evaluateTableWith<false>(hn::CappedTag<double, 4>(), count - done, rest);
    return;
  }
#endif
  run(hn::CappedTag<double, 4>());
}

} // namespace HWY_NAMESPACE
} // namespace kernels_impl
} // namespace curvenet
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace curvenet {
namespace kernels_impl {
HWY_EXPORT(EvaluateTable);
} // namespace kernels_impl

inline namespace v1 {
namespace kernels {
using namespace curvenet::kernels_impl;

void evaluateTable(std::size_t count, const PolynomialTable &table, const double *s, double *const *values,
                   double *const *slopes, std::int64_t width) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  HWY_DISPATCH_TABLE(EvaluateTable)[index](count, {&table, s, values, slopes}, reference);
}

} // namespace kernels
} // namespace v1
} // namespace curvenet
#endif
