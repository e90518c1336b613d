// Patch evaluation through an evaluation plan or at batches of domain
// points: per side, the ribbon at the side parameters (from the ribbon
// tables, or exactly at low plan resolutions: the only geometry-dependent
// work); then the Gregory formula ([SV14] eqs. 16–18, 22) in one pass of
// a SIMD kernel — kernels::gregoryPositions for points alone,
// kernels::gregoryJets with exact first derivatives.
#include <algorithm>
#include <array>
#include <span>
#include <type_traits>
#include <vector>

#include "curvenet/error.hpp"
#include "curvenet/kernels/kernels.hpp"
#include "patches/patch.hpp"
#include "plans/plan.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

/// Per-thread structure-of-arrays scratch of `count` doubles per array, each
/// array on a cache line (the kernels' vector loads and stores then never
/// straddle two) and one line further modulo 4 KB than the one before: at a
/// power-of-two stride the arrays would share their low address bits, and
/// the CPU, comparing loads with earlier stores by those bits first, stalls
/// loads behind stores to other arrays (the table pass measured 30% slower
/// at a 1 KB stride).
struct Scratch {
  kernels::AlignedVector<double> data;
  std::size_t stride = 0, used = 0;
  void reset(std::size_t samples, std::size_t arrays) {
    stride = (samples + 7) / 8 * 8 + 8, used = 0;
    if (data.size() < stride * arrays) data.resize(stride * arrays);
  }
  double *take() {
    double *p = data.data() + used * stride;
    ++used;
    return p;
  }
};

/// Sample k of jet arrays r[c] (value, ∂/∂u, ∂/∂v; x, y, z each: JetBlockSink).
void setJet(double *const r[9], std::size_t k, const DualVec3 &p) {
  r[0][k] = p.v.x, r[1][k] = p.v.y, r[2][k] = p.v.z, r[3][k] = p.du.x, r[4][k] = p.du.y, r[5][k] = p.du.z;
  r[6][k] = p.dv.x, r[7][k] = p.dv.y, r[8][k] = p.dv.z;
}

struct DualArray {
  double *v, *du, *dv;
  void take(Scratch &s) { v = s.take(), du = s.take(), dv = s.take(); }
  void set(std::size_t k, const Dual &x) { v[k] = x.v, du[k] = x.du, dv[k] = x.dv; }
};

struct Vec3Array {
  double *c[3];
  void take(Scratch &s) { c[0] = s.take(), c[1] = s.take(), c[2] = s.take(); }
  void set(std::size_t k, const Vec3 &x) { c[0][k] = x.x, c[1][k] = x.y, c[2][k] = x.z; }
};

struct JetArrays {
  Vec3Array P, dP, T, dT, C, dC;
};

constexpr int kMaxCornerVectors = 17; // a00 and the eight (a, b) pairs of eq. 22
// Samples per pass of the position path: their ribbon values (up to 10
// arrays per side: 51 KB for a G² pentagon) stay in the cache between the
// table pass and the kernel pass. 128 measured fastest of 32 … 512
// (pentagon r256: 64 is ~4% slower, the per-block calls, and 512 ~15%, the
// cache).
constexpr std::size_t kPositionBlock = 128;
// Samples per block of the jet pass: the ribbons' values and slopes (up to
// 18 arrays per side) then stay near the kernel (the L1 and L2 caches)
// between the table pass and the kernel pass; whole tiles would spill them
// to L3 (32 and 128 measured no faster).
constexpr std::size_t kJetBlock = 64;

/// A composite-ribbon batch's inputs as arrays: side i's parameter s[i][k],
/// distance d[i][k] and blend b[i][k] = q_i + q_{i+1} from the per-corner
/// quantities q (the plan's blends), through value(i, k, which).
template <class T> struct CompositeInputs {
  std::vector<T> storage;
  std::array<T *, Patch::kMaxSides> s{}, d{}, b{};
  template <class Value> void fill(int n, std::size_t count, const Value &value) {
    storage.resize(3 * static_cast<std::size_t>(n) * count);
    for (int i = 0; i < n; ++i)
      s[i] = &storage[(3 * i) * count], d[i] = &storage[(3 * i + 1) * count], b[i] = &storage[(3 * i + 2) * count];
    for (int i = 0; i < n; ++i)
      for (std::size_t k = 0; k < count; ++k)
        s[i][k] = value(i, k, 0), d[i][k] = value(i, k, 1), b[i][k] = value(i, k, 2);
    // b_i = q_i + q_{i+1} in place, each q read once (q_0 kept for the last side).
    for (std::size_t k = 0; k < count; ++k) {
      const T first = b[0][k];
      for (int i = 0; i + 1 < n; ++i) b[i][k] += b[i + 1][k];
      b[n - 1][k] += first;
    }
  }
  /// f(k, s, d, b) with every side's values at sample k, for each sample.
  template <class F> void eachSample(int n, std::size_t count, const F &f) const {
    std::array<T, Patch::kMaxSides> sk, dk, bk;
    for (std::size_t k = 0; k < count; ++k) {
      for (int i = 0; i < n; ++i) sk[i] = s[i][k], dk[i] = d[i][k], bk[i] = b[i][k];
      f(k, sk.data(), dk.data(), bk.data());
    }
  }
};

/// A Dual as the column type T of a batch: the value alone (double) or with its gradient (Dual).
template <class T> T columnValue(const Dual &x) {
  if constexpr (std::is_same_v<T, double>) {
    return x.v;
  } else {
    return x;
  }
}

/// The composite-ribbon inputs of `count` points, chunk by chunk: per point
/// parameters(u, v, s, d, blend) (Patch::compositeParameters at the snapped
/// point) stored as T in columns per side, then kernel(first, size, s, d,
/// blend) on the chunk's columns (the CR position or jet kernel).
template <class T, class Parameters, class Kernel>
void forCompositeRibbonChunks(int n, std::size_t count, const double *u, const double *v, const Parameters &parameters,
                              const Kernel &kernel) {
  constexpr std::size_t kChunk = 512;
  thread_local std::vector<T> columns;
  for (std::size_t first = 0; first < count; first += kChunk) {
    const std::size_t m = std::min(kChunk, count - first);
    columns.resize(3 * static_cast<std::size_t>(n) * m);
    std::array<const T *, Patch::kMaxSides> side, distance, blend;
    auto column = [&](int which, int i) { return columns.data() + (static_cast<std::size_t>(which) * n + i) * m; };
    for (std::size_t k = 0; k < m; ++k) {
      std::array<Dual, Patch::kMaxSides> sk, dk, bk;
      parameters(u[first + k], v[first + k], sk.data(), dk.data(), bk.data());
      for (int i = 0; i < n; ++i)
        column(0, i)[k] = columnValue<T>(sk[i]), column(1, i)[k] = columnValue<T>(dk[i]),
        column(2, i)[k] = columnValue<T>(bk[i]);
    }
    for (int i = 0; i < n; ++i) side[i] = column(0, i), distance[i] = column(1, i), blend[i] = column(2, i);
    kernel(first, m, side.data(), distance.data(), blend.data());
  }
}


