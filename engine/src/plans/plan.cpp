#include "plans/plan.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <future>
#include <map>
#include <mutex>
#include <numbers>

#include "curvenet/error.hpp"
#include "curvenet/kernels/kernels.hpp"
#include "curvenet/tessellate.hpp"
#include "patches/domain.hpp"
#include "parallel/fork_join.hpp"

namespace curvenet {
inline namespace v1 {

std::uint32_t faceInteriorCount(int n, int r) {
  // In 64 bits: n (r − 1)(r − 2) passes 2³¹ long before the count leaves
  // 32 bits (the tessellator refuses resolutions whose counts would).
  const std::uint64_t m = static_cast<std::uint64_t>(r - 1), sides = static_cast<std::uint64_t>(n);
  return static_cast<std::uint32_t>(1 + sides * m + sides * (m * (m - 1) / 2));
}

PlanKey planKey(const SurfaceOptions &options, int sides, int resolution) {
  Sweepline sweep = options.sweepline;
  if (sweep == Sweepline::Auto) sweep = options.scheme == Scheme::GregoryG2 ? Sweepline::Hermite : Sweepline::Radial;
  if (options.scheme == Scheme::CompositeRibbon) sweep = Sweepline::Auto; // CR has its own linear sweep
  return {options.scheme, sweep, sides, resolution};
}

namespace {
constexpr std::size_t kGrain = 1024; // samples per task when building
} // namespace

EvaluationPlan::EvaluationPlan(const PlanKey &key) : key_(key) {
  const int n = key.sides, r = key.resolution;
  CURVENET_CHECK(n >= 3 && n <= 8 && r >= 1, "plan for n = " + std::to_string(n) + ", r = " + std::to_string(r));
  const RegularDomain domain(n);
  placeSamples(domain);
  sampleSidesAndBlends(domain);
  if (key.scheme != Scheme::CompositeRibbon) splitValuesAndGradients();
  if (key.scheme != Scheme::CompositeRibbon && !perSide_) sampleSideZeroBoundary(domain);
}

void EvaluationPlan::placeSamples(const RegularDomain &domain) {
  const int n = key_.sides, r = key_.resolution;
  const std::size_t count = faceInteriorCount(n, r);
  samples_.resize(count);
  // The tessellator's pattern (tessellate.cpp), with the same arithmetic so
  // that the sample positions are the same doubles.
  perTriangle_ = static_cast<std::size_t>((r - 1) * (r - 2) / 2);
  interiorBase_ = 1 + static_cast<std::size_t>(n) * (r - 1);
  const std::size_t perTriangle = perTriangle_, interiorBase = interiorBase_;
  auto spoke = [&](int i, int k) { return 1 + static_cast<std::size_t>(((i % n + n) % n) * (r - 1) + (k - 1)); };
  samples_[0] = {0, 0};
  for (int t = 0; t < n; ++t) {
    const Vec2 p0 = domain.corner(t), p1 = domain.corner(t + 1);
    std::size_t local = 0;
    for (int k = 1; k < r; ++k) {
      const Vec2 a = p0 * (1.0 - double(k) / r), b = p1 * (1.0 - double(k) / r);
      const int m = r - k;
      for (int j = 0; j < m; ++j) {
        const Vec2 uv = a + (b - a) * (double(j) / m);
        if (j == 0) samples_[spoke(t, k)] = uv;
        else samples_[interiorBase + t * perTriangle + local++] = uv;
      }
    }
  }
  for (int i = 0; i < n; ++i) {
    const double angle = 2 * std::numbers::pi * i / n;
    cos_.push_back(std::cos(angle));
    sin_.push_back(std::sin(angle));
  }
}

void EvaluationPlan::sampleSidesAndBlends(const RegularDomain &domain) {
  const PlanKey &key = key_;
  const int n = key.sides;
  const std::size_t count = samples_.size();
  // On a triangle every side is computed at the sample itself, as
  // Surface::evaluate does: the quintic sweeplines cross near the opposite
  // corner, and on the bisector there the two roots tie (see Sweepline), so
  // a rotated sample, off by a rounding error, may pick the other one; the
  // cubic sweep is closed-form there (RegularDomain::triangleSideParameter)
  // and costs no more than a rotation.
  perSide_ = n == 3 && key.scheme != Scheme::CompositeRibbon && key.sweepline != Sweepline::Radial;
  s_.resize(perSide_ ? n * count : count), d_.resize(count), b_.resize(count);
  const bool cr = key.scheme == Scheme::CompositeRibbon;
  const bool cubicHermite = !cr && key.sweepline == Sweepline::Hermite && !perSide_;
  const kernels::SweepFrame frame = domain.sweepFrame(0);
  parallel::parallelFor(tbb::blocked_range<std::size_t>(0, count, kGrain), [&](const tbb::blocked_range<std::size_t> &range) {
    // Side 0's cubic Hermite roots for the whole block in one batched solve.
    std::vector<double> x, y, roots, dist;
    if (cubicHermite) {
      const std::size_t m = range.size();
      x.resize(m), y.resize(m), roots.resize(m), dist.resize(m);
      for (std::size_t k = range.begin(); k < range.end(); ++k) {
        Dual fx, fy;
        domain.sideFrame(0, samples_[k].x, samples_[k].y, fx, fy);
        x[k - range.begin()] = fx.v, y[k - range.begin()] = fy.v;
      }
      kernels::hermiteSweepRoots(m, frame, x.data(), y.data(), roots.data(), dist.data());
    }
    std::array<Dual, 16> wachspress;
    for (std::size_t k = range.begin(); k < range.end(); ++k) {
      const Dual u = Dual::u(samples_[k].x), v = Dual::vCoord(samples_[k].y);
      std::array<Dual, 8> power;
      if (cr) {
        domain.wachspressDistances(u, v, wachspress);
        s_[k] = domain.linearSweepSideParameter(0, u, v);
        d_[k] = wachspress[0];
        for (int j = 0; j < n; ++j) power[j] = wachspress[j] * wachspress[j];
      } else {
        std::array<Dual, 8> distance;
        for (int j = 0; j < n; ++j) distance[j] = domain.perpendicularDistance(j, u, v);
        if (perSide_ && key.sweepline == Sweepline::Hermite) {
          // The triangle's closed-form sweep on the three distances computed
          // once (RegularDomain::triangleSweep's very operations).
          for (int i = 0; i < n; ++i)
            s_[i * count + k] =
                domain.triangleSideParameter(distance[domain.wrap(i - 1)], distance[domain.wrap(i + 1)], distance[i]);
        } else {
          if (perSide_)
            for (int i = 1; i < n; ++i)
              s_[i * count + k] = domain.hermiteSweep(i, u, v, key.sweepline == Sweepline::QuinticHermite).s;
          switch (key.sweepline) {
          case Sweepline::Hermite: s_[k] = domain.hermiteSweepFromRoot(0, u, v, roots[k - range.begin()]).s; break;
          case Sweepline::QuinticHermite: s_[k] = domain.hermiteSweep(0, u, v, true).s; break;
          default: s_[k] = domain.radialSideParameter(0, u, v); break;
          }
        }
        d_[k] = distance[0];
        const bool g2 = key.scheme == Scheme::GregoryG2;
        for (int j = 0; j < n; ++j) power[j] = g2 ? distance[j] * distance[j] * distance[j] : distance[j] * distance[j];
      }
      // Corner products in the order Patch uses, so corner 0's blend is the
      // same number the pointwise evaluation computes.
      Dual total = 0.0, first = 0.0;
      for (int i = 0; i < n; ++i) {
        Dual product = 1.0;
        for (int j = 0; j < n; ++j)
          if (j != i && j != domain.wrap(i - 1)) product *= power[j];
        if (i == 0) first = product;
        total += product;
      }
      b_[k] = first / total;
    }
  });
}

void EvaluationPlan::splitValuesAndGradients() {
  // Side 0's parameter values (every side's when perSide_) and corner 0's
  // blend values as plain arrays for the position-only path: side i's over
  // a rotation run are side 0's over the rotated run (sideValuesFrom).
  // The Gregory schemes then keep values and gradients as separate arrays
  // alone (the jet pass's sidesAndBlends reads them with vector loads).
  const std::size_t stored = s_.size(), count = b_.size();
  sideValues_.resize(stored), sideDu_.resize(stored), sideDv_.resize(stored);
  blendValues_.resize(count), blendDu_.resize(count), blendDv_.resize(count);
  for (std::size_t j = 0; j < stored; ++j) sideValues_[j] = s_[j].v, sideDu_[j] = s_[j].du, sideDv_[j] = s_[j].dv;
  for (std::size_t k = 0; k < count; ++k) blendValues_[k] = b_[k].v, blendDu_[k] = b_[k].du, blendDv_[k] = b_[k].dv;
  std::vector<Dual>().swap(s_), std::vector<Dual>().swap(b_);
  soa_ = true;
}

void EvaluationPlan::sampleSideZeroBoundary(const RegularDomain &domain) {
  // Side 0's boundary samples, as Patch::evaluate computes them (sweeps by
  // hermiteSweepSides, blends in product form) at the tessellator's points.
  const int n = key_.sides, r = key_.resolution;
  boundary_.resize(static_cast<std::size_t>(r + 1) * n * 2);
  const bool g2 = key_.scheme == Scheme::GregoryG2;
  const Vec2 p0 = domain.corner(0), p1 = domain.corner(1);
  std::array<Dual, 8> side, power, product;
  for (int j = 0; j <= r; ++j) {
    const double t = double(j) / r; // boundaryRows' t on a one-segment side
    const Vec2 uv = p0 + (p1 - p0) * t;
    const Dual u = Dual::u(uv.x), v = Dual::vCoord(uv.y);
    if (key_.sweepline == Sweepline::Radial)
      for (int k = 0; k < n; ++k) side[k] = domain.radialSideParameter(k, u, v);
    else domain.hermiteSweepSides(u, v, key_.sweepline == Sweepline::QuinticHermite, std::span<Dual>(side.data(), n));
    for (int k = 0; k < n; ++k) {
      const Dual distance = domain.perpendicularDistance(k, u, v);
      power[k] = g2 ? distance * distance * distance : distance * distance;
    }
    const Dual total = domain.cornerProducts(power, product);
    for (int k = 0; k < n; ++k) {
      boundary_[2 * (static_cast<std::size_t>(j) * n + k)] = side[k];
      boundary_[2 * (static_cast<std::size_t>(j) * n + k) + 1] = product[k] / total;
    }
  }
}

void EvaluationPlan::boundarySidesAndBlends(int i, int k, const std::uint32_t *j, std::size_t count,
                                            double *const s[3], double *const blend[3]) const {
  CURVENET_CHECK(hasBoundary(), "boundary samples of a plan without them");
  const int n = key_.sides;
  const std::size_t from = static_cast<std::size_t>(((k - i) % n + n) % n); // side k on side i's row: side k − i on side 0's
  const double c = cos_[i], t = sin_[i];
  for (std::size_t q = 0; q < count; ++q) {
    const Dual *at = boundary_.data() + 2 * (static_cast<std::size_t>(j[q]) * n + from);
    const Dual x = at[0], y = at[1];
    s[0][q] = x.v, s[1][q] = c * x.du - t * x.dv, s[2][q] = t * x.du + c * x.dv;
    blend[0][q] = y.v, blend[1][q] = c * y.du - t * y.dv, blend[2][q] = t * y.du + c * y.dv;
  }
}

std::size_t EvaluationPlan::rotationRun(std::size_t k) const {
  // The constructor's layout: the centre; n spokes of r − 1 samples; n
  // triangle interiors of perTriangle_ samples. A rotation maps each of
  // these pieces onto one of its kind sample for sample.
  if (k == 0) return 1;
  if (k < interiorBase_) {
    const std::size_t spoke = static_cast<std::size_t>(key_.resolution - 1);
    return 1 + ((k - 1) / spoke + 1) * spoke - k;
  }
  return interiorBase_ + ((k - interiorBase_) / perTriangle_ + 1) * perTriangle_ - k;
}

void EvaluationPlan::prefetchSidesAndBlends(std::size_t first, std::size_t count) const {
  if (!soa_ || perSide_ || first >= size()) return;
  count = std::min(count, size() - first);
  constexpr std::size_t kLine = 64 / sizeof(double); // doubles a cache line
  for (const std::vector<double> *array : {&sideValues_, &sideDu_, &sideDv_, &blendValues_, &blendDu_, &blendDv_})
    for (std::size_t k = first; k < first + count; k += kLine) __builtin_prefetch(array->data() + k);
}

void EvaluationPlan::prefetchSideAndBlendValues(std::size_t first, std::size_t count) const {
  if (!soa_ || perSide_ || first >= size()) return;
  count = std::min(count, size() - first);
  constexpr std::size_t kLine = 64 / sizeof(double); // doubles a cache line
  for (const std::vector<double> *array : {&sideValues_, &blendValues_})
    for (std::size_t k = first; k < first + count; k += kLine) __builtin_prefetch(array->data() + k);
}

SideBlendArrays EvaluationPlan::sidesAndBlends(int i, std::size_t first, std::size_t count, double *const s[3],
                                               double *const blend[3]) const {
  CURVENET_CHECK(soa_, "sidesAndBlends on a composite-ribbon plan");
  SideBlendArrays out;
  // Every side's own parameters (perSide_) are in the domain's frame; side
  // 0's, read for side i, and corner 0's blends are turned by side i's angle.
  out.sideTurn[0] = perSide_ ? 1.0 : cos_[i], out.sideTurn[1] = perSide_ ? 0.0 : sin_[i];
  out.blendTurn[0] = cos_[i], out.blendTurn[1] = sin_[i];
  auto sideAt = [&](std::size_t k) { return perSide_ ? static_cast<std::size_t>(i) * size() + k : rotated(i, k); };
  if (count <= rotationRun(first)) {
    // The run's samples are consecutive in every rotation: the plan's own arrays.
    const std::size_t side = sideAt(first), corner = rotated(i, first);
    out.s[0] = sideValues_.data() + side, out.s[1] = sideDu_.data() + side, out.s[2] = sideDv_.data() + side;
    out.blend[0] = blendValues_.data() + corner, out.blend[1] = blendDu_.data() + corner;
    out.blend[2] = blendDv_.data() + corner;
    return out;
  }
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t j = sideAt(first + k), c = rotated(i, first + k);
    s[0][k] = sideValues_[j], s[1][k] = sideDu_[j], s[2][k] = sideDv_[j];
    blend[0][k] = blendValues_[c], blend[1][k] = blendDu_[c], blend[2][k] = blendDv_[c];
  }
  for (int c = 0; c < 3; ++c) out.s[c] = s[c], out.blend[c] = blend[c];
  return out;
}

std::vector<EvaluationPlan::Group> EvaluationPlan::groups(std::size_t maxCount) const {
  // The layout of the constructor: the centre; n spokes of r − 1 samples and
  // n triangle interiors, each permuted as wholes by the rotations.
  CURVENET_CHECK(maxCount > 0, "sample groups of at most 0 samples");
  const int n = key_.sides;
  const std::size_t spoke = static_cast<std::size_t>(key_.resolution - 1), perTriangle = perTriangle_;
  std::vector<Group> out{{0, 1, 0, 1}};
  for (std::size_t q = 0; q < spoke; q += maxCount) out.push_back({1 + q, std::min(maxCount, spoke - q), spoke, n});
  for (std::size_t q = 0; q < perTriangle; q += maxCount)
    out.push_back({interiorBase_ + q, std::min(maxCount, perTriangle - q), perTriangle, n});
  return out;
}

std::size_t EvaluationPlan::memory() const {
  return samples_.size() * sizeof(Vec2) + (s_.size() + d_.size() + b_.size() + boundary_.size()) * sizeof(Dual) +
         (sideValues_.size() + blendValues_.size() + sideDu_.size() + sideDv_.size() + blendDu_.size() +
          blendDv_.size()) *
             sizeof(double);
}

namespace {
struct PlanCache {
  std::mutex mutex;
  std::map<PlanKey, std::shared_future<std::shared_ptr<const EvaluationPlan>>> plans;
};
PlanCache &cache() {
  static PlanCache instance;
  return instance;
}
} // namespace

std::shared_ptr<const EvaluationPlan> evaluationPlan(const PlanKey &key) {
  PlanCache &c = cache();
  std::promise<std::shared_ptr<const EvaluationPlan>> promise;
  std::shared_future<std::shared_ptr<const EvaluationPlan>> future;
  bool build = false;
  {
    std::lock_guard lock(c.mutex);
    if (auto it = c.plans.find(key); it != c.plans.end()) {
      future = it->second; // built, or being built by another caller: wait outside the lock
    } else {
      future = promise.get_future().share();
      c.plans.emplace(key, future);
      build = true;
    }
  }
  if (build) {
    try {
      promise.set_value(std::make_shared<const EvaluationPlan>(key));
    } catch (...) {
      {
        std::lock_guard lock(c.mutex);
        c.plans.erase(key); // a later caller may retry
      }
      promise.set_exception(std::current_exception());
    }
  }
  return future.get();
}

PlanCacheStats evaluationPlanCache() {
  PlanCache &c = cache();
  std::vector<std::shared_future<std::shared_ptr<const EvaluationPlan>>> futures;
  {
    std::lock_guard lock(c.mutex);
    for (const auto &[key, future] : c.plans) futures.push_back(future);
  }
  PlanCacheStats stats{};
  for (const auto &f : futures) {
    if (f.wait_for(std::chrono::seconds(0)) != std::future_status::ready) continue;
    try {
      stats.bytes += f.get()->memory();
      ++stats.plans;
    } catch (...) {
    }
  }
  return stats;
}

void clearEvaluationPlans() {
  PlanCache &c = cache();
  std::lock_guard lock(c.mutex);
  c.plans.clear(); // plans in use stay alive through their shared_ptr
}

} // namespace v1
} // namespace curvenet
