// G² surfaces ([SV14]): vertex curvature fit on the built-ins, parabolic
// ribbons, the gregory-g2 scheme's continuity and accuracy against the
// reference surfaces, and the curvature-jump figure itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <random>

#include "curvenet/builtins.hpp"
#include "curvenet/sketch.hpp"
#include "curvenet/curvature_jump.hpp"
#include "curvenet/error.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"
#include "patches/patch.hpp"
#include "ribbons/ribbons.hpp"

using namespace curvenet;

namespace {

std::vector<std::string> builtinNames() {
  std::vector<std::string> names;
  for (const BuiltinInfo &info : builtinNetworks()) names.push_back(info.name);
  return names;
}

const Network &builtin(const std::string &name) {
  static std::map<std::string, Network> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, Network::build(builtinNetwork(name), "builtin:" + name)).first;
  return it->second;
}

SurfaceOptions g2Options(EdgeCurvature source, Sweepline sweepline = Sweepline::Hermite) {
  SurfaceOptions o;
  o.scheme = Scheme::GregoryG2;
  o.sweepline = sweepline;
  o.edgeCurvature = source;
  return o;
}

struct EdgeFigures {
  double positionGap = 0; ///< relative to the diagonal
  double normalAngleDeg = 0;
  double boundaryGap = 0; ///< patch vs curve, relative to the diagonal
};

/// Position gap and normal angle between the two faces of every shared
/// segment, and boundary reproduction on every face side, at the same curve
/// parameters from both sides (ends included).
EdgeFigures edgeFigures(const Surface &surface, int samples = 9) {
  const Network &net = surface.network();
  EdgeFigures fig;
  for (size_t e = 0; e < net.segments().size(); ++e) {
    const Segment &seg = net.segments()[e];
    for (int j = 0; j <= samples; ++j) {
      const double u = 0.01 + 0.98 * double(j) / samples;
      const Vec3 onCurve = seg.curve.point(u);
      SurfacePoint p[2];
      for (int side = 0; side < (seg.isBoundary() ? 1 : 2); ++side) {
        p[side] = surface.evaluate(seg.faces[side], surface.domainPointOnSegment(seg.faces[side], int(e), u));
        fig.boundaryGap = std::max(fig.boundaryGap, norm(p[side].point - onCurve) / net.diagonal());
      }
      if (seg.isBoundary()) continue;
      fig.positionGap = std::max(fig.positionGap, norm(p[0].point - p[1].point) / net.diagonal());
      fig.normalAngleDeg =
          std::max(fig.normalAngleDeg, angleBetween(p[0].normal, p[1].normal) * 180 / std::numbers::pi);
    }
  }
  return fig;
}

/// Max |signed distance| to the reference of a coarse tessellation, relative to the diagonal.
double referenceDeviation(const Surface &surface) {
  const Network &net = surface.network();
  const Mesh mesh = tessellate(surface, {8, 0});
  double worst = 0;
  for (const Vec3 &p : mesh.positions) worst = std::max(worst, std::abs(net.reference()->signedDistance(p)));
  return worst / net.diagonal();
}

} // namespace