/// Per chunk of evaluateJets, structure of arrays of `count` samples: x, y
/// (snapped points), the root solver's distances of the side at hand, then
/// for every side its parameter (value, ∂u, ∂v), its frame coordinates and the
/// corner blend (value, ∂u, ∂v).
struct JetColumns {
  int sides = 0;
  std::size_t count = 0;
  std::vector<double> data;
  void reset(int n, std::size_t samples) {
    sides = n, count = samples;
    data.resize(static_cast<std::size_t>(8 * n + 3) * samples);
  }
  double *at(std::size_t array) { return data.data() + array * count; }
  double *x() { return at(0); }
  double *y() { return at(1); }
  double *unused() { return at(2); } // the root solver's second output
  double *side(int i, int c) { return at(3 + 3 * static_cast<std::size_t>(i) + c); }
  double *fx(int i) { return at(3 + 3 * static_cast<std::size_t>(sides) + i); }
  double *fy(int i) { return at(3 + 4 * static_cast<std::size_t>(sides) + i); }
  double *blend(int i, int c) { return at(3 + 3 * static_cast<std::size_t>(sides + i) + 2 * sides + c); }
};

/// Side i's frame unit: e = (p_{i+1} − p_i) / |p_{i+1} − p_i|². The frame
/// (the side from (0, 0) to (1, 0), the domain at y > 0) is affine in
/// (u, v): ∂(fx, fy)/∂u = (e.x, −e.y), ∂/∂v = (e.y, e.x).
Vec2 sideFrameAxis(const RegularDomain &domain, int i) {
  const Vec2 edge = domain.corner(i + 1) - domain.corner(i);
  return edge / dot(edge, edge);
}

/// The domain's sides as the frame and blend kernels take them.
kernels::DomainSides kernelSides(const RegularDomain &domain) {
  kernels::DomainSides sides;
  sides.sides = domain.sides();
  for (int i = 0; i < domain.sides(); ++i) {
    const Vec2 p = domain.corner(i), e = sideFrameAxis(domain, i);
    sides.px[i] = p.x, sides.py[i] = p.y, sides.ex[i] = e.x, sides.ey[i] = e.y;
  }
  return sides;
}

/// Side i's radial sweep parameter from the frame coordinates: the closed
/// form s = X − Y (x − X) / (y − Y) about the apex (X, Y), or x − y a_x / a_y
/// for parallel neighbours, differentiated.
void radialSweepJets(const RegularDomain &domain, int i, JetColumns &c) {
  const kernels::SweepFrame &frame = domain.sweepFrame(i);
  const Vec2 e = sideFrameAxis(domain, i);
  const double *fx = c.fx(i), *fy = c.fy(i);
  double *s[3] = {c.side(i, 0), c.side(i, 1), c.side(i, 2)};
  for (std::size_t k = 0; k < c.count; ++k) {
    double sx, sy;
    s[0][k] = RegularDomain::radialSideParameter(frame, fx[k], fy[k]);
    if (frame.parallel) {
      sx = 1, sy = -frame.ax / frame.ay;
    } else {
      const double inverse = 1 / (fy[k] - frame.apexY), ratio = frame.apexY * inverse;
      sx = -ratio, sy = ratio * (fx[k] - frame.apexX) * inverse;
    }
    s[1][k] = sx * e.x - sy * e.y, s[2][k] = sx * e.y + sy * e.x;
  }
}

/// Side i's cubic Hermite sweep parameter from the frame coordinates: the
/// roots in one batched solve, their gradients by implicit differentiation
/// of F(s; x, y) = (x − s) w_y(s) − y w_x(s) (as
/// RegularDomain::hermiteSweepFromRoot).
void cubicHermiteSweepJets(const RegularDomain &domain, int i, JetColumns &c) {
  const kernels::SweepFrame &frame = domain.sweepFrame(i);
  const Vec2 e = sideFrameAxis(domain, i);
  kernels::hermiteSweepRoots(c.count, frame, c.fx(i), c.fy(i), c.side(i, 0), c.unused());
  kernels::hermiteSweepGradients(c.count, frame, e.x, e.y, c.fx(i), c.fy(i), c.side(i, 0), c.side(i, 1), c.side(i, 2));
}

/// visit(k, j) for each sample k of a batch at the domain's corner j
/// (RegularDomain::cornerAt).
template <class Visit>
void forEachCornerSample(const RegularDomain &domain, std::size_t count, const double *u, const double *v,
                         const Visit &visit) {
  // Mostly no sample is near the unit circle, where the corners lie: one
  // vectorized pass to find that out.
  int nearCircle = 0;
  for (std::size_t k = 0; k < count; ++k) nearCircle |= u[k] * u[k] + v[k] * v[k] >= 1 - 1e-9;
  if (!nearCircle) return;
  for (std::size_t k = 0; k < count; ++k)
    if (const int j = domain.cornerAt(u[k], v[k]); j >= 0) visit(k, j);
}

/// The Hermite sweeps of a batch at the domain's exact corners: the two
/// sides meeting there at their ends exactly, as the pointwise sweep
/// (hermiteSweepSides) gives them. s[i]: side i's values.
void exactSweepEndsAtCorners(const RegularDomain &domain, std::size_t count, const double *u, const double *v,
                             double *const *s) {
  forEachCornerSample(domain, count, u, v, [&](std::size_t k, int j) { s[j][k] = 0, s[domain.wrap(j - 1)][k] = 1; });
}

} // namespace

