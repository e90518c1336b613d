// The Gregory formula's positions of curvenet/kernels/kernels.hpp
// (gregoryPositions, gregoryPositionsInterleaved), the G² corners'
// rational weights (gregoryCornerWeights, gregoryCornerTerms) and the
// saturated cross parameter (saturatedCross). Written once
// over a Highway descriptor D (CappedTag<double, 1> the width-1 scalar
// reference); compiled once per target (foreach_target), dispatched at run
// time. The derivatives: gregory_jets.cpp.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "gregory.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

#include "gregory-inl.h"
#include "loops-inl.h"

#include <array>
#include <cstddef>
#include <cstdint>

#include "curvenet/kernels/kernels.hpp"
#include "dispatch.hpp"

// Argument bundles, shared by every target's instance (defined once).
#ifndef CURVENET_GREGORY_ARGS
#define CURVENET_GREGORY_ARGS
namespace curvenet::kernels_impl {
namespace ck = curvenet::kernels;
struct GregoryArgs {
  const ck::GregorySamples *in;
  const ck::GregoryCorner *corners;
  double *const *out;
  const ck::GregoryCornerTerms *terms; ///< per corner, G² only
  double *interleaved;                 ///< when set: points here (plus offset) instead of out
  double offset[3];
};

struct CornerWeightArgs {
  const double *s, *sPrevious;
  double *weights;
  std::size_t stride;
};

struct SaturatedCrossArgs {
  const double *x;
  double reach;
  double *value, *slope;
};
} // namespace curvenet::kernels_impl
#endif