// Issue item 1: on the built-ins the fit recovers the analytic κ1, κ2, λ
// wherever three or more independent curves determine them; with two it
// reproduces both curves' normal curvatures (the paper's underdetermined case).
TEST(VertexCurvature, FitRecoversTheAnalyticTensorOnTheBuiltins) {
  for (const std::string &name : builtinNames()) {
    // Only the built-ins fitted to their analytic surface (to 5e-12, with
    // vertex facts); the cubic Bézier networks approximate theirs to ~1e-3.
    // setback-vertex-blend has no reference surface (only its fillets are
    // analytic; tests/apps_test.cpp checks its slave against them).
    if (builtinVertexFacts(name).empty() || !builtin(name).reference()) continue;
    SCOPED_TRACE(name);
    const Network &net = builtin(name);
    SurfaceOptions curvesOnly;
    curvesOnly.fenceNormals = FenceNormals::Curves; // vertex normals from the curves alone
    const Surface surface = Surface::build(net, curvesOnly);
    int checked = 0;
    for (size_t v = 0; v < net.vertices().size(); ++v) {
      const VertexCurvatureInfo info = surface.vertexCurvature(int(v));
      const Vec3 normal = surface.vertexNormal(int(v));
      if (info.independentDirections >= 3) {
        const SurfaceFrame ref = net.reference()->closest(net.vertices()[v].position);
        const double sign = dot(ref.normal, normal) < 0 ? -1 : 1;
        const double k1 = sign > 0 ? ref.k1 : -ref.k2, k2 = sign > 0 ? ref.k2 : -ref.k1;
        const double scale = std::max(std::abs(k1), std::abs(k2));
        EXPECT_NEAR(info.tensor.k1, k1, 1e-5 * scale) << "vertex " << v;
        EXPECT_NEAR(info.tensor.k2, k2, 1e-5 * scale) << "vertex " << v;
        if (k1 - k2 > 1e-2 * scale) {
          // Principal direction of the larger curvature (a line: compare mod π).
          const Vec3 y = cross(normal, info.xAxis);
          const Vec3 e1 = info.xAxis * std::cos(info.tensor.lambda) + y * std::sin(info.tensor.lambda);
          const Vec3 refE1 = sign > 0 ? ref.direction1 : cross(ref.normal, ref.direction1);
          EXPECT_LE(norm(cross(e1, refE1)), 1e-5 * scale / (k1 - k2)) << "vertex " << v;
        }
        ++checked;
      } else {
        EXPECT_LE(info.maxResidual, 1e-9 * std::max(1.0, std::abs(info.tensor.k1) + std::abs(info.tensor.k2)))
            << "vertex " << v;
      }
    }
    if (name != "pentagon") {
      EXPECT_GT(checked, 0);
    }
  }
}

// docs/design.md §3 check: the curve d ↦ P + dT + ½d²C has normal curvature κ_T,
// the normal curvature of the intended surface in the direction of T. With
// the reference fence and κ_D the intended surface is the reference itself.
TEST(ParabolicRibbon, CrossCurvatureIsTheSurfaceCurvatureAlongT) {
  const Network &net = builtin("ellipsoid-truncated-icosahedron");
  const ReferenceSurface &ref = *net.reference();
  for (int e : {0, 7, 31}) {
    const Segment &seg = net.segments()[e];
    const Vec3 side = ref.closest(seg.curve.point(0)).normal;
    auto oriented = [&](const Vec3 &p) {
      const Vec3 n = ref.closest(p).normal;
      return dot(n, side) < 0 ? -n : n;
    };
    const NormalFence fence =
        NormalFence::fromNormalField(seg.curve, oriented, oriented(seg.curve.point(0)), oriented(seg.curve.point(1)));
    std::vector<double> samples;
    for (int j = 0; j <= 32; ++j) {
      const double u = j / 32.0;
      const auto c = seg.curve.derivatives(u);
      samples.push_back(ref.closest(c[0]).normalCurvature(cross(fence.normal(u), c[1])));
    }
    const TransversalCurvature kappa(samples);
    LinearRibbon linear(seg.curve, {{&fence, 0.0, 1.0, false, e}});
    // A cross-derivative that turns from D towards P' and back: α, β vary.
    const Vec3 d0 = linear.fenceDirection(0), d1 = linear.fenceDirection(1);
    linear.setEndConditions(d0 + seg.curve.derivatives(0)[1] * 0.4, d1 * 0.7 - seg.curve.derivatives(1)[1] * 0.3);
    const ParabolicRibbon ribbon(linear, {&kappa});
    for (double s : {0.0, 0.13, 0.5, 0.77, 1.0}) {
      const ParabolicJet j = ribbon.at(s);
      const SurfaceFrame frame = ref.closest(j.P);
      const double expected = frame.normalCurvature(j.T);
      EXPECT_NEAR(ribbon.crossCurvature(s), expected, 1e-4 * std::abs(expected)) << "segment " << e << " s " << s;
      // C is along the fence normal, and C' is its exact derivative.
      const double h = 1e-6;
      const Vec3 numeric = (ribbon.at(s + h).C - ribbon.at(s - h).C) / (2 * h);
      if (s > 0 && s < 1) {
        EXPECT_LE(norm(numeric - j.dC), 1e-6 * norm(j.C) + 1e-7) << "s " << s;
      }
    }
  }
}

TEST(SecondDerivatives, DifferencedHessianIsStableUnderStepHalving) {
  const Network &net = builtin("torus-mixed");
  const Surface surface = Surface::build(net, g2Options(EdgeCurvature::Direct));
  for (int f : {0, 5, 11}) {
    for (const Vec2 &uv : {Vec2{0.1, 0.05}, surface.domainPointOnFaceSide(f, 0, 0.37)}) {
      const SurfacePoint2 a = surface.evaluateSecondOrder(f, uv, 1e-3), b = surface.evaluateSecondOrder(f, uv, 5e-4);
      const double scale = norm(a.duu) + norm(a.dvv) + norm(a.duv);
      EXPECT_LE(norm(a.duu - b.duu) + norm(a.duv - b.duv) + norm(a.dvv - b.dvv), 1e-6 * scale);
    }
  }
}