kernels::GregoryCorner kernelCorner(const CornerData &c) {
  // {a00, a10, a01, a11, b10, b01, b11} in kernel order.
  const Vec3 vectors[7] = {c.a00, c.a10, c.b10, c.a01, c.b01, c.a11, c.b11};
  kernels::GregoryCorner corner{};
  for (int j = 0; j < 7; ++j)
    corner.v[j][0] = vectors[j].x, corner.v[j][1] = vectors[j].y, corner.v[j][2] = vectors[j].z;
  return corner;
}

kernels::GregoryCorner Patch::cornerVectors(int i) const {
  if (options_.scheme != Scheme::GregoryG2) return kernelCorner(corners_[i]);
  const CornerData2 &c = corners2_[i];
  std::array<Vec3, kMaxCornerVectors> vectors{};
  int used = 0;
  vectors[used++] = c.a[0][0];
  for (int p = 0; p <= 2; ++p)
    for (int r = 0; r <= 2; ++r)
      if (p || r) vectors[used++] = c.a[p][r], vectors[used++] = c.b[p][r];
  kernels::GregoryCorner corner{};
  for (int j = 0; j < kMaxCornerVectors; ++j)
    corner.v[j][0] = vectors[j].x, corner.v[j][1] = vectors[j].y, corner.v[j][2] = vectors[j].z;
  return corner;
}

std::size_t PatchTables::memory() const {
  std::size_t bytes = 0;
  for (const RibbonTable &t : sides) bytes += t.memory();
  return bytes;
}

namespace {

/// The table of side `side`; a table that cannot be built says which side.
void addSideTable(PatchTables &tables, int side, int dims, std::vector<double> breaks, const RibbonTable::Exact &exact) {
  try {
    tables.sides.emplace_back(dims, std::move(breaks), exact);
  } catch (const InternalError &e) {
    throw InternalError("side " + std::to_string(side) + ": " + e.what());
  } catch (const InputError &e) {
    throw InputError(e.file(), "side " + std::to_string(side), e.reason());
  }
}

} // namespace

const PatchTables &Patch::tables() const {
  CURVENET_CHECK(options_.scheme == Scheme::GregoryG1 || options_.scheme == Scheme::GregoryG2 ||
                     options_.scheme == Scheme::CompositeRibbon,
                 "ribbon tables are built for the transfinite schemes");
  std::call_once(tables_->once, [this] {
    PatchTables &t = tables_->tables;
    const bool g2 = options_.scheme == Scheme::GregoryG2;
    for (int i = 0; i < domain_.sides(); ++i) {
      // Exact jets without snapping: the table asks one ulp inside each
      // interval to get the side of a segment break it needs.
      RibbonTable::Exact exact;
      if (g2) {
        exact = [&ribbon = parabolic_[i]](std::span<const double> at, double *values, double *slopes) {
          std::vector<ParabolicJet> jets(at.size());
          ribbon.at(at, jets);
          for (std::size_t k = 0; k < at.size(); ++k) {
            const ParabolicJet &j = jets[k];
            const Vec3 v[3] = {j.P, j.T, j.C}, d[3] = {j.dP, j.dT, j.dC};
            for (int f = 0; f < 3; ++f)
              for (int c = 0; c < 3; ++c) values[k * 9 + f * 3 + c] = v[f][c], slopes[k * 9 + f * 3 + c] = d[f][c];
          }
        };
        addSideTable(t, i, 9, parabolic_[i].breakpoints(), exact);
      } else {
        exact = [&ribbon = ribbons_[i]](std::span<const double> at, double *values, double *slopes) {
          std::vector<RibbonJet> jets(at.size());
          ribbon.at(at, jets);
          for (std::size_t k = 0; k < at.size(); ++k) {
            const RibbonJet &j = jets[k];
            const Vec3 v[2] = {j.P, j.T}, d[2] = {j.dP, j.dT};
            for (int f = 0; f < 2; ++f)
              for (int c = 0; c < 3; ++c) values[k * 6 + f * 3 + c] = v[f][c], slopes[k * 6 + f * 3 + c] = d[f][c];
          }
        };
        addSideTable(t, i, 6, ribbons_[i].breakpoints(), exact);
      }
    }
  });
  return tables_->tables;
}

void Patch::checkPlan(const EvaluationPlan &plan) const {
  CURVENET_CHECK(plan.key().sides == domain_.sides() && plan.key().scheme == options_.scheme,
                 "plan for " + std::to_string(plan.key().sides) + " sides used on a patch with " +
                     std::to_string(domain_.sides()));
}

void Patch::evaluatePlannedPositions(const EvaluationPlan &plan, std::size_t first, std::size_t count,
                                     const PositionSink &out) const {
  checkPlan(plan);
  const int n = domain_.sides();
  if (options_.scheme == Scheme::CompositeRibbon) {
    // The CR formula on values alone (no gradients): batched through the
    // tables at high resolutions, else per sample with exact ribbons.
    thread_local CompositeInputs<double> in;
    in.fill(n, count, [&](int i, std::size_t k, int which) {
      return which == 0 ? plan.sideValue(i, first + k)
             : which == 1 ? plan.distanceValue(i, first + k)
                          : plan.blendValue(i, first + k);
    });
    if (plan.key().resolution >= kTableResolution) {
      compositeRibbonPositions(count, in.s.data(), in.d.data(), in.b.data(), out);
      return;
    }
    in.eachSample(n, count, [&](std::size_t k, const double *s, const double *d, const double *b) {
      out.set(k, compositeRibbonPoint(s, d, b));
    });
    return;
  }
  // Run by run of the rotation: every side reads side 0's values (and
  // corner 0's blends) at its rotated run. The tessellator's tiles lie
  // within runs and come in rotation groups, so a group reads one stretch of
  // the plan n times from the cache.
  std::array<const double *, Patch::kMaxSides> side, blend;
  for (std::size_t k = first; k < first + count;) {
    const std::size_t m = std::min(plan.rotationRun(k), first + count - k);
    for (int i = 0; i < n; ++i) side[i] = plan.sideValuesFrom(i, k), blend[i] = plan.blendValuesFrom(i, k);
    gregoryPositionsFrom(m, side.data(), blend.data(), out.from(k - first));
    k += m;
  }
}

