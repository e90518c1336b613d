// curvenet/kernels/kernels.hpp — batched evaluation kernels over many samples.
//
// Every kernel is one template over the SIMD width (docs/design.md §4, STYLE.md
// practice 5). The width-1 instance is the scalar reference; the other
// instances are compiled for each instruction set the build supports and
// chosen at run time for the CPU (Google Highway's dynamic dispatch). This
// header is the only view of the kernels: it names no SIMD library, so no
// engine code depends on one.
//
// Data are structures of arrays: a batch of `count` Dual numbers (value and
// the two partial derivatives over the domain) is three arrays; a batch of
// Dual 3-vectors is nine. Arrays need no alignment, but cache-line aligned
// ones (AlignedVector) are faster: no vector load straddles two lines (on
// the ribbon tables ~18% of the table kernel's time). Output arrays may not
// alias inputs unless stated.
//
// Threads: every kernel is a pure function of its arguments; calls on
// disjoint outputs may run concurrently. Cost: linear in `count`, no
// allocation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <optional>
#include <string>
#include <vector>

namespace curvenet {
inline namespace v1 {
namespace kernels {

/// One SIMD width the kernels can run at on this CPU.
struct Width {
  /// Opaque selector passed to the kernels; kBestWidth picks the widest the
  /// CPU supports, kScalarReference the width-1 reference.
  std::int64_t id;
  std::string name; ///< instruction set, e.g. "AVX2"; "scalar" for the reference
  std::size_t lanes; ///< doubles per vector
};
constexpr std::int64_t kBestWidth = 0;
constexpr std::int64_t kScalarReference = -1;

/// The scalar reference first, then every compiled instruction set this CPU
/// runs, widest first. Thread-safe.
std::vector<Width> availableWidths();
/// The width kBestWidth resolves to on this CPU.
Width bestWidth();

/// Whether evaluateTable takes its eight-lane AVX-512 path (eight samples
/// transposed at a time) for the engine's layouts, or the four-lane one. By
/// default eight lanes except on CPUs that run a 512-bit vector as two
/// 256-bit halves (Zen 4), where the transposes cost more than they save.
/// Both paths give the same bits; setEightLaneTables overrides the choice
/// (std::nullopt: back to the CPU's), for tests and benchmarks. Thread-safe.
bool eightLaneTables();
void setEightLaneTables(std::optional<bool> eightLanes);

/// Allocator of cache-line (64-byte) aligned storage for kernel arrays.
template <class T> struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlignment{64};
  CacheLineAllocator() = default;
  template <class U> CacheLineAllocator(const CacheLineAllocator<U> &) noexcept {}
  T *allocate(std::size_t n) { return static_cast<T *>(::operator new(n * sizeof(T), kAlignment)); }
  void deallocate(T *p, std::size_t) noexcept { ::operator delete(p, kAlignment); }
  template <class U> bool operator==(const CacheLineAllocator<U> &) const noexcept { return true; }
};
/// A std::vector whose data start on a cache line.
template <class T> using AlignedVector = std::vector<T, CacheLineAllocator<T>>;

/// Batch of Dual 3-vectors: component c of the value is v[c][k], of ∂/∂u du[c][k], …
struct DualVec3Span {
  double *v[3], *du[3], *dv[3];
};
/// A piecewise degree-5 polynomial in one parameter s ∈ [0, 1] with `dims`
/// coordinates (RibbonTable's storage): interval j covers (starts[j],
/// ends[j]] (the first also s = 0); its coefficients of t⁰ … t⁵ in
/// t = (s − starts[j]) · inverseWidths[j] are a block of blockSize()
/// doubles at coefficients + j · blockSize(): 6 rows of `paddedDims`
/// doubles (a multiple of 4) holding the first min(dims, paddedDims)
/// coordinates, padded with zeros; then each remaining coordinate (the
/// tail) as 8 doubles, t⁰ … t⁵ and two zeros. (A lone coordinate past a
/// multiple of 4 is cheaper as a tail than as a row of four mostly zero
/// lanes: the kernel evaluates tails four samples at a time.)
/// cellFirst[c] is the first interval reaching c / cells; at most `steps`
/// moves forward from it reach any s of the cell. Optional, for steps ≤ 1:
/// cellFirstEnd[c], the end of interval cellFirst[c] (+∞ for the last), so
/// that the lookup reads one cell rather than a cell and then an interval.
/// At most kMaxDims coordinates.
struct PolynomialTable {
  static constexpr int kMaxDims = 16;
  int dims = 0, paddedDims = 0, steps = 0;
  /// Coordinates in the rows, and in the tail.
  int rowDims() const { return dims < paddedDims ? dims : paddedDims; }
  int tailDims() const { return dims - rowDims(); }
  std::size_t blockSize() const { return static_cast<std::size_t>(6 * paddedDims + 8 * tailDims()); }
  std::size_t intervals = 0, cells = 0;
  const double *starts = nullptr, *ends = nullptr, *inverseWidths = nullptr, *coefficients = nullptr;
  const std::uint32_t *cellFirst = nullptr;
  const double *cellFirstEnd = nullptr;
  /// Optional: the tail coordinates' coefficients again, interval after
  /// interval — t^r of tail coordinate e for interval j at
  /// [(6e + r) · intervals + j] — from which eight samples in a window of
  /// eight intervals take them with one permutation each instead of a
  /// transpose (AVX-512; see evaluateTable).
  const double *tailByInterval = nullptr;
};

/// (b) Batched ribbon evaluation: the table at s[0 .. count) into
/// values[c][k] and, when slopes is not null, d/ds into slopes[c][k]. Each
/// sample's interval is looked up — a vector of samples at a time where
/// they lie within a window of intervals, as a plan's rows do — then its
/// row polynomials evaluated with the coordinates across the SIMD lanes and
/// its tail ones with the samples across the lanes; a vector of samples in
/// one interval takes every coordinate with the samples across the lanes.
/// On AVX-512, rows of 8 (the engine's layouts) take eight samples at a
/// time at eight lanes, with the same bits as four. The reference: one
/// sample at a time.
void evaluateTable(std::size_t count, const PolynomialTable &table, const double *s, double *const *values,
                   double *const *slopes, std::int64_t width = kBestWidth);

/// Per-sample data of a Gregory corner-based patch for its positions: for
/// each side i < sides, the side parameter s_i (also the distance parameter
/// of the neighbouring side's ribbon), the normalized corner blend
/// B_{i,i−1}, and that side's ribbon P_i, T_i (C_i when parabolic) at s_i.
struct GregorySamples {
  static constexpr int kMaxSides = 8;
  int sides = 0;          ///< 3 … 8
  bool parabolic = false; ///< G² (parabolic ribbons, nine-term correction) or G¹
  const double *s[kMaxSides] = {}, *blend[kMaxSides] = {};
  const double *P[kMaxSides][3] = {}, *T[kMaxSides][3] = {}, *C[kMaxSides][3] = {};
  /// G², optional: corner i's rational weights from gregoryCornerWeights,
  /// weight j of sample k at weights[i][j · weightStride + k]. They depend on
  /// (s_i, t_i) alone, so samples that a rotation of the domain maps onto
  /// one another share them: the engine computes them once per rotation
  /// group of a plan's samples for all n corners. Null: computed here.
  const double *weights[kMaxSides] = {};
  std::size_t weightStride = 0;
  /// Corner i's share μ_i ∈ [0, 1] of the two-ribbon blend in its
  /// interpolant, I_i = (1 − μ_i)(R_{i−1} + R_i − Q_i) + μ_i (λ_i R_{i−1} +
  /// (1 − λ_i) R_i), λ_i = t_i^m / (s_i^m + t_i^m) (½ at the corner itself;
  /// m = 3 for G², 2 for G¹). Both parts meet each ribbon along its side to
  /// the scheme's order; the blend is a convex combination of ribbon
  /// values, so it cannot carry the ribbons' disagreement at the corner
  /// into the interior as Q_i does. 0 (the default) is [SV14] eq. 17 alone;
  /// at 1, Q_i is not evaluated.
  double blendShare[kMaxSides] = {};
  /// G² only: ribbon i's reach r_i. Its cross parameter δ (s_{i+1} at
  /// corner i + 1, t_i at corner i) saturates, δ ↦ r_i tanh(δ / r_i), where
  /// its neighbours' corner expansions stop holding; the correction patch
  /// Q_i takes the same saturated pair (r_{i−1} tanh(s_i / r_{i−1}),
  /// r_i tanh(t_i / r_i)), the two-ribbon blend and the corner blends the
  /// sweep's own. tanh is odd, so the ribbons on their sides are unchanged.
  /// r_i ≥ 1 (the default) leaves δ as it is, in the very same operations.
  /// A corner either of whose two ribbons saturates computes its rational
  /// weights here, from the saturated pair: `weights` is not read there.
  double reach[kMaxSides] = {1, 1, 1, 1, 1, 1, 1, 1};
  static_assert(kMaxSides == 8, "one reach of 1 per side in reach's initializer");
};

/// The correction patch's constant vectors at corner i (where side i − 1
/// ends and side i starts). G¹ (7 used): a00, a10, b10, a01, b01, a11, b11
/// of Q = a00 + s W(a10, b10; s, t²) + t W(a01, b01; s², t) + s t W(a11, b11; s, t);
/// G² (17): a00, then a_pq, b_pq for p, q ∈ {0, 1, 2} row by row without
/// (0, 0), of [SV14] eq. 22 (W_pq = (s^{3−p} a + t^{3−q} b) / (s^{3−p} + t^{3−q})).
struct GregoryCorner {
  double v[17][3];
};

/// A G² corner's correction patch rearranged for positions: with
/// f_pq = s^p t^q / (p! q!) and W_pq as above,
/// Q = a00 + Σ f_pq W_pq = Σ_{p,q} s^p t^q taylor[p][q]
///                         + s³ Σ_{(p,q)≠(0,0)} t^q / (s^{3−p} + t^{3−q}) rational[j],
/// taylor[p][q] = b_pq / (p! q!) (taylor[0][0] = a00), rational[j] =
/// (a_pq − b_pq) / (p! q!), j counting (p, q) row by row: a polynomial in
/// Horner form and one product per rational term instead of a weighted pair.
struct GregoryCornerTerms {
  double taylor[3][3][3];
  double rational[8][3];
};

/// The rearranged form of a G² corner (17 vectors).
GregoryCornerTerms gregoryCornerTerms(const GregoryCorner &corner);

/// The G² correction patch's eight rational weights at a corner, for
/// s[0 .. count) and t = 1 − sPrevious[k] (GregorySamples: s_i and
/// s_{i−1}): weights[j · stride + k] = s³ t^q / (s^{3−p} + t^{3−q}), j
/// counting (p, q) ≠ (0, 0) row by row, so that Q = Σ s^p t^q taylor[p][q]
/// + Σ_j w_j rational[j] (GregoryCornerTerms); 0 at s = t = 0, the limit.
/// The eight share one division (batch inversion). gregoryPositions
/// computes the same numbers in the same operations when not given them.
void gregoryCornerWeights(std::size_t count, const double *s, const double *sPrevious, double *weights,
                          std::size_t stride, std::int64_t width = kBestWidth);

/// A G² ribbon's saturated cross parameter r tanh(x / r) and its slope
/// 1 − tanh²(x / r) at x[0 .. count), as the Gregory kernels compute them
/// for a ribbon of reach r < 1 (GregorySamples::reach).
void saturatedCross(std::size_t count, const double *x, double reach, double *value, double *slope,
                    std::int64_t width = kBestWidth);

/// (b) Gregory patch positions ([SV14] eqs. 16–18, 22):
/// out[c][k] = Σ_i B_i (R_{i−1}(s_{i−1}, s_i) + R_i(s_i, t_i) − Q_i(s_i, t_i)),
/// t_i = 1 − s_{i−1}, R(σ, δ) = P(σ) + δ T(σ) [+ ½ δ² C(σ)]; corners with
/// a blendShare take that share from the two-ribbon blend instead. The rational
/// weights of each corner share one division (batch inversion). Samples
/// exactly at a corner (s_i = t_i = 0) give that corner's finite limit.
/// G² ribbons with a reach below 1 take their saturated cross parameters
/// (GregorySamples::reach) in R and Q alike.
/// G² uses each corner's GregoryCornerTerms: pass them in `terms` (one per
/// side, from gregoryCornerTerms) when calling often with the same corners;
/// null computes them on each call.
void gregoryPositions(std::size_t count, const GregorySamples &samples, const GregoryCorner *corners,
                      double *const out[3], std::int64_t width = kBestWidth,
                      const GregoryCornerTerms *terms = nullptr);
/// gregoryPositions writing points instead: xyz[3k + c] = position_c +
/// offset[c] (e.g. an array of 3-double points, with the model's origin).
void gregoryPositionsInterleaved(std::size_t count, const GregorySamples &samples, const GregoryCorner *corners,
                                 double *xyz, const double offset[3], std::int64_t width = kBestWidth,
                                 const GregoryCornerTerms *terms = nullptr);

/// gregoryPositions' data with the first derivatives over the domain: of
/// the side parameters and blends (∂/∂u, ∂/∂v), and of the ribbons along
/// their sides (d/ds of P, T, C).
struct GregoryJetSamples {
  GregorySamples values;
  const double *sDu[GregorySamples::kMaxSides] = {}, *sDv[GregorySamples::kMaxSides] = {};
  const double *blendDu[GregorySamples::kMaxSides] = {}, *blendDv[GregorySamples::kMaxSides] = {};
  const double *dP[GregorySamples::kMaxSides][3] = {}, *dT[GregorySamples::kMaxSides][3] = {},
               *dC[GregorySamples::kMaxSides][3] = {};
  /// Side i's parameter gradient (sDu, sDv) and corner i's blend gradient
  /// (blendDu, blendDv) may be given in a frame turned from the domain's by
  /// (cos θ, sin θ): the kernel turns them back, ∂/∂u = c g₁ − s g₂,
  /// ∂/∂v = s g₁ + c g₂. A plan stores one side's data for all the sides a
  /// rotation of the domain maps onto it, so its arrays are read as they are.
  /// (1, 0), the default: the gradients are the domain's.
  double sideTurn[GregorySamples::kMaxSides][2] = {{1, 0}, {1, 0}, {1, 0}, {1, 0}, {1, 0}, {1, 0}, {1, 0}, {1, 0}};
  double blendTurn[GregorySamples::kMaxSides][2] = {{1, 0}, {1, 0}, {1, 0}, {1, 0}, {1, 0}, {1, 0}, {1, 0}, {1, 0}};
  static_assert(GregorySamples::kMaxSides == 8, "one turn of (1, 0) per side in the turns' initializers");
  /// G², optional: corner i's rational weights with their partials in s and
  /// t from gregoryCornerWeightJets, row j of sample k at
  /// weightJets[i][j · weightJetStride + k] — shared, like
  /// GregorySamples::weights, by the samples a rotation maps onto one
  /// another. Used at the corners whose two cross parameters do not
  /// saturate (values.reach ≥ 1 on both), where the weights are those of
  /// the side parameters themselves; null: computed here.
  const double *weightJets[GregorySamples::kMaxSides] = {};
  std::size_t weightJetStride = 0;
};

/// gregoryCornerWeights with the partials: rows j = 0 … 7 the eight weights
/// ρ_j at (s[k], t = 1 − sPrevious[k]), rows 8 + j their ∂/∂s, rows 16 + j
/// their ∂/∂t, row r of sample k at weights[r · stride + k]. gregoryJets
/// computes the same numbers in the same operations when not given them.
void gregoryCornerWeightJets(std::size_t count, const double *s, const double *sPrevious, double *weights,
                             std::size_t stride, std::int64_t width = kBestWidth);

/// (b) gregoryPositions with exact first derivatives: the point into out.v,
/// ∂/∂u into out.du, ∂/∂v into out.dv (product, quotient and chain rules
/// through the ribbons and the rational weights, in one pass; a saturated
/// cross parameter δ = r tanh(d / r) with its slope 1 − tanh²). G² takes
/// its correction patches in the GregoryCornerTerms form, as
/// gregoryPositions does (`terms`: one per side, or null to compute them).
void gregoryJets(std::size_t count, const GregoryJetSamples &samples, const GregoryCorner *corners, DualVec3Span out,
                 std::int64_t width = kBestWidth, const GregoryCornerTerms *terms = nullptr);

/// (b) A tessellation's vertices from `count` jets (jet[0..2] the point's
/// x, y, z, jet[3..5] ∂/∂u and jet[6..8] ∂/∂v, as gregoryJets writes them):
/// points[3k + c] = jet[c][k] + offset[c] and normals[3k + c] the unit
/// normal du × dv / |du × dv| — one square root and one division a point,
/// the components scaled by the reciprocal length (within 2 ulp of dividing
/// each; zero where the length is not above zero, as normalized() gives).
/// Returns how many jets are degenerate, |du × dv|² ≤ 1e-24 |du|² |dv|²
/// (their normals rounding noise, for the caller to replace), and writes
/// their indices in increasing order to `degenerate` unless it is null
/// (room for `count`).
std::size_t jetVertices(std::size_t count, const double *const jet[9], const double offset[3], double *points,
                        double *normals, std::uint32_t *degenerate = nullptr, std::int64_t width = kBestWidth);

/// The triangles between two rows of vertex ids, `lower` (m + 1 ids) one
/// longer than `upper` (m ≥ 1 ids), as three ids each into `triangles`
/// (room for 2m − 1): for j < m − 2 the pair (lower[j], lower[j + 1],
/// upper[j]) and (lower[j + 1], upper[j + 1], upper[j]), then
/// (lower[m − 2], lower[m − 1], upper[m − 2]), (lower[m − 1], lower[m],
/// upper[m − 2]) and (lower[m], upper[m − 1], upper[m − 2]); for m = 1 the
/// one triangle (lower[0], lower[1], upper[0]). Every width writes the same.
void zipRows(std::size_t m, const std::uint32_t *lower, const std::uint32_t *upper, std::uint32_t *triangles,
             std::int64_t width = kBestWidth);

/// Per-sample data of a Composite Ribbon patch ([VSR] Sec. 2). Side i
/// contributes B_i C_i, its curved ribbon C_i a Coons patch of three
/// ribbons: R_i at (s_i, d_i), R_{i−1} at (1 − d_i, s_i) and R_{i+1} at
/// (d_i, 1 − s_i), each R(σ, δ) = P(σ) + γ(δ) T(σ) with γ(x) = x / (2x + 1),
/// less the Gregory corrections of its two corners. ribbon r of side i
/// (0: R_i, 1: R_{i−1}, 2: R_{i+1}) is given at its own parameter (s_i,
/// 1 − d_i, d_i): P and T, and for the jets their σ-derivatives dP, dT.
/// Parameters and blends come with their domain partials ([0] the value,
/// [1] ∂/∂u, [2] ∂/∂v; the partials only for the jets).
struct CompositeSamples {
  static constexpr int kMaxSides = 8;
  int sides = 0; ///< 3 … 8
  const double *s[kMaxSides][3] = {}, *d[kMaxSides][3] = {}, *blend[kMaxSides][3] = {};
  const double *P[kMaxSides][3][3] = {}, *T[kMaxSides][3][3] = {};   ///< [side][ribbon][x, y, z]
  const double *dP[kMaxSides][3][3] = {}, *dT[kMaxSides][3][3] = {}; ///< jets only
};

/// (b) Composite Ribbon points: out[c][k] = ½ Σ_i B_i C_i. The corrections
/// are Gregory's G¹ ones in GregoryCorner's G¹ layout (a00, a10, b10, a01,
/// b01, a11, b11): `left[i]` at side i's start in (s_i, d_i), `right[i]` at
/// its end in (1 − s_i, d_i), each Q = a00 + γ(s) W(a10, b10; s, t²) +
/// γ(t) W(a01, b01; s², t) + γ(s) γ(t) W(a11, b11; s, t), W(a, b; x, y) =
/// (x a + y b) / (x + y) ((a + b) / 2 where x + y = 0). Samples whose blend
/// and its partials are all zero contribute nothing (their interpolant may
/// be undefined there).
void compositeRibbonPositions(std::size_t count, const CompositeSamples &samples, const GregoryCorner *left,
                              const GregoryCorner *right, double *const out[3], std::int64_t width = kBestWidth);
/// compositeRibbonPositions with exact first derivatives over the domain
/// (product, quotient and chain rules in dual arithmetic, lane by lane).
void compositeRibbonJets(std::size_t count, const CompositeSamples &samples, const GregoryCorner *left,
                         const GregoryCorner *right, DualVec3Span out, std::int64_t width = kBestWidth);

/// The sides of a regular domain polygon for the batched blends: side i
/// runs from corner (px[i], py[i]) to the next, with axis (ex[i], ey[i]) =
/// its edge / |edge|², so that its frame (the side from (0, 0) to (1, 0),
/// the domain at y > 0) is x = (u − px) ex + (v − py) ey, y = (v − py) ex −
/// (u − px) ey: affine in (u, v), ∂(x, y)/∂u = (ex, −ey), ∂/∂v = (ey, ex).
struct DomainSides {
  static constexpr int kMaxSides = 8;
  int sides = 0; ///< 3 … 8
  double px[kMaxSides] = {}, py[kMaxSides] = {}, ex[kMaxSides] = {}, ey[kMaxSides] = {};
};

/// (a) Every side's frame coordinates at the points (u[k], v[k]): x[i][k]
/// along side i (its sweep's input), y[i][k] the distance parameter Δ_i.
void sideFrames(std::size_t count, const DomainSides &domain, const double *u, const double *v, double *const *x,
                double *const *y, std::int64_t width = kBestWidth);

/// (b) Corner blends from the distances y[i] of sideFrames: B_i = Π_{j∉{i,
/// i−1}} Δ_j^m / Σ_k Π_{j∉{k, k−1}} Δ_j^m, m = `exponent` (2 for G¹, 3 for
/// G²), products in ascending j as RegularDomain::cornerProducts takes them.
/// When blendDu and blendDv are not null, also ∂B_i/∂u and ∂B_i/∂v (the
/// quotient rule with one reciprocal; the value a true division). Without
/// them the value is the product times the sum's reciprocal. Samples where
/// every product vanishes (not inside a domain) give NaN.
void cornerBlends(std::size_t count, const DomainSides &domain, int exponent, const double *const *y,
                  double *const *blend, double *const *blendDu, double *const *blendDv,
                  std::int64_t width = kBestWidth);

/// Constants of one side of a regular domain for the cubic Hermite sweepline
/// ([SV14] eq. 20) in that side's frame (side from (0,0) to (1,0), domain
/// at y > 0): a, b the directions of the neighbouring sides leaving the two
/// ends; apex the intersection of their lines (the radial sweep's centre),
/// or parallel = true when they do not meet (n = 4).
struct SweepFrame {
  double ax, ay, bx, by;
  double apexX = 0, apexY = 0;
  bool parallel = false;
};

/// (c) Sweepline roots for arbitrary points (x, y) of a side frame: the s ∈
/// [0, 1] with F(s) = (x − s) w_y(s) − y w_x(s) = 0, w = a H(s) + b H(1 − s),
/// H(s) = 2s³ − 3s² + 1 — a quartic. Among the roots on [0, 1] with d ≥ 0 the
/// orientation-preserving one nearest the radial parameter wins (the rule of
/// the engine's scalar solver); points on no sweepline get clamp(x, 0, 1).
/// Writes s and the distance parameter d with (x, y) = (s, 0) + d w(s).
///
/// Two solvers give one result (to ~1e-13): a fast one, Newton from the
/// radial parameter with a per-point certificate that the root found is the
/// only one on [0, 1] and is the selection (deflation, then the sign of the
/// cubic quotient's Bernstein coefficients); the points it cannot certify —
/// near the fold of a triangle's sweeplines, on the neighbouring sides, at
/// corners, outside the domain — are gathered and solved by the robust one
/// (hermiteSweepRootsRobust). Cost: inside a regular domain of n ≥ 4 sides
/// almost every point takes the fast path, about 15 polynomial evaluations.
/// Returns how many points needed the robust solver.
std::size_t hermiteSweepRoots(std::size_t count, const SweepFrame &frame, const double *x, const double *y, double *s,
                              double *d, std::int64_t width = kBestWidth);

/// (c) The gradient over the domain of the roots s that hermiteSweepRoots
/// gave at (x, y), by implicit differentiation of F(s; x, y) = 0: ∂s/∂x =
/// −w_y / F_s, ∂s/∂y = w_x / F_s (both 0 where F_s = 0), carried to (u, v)
/// through the side's axis (ex, ey) as DomainSides gives it: du[k] = ∂s/∂x
/// ex − ∂s/∂y ey, dv[k] = ∂s/∂x ey + ∂s/∂y ex.
void hermiteSweepGradients(std::size_t count, const SweepFrame &frame, double ex, double ey, const double *x,
                           const double *y, const double *s, double *du, double *dv, std::int64_t width = kBestWidth);

/// The robust solver alone, for checks and comparisons: every root on
/// [0, 1] isolated by the derivative cascade F'' → F' → F (monotone pieces,
/// each bisected to the last bit), then the selection rule above. About 15×
/// the fast path's cost; same arguments and result as hermiteSweepRoots.
void hermiteSweepRootsRobust(std::size_t count, const SweepFrame &frame, const double *x, const double *y, double *s,
                             double *d, std::int64_t width = kBestWidth);

} // namespace kernels
} // namespace v1
} // namespace curvenet