// A point on a domain side near a corner, computed from either end of the
// side (the two differ by an ulp, and so do their sweeps across the side),
// gets the same second derivatives: those of the side itself. There the
// correction patch's rational terms turn over within the cube of the
// distance to the corner, so an ulp of the cross parameter moved the
// Hessian by up to 4.7e-10 of its size on the uneven loop's parts (now
// 2.5e-12: the rounding of the correction patch, which cancels with the
// ribbons' to 1/170 of their size there).
TEST(SecondDerivatives, PointsOnASideGetTheSideLimitFromEitherEnd) {
  const Network &net = builtin("uneven-loop");
  const Surface surface = Surface::build(net, g2Options(EdgeCurvature::Averaging));
  double worst = 0;
  for (int f = 0; f < static_cast<int>(net.faces().size()); ++f) {
    const int n = surface.domainSides(f);
    for (int k = 0; k < n; ++k) {
      const Vec2 from = surface.domainCorner(f, k), to = surface.domainCorner(f, (k + 1) % n);
      for (double x : {0.005, 0.01, 0.02, 0.98, 0.99, 0.995}) {
        const SurfacePoint2 a = surface.evaluateSecondOrder(f, from + (to - from) * x);
        const SurfacePoint2 b = surface.evaluateSecondOrder(f, to + (from - to) * (1 - x));
        const double scale = norm(a.duu) + norm(a.dvv) + norm(a.duv);
        worst = std::max(worst, (norm(a.duu - b.duu) + norm(a.duv - b.duv) + norm(a.dvv - b.dvv)) / scale);
      }
    }
  }
  EXPECT_LE(worst, 1e-11);
}

class G2Builtin : public ::testing::TestWithParam<std::string> {};

// Done-when of the issue: with each of averaging, direct and reference, G² at
// every shared edge; boundaries reproduced; tangent planes shared.
TEST_P(G2Builtin, ContinuityWithEverySource) {
  const Network &net = builtin(GetParam());
  for (EdgeCurvature source : {EdgeCurvature::Averaging, EdgeCurvature::Direct, EdgeCurvature::Reference}) {
    // The reference source needs a reference surface, which
    // setback-vertex-blend does not carry (its blend is not analytic).
    if (source == EdgeCurvature::Reference && !net.reference()) continue;
    SCOPED_TRACE(edgeCurvatureName(source));
    const Surface surface = Surface::build(net, g2Options(source));
    const EdgeFigures fig = edgeFigures(surface);
    EXPECT_LE(fig.positionGap, 1e-12);
    EXPECT_LE(fig.boundaryGap, 1e-12);
    EXPECT_LE(fig.normalAngleDeg, 1e-6);
    const CurvatureJumpReport jump = measureCurvatureJump(surface);
    EXPECT_LE(jump.maxJump, 1e-4) << "worst segment " << jump.worstSegment << " u " << jump.worstU;
    std::printf("%-32s %-12s gap %.2e angle %.2e deg jump %.2e (mean %.2e)\n", GetParam().c_str(),
                edgeCurvatureName(source).c_str(), fig.positionGap, fig.normalAngleDeg, jump.maxJump, jump.meanJump);
  }
}

INSTANTIATE_TEST_SUITE_P(All, G2Builtin, ::testing::ValuesIn(builtinNames()),
                         [](const auto &param) {
                           std::string s = param.param;
                           std::replace(s.begin(), s.end(), '-', '_');
                           return s;
                         });