namespace {
/// The rotation-group pass both evaluatePlannedGroup share: the group's
/// members block by block (`block` samples), corner 0's weights on every
/// member first — weigh(count, s_0, s_{n−1}, into, stride), `rows` arrays
/// of it a member — then evaluate(m, offset, count, cornerWeights, stride)
/// for each member m, corner i's weights being corner 0's on member
/// source(m, i) (Group::source). The weight arrays lie a cache line apart
/// modulo 4 KB (as the Scratch arrays: at a 1 KB stride, loads wait behind
/// stores to other arrays that share their address bits).
template <class Weigh, class Evaluate>
void forEachGroupBlockWithSharedWeights(const EvaluationPlan &plan, const EvaluationPlan::Group &group,
                                        std::size_t block, std::size_t rows, const Weigh &weigh,
                                        const Evaluate &evaluate) {
  const int n = plan.key().sides, members = group.members;
  const std::size_t stride = block + 8;
  thread_local kernels::AlignedVector<double> weights;
  weights.resize(static_cast<std::size_t>(members) * rows * stride);
  auto memberWeights = [&](int m) { return weights.data() + static_cast<std::size_t>(m) * rows * stride; };
  std::array<const double *, Patch::kMaxSides> cornerWeights;
  for (std::size_t offset = 0; offset < group.count; offset += block) {
    const std::size_t count = std::min(block, group.count - offset);
    auto start = [&](int m) { return group.first + m * group.stride + offset; };
    // Corner 0's weights on every member: its s_0 and t_0 = 1 − s_{n−1}.
    for (int m = 0; m < members; ++m)
      weigh(count, plan.sideValuesFrom(0, start(m)), plan.sideValuesFrom(0, start(group.source(m, n - 1))),
            memberWeights(m), stride);
    for (int m = 0; m < members; ++m) {
      for (int i = 0; i < n; ++i) cornerWeights[i] = memberWeights(group.source(m, i));
      evaluate(m, offset, count, cornerWeights.data(), stride);
    }
  }
}
} // namespace

bool Patch::sharesGroupWeights(const EvaluationPlan &plan) const {
  // Shared weights need every side's parameters to be side 0's rotated
  // (not so on triangles, perSide()). G¹'s are too cheap to repay the round
  // trip through memory: shared, its evaluation measured no faster (they are
  // 7% of its kernel even when free, G²'s 29%). A patch whose ribbons
  // saturate has weights of its own per corner (of the saturated cross
  // parameters, kernels::GregorySamples::reach): nothing to share.
  return options_.scheme == Scheme::GregoryG2 && !plan.perSide() && !reachLimited_;
}

void Patch::evaluatePlannedGroup(const EvaluationPlan &plan, const EvaluationPlan::Group &group,
                                 const PositionSink &out) const {
  checkPlan(plan);
  if (!sharesGroupWeights(plan)) {
    for (int m = 0; m < group.members; ++m)
      evaluatePlannedPositions(plan, group.first + m * group.stride, group.count, out.from(m * group.stride));
    return;
  }
  // Side i's (corner i's) data on member m: side 0's on member m − i.
  forEachGroupBlockWithSharedWeights(
      plan, group, kPositionBlock, 8,
      [](std::size_t count, const double *s, const double *sPrevious, double *into, std::size_t stride) {
        kernels::gregoryCornerWeights(count, s, sPrevious, into, stride);
      },
      [&](int m, std::size_t offset, std::size_t count, const double *const *cornerWeights, std::size_t stride) {
        // Member m's next block asked for while it computes this one (as the
        // jets' below): the weights' pass brings each block's side values
        // in, but the blends were first read by the kernel, where its loads
        // of them missed. On a Zen 5 the G² face interiors −3 to −4 %
        // (curvenet bench, four alternating runs); on the Intel machine the
        // same hint had measured no clear gain.
        if (offset + count < group.count)
          plan.prefetchSideAndBlendValues(group.first + m * group.stride + offset + count,
                                          std::min(count, group.count - offset - count));
        std::array<const double *, Patch::kMaxSides> side, blend;
        for (int i = 0; i < domain_.sides(); ++i) {
          const std::size_t from = group.first + group.source(m, i) * group.stride + offset;
          side[i] = plan.sideValuesFrom(0, from), blend[i] = plan.blendValuesFrom(0, from);
        }
        gregoryPositionsFrom(count, side.data(), blend.data(), out.from(m * group.stride + offset), cornerWeights,
                             stride);
      });
}

void Patch::evaluatePlannedGroup(const EvaluationPlan &plan, const EvaluationPlan::Group &group,
                                 const GroupJetSink &out) const {
  checkPlan(plan);
  if (!sharesGroupWeights(plan)) {
    for (int m = 0; m < group.members; ++m)
      evaluatePlanned(plan, group.first + m * group.stride, group.count,
                      [&out, m](std::size_t at, std::size_t size, const double *const jet[9]) { out(m, at, size, jet); });
    return;
  }
  // The jets' weights come with their partials: three times the positions' rows.
  const bool useTables = plan.key().resolution >= kTableResolution;
  forEachGroupBlockWithSharedWeights(
      plan, group, kJetBlock, 24,
      [](std::size_t count, const double *s, const double *sPrevious, double *into, std::size_t stride) {
        kernels::gregoryCornerWeightJets(count, s, sPrevious, into, stride);
      },
      [&](int m, std::size_t offset, std::size_t count, const double *const *cornerWeights, std::size_t stride) {
        const std::size_t first = group.first + m * group.stride + offset;
        // Every member reads the others' side data, megabytes at high
        // resolutions that the first member to read misses in the cache:
        // the next block's of member m + 1 asked for while m computes, so
        // that a block offset's members ask for all the next one's.
        // TessellateCpu G² −2 to −5 % (four sets of seven to fifteen
        // alternating runs).
        if (offset + count < group.count)
          plan.prefetchSidesAndBlends(group.first + ((m + 1) % group.members) * group.stride + offset + count,
                                      std::min(count, group.count - offset - count));
        gregoryJetsFrom(
            count,
            [&](int i, std::size_t block, std::size_t size, double *const s[3], double *const b[3]) {
              return plan.sidesAndBlends(i, first + block, size, s, b);
            },
            useTables,
            [&](std::size_t at, std::size_t size, const double *const jet[9]) { out(m, offset + at, size, jet); },
            cornerWeights, stride);
      });
}