HWY_BEFORE_NAMESPACE();
namespace curvenet {
namespace kernels_impl {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace ck = curvenet::kernels;

/// Saturated: a G² patch with a ribbon whose reach is below 1; Shared: a
/// patch with a corner of non-zero blend share. Each its own instance, so
/// that the others run the code they ran before reaches and shares (the
/// shares' bookkeeping cost the face interiors ~8 % on AVX-512 where every
/// share is 0).
template <bool Parabolic, bool Saturated, bool Shared, class D>
HWY_INLINE void gregoryBody(D d, std::size_t k, const GregoryArgs &a) {
  using V = hn::Vec<D>;
  const ck::GregorySamples &in = *a.in;
  const int n = in.sides;
  const V one = hn::Set(d, 1.0), half = hn::Set(d, 0.5);
  V side[ck::GregorySamples::kMaxSides], blend[ck::GregorySamples::kMaxSides];
  for (int i = 0; i < n; ++i) side[i] = hn::LoadU(d, in.s[i] + k), blend[i] = hn::LoadU(d, in.blend[i] + k);
  // Corner i's weights of its two ribbons: B_i for both in eq. 17; with a
  // blend share μ, B_i (1 − μ (1 − λ)) for R_{i−1} and B_i (1 − μ λ) for R_i.
  V previousWeight[Shared ? ck::GregorySamples::kMaxSides : 1], ownWeight[Shared ? ck::GregorySamples::kMaxSides : 1];
  if constexpr (Shared)
    for (int i = 0; i < n; ++i) {
      const double mu = in.blendShare[i];
      if (mu == 0) {
        previousWeight[i] = ownWeight[i] = blend[i];
        continue;
      }
      const V lambda = sideBlendWeight<Parabolic ? 3 : 2>(d, side[i], hn::Sub(one, side[i == 0 ? n - 1 : i - 1]));
      const V muLambda = hn::Mul(hn::Set(d, mu), lambda);
      ownWeight[i] = hn::NegMulAdd(blend[i], muLambda, blend[i]);
      previousWeight[i] = hn::Mul(blend[i], hn::Add(hn::Set(d, 1.0 - mu), muLambda));
    }
  auto own = [&](int i) { if constexpr (Shared) return ownWeight[i]; else return blend[i]; };
  auto previous = [&](int i) { if constexpr (Shared) return previousWeight[i]; else return blend[i]; };
  // Corner i's cross parameters: s_i for R_{i−1}, t_i = 1 − s_{i−1} for R_i,
  // each saturated at its ribbon's reach (GregorySamples::reach).
  static_assert(Parabolic || !Saturated, "reaches are G² only");
  V sCross[Saturated ? ck::GregorySamples::kMaxSides : 1], tCross[Saturated ? ck::GregorySamples::kMaxSides : 1];
  if constexpr (Saturated)
    for (int i = 0; i < n; ++i) {
      const int prev = i == 0 ? n - 1 : i - 1;
      sCross[i] = side[i], tCross[i] = hn::Sub(one, side[prev]);
      if (in.reach[prev] < 1) sCross[i] = saturatedCross(d, sCross[i], in.reach[prev]);
      if (in.reach[i] < 1) tCross[i] = saturatedCross(d, tCross[i], in.reach[i]);
    }
  auto crossS = [&](int i) { if constexpr (Saturated) return sCross[i]; else return side[i]; };
  auto crossT = [&](int i) {
    if constexpr (Saturated) return tCross[i]; else return hn::Sub(one, side[i == 0 ? n - 1 : i - 1]);
  };
  V acc[3] = {hn::Zero(d), hn::Zero(d), hn::Zero(d)};
  // The ribbon terms gathered per ribbon: R_i enters corner i at δ = t_i =
  // 1 − s_{i−1} with weight B_i and corner i + 1 at δ = s_{i+1} with weight
  // B_{i+1}, so its share is (B_i + B_{i+1}) P_i + (B_i t_i + B_{i+1} s_{i+1}) T_i
  // [+ ½ (B_i t_i² + B_{i+1} s_{i+1}²) C_i]: each ribbon value is read once.
  // (The weights there are ownWeight[i] and previousWeight[i + 1]; t_i and
  // s_{i+1} the saturated ones.)
  for (int i = 0; i < n; ++i) {
    const int next = i + 1 == n ? 0 : i + 1;
    const V t = crossT(i), sNext = crossS(next);
    const V atCorner = hn::Mul(own(i), t), atNext = hn::Mul(previous(next), sNext);
    const V wP = hn::Add(own(i), previous(next)), wT = hn::Add(atCorner, atNext);
    V wC = hn::Zero(d);
    if constexpr (Parabolic) wC = hn::Mul(half, hn::MulAdd(atCorner, t, hn::Mul(atNext, sNext)));
    for (int c = 0; c < 3; ++c) {
      acc[c] = hn::MulAdd(wP, hn::LoadU(d, in.P[i][c] + k), acc[c]);
      acc[c] = hn::MulAdd(wT, hn::LoadU(d, in.T[i][c] + k), acc[c]);
      if constexpr (Parabolic) acc[c] = hn::MulAdd(wC, hn::LoadU(d, in.C[i][c] + k), acc[c]);
    }
  }
  // − Σ B_i (1 − μ_i) Q_i(s_i, t_i).
  for (int i = 0; i < n; ++i) {
    if (Shared && in.blendShare[i] == 1) continue;
    const int prev = i == 0 ? n - 1 : i - 1;
    const V s = crossS(i), t = crossT(i);
    const double(*vec)[3] = a.corners[i].v;
    V q[3];
    if constexpr (Parabolic) {
      // Q in the form of GregoryCornerTerms (a00 is in taylor[0][0]): the
      // polynomial in Horner form, then the rational terms. Weights given
      // are of the sweep's own (s, t): not those of a saturated corner.
      V w[8];
      if (in.weights[i] && (!Saturated || (in.reach[prev] >= 1 && in.reach[i] >= 1))) {
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
    V correctionWeight = blend[i];
    if constexpr (Shared) correctionWeight = hn::Mul(blend[i], hn::Set(d, 1.0 - in.blendShare[i]));
    for (int c = 0; c < 3; ++c) acc[c] = hn::NegMulAdd(correctionWeight, q[c], acc[c]);
  }
  if (a.interleaved) {
    hn::StoreInterleaved3(hn::Add(acc[0], hn::Set(d, a.offset[0])), hn::Add(acc[1], hn::Set(d, a.offset[1])),
                          hn::Add(acc[2], hn::Set(d, a.offset[2])), d, a.interleaved + 3 * k);
    return;
  }
  for (int c = 0; c < 3; ++c) hn::StoreU(acc[c], d, a.out[c] + k);
}

void GregoryPositions(std::size_t count, const GregoryArgs &args, bool reference) {
  const ck::GregorySamples &in = *args.in;
  bool saturated = false, shared = false;
  for (int i = 0; i < in.sides; ++i) saturated = saturated || in.reach[i] < 1, shared = shared || in.blendShare[i] != 0;
  auto run = [&]<bool Parabolic, bool Saturated>() {
    if (shared) forEachVectorOrReference(reference, count,
        [&](auto d, std::size_t k) { gregoryBody<Parabolic, Saturated, true>(d, k, args); });
    else forEachVectorOrReference(reference, count,
        [&](auto d, std::size_t k) { gregoryBody<Parabolic, Saturated, false>(d, k, args); });
  };
  if (in.parabolic && saturated) run.template operator()<true, true>();
  else if (in.parabolic) run.template operator()<true, false>();
  else run.template operator()<false, false>();
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

void SaturatedCross(std::size_t count, const SaturatedCrossArgs &a, bool reference) {
  forEachVectorOrReference(reference, count, [&](auto d, std::size_t k) {
    hn::Vec<decltype(d)> slope;
    hn::StoreU(saturatedCross(d, hn::LoadU(d, a.x + k), a.reach, &slope), d, a.value + k);
    hn::StoreU(slope, d, a.slope + k);
  });
}

} // namespace HWY_NAMESPACE
} // namespace kernels_impl
} // namespace curvenet
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace curvenet {
namespace kernels_impl {
HWY_EXPORT(GregoryPositions);
HWY_EXPORT(GregoryCornerWeights);
HWY_EXPORT(SaturatedCross);
} // namespace kernels_impl

inline namespace v1 {
namespace kernels {
using namespace curvenet::kernels_impl;

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

void saturatedCross(std::size_t count, const double *x, double reach, double *value, double *slope,
                    std::int64_t width) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  HWY_DISPATCH_TABLE(SaturatedCross)[index](count, {x, reach, value, slope}, reference);
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

} // namespace kernels
} // namespace v1
} // namespace curvenet
#endif
