// One transfinite patch: a regular domain, a linear ribbon per domain side,
// and the scheme's formula. Internal to the engine; see curvenet/surface.hpp.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "curvenet/surface.hpp"
#include "patches/domain.hpp"
#include "plans/plan.hpp"
#include "curvenet/kernels/kernels.hpp"
#include "ribbons/ribbon_table.hpp"
#include "ribbons/ribbons.hpp"

namespace curvenet {
inline namespace v1 {

/// What the fast evaluation paths of a patch need besides a plan and the
/// patch's corner data: each side's ribbon as a RibbonTable (P, T; G²: also C).
struct PatchTables {
  std::vector<RibbonTable> sides;
  std::size_t memory() const;
};

/// Where a batch of positions goes: structure-of-arrays arrays[c][k], or
/// (with `points` set) points[k] = position + offset.
struct PositionSink {
  double *arrays[3] = {nullptr, nullptr, nullptr};
  Vec3 *points = nullptr;
  Vec3 offset{};
  static PositionSink soa(double *const out[3]) { return {{out[0], out[1], out[2]}}; }
  static PositionSink interleaved(Vec3 *out, const Vec3 &offset) { return {{}, out, offset}; }
  /// The sink from sample `first` on.
  PositionSink from(std::size_t first) const {
    if (points) return interleaved(points + first, offset);
    return {{arrays[0] + first, arrays[1] + first, arrays[2] + first}};
  }
  void set(std::size_t k, const Vec3 &p) const {
    if (points) points[k] = p + offset;
    else arrays[0][k] = p.x, arrays[1][k] = p.y, arrays[2][k] = p.z;
  }
};

/// Corner data of two parabolic ribbons for the G² correction patch:
/// a[p][q] = ∂_s^p ∂_t^q R_{i−1}(1 − t, s), b[p][q] = ∂_s^p ∂_t^q R_i(s, t)
/// at (0, 0), p, q ∈ {0, 1, 2} (docs/design.md §3).
struct CornerData2 {
  Vec3 a[3][3], b[3][3];
};

/// Corner data of two ribbons meeting at a corner, in the corner's local
/// coordinates (s along the first side, t across it): a_pq from the ribbon
/// that must be matched across t = 0, b_pq from the one matched across s = 0,
/// p, q ∈ {0, 1}. Used by both schemes' correction patches.
struct CornerData {
  Vec3 a00, a10, a01, a11, b10, b01, b11;
};

/// gregory-g2: each corner's share μ ∈ [0, 1] of the two-ribbon blend in
/// its interpolant (kernels::GregorySamples::blendShare), from how far the
/// nine-term correction patch would carry the ribbons' disagreement there.
std::vector<double> cornerBlendShares(const std::vector<LinearRibbon> &ribbons,
                                      const std::vector<ParabolicRibbon> &parabolic);
/// gregory-g1: the same from how far the ribbons' end twists, which the
/// four-term correction patch extrapolates, depart from how T turns along
/// each side (corner i at side i's start).
std::vector<double> cornerBlendShares(const std::vector<LinearRibbon> &ribbons);

/// c in the kernels' G¹ layout (a00, a10, b10, a01, b01, a11, b11).
kernels::GregoryCorner kernelCorner(const CornerData &c);

class Patch {
public:
  /// The most sides a patch has (Network refuses longer loops; connection
  /// curves split them): the evaluation's per-side arrays live on the stack.
  static constexpr int kMaxSides = 8;

  /// `parabolic` (one per side, over the same linear ribbons) is required by
  /// gregory-g2 and ignored by the other schemes.
  /// Gregory schemes: `blendShares` (one per corner, see cornerBlendShares)
  /// or empty to compute them from the ribbons.
  Patch(std::vector<LinearRibbon> ribbons, const SurfaceOptions &options,
        std::vector<ParabolicRibbon> parabolic = {}, std::vector<double> blendShares = {});

  const RegularDomain &domain() const { return domain_; }
  const LinearRibbon &ribbon(int side) const { return ribbons_[domain_.wrap(side)]; }
  /// Gregory schemes: corner i's share of the two-ribbon blend
  /// (cornerBlendShares); empty for the other schemes.
  const std::vector<double> &blendShares() const { return blendShare_; }
  /// gregory-g2: side i's parabolic ribbon (empty for the other schemes).
  const std::vector<ParabolicRibbon> &parabolicRibbons() const { return parabolic_; }
  /// gregory-g2: where each ribbon's cross parameter saturates (1: not at all).
  const std::vector<double> &crossReach() const { return crossReach_; }

  /// Surface point with exact ∂/∂u, ∂/∂v at domain point (u, v).
  DualVec3 evaluate(double u, double v) const;
  /// gregory-g2 only: with second derivatives too (hyper-dual evaluation).
  Dual2Vec3 evaluateSecondOrder(double u, double v) const;

  /// Samples [first, first + count) of `plan` (made for this patch's scheme,
  /// side count and sweepline), with exact first derivatives, into out.
  /// Gregory schemes: the ribbons are evaluated per side at the plan's side
  /// parameters, then combined by the SIMD kernels (ribbon points, blend and
  /// correction sums); composite-ribbon: per sample from the plan's
  /// parameters. Equals evaluate() at those samples to ~1e-12 relative.
  /// Thread-safe; scratch is per thread.
  /// At plan resolutions from kTableResolution on, the ribbons come from
  /// tables() instead of exact evaluation (agreeing to ~1e-14 of their size).
  void evaluatePlanned(const EvaluationPlan &plan, std::size_t first, std::size_t count, DualVec3 *out) const;
  /// Where a jet pass hands its results, block by block: block(at, m, jet)
  /// for samples at … at + m − 1 (relative to the pass's first), jet[c][k]
  /// with c = value x, y, z, ∂/∂u x, y, z, ∂/∂v x, y, z. The arrays are the
  /// pass's scratch, valid during the call.
  using JetBlockSink = std::function<void(std::size_t at, std::size_t count, const double *const jet[9])>;
  /// evaluatePlanned into a sink: the tessellator writes its vertices and
  /// normals straight from the kernel's arrays (no DualVec3 copy between).
  void evaluatePlanned(const EvaluationPlan &plan, std::size_t first, std::size_t count,
                       const JetBlockSink &out) const;
  /// Domain side i's boundary samples j[0 … count − 1] of `plan` (t = j / r
  /// along the side: EvaluationPlan::boundarySidesAndBlends, which needs
  /// hasBoundary()) with exact first derivatives, into a sink: the
  /// tessellator's boundary normals without solving their sweeps (on a
  /// side, the neighbouring sides' roots lie at the ends of [0, 1], where
  /// the batched solver falls back to its robust search).
  void evaluatePlannedBoundary(const EvaluationPlan &plan, int i, const std::uint32_t *j, std::size_t count,
                               const JetBlockSink &out) const;
  /// Positions alone of the same samples into out[c][k] (c = x, y, z):
  /// Gregory schemes through tables() and one SIMD kernel pass
  /// (kernels::gregoryPositions); composite-ribbon through evaluatePlanned.
  /// Thread-safe.
  void evaluatePlannedPositions(const EvaluationPlan &plan, std::size_t first, std::size_t count,
                                double *const out[3]) const {
    evaluatePlannedPositions(plan, first, count, PositionSink::soa(out));
  }
  /// The same into a sink (e.g. points with the surface's origin added,
  /// written by the kernel itself).
  void evaluatePlannedPositions(const EvaluationPlan &plan, std::size_t first, std::size_t count,
                                const PositionSink &out) const;
  /// evaluatePlannedPositions on every member of a rotation group
  /// (EvaluationPlan::groups), member m into out.from(m · group.stride).
  /// G²: the corners' correction weights are computed once for the group
  /// and shared by rotation (corner i on member m has corner 0's on member
  /// m − i): on a pentagon a fifth of the weights' work, which is a third
  /// of the kernel's. The same numbers as evaluatePlannedPositions.
  void evaluatePlannedGroup(const EvaluationPlan &plan, const EvaluationPlan::Group &group,
                            const PositionSink &out) const;
  /// Where a group's jet pass hands its results: member m's blocks as
  /// JetBlockSink's, `at` relative to the member's first sample.
  using GroupJetSink =
      std::function<void(int member, std::size_t at, std::size_t count, const double *const jet[9])>;
  /// evaluatePlanned (jets, into a sink) on every member of a rotation
  /// group. G² without saturating ribbons: the corners' weights and their
  /// partials computed once per group and shared by rotation, as for
  /// positions. The same numbers as evaluatePlanned member by member.
  void evaluatePlannedGroup(const EvaluationPlan &plan, const EvaluationPlan::Group &group,
                            const GroupJetSink &out) const;
  /// evaluate() at many domain points (u[k], v[k]) at once: Hermite roots
  /// by the batched solver, exact ribbons, the derivative kernel
  /// (kernels::gregoryJets). Gregory schemes with the radial or cubic
  /// Hermite sweep; other schemes and sweeps point by point. Agrees with
  /// evaluate() to ~1e-12 relative. Thread-safe; scratch is per thread.
  void evaluateBatch(std::size_t count, const double *u, const double *v, DualVec3 *out) const;
  /// evaluate() at many arbitrary domain points (u[k], v[k]), k < count,
  /// for an embedding program's batches: per side the sweep parameter with
  /// its gradient (radial in closed form, cubic Hermite by the batched
  /// solver and implicit differentiation; triangles and the quintic sweep
  /// per point as evaluate()), the corner blends, then tables() and the
  /// derivative kernel; composite-ribbon through the tables and its jet
  /// kernel; the Bézier schemes point by point. Agrees with evaluate() to
  /// ~1e-12 relative (derivatives: the tables' slopes, ~1e-11). With
  /// `count` a multiple of 8 no point falls into the kernels' one-lane
  /// tails, which round differently from their vector lanes: each point's
  /// result is then the same whatever batch and lane it comes in.
  /// Thread-safe; scratch is per thread.
  void evaluateJets(std::size_t count, const double *u, const double *v, DualVec3 *out) const;
  /// Positions at arbitrary domain points (u[k], v[k]), k < count, into
  /// out[c][k]: per side the sweep parameter (radial in closed form, cubic
  /// Hermite by the batched solver kernels::hermiteSweepRoots), the corner
  /// blends, then tables() and kernels::gregoryPositions as for plans.
  /// Gregory schemes with radial or cubic Hermite sweeps; other schemes and
  /// sweeps evaluate point by point. Agrees with evaluate() to ~1e-12
  /// relative inside the domain. Thread-safe; scratch is per thread.
  void evaluatePositions(std::size_t count, const double *u, const double *v, double *const out[3]) const {
    evaluatePositions(count, u, v, PositionSink::soa(out));
  }
  void evaluatePositions(std::size_t count, const double *u, const double *v, const PositionSink &out) const;
  /// Plan resolution from which evaluatePlanned uses the tables: below it
  /// a face has too few samples to repay building them.
  static constexpr int kTableResolution = 32;
  /// Gregory schemes: the ribbon tables and corner vectors, built on first
  /// use (thread-safe, once per patch; copies of a patch share them).
  const PatchTables &tables() const;
  const SurfaceOptions &options() const { return options_; }

private:
  DualVec3 gregory(Dual u, Dual v) const;
  DualVec3 compositeRibbon(Dual u, Dual v) const;
  /// The composite-ribbon inputs at a domain point: every side's
  /// linear-sweep parameter s, Wachspress distance d and CR blend.
  void compositeParameters(Dual u, Dual v, Dual *s, Dual *d, Dual *blend) const;
  /// (u, v) moved onto a corner when within 1e-14 of it (see evaluate()).
  void snapToCorner(double &u, double &v) const;
  /// compositeParameters at (u, v) after snapToCorner: the inputs of a
  /// composite-ribbon batch's point.
  void compositeParametersAt(double u, double v, Dual *s, Dual *d, Dual *blend) const;
  /// The CR formula from the side parameters, distances and blends of all
  /// sides, the ribbons evaluated exactly (compositeRibbonBatch: from tables).
  DualVec3 compositeRibbonFrom(const Dual *s, const Dual *d, const Dual *blends) const;
  /// The same formula's point alone from values (no gradients).
  Vec3 compositeRibbonPoint(const double *s, const double *d, const double *blends) const;
  /// Both of the above: the formula once, over Dual or double.
  template <class T> auto compositeRibbonWith(const T *s, const T *d, const T *blends) const;
  /// compositeRibbonPoint at many samples (arrays s[i][k], d[i][k],
  /// blends[i][k]) with the ribbons from the tables, three batches of the
  /// table kernel per side.
  void compositeRibbonPositions(std::size_t count, const double *const *s, const double *const *d,
                                const double *const *blends, const PositionSink &out) const;
  /// The same with gradients, into out[k].
  void compositeRibbonJets(std::size_t count, const Dual *const *s, const Dual *const *d, const Dual *const *blends,
                           DualVec3 *out) const;
  /// Both batch forms: emit(k, point) per sample.
  template <class T, class Emit>
  void compositeRibbonBatch(std::size_t count, const T *const *s, const T *const *d, const T *const *blends,
                            const Emit &emit) const;
  DualVec3 gregoryG2(Dual u, Dual v) const;
  /// The G² formula from every side's parameter, normalized corner blend and
  /// parabolic jet there (value and gradient), as the kernels compute it in
  /// the batched paths.
  DualVec3 gregoryG2From(const Dual *side, const Dual *blend, const ParabolicJet *jet) const;
  /// Side i's parameter and corner i's blend with their gradients (value,
  /// ∂/∂u, ∂/∂v arrays) for samples [first, first + count): written into the
  /// arrays s, blend it is given, or where the source holds them, each with
  /// the turn of its gradients (SideBlendArrays).
  using SideBlendSource = std::function<SideBlendArrays(int i, std::size_t first, std::size_t count,
                                                        double *const s[3], double *const blend[3])>;
  /// The Gregory formula with derivatives from every side's parameter and
  /// corner blend: ribbons from the tables or exactly, then the kernel, in
  /// blocks small enough for their arrays to stay in the fast caches.
  void gregoryJetsFrom(std::size_t count, const SideBlendSource &source, bool useTables, DualVec3 *out) const;
  /// With weightJets (G²): corner i's weights and partials for the samples
  /// from weightJets[i] (kernels::GregoryJetSamples::weightJets).
  void gregoryJetsFrom(std::size_t count, const SideBlendSource &source, bool useTables, const JetBlockSink &out,
                       const double *const *weightJets = nullptr, std::size_t weightJetStride = 0) const;
  /// The same from arrays sides[i·count + k], blends[i·count + k].
  void gregoryJetsFrom(std::size_t count, const Dual *sides, const Dual *blends, bool useTables, DualVec3 *out) const;
  /// Throws unless `plan` was made for this patch's sides and scheme.
  void checkPlan(const EvaluationPlan &plan) const;
  /// Whether evaluatePlannedGroup shares the G² corners' weights across
  /// the group's members for this plan.
  bool sharesGroupWeights(const EvaluationPlan &plan) const;
  /// The Gregory formula's positions from every side's parameter and
  /// corner blend values (arrays of `count`): tables, then the kernel.
  /// G²: corner i's rational weights may come in cornerWeights[i]
  /// (kernels::GregorySamples::weights, stride weightStride).
  void gregoryPositionsFrom(std::size_t count, const double *const *side, const double *const *blend,
                            const PositionSink &out, const double *const *cornerWeights = nullptr,
                            std::size_t weightStride = 0) const;
  /// Corner i's correction-patch vectors (kernels::GregoryCorner order).
  kernels::GregoryCorner cornerVectors(int i) const;

  struct TableCache;
  std::shared_ptr<TableCache> tables_;
  RegularDomain domain_;
  std::vector<LinearRibbon> ribbons_;
  std::vector<ParabolicRibbon> parabolic_;
  /// The linear ribbons' corner data, computed once: corners_[i] at corner i
  /// in (s_i, t = 1 − s_{i−1}) (R_{i−1} matched across t = 0, R_i across
  /// s = 0; the Gregory G¹ correction patch and the CR left corner), and
  /// endCorners_[i] at corner i + 1 seen from side i, in (σ = 1 − s_i, d_i)
  /// (R_{i+1} matched across d = 0, R_i across σ = 0; the CR right corner).
  std::vector<CornerData> corners_, endCorners_;
  /// G²: the parabolic ribbons' corner data (cornerData2 of the ends meeting
  /// at corner i), computed once instead of at every point.
  std::vector<CornerData2> corners2_;
  /// Gregory schemes: corner i's share of the two-ribbon blend in its
  /// interpolant (kernels::GregorySamples::blendShare; cornerBlendShares).
  std::vector<double> blendShare_;
  /// The same corner data as the kernels take it, computed once: the
  /// Gregory schemes' correction patches (cornerVectors) and, for G², their
  /// rearranged form; composite-ribbon: corners_ and endCorners_.
  std::vector<kernels::GregoryCorner> kernelCorners_, kernelEndCorners_;
  std::vector<kernels::GregoryCornerTerms> cornerTerms_;
  /// G²: per ribbon, where its cross parameter d saturates (d ↦ r tanh(d / r),
  /// see limitedCross in patch.cpp); 1 leaves d as it is. The batched paths
  /// hand them to the kernels (kernels::GregorySamples::reach). reachLimited_
  /// when any is below 1: the shared plans' corner weights (of the sweep's
  /// own parameters, one set for every corner) do not serve such a patch.
  std::vector<double> crossReach_;
  bool reachLimited_ = false;
  SurfaceOptions options_;
};

struct Patch::TableCache {
  std::once_flag once;
  PatchTables tables;
};

/// Gregory's rational correction term (docs/design.md §3, G¹ case):
/// Q(s,t) = a00 + gs W10 + gt W01 + gs gt W11 with
/// W_pq = (s^{2−p} a_pq + t^{2−q} b_pq) / (s^{2−p} + t^{2−q}), where gs, gt are
/// the (possibly reparameterized) coordinates multiplying the terms. Every
/// term carries s^p t^q, so at the corner itself it is the corner point.
DualVec3 gregoryCorrection(const CornerData &c, Dual s, Dual t, Dual gs, Dual gt);
/// The same with gs = s, gt = t (the Gregory patch) in closed form: the
/// polynomial part and the three rational terms s²/(s + t²), s²t/(s² + t),
/// s²t/(s + t) with their partials, one division, the chain rule once.
/// Within underflow of the corner it returns the general form's value.
DualVec3 gregoryCorrection(const CornerData &c, Dual s, Dual t);


/// The nine-term correction patch of [SV14] eq. 22:
/// Q = Σ_{p,q ≤ 2} s^p t^q / (p! q!) W_pq with
/// W_pq = (s^{3−p} a_pq + t^{3−q} b_pq) / (s^{3−p} + t^{3−q}); W_00 = a_00.
/// Q − R_{i−1}(1 − t, s) = O(t³) and Q − R_i(s, t) = O(s³) whatever the
/// incompatibility of the two ribbons' corner derivatives. The reference
/// form: each W_pq as its weighted pair in Dual arithmetic (three divisions
/// each), which the tests hold the faster forms against.
DualVec3 gregoryCorrection2(const CornerData2 &c, Dual s, Dual t);

/// The same patch from its rearranged form (kernels::GregoryCornerTerms of
/// c): the biquadratic part by Horner and each rational term with its
/// closed-form partials in s and t, one division for all eight
/// denominators, the chain rule once at the end — as the kernels evaluate
/// it. Within underflow of the corner (s = t = 0) it returns the reference
/// form's value.
DualVec3 gregoryCorrection2(const kernels::GregoryCornerTerms &terms, const CornerData2 &c, Dual s, Dual t);

} // namespace v1
} // namespace curvenet