void Patch::gregoryPositionsFrom(std::size_t count, const double *const *sideValues, const double *const *blendValues,
                                 const PositionSink &out, const double *const *cornerWeights,
                                 std::size_t weightStride) const {
  const int n = domain_.sides();
  if (count > kPositionBlock) {
    std::array<const double *, Patch::kMaxSides> side, blend, weights;
    for (std::size_t first = 0; first < count; first += kPositionBlock) {
      for (int i = 0; i < n; ++i) {
        side[i] = sideValues[i] + first, blend[i] = blendValues[i] + first;
        if (cornerWeights) weights[i] = cornerWeights[i] + first;
      }
      gregoryPositionsFrom(std::min(kPositionBlock, count - first), side.data(), blend.data(), out.from(first),
                           cornerWeights ? weights.data() : nullptr, weightStride);
    }
    return;
  }
  const PatchTables &t = tables();
  const bool g2 = options_.scheme == Scheme::GregoryG2;
  const int dims = g2 ? 9 : 6;
  thread_local Scratch scratch;
  scratch.reset(count, static_cast<std::size_t>(n) * (dims + 1));
  kernels::GregorySamples in;
  in.sides = n, in.parabolic = g2;
  for (int i = 0; i < int(blendShare_.size()); ++i) in.blendShare[i] = blendShare_[i];
  for (int i = 0; i < n; ++i) {
    // The side parameters serve as table parameters as they are (they lie
    // in [0, 1]), except on sides made of several segments: there the
    // ribbon may jump at a break (T-nodes), and a parameter within a
    // rounding error of it must take the break's left piece, as
    // Surface::evaluate does (LinearRibbon::snap).
    in.s[i] = sideValues[i], in.blend[i] = blendValues[i];
    const double *at = in.s[i];
    if (ribbons_[i].pieces().size() > 1) {
      double *snapped = scratch.take();
      for (std::size_t k = 0; k < count; ++k) snapped[k] = ribbons_[i].snap(std::clamp(in.s[i][k], 0.0, 1.0));
      at = snapped;
    }
    double *jets[9];
    for (int c = 0; c < dims; ++c) jets[c] = scratch.take();
    t.sides[i].evaluate(count, at, jets, nullptr);
    for (int c = 0; c < 3; ++c) {
      in.P[i][c] = jets[c], in.T[i][c] = jets[3 + c];
      if (g2) in.C[i][c] = jets[6 + c];
    }
  }
  if (g2)
    for (int i = 0; i < n; ++i) in.reach[i] = crossReach_[i];
  if (g2 && cornerWeights) {
    for (int i = 0; i < n; ++i) in.weights[i] = cornerWeights[i];
    in.weightStride = weightStride;
  }
  const kernels::GregoryCornerTerms *terms = g2 ? cornerTerms_.data() : nullptr;
  if (out.points) {
    static_assert(sizeof(Vec3) == 3 * sizeof(double), "points are read as three doubles each");
    const double offset[3] = {out.offset.x, out.offset.y, out.offset.z};
    kernels::gregoryPositionsInterleaved(count, in, kernelCorners_.data(), &out.points[0].x, offset,
                                         kernels::kBestWidth, terms);
  } else {
    kernels::gregoryPositions(count, in, kernelCorners_.data(), out.arrays, kernels::kBestWidth, terms);
  }
}

void Patch::compositeParametersAt(double u, double v, Dual *s, Dual *d, Dual *blend) const {
  snapToCorner(u, v);
  compositeParameters(Dual::u(u), Dual::vCoord(v), s, d, blend);
}

void Patch::evaluatePositions(std::size_t count, const double *u, const double *v, const PositionSink &out) const {
  const int n = domain_.sides();
  const bool gregory = options_.scheme == Scheme::GregoryG1 || options_.scheme == Scheme::GregoryG2;
  // Composite-ribbon batches large enough to pay for the ribbon tables
  // (~1–4 ms a face, once): each point's Wachspress distances, linear-sweep
  // side parameters and blends (compositeRibbon's formulas), then the tables
  // and the CR kernel; smaller batches point by point.
  constexpr std::size_t kCompositeBatch = 512;
  if (options_.scheme == Scheme::CompositeRibbon && count >= kCompositeBatch) {
    const auto compositeAt = [this](double x, double y, Dual *side, Dual *distance, Dual *blend) {
      compositeParametersAt(x, y, side, distance, blend);
    };
    forCompositeRibbonChunks<double>(
        n, count, u, v, compositeAt,
        [&](std::size_t first, std::size_t m, const double *const *side, const double *const *distance,
            const double *const *blend) { compositeRibbonPositions(m, side, distance, blend, out.from(first)); });
    return;
  }
  if (!gregory || options_.sweepline == Sweepline::QuinticHermite) {
    for (std::size_t k = 0; k < count; ++k) out.set(k, evaluate(u[k], v[k]).v);
    return;
  }
  // Chunks small enough for the per-thread scratch to stay in the L2 cache.
  constexpr std::size_t kChunk = 512;
  const bool g2 = options_.scheme == Scheme::GregoryG2;
  const bool radial = options_.sweepline == Sweepline::Radial;
  const bool triangle = n == 3 && !radial;
  struct Frames {
    std::size_t count = 0;
    std::vector<double> data;
    double *at(std::size_t array) { return data.data() + array * count; }
  };
  const kernels::DomainSides sides = kernelSides(domain_);
  thread_local Frames scratch;
  for (std::size_t first = 0; first < count; first += kChunk) {
    const std::size_t m = std::min(kChunk, count - first);
    scratch.count = m;
    scratch.data.resize(static_cast<std::size_t>(4 * n + 1) * m);
    // Per side: its parameter, its frame coordinates (y the perpendicular
    // distance Δ_i of the blends) and its corner blend.
    std::array<double *, Patch::kMaxSides> side, x, y, blend;
    for (int i = 0; i < n; ++i)
      side[i] = scratch.at(i), x[i] = scratch.at(n + i), y[i] = scratch.at(2 * n + i), blend[i] = scratch.at(3 * n + i);
    kernels::sideFrames(m, sides, u + first, v + first, x.data(), y.data());
    for (int i = 0; i < n; ++i) {
      const kernels::SweepFrame frame = domain_.sweepFrame(i);
      if (radial) {
        // Closed form: the domain's own formula (as evaluate() uses it) on the frame coordinates.
        for (std::size_t k = 0; k < m; ++k) side[i][k] = RegularDomain::radialSideParameter(frame, x[i][k], y[i][k]);
      } else if (triangle) {
        // A triangle's sweep is closed-form in the three distances (RegularDomain::triangleSideParameter).
        const double *previous = y[domain_.wrap(i - 1)], *next = y[domain_.wrap(i + 1)];
        for (std::size_t k = 0; k < m; ++k) side[i][k] = domain_.triangleSideParameter(previous[k], next[k], y[i][k]);
      } else {
        kernels::hermiteSweepRoots(m, frame, x[i], y[i], side[i], scratch.at(4 * n));
      }
    }
    if (!radial) exactSweepEndsAtCorners(domain_, m, u + first, v + first, side.data());
    // Corner blends B_{i,i−1} = ∏_{j∉{i,i−1}} Δ_j^m / Σ_k ∏_{j∉{k,k−1}} Δ_j^m, in
    // the product order of RegularDomain::cornerProducts.
    kernels::cornerBlends(m, sides, g2 ? 3 : 2, y.data(), blend.data(), nullptr, nullptr);
    gregoryPositionsFrom(m, side.data(), blend.data(), out.from(first));
  }
}