// Done-when of the issue: G¹ patches jump in curvature at least 10x more
// than G² ones. With reference curvature G² deviates less from the reference
// than G¹ on every built-in, and at most half as much on the two named ones
// ([SV14] Fig. 10: 2–4x). Measured: ellipsoid 0.55% vs 1.60%, torus 0.82%
// vs 2.54% of the diagonal. With linear α, β in the parabolic ribbons the
// twist mismatch at the corners left G² at 1.07% / 1.74% (ratio ≈ 0.67).
// The G¹ figure comes from differenced derivatives: halving the step must
// change it by less than 10%.
TEST(G2VersusG1, CurvatureJumpAndReferenceDeviation) {
  for (const std::string &name : builtinNames()) {
    SCOPED_TRACE(name);
    const Network &net = builtin(name);
    const Surface g1 = Surface::build(net, {});
    if (!net.reference()) {
      // setback-external-masters is one face: no shared edge to jump across
      // (tests/master_surface_test.cpp measures it against its masters).
      if (measureCurvatureJump(g1).samples.empty()) continue;
      // setback-vertex-blend: no reference to deviate from; every shared
      // edge is a master edge, where the G² blend takes the master's curvature.
      const double jump1 = measureCurvatureJump(g1).maxJump;
      const double jump2 = measureCurvatureJump(Surface::build(net, g2Options(EdgeCurvature::Direct))).maxJump;
      std::printf("%-32s G1 jump %.3e | G2 jump %.3e (no reference)\n", name.c_str(), jump1, jump2);
      EXPECT_LE(jump2, 1e-4);
      EXPECT_GE(jump1, 10 * std::max(jump2, 1e-6));
      continue;
    }
    const Surface g2 = Surface::build(net, g2Options(EdgeCurvature::Reference));
    const double jump1 = measureCurvatureJump(g1).maxJump, jump2 = measureCurvatureJump(g2).maxJump;
    const double dev1 = referenceDeviation(g1), dev2 = referenceDeviation(g2);
    std::printf("%-32s G1 jump %.3e dev %.3e | G2 jump %.3e dev %.3e (direct dev %.3e)\n", name.c_str(), jump1, dev1,
                jump2, dev2, referenceDeviation(Surface::build(net, g2Options(EdgeCurvature::Direct))));
    EXPECT_LE(jump2, 1e-4);
    // The cubic Bézier networks (no vertex facts) lie on their reference
    // surface only to ~1e-3: their curves' own normal curvatures disagree
    // with the reference, and G² reproduces the curves, so the deviation
    // comparison is meaningful only for the networks fitted to 5e-12.
    if (builtinVertexFacts(name).empty()) continue;
    if (name == "ellipsoid-truncated-icosahedron" || name == "torus-mixed") {
      EXPECT_GE(jump1, 10 * std::max(jump2, 1e-6));
      EXPECT_LE(dev2, 0.5 * dev1);
      CurvatureJumpOptions halved;
      halved.step = 0.5 * CurvatureJumpOptions{}.step;
      EXPECT_NEAR(measureCurvatureJump(g1, halved).maxJump, jump1, 0.1 * jump1);
    }
    // saddle-nodes: four gregory-g2 patches fold (README Status), and since
    // the G¹ cross-derivatives stopped following the curves' speed (unit-frame
    // α, β) G¹ deviates less there (0.94 % against 1.14 %).
    if (name != "saddle-nodes") {
      EXPECT_LT(dev2, dev1);
    }
  }
}

TEST(G2Options, QuinticSweepAndBadOptions) {
  const Network &net = builtin("torus-mixed");
  const Surface quintic = Surface::build(net, g2Options(EdgeCurvature::Direct, Sweepline::QuinticHermite));
  EXPECT_LE(measureCurvatureJump(quintic).maxJump, 1e-4);
  EXPECT_LE(edgeFigures(quintic).normalAngleDeg, 1e-6);
  EXPECT_THROW(Surface::build(net, g2Options(EdgeCurvature::Direct, Sweepline::Radial)), InputError);
  NetworkDescription bare = builtinNetwork("pentagon");
  bare.reference.reset();
  const Network plain = Network::build(bare);
  EXPECT_THROW(Surface::build(plain, g2Options(EdgeCurvature::Reference)), InputError);
  SurfaceOptions fromReference;
  fromReference.fenceNormals = FenceNormals::Reference;
  EXPECT_THROW(Surface::build(plain, fromReference), InputError);
  EXPECT_NO_THROW(Surface::build(plain, g2Options(EdgeCurvature::Direct)));
  EXPECT_EQ(schemeFromName("gregory-g2"), Scheme::GregoryG2);
  EXPECT_EQ(edgeCurvatureFromName("averaging"), EdgeCurvature::Averaging);
}

