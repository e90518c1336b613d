// Evaluation plans (docs/design.md §4): everything a transfinite patch needs at
// the tessellator's samples that depends only on (scheme, n, resolution,
// sweepline) — the domain samples, side 0's parameters (s_0, d_0) and corner
// 0's blend at each, with exact first derivatives. The pattern is n-fold
// symmetric, so side i's data at a sample is side 0's at the sample rotated
// by −i·2π/n (a table lookup) with the gradients turned by +i·2π/n: one
// sweepline root solve per sample serves all n sides. Plans never touch
// curves; a patch evaluation through a plan is ribbon evaluation at the
// plan's parameters plus weighted sums (see Patch::evaluatePlanned).
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "curvenet/surface.hpp"
#include "patches/dual.hpp"

namespace curvenet {
inline namespace v1 {

class RegularDomain;

struct PlanKey {
  Scheme scheme;        ///< gregory-g1, gregory-g2 or composite-ribbon
  Sweepline sweepline;  ///< resolved (never Auto); ignored by composite-ribbon
  int sides;            ///< 3 … 8
  int resolution;       ///< rows per centre–side triangle, ≥ 1
  friend auto operator<=>(const PlanKey &, const PlanKey &) = default;
};

/// Side i's parameter and corner i's blend over a run of samples: value,
/// ∂/∂u, ∂/∂v arrays, their gradients given in a frame turned from the
/// domain's by (cos, sin) = sideTurn, blendTurn (the turns of
/// kernels::GregoryJetSamples, which the jet kernel applies).
struct SideBlendArrays {
  const double *s[3] = {}, *blend[3] = {};
  double sideTurn[2] = {1, 0}, blendTurn[2] = {1, 0};
};

class EvaluationPlan {
public:
  /// Builds the plan (parallel over samples; cost O(n r²) sweep solves).
  explicit EvaluationPlan(const PlanKey &key);

  const PlanKey &key() const { return key_; }
  /// Interior samples of one face in the tessellator's vertex order: the
  /// centre, the spokes (corner-major, level 1 … r−1), then the interior of
  /// each centre–side triangle row by row.
  const std::vector<Vec2> &samples() const { return samples_; }
  std::size_t size() const { return samples_.size(); }

  /// Side i's (or corner i's) quantities at sample k, by rotation of side 0's.
  /// Arithmetic on the layout (samples()): the rotation by side i maps the
  /// centre to itself and spoke or triangle t to t − i (mod n), offset for
  /// offset. No table: a table of n × size() entries missed the cache on
  /// every block of the tessellation's jet pass (4.6 % of its time at r256).
  std::size_t rotated(int i, std::size_t k) const {
    if (i == 0 || k == 0) return k;
    const std::size_t n = static_cast<std::size_t>(key_.sides), shift = n - static_cast<std::size_t>(i);
    const bool spoke = k < interiorBase_;
    // A spoke holds r − 1 samples (k ≥ 1 lies on one only if r ≥ 2).
    const std::size_t base = spoke ? 1 : interiorBase_;
    const std::size_t piece = spoke ? static_cast<std::size_t>(key_.resolution - 1) : perTriangle_;
    const std::size_t t = (k - base) / piece, offset = (k - base) - t * piece;
    return base + (t + shift) % n * piece + offset;
  }
  /// Gradient turned from side 0 to side i.
  Dual turn(int i, const Dual &x) const {
    return {x.v, cos_[i] * x.du - sin_[i] * x.dv, sin_[i] * x.du + cos_[i] * x.dv};
  }
  Dual side(int i, std::size_t k) const {
    return perSide_ ? storedSide(static_cast<std::size_t>(i) * size() + k) : turn(i, storedSide(rotated(i, k)));
  }
  Dual distance(int i, std::size_t k) const { return turn(i, d_[rotated(i, k)]); }
  /// Values alone (no gradient turn), for position-only evaluation.
  double sideValue(int i, std::size_t k) const {
    return perSide_ ? storedSide(static_cast<std::size_t>(i) * size() + k).v : storedSide(rotated(i, k)).v;
  }
  double blendValue(int i, std::size_t k) const { return storedBlend(rotated(i, k)).v; }
  double distanceValue(int i, std::size_t k) const { return d_[rotated(i, k)].v; }
  /// The samples from k on that every rotation maps to consecutive samples
  /// (the rest of k's piece of the layout: the centre, a spoke or a triangle
  /// interior): rotated(i, k + m) = rotated(i, k) + m for m < rotationRun(k).
  std::size_t rotationRun(std::size_t k) const;
  /// Gregory schemes: p with p[m] = sideValue(i, k + m), and q with q[m] =
  /// blendValue(i, k + m), for m < rotationRun(k). Side 0's values serve all
  /// sides through the rotation (every side's are stored when perSide()).
  const double *sideValuesFrom(int i, std::size_t k) const {
    return perSide_ ? sideValues_.data() + static_cast<std::size_t>(i) * size() + k : sideValues_.data() + rotated(i, k);
  }
  const double *blendValuesFrom(int i, std::size_t k) const { return blendValues_.data() + rotated(i, k); }
  /// True when every side's parameters are stored (see the constructor).
  bool perSide() const { return perSide_; }
  /// Gregory: corner i's normalized blend B_{i,i−1}; composite-ribbon: the
  /// normalized corner product D_{i,i−1} / Σ_j D_{j,j−1}.
  Dual blend(int i, std::size_t k) const { return turn(i, storedBlend(rotated(i, k))); }
  /// side(i, k) and blend(i, k) for k in [first, first + count) as arrays
  /// of value, ∂/∂u, ∂/∂v, their gradients in side 0's frame with the turn
  /// (cos, sin) that brings them into the domain's (SideBlendArrays). A run
  /// that every rotation maps to consecutive samples (rotationRun) is read
  /// where the plan holds it; any other is gathered into s[0 .. 2][j],
  /// blend[0 .. 2][j], j = k − first.
  SideBlendArrays sidesAndBlends(int i, std::size_t first, std::size_t count, double *const s[3],
                                 double *const blend[3]) const;
  /// Asks the cache for side 0's parameters and corner 0's blends with
  /// their gradients at samples [first, first + count) (the arrays
  /// sidesAndBlends reads) ahead of their use; a hint, no effect on results.
  void prefetchSidesAndBlends(std::size_t first, std::size_t count) const;
  /// The same for the values alone (the arrays a position pass reads).
  void prefetchSideAndBlendValues(std::size_t first, std::size_t count) const;

  /// The tessellator's boundary rows of a uniform layout: every side's
  /// parameter and every corner's blend with their gradients at the samples
  /// t = j / r (j = 0 … r) of domain side 0, side i's rows by rotation.
  /// Gregory schemes with a rotated plan (not perSide(), not
  /// composite-ribbon); empty otherwise.
  bool hasBoundary() const { return !boundary_.empty(); }
  /// For domain side i's samples j[0 … count − 1]: side k's parameter and
  /// corner k's blend, as sidesAndBlends gives them for interior samples.
  void boundarySidesAndBlends(int i, int k, const std::uint32_t *j, std::size_t count, double *const s[3],
                              double *const blend[3]) const;

  /// Samples that the rotations permute among themselves: `members` ranges
  /// of `count` samples, member m being [first + m·stride, first + m·stride
  /// + count), where side i's and corner i's data on member m are side 0's
  /// and corner 0's on member (m − i) mod members, sample for sample. The
  /// centre is a group of one member (every rotation fixes it); the spokes'
  /// levels and the triangle interiors' rows come in groups of n.
  struct Group {
    std::size_t first = 0, count = 0, stride = 0;
    int members = 1;
    /// The member whose side-0 (corner-0) data are side i's (corner i's) on member m.
    int source(int m, int i) const { return ((m - i) % members + members) % members; }
  };
  /// Groups covering every sample once, members of at most `maxCount`
  /// samples, in sample order of their first members. Evaluated a group at
  /// a time, the side data its members read through rotated() are the
  /// group's own, still in the cache from the previous member.
  std::vector<Group> groups(std::size_t maxCount) const;

  /// Bytes held.
  std::size_t memory() const;

private:
  /// The constructor's steps: the tessellator's sample pattern and its
  /// rotations; side 0's parameter (every side's on a triangle), distance
  /// and corner-0 blend at each sample; the Gregory schemes' values and
  /// gradients as separate arrays; side 0's boundary samples.
  void placeSamples(const RegularDomain &domain);
  void sampleSidesAndBlends(const RegularDomain &domain);
  void splitValuesAndGradients();
  void sampleSideZeroBoundary(const RegularDomain &domain);

  /// Stored side parameter j (side-major when perSide_) and corner-0 blend j.
  Dual storedSide(std::size_t j) const { return soa_ ? Dual{sideValues_[j], sideDu_[j], sideDv_[j]} : s_[j]; }
  Dual storedBlend(std::size_t j) const { return soa_ ? Dual{blendValues_[j], blendDu_[j], blendDv_[j]} : b_[j]; }

  PlanKey key_;
  std::vector<Vec2> samples_;
  /// Composite-ribbon: the stored parameters as Duals. The Gregory schemes
  /// keep them as arrays of values and of gradients (soa_): the jet pass
  /// reads them with plain vector loads (sidesAndBlends).
  std::vector<Dual> s_, d_, b_;
  std::vector<double> sideValues_, blendValues_;
  std::vector<double> sideDu_, sideDv_, blendDu_, blendDv_;
  /// hasBoundary(): side 0's boundary sample j, side (corner) k at
  /// boundary_[2 (j n + k)] (parameter) and the next entry (blend).
  std::vector<Dual> boundary_;
  bool soa_ = false;
  std::vector<double> cos_, sin_;
  bool perSide_ = false;
  /// The layout: centre and spokes below interiorBase_, then n centre–side
  /// triangle interiors of perTriangle_ samples each.
  std::size_t interiorBase_ = 0, perTriangle_ = 0;
};

/// The process-wide plan cache: concurrent lookups, one build per key (later
/// callers of a key being built wait for it). Thread-safe.
std::shared_ptr<const EvaluationPlan> evaluationPlan(const PlanKey &key);

/// The plan key of a transfinite surface's face with `sides` domain sides.
PlanKey planKey(const SurfaceOptions &options, int sides, int resolution);

/// Interior samples of an n-gon face at resolution r (the tessellator's
/// count), for resolutions the tessellator accepts (checkResolution).
std::uint32_t faceInteriorCount(int n, int r);

} // namespace v1
} // namespace curvenet