void Patch::evaluatePlanned(const EvaluationPlan &plan, std::size_t first, std::size_t count,
                            const JetBlockSink &out) const {
  if (options_.scheme == Scheme::CompositeRibbon) {
    // The CR formula's own batch (DualVec3), handed on as one block of arrays.
    thread_local std::vector<DualVec3> values;
    thread_local std::vector<double> arrays;
    values.resize(count), arrays.resize(9 * count);
    evaluatePlanned(plan, first, count, values.data());
    double *jet[9];
    for (int c = 0; c < 9; ++c) jet[c] = arrays.data() + c * count;
    for (std::size_t k = 0; k < count; ++k) setJet(jet, k, values[k]);
    out(0, count, jet);
    return;
  }
  checkPlan(plan);
  gregoryJetsFrom(
      count,
      [&](int i, std::size_t block, std::size_t m, double *const s[3], double *const b[3]) {
        return plan.sidesAndBlends(i, first + block, m, s, b);
      },
      plan.key().resolution >= kTableResolution, out);
}

void Patch::evaluatePlanned(const EvaluationPlan &plan, std::size_t first, std::size_t count, DualVec3 *out) const {
  checkPlan(plan);
  const int n = domain_.sides();
  if (options_.scheme == Scheme::CompositeRibbon) {
    // With gradients: batched through the tables at high resolutions, else
    // per sample with exact ribbons.
    thread_local CompositeInputs<Dual> in;
    in.fill(n, count, [&](int i, std::size_t k, int which) {
      return which == 0 ? plan.side(i, first + k) : which == 1 ? plan.distance(i, first + k) : plan.blend(i, first + k);
    });
    if (plan.key().resolution >= kTableResolution) {
      compositeRibbonJets(count, in.s.data(), in.d.data(), in.b.data(), out);
      return;
    }
    in.eachSample(n, count, [&](std::size_t k, const Dual *s, const Dual *d, const Dual *b) {
      out[k] = compositeRibbonFrom(s, d, b);
    });
    return;
  }

  gregoryJetsFrom(
      count,
      [&](int i, std::size_t block, std::size_t m, double *const s[3], double *const b[3]) {
        return plan.sidesAndBlends(i, first + block, m, s, b);
      },
      plan.key().resolution >= kTableResolution, out);
}

void Patch::gregoryJetsFrom(std::size_t count, const SideBlendSource &source, bool useTables, DualVec3 *out) const {
  gregoryJetsFrom(count, source, useTables, [out](std::size_t at, std::size_t m, const double *const r[9]) {
    for (std::size_t k = 0; k < m; ++k)
      out[at + k] = {{r[0][k], r[1][k], r[2][k]}, {r[3][k], r[4][k], r[5][k]}, {r[6][k], r[7][k], r[8][k]}};
  });
}