// Ribbons hand their curve's derivatives to the fence instead of letting it
// evaluate its own copy of the segment: through the chain rule (a reversed
// side, a side that is half the segment) the normals equal the fence's own to
// rounding, and the batch calls equal the single calls bit for bit.
TEST(Ribbons, SuppliedCurveJetAndBatchesAgreeWithTheFence) {
  const Network &net = builtin("ellipsoid-truncated-icosahedron");
  const Segment &seg = net.segments()[5];
  const Vec3 n0 = cross(seg.curve.derivatives(0)[1], seg.curve.derivatives(0)[2]);
  const Vec3 n1 = cross(seg.curve.derivatives(1)[1], seg.curve.derivatives(1)[2]);
  const NormalFence fence = NormalFence::curvatureCompatible(seg.curve, normalized(n0), normalized(n1), 0.3, -0.2);
  std::vector<double> samples(9, 0.5);
  const TransversalCurvature kappa(samples);
  struct Case {
    BSplineCurve curve;
    LinearRibbon::Piece piece;
    double uAt0, dudS; // segment parameter u = uAt0 + dudS s
  };
  const std::vector<Case> cases = {
      {seg.curve, {&fence, 0.0, 1.0, false, 5}, 0.0, 1.0},
      {seg.curve.reversed(), {&fence, 0.0, 1.0, true, 5}, 1.0, -1.0},
      // A side running over the segment's second half only, on [0, 1].
      {seg.curve.restricted(0.5, 1.0).reparameterized(0, 1), {&fence, -1.0, 1.0, false, 5}, 0.5, 0.5},
  };
  for (const Case &c : cases) {
    LinearRibbon linear(c.curve, {c.piece});
    linear.setEndConditions(linear.fenceDirection(0), linear.fenceDirection(1));
    const ParabolicRibbon parabolic(linear, {&kappa});
    std::vector<double> s;
    for (int k = 0; k <= 40; ++k) s.push_back(k / 40.0);
    std::vector<RibbonJet> batch(s.size());
    std::vector<ParabolicJet> parabolicBatch(s.size());
    linear.at(s, batch);
    parabolic.at(s, parabolicBatch);
    for (size_t k = 0; k < s.size(); ++k) {
      const RibbonJet single = linear.at(s[k]);
      EXPECT_TRUE(single.P == batch[k].P && single.dP == batch[k].dP && single.T == batch[k].T &&
                  single.dT == batch[k].dT);
      const ParabolicJet p = parabolic.at(s[k]);
      EXPECT_TRUE(p.C == parabolicBatch[k].C && p.dC == parabolicBatch[k].dC && p.T == parabolicBatch[k].T);
      // The fence on its own copy of the segment, converted to d/ds.
      const double u = c.uAt0 + c.dudS * s[k];
      Vec3 n, dn;
      fence.normalAndDerivative(u, n, dn);
      const LinearRibbon::SecondJet j = linear.secondJet(s[k]);
      EXPECT_LE(norm(j.N - n), 1e-12) << "s " << s[k];
      EXPECT_LE(norm(j.dN - dn * c.dudS), 1e-10 * (1 + norm(dn))) << "s " << s[k];
    }
  }
}

namespace {

/// 2000 corner parameter pairs for the correction-patch tests: inside the
/// corner's quadrant, on its two sides, near the corner and at it. Calls
/// check(randomVector, s, t) with Dual s, t carrying random partials.
template <class Check> void forCorrectionSamples(unsigned seed, const Check &check) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1), coordinate(-2, 2);
  auto randomVector = [&] { return Vec3{coordinate(rng), coordinate(rng), coordinate(rng)}; };
  const std::pair<double, double> fixed[] = {{0, 0.3}, {0.4, 0}, {1e-5, 2e-5}, {1e-3, 1e-4}, {0, 0}, {1, 1}};
  for (int trial = 0; trial < 2000; ++trial) {
    const auto [sv, tv] = trial < 6 ? fixed[trial] : std::pair{unit(rng), unit(rng)};
    const Dual s{sv, coordinate(rng), coordinate(rng)}, t{tv, coordinate(rng), coordinate(rng)};
    check(randomVector, s, t);
  }
}

void expectSameJet(const DualVec3 &fast, const DualVec3 &reference, Dual s, Dual t) {
  const Vec3 parts[3][2] = {{fast.v, reference.v}, {fast.du, reference.du}, {fast.dv, reference.dv}};
  for (const auto &[x, y] : parts)
    EXPECT_LE(norm(x - y), 1e-12 * std::max({1.0, norm(x), norm(y)})) << "s = " << s.v << ", t = " << t.v;
}

} // namespace