void Patch::gregoryJetsFrom(std::size_t count, const SideBlendSource &source, bool useTables, const JetBlockSink &out,
                            const double *const *weightJets, std::size_t weightJetStride) const {
  const int n = domain_.sides();
  const bool g2 = options_.scheme == Scheme::GregoryG2;
  const PatchTables *tables = useTables ? &this->tables() : nullptr;
  thread_local Scratch scratch;
  thread_local std::vector<RibbonJet> linearJets;
  thread_local std::vector<ParabolicJet> parabolicJets;
  const std::size_t jetArrays = g2 ? 18 : 12;
  for (std::size_t first = 0; first < count; first += kJetBlock) {
    const std::size_t m = std::min(kJetBlock, count - first);
    scratch.reset(m, static_cast<std::size_t>(n) * (6 + jetArrays) + 10);
    kernels::GregoryJetSamples in;
    std::array<JetArrays, Patch::kMaxSides> jets;
    for (int i = 0; i < n; ++i) {
      DualArray sideBuffer, blendBuffer; // for a source that writes its arrays
      sideBuffer.take(scratch), blendBuffer.take(scratch);
      double *const s[3] = {sideBuffer.v, sideBuffer.du, sideBuffer.dv};
      double *const b[3] = {blendBuffer.v, blendBuffer.du, blendBuffer.dv};
      // Where the source put side i's and corner i's arrays, straight into
      // the kernel's inputs: copied through an array of these, the source's
      // 8-byte stores met 16-byte loads, which the CPU does not forward
      // (~1 % of a G² tessellation stalled there).
      const SideBlendArrays g = source(i, first, m, s, b);
      in.values.s[i] = g.s[0], in.sDu[i] = g.s[1], in.sDv[i] = g.s[2];
      in.values.blend[i] = g.blend[0], in.blendDu[i] = g.blend[1], in.blendDv[i] = g.blend[2];
      in.sideTurn[i][0] = g.sideTurn[0], in.sideTurn[i][1] = g.sideTurn[1];
      in.blendTurn[i][0] = g.blendTurn[0], in.blendTurn[i][1] = g.blendTurn[1];
      jets[i].P.take(scratch), jets[i].dP.take(scratch), jets[i].T.take(scratch), jets[i].dT.take(scratch);
      if (g2) jets[i].C.take(scratch), jets[i].dC.take(scratch);
    }
    double *result[9];
    for (double *&p : result) p = scratch.take();
    // Made long before the kernel's call, which copies it 16 bytes at a
    // time: made just before, the copy waited on its own 8-byte stores.
    const kernels::DualVec3Span jetsOut{{result[0], result[1], result[2]},
                                        {result[3], result[4], result[5]},
                                        {result[6], result[7], result[8]}};
    double *at = scratch.take();

    // Geometry: each side's ribbon at the plan's side parameters, one batch
    // per side — from the tables at high resolutions, else exactly (the
    // plan's samples run along rows, so consecutive side parameters mostly
    // share a knot span).
    for (int i = 0; i < n; ++i) {
      // As in gregoryPositionsFrom: the side parameters are table parameters
      // as they are, except on sides of several segments (and for the exact
      // ribbons), where a parameter at a break takes its left piece.
      std::span<const double> parameters;
      if (tables && ribbons_[i].pieces().size() == 1) {
        parameters = {in.values.s[i], m};
      } else {
        for (std::size_t k = 0; k < m; ++k) at[k] = ribbons_[i].snap(std::clamp(in.values.s[i][k], 0.0, 1.0));
        parameters = {at, m};
      }
      if (tables) {
        double *values[9] = {jets[i].P.c[0], jets[i].P.c[1], jets[i].P.c[2], jets[i].T.c[0], jets[i].T.c[1],
                             jets[i].T.c[2], jets[i].C.c[0], jets[i].C.c[1], jets[i].C.c[2]};
        double *slopes[9] = {jets[i].dP.c[0], jets[i].dP.c[1], jets[i].dP.c[2], jets[i].dT.c[0], jets[i].dT.c[1],
                             jets[i].dT.c[2], jets[i].dC.c[0], jets[i].dC.c[1], jets[i].dC.c[2]};
        tables->sides[i].evaluate(m, parameters.data(), values, slopes);
      } else if (g2) {
        parabolicJets.resize(m);
        parabolic_[i].at(parameters, parabolicJets);
        for (std::size_t k = 0; k < m; ++k) {
          const ParabolicJet &j = parabolicJets[k];
          jets[i].P.set(k, j.P), jets[i].dP.set(k, j.dP), jets[i].T.set(k, j.T), jets[i].dT.set(k, j.dT);
          jets[i].C.set(k, j.C), jets[i].dC.set(k, j.dC);
        }
      } else {
        linearJets.resize(m);
        ribbons_[i].at(parameters, linearJets);
        for (std::size_t k = 0; k < m; ++k) {
          const RibbonJet &j = linearJets[k];
          jets[i].P.set(k, j.P), jets[i].dP.set(k, j.dP), jets[i].T.set(k, j.T), jets[i].dT.set(k, j.dT);
        }
      }
    }

    // The Gregory formula (eqs. 16–18, 22) with its derivatives in one kernel
    // pass, saturated cross parameters (crossReach_) included.
    in.values.sides = n, in.values.parabolic = g2;
    for (int i = 0; i < int(blendShare_.size()); ++i) in.values.blendShare[i] = blendShare_[i];
    if (g2)
      for (int i = 0; i < n; ++i) in.values.reach[i] = crossReach_[i];
    for (int i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) {
        in.values.P[i][c] = jets[i].P.c[c], in.values.T[i][c] = jets[i].T.c[c];
        in.dP[i][c] = jets[i].dP.c[c], in.dT[i][c] = jets[i].dT.c[c];
        if (g2) in.values.C[i][c] = jets[i].C.c[c], in.dC[i][c] = jets[i].dC.c[c];
      }
    }
    if (g2 && weightJets) {
      for (int i = 0; i < n; ++i) in.weightJets[i] = weightJets[i] + first;
      in.weightJetStride = weightJetStride;
    }
    kernels::gregoryJets(m, in, kernelCorners_.data(), jetsOut, kernels::kBestWidth,
                         g2 ? cornerTerms_.data() : nullptr);
    out(first, m, result);
  }
}

void Patch::gregoryJetsFrom(std::size_t count, const Dual *sides, const Dual *blends, bool useTables,
                            DualVec3 *out) const {
  gregoryJetsFrom(
      count,
      [&](int i, std::size_t first, std::size_t m, double *const s[3], double *const b[3]) {
        for (std::size_t k = 0; k < m; ++k) {
          const Dual x = sides[i * count + first + k], y = blends[i * count + first + k];
          s[0][k] = x.v, s[1][k] = x.du, s[2][k] = x.dv, b[0][k] = y.v, b[1][k] = y.du, b[2][k] = y.dv;
        }
        return SideBlendArrays{{s[0], s[1], s[2]}, {b[0], b[1], b[2]}};
      },
      useTables, out);
}

void Patch::evaluateBatch(std::size_t count, const double *u, const double *v, DualVec3 *out) const {
  const int n = domain_.sides();
  const bool gregory = options_.scheme == Scheme::GregoryG1 || options_.scheme == Scheme::GregoryG2;
  if (!gregory || options_.sweepline == Sweepline::QuinticHermite) {
    for (std::size_t k = 0; k < count; ++k) out[k] = evaluate(u[k], v[k]);
    return;
  }
  const bool g2 = options_.scheme == Scheme::GregoryG2, radial = options_.sweepline == Sweepline::Radial;
  thread_local std::vector<Dual> sides, blends;
  thread_local std::vector<double> x, y, roots, unused;
  sides.resize(static_cast<std::size_t>(n) * count), blends.resize(static_cast<std::size_t>(n) * count);
  x.resize(count), y.resize(count), roots.resize(count), unused.resize(count);
  for (int i = 0; i < n; ++i) {
    const kernels::SweepFrame frame = domain_.sweepFrame(i);
    if (radial) {
      // Closed form on the frame coordinates, the side's frame computed once.
      for (std::size_t k = 0; k < count; ++k) {
        Dual fx, fy;
        domain_.sideFrame(i, Dual::u(u[k]), Dual::vCoord(v[k]), fx, fy);
        sides[i * count + k] = RegularDomain::radialSideParameter(frame, fx, fy);
      }
      continue;
    }
    if (n == 3) {
      // A triangle's sweep is closed-form (RegularDomain::triangleSideParameter).
      for (std::size_t k = 0; k < count; ++k) sides[i * count + k] = domain_.triangleSweep(i, Dual::u(u[k]), Dual::vCoord(v[k]));
      continue;
    }
    // Side i's frame coordinates, then all its cubic Hermite roots in one batched solve.
    for (std::size_t k = 0; k < count; ++k) {
      Dual fx, fy;
      domain_.sideFrame(i, Dual::u(u[k]), Dual::vCoord(v[k]), fx, fy);
      x[k] = fx.v, y[k] = fy.v;
    }
    kernels::hermiteSweepRoots(count, frame, x.data(), y.data(), roots.data(), unused.data());
    for (std::size_t k = 0; k < count; ++k)
      sides[i * count + k] = domain_.hermiteSweepFromRoot(i, Dual::u(u[k]), Dual::vCoord(v[k]), roots[k]).s;
  }
  // At the exact corners, the two sides' exact ends (as exactSweepEndsAtCorners).
  if (!radial)
    for (std::size_t k = 0; k < count; ++k)
      if (const int j = domain_.cornerAt(u[k], v[k]); j >= 0)
        sides[j * count + k].v = 0, sides[domain_.wrap(j - 1) * count + k].v = 1;
  // Corner blends in product form (m = 2 for G¹, 3 for G²), as Patch::evaluate.
  for (std::size_t k = 0; k < count; ++k) {
    const Dual du = Dual::u(u[k]), dv = Dual::vCoord(v[k]);
    std::array<Dual, Patch::kMaxSides> power, product;
    for (int j = 0; j < n; ++j) {
      const Dual distance = domain_.perpendicularDistance(j, du, dv);
      power[j] = g2 ? distance * distance * distance : distance * distance;
    }
    const Dual total = domain_.cornerProducts(power, product);
    for (int i = 0; i < n; ++i) blends[i * count + k] = product[i] / total;
  }
  gregoryJetsFrom(count, sides.data(), blends.data(), false, out);
}

void Patch::evaluateJets(std::size_t count, const double *u, const double *v, DualVec3 *out) const {
  const int n = domain_.sides();
  const bool gregory = options_.scheme == Scheme::GregoryG1 || options_.scheme == Scheme::GregoryG2;
  constexpr std::size_t kChunk = 512;
  if (options_.scheme == Scheme::CompositeRibbon) {
    // Each point's Wachspress distances, linear-sweep parameters and blends
    // with their gradients (compositeRibbon's formulas), then the tables and
    // the CR jet kernel.
    const auto compositeAt = [this](double x, double y, Dual *side, Dual *distance, Dual *blend) {
      compositeParametersAt(x, y, side, distance, blend);
    };
    forCompositeRibbonChunks<Dual>(
        n, count, u, v, compositeAt,
        [&](std::size_t first, std::size_t m, const Dual *const *side, const Dual *const *distance,
            const Dual *const *blend) { compositeRibbonJets(m, side, distance, blend, out + first); });
    return;
  }
  if (!gregory) {
    for (std::size_t k = 0; k < count; ++k) out[k] = evaluate(u[k], v[k]);
    return;
  }
  const bool g2 = options_.scheme == Scheme::GregoryG2;
  const bool radial = options_.sweepline == Sweepline::Radial;
  const bool quintic = options_.sweepline == Sweepline::QuinticHermite;
  // Triangles and the quintic sweep take their sweep parameters as
  // evaluate() does (the grid solver: a triangle's sweeplines cross near the
  // opposite corner, where the batched solver's choice of root may part from
  // it); the rest of their formula runs batched all the same.
  const bool pointwiseSweeps = !radial && (quintic || n == 3);
  const kernels::DomainSides sides = kernelSides(domain_);
  thread_local JetColumns columns;
  for (std::size_t first = 0; first < count; first += kChunk) {
    const std::size_t m = std::min(kChunk, count - first);
    columns.reset(n, m);
    for (std::size_t k = 0; k < m; ++k) {
      columns.x()[k] = u[first + k], columns.y()[k] = v[first + k];
      snapToCorner(columns.x()[k], columns.y()[k]);
    }
    if (pointwiseSweeps) {
      std::array<Dual, Patch::kMaxSides> s;
      for (std::size_t k = 0; k < m; ++k) {
        domain_.hermiteSweepSides(Dual::u(columns.x()[k]), Dual::vCoord(columns.y()[k]), quintic, s);
        for (int i = 0; i < n; ++i)
          columns.side(i, 0)[k] = s[i].v, columns.side(i, 1)[k] = s[i].du, columns.side(i, 2)[k] = s[i].dv;
      }
    }
    std::array<double *, Patch::kMaxSides> fx, fy, blend[3];
    for (int i = 0; i < n; ++i) {
      fx[i] = columns.fx(i), fy[i] = columns.fy(i);
      for (int c = 0; c < 3; ++c) blend[c][i] = columns.blend(i, c);
    }
    kernels::sideFrames(m, sides, columns.x(), columns.y(), fx.data(), fy.data());
    if (!pointwiseSweeps) {
      for (int i = 0; i < n; ++i) {
        if (radial) radialSweepJets(domain_, i, columns);
        else cubicHermiteSweepJets(domain_, i, columns);
      }
      if (!radial) {
        std::array<double *, Patch::kMaxSides> values;
        for (int i = 0; i < n; ++i) values[i] = columns.side(i, 0);
        exactSweepEndsAtCorners(domain_, m, columns.x(), columns.y(), values.data());
      }
    }
    // Corner blends B_{i,i−1} = ∏_{j∉{i,i−1}} Δ_j^m / Σ_k ∏_{j∉{k,k−1}} Δ_j^m with their gradients.
    kernels::cornerBlends(m, sides, g2 ? 3 : 2, fy.data(), blend[0].data(), blend[1].data(), blend[2].data());
    gregoryJetsFrom(
        m,
        [&](int i, std::size_t block, std::size_t, double *const *, double *const *) {
          // The columns themselves: no copy.
          SideBlendArrays arrays;
          for (int c = 0; c < 3; ++c) arrays.s[c] = columns.side(i, c) + block, arrays.blend[c] = columns.blend(i, c) + block;
          return arrays;
        },
        true, out + first);
    // A corner itself, where the correction's weights have partials without
    // a limit: the pointwise formula, which takes the corner's own.
    forEachCornerSample(domain_, m, columns.x(), columns.y(), [&](std::size_t k, int) {
      out[first + k] = evaluate(columns.x()[k], columns.y()[k]);
    });
  }
}

} // namespace v1
} // namespace curvenet