TEST(CorrectionPatch, RearrangedFormAgreesWithTheReference) {
  // The evaluation form (Taylor part by Horner, closed-form partials of the
  // rational terms, one division) against the reference (each W_pq as a
  // weighted pair in Dual arithmetic).
  forCorrectionSamples(7, [](auto &randomVector, Dual s, Dual t) {
    CornerData2 c{};
    kernels::GregoryCorner corner{};
    int slot = 0;
    auto store = [&](const Vec3 &v) {
      corner.v[slot][0] = v.x, corner.v[slot][1] = v.y, corner.v[slot][2] = v.z, ++slot;
    };
    c.a[0][0] = randomVector();
    store(c.a[0][0]);
    for (int p = 0; p <= 2; ++p)
      for (int r = 0; r <= 2; ++r)
        if (p || r) c.a[p][r] = randomVector(), c.b[p][r] = randomVector(), store(c.a[p][r]), store(c.b[p][r]);
    expectSameJet(gregoryCorrection2(kernels::gregoryCornerTerms(corner), c, s, t), gregoryCorrection2(c, s, t), s, t);
  });
}

TEST(CorrectionPatch, G1ClosedFormAgreesWithTheGeneralForm) {
  forCorrectionSamples(11, [](auto &randomVector, Dual s, Dual t) {
    const CornerData c{randomVector(), randomVector(), randomVector(), randomVector(),
                       randomVector(), randomVector(), randomVector()};
    expectSameJet(gregoryCorrection(c, s, t), gregoryCorrection(c, s, t, s, t), s, t);
  });
}

// The default (direct) transversal curvature blends the end vertices'
// normal curvatures across the edge and moves them by a third of the
// curve's own disagreement with the blended tensor only while that
// disagreement is of the size of the ends' transversal curvature: κ_D then
// stays within the range of its end values widened by their largest
// magnitude (or 1 / diagonal). On saddle-nodes the shift is taken (the curves' curvature
// departs from the blend by up to 0.6 of κ_D, the surface's own variation:
// without it the network deviates 1.64 % instead of 1.44 %); on a sketch
// whose curves have curvature spikes near nodes it is not (bathtub.obj's
// rim: −13.6 between ends of 0.85 and −1.49 when it was, 18 folded faces).
double directShiftBeyondEnds(const Surface &surface, double &largestShift) {
  double worst = -INFINITY;
  largestShift = 0;
  for (int e = 0; e < static_cast<int>(surface.network().segments().size()); ++e) {
    // Connection curves and master edges take their curvature from G¹
    // patches or master surfaces, whatever the source.
    const Segment &seg = surface.network().segments()[e];
    if (seg.connection || seg.masterFace >= 0 || seg.masterSurface >= 0) continue;
    const double a = surface.transversalCurvature(e, 0.0), b = surface.transversalCurvature(e, 1.0);
    const double widen = std::max({std::abs(a), std::abs(b), 1 / surface.network().diagonal()});
    for (int k = 1; k < 64; ++k) {
      const double x = k / 64.0, kappa = surface.transversalCurvature(e, x);
      worst = std::max({worst, std::min(a, b) - widen - kappa, kappa - std::max(a, b) - widen});
      largestShift = std::max(largestShift, std::abs(kappa - ((1 - x) * a + x * b)));
    }
  }
  return worst;
}

TEST(G2EdgeCurvature, DirectSourceFollowsTheSurfaceNotTheCurvesSpikes) {
  double shift = 0;
  const Surface saddle = Surface::build(Network::build(builtinNetwork("saddle-nodes")), {Scheme::GregoryG2});
  EXPECT_LE(directShiftBeyondEnds(saddle, shift), 0.0);
  std::printf("saddle-nodes: κ_D departs from the plain blend of its ends by up to %.3f\n", shift);
  EXPECT_GE(shift, 0.05) << "the refit's shift is kept where the disagreement is small";
  const std::string bathtub = std::string(CURVENET_SHARED_DATA_DIR) + "/sketches/bathtub.obj";
  if (!std::filesystem::exists(bathtub)) GTEST_SKIP() << bathtub << " is absent: no sketch with curvature spikes";
  const Network network = Network::build(networkFromCurveGraph(readCurveGraphFile(bathtub), {}, bathtub).description);
  const Surface sketch = Surface::build(network, {Scheme::GregoryG2});
  const double beyond = directShiftBeyondEnds(sketch, shift);
  std::printf("bathtub.obj: κ_D beyond its widened end range by %.3g\n", beyond);
  // The samples keep the bound exactly; their cubic interpolant may
  // overshoot it a little between them.
  EXPECT_LE(beyond, 0.05);
}
