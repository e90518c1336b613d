// Bounded patches: the triangle's closed-form sweep (no crossing sweeplines,
// first-order agreement of the corner interpolants' parameters across every
// side), cross-derivatives that do not follow the curves' parameter speed,
// and no fold where these two used to make patches fold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include "bezier/bezier_surface.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/io.hpp"
#include "curvenet/surface.hpp"
#include "patches/domain.hpp"
#include "patches/patch.hpp"

using namespace curvenet;
namespace fs = std::filesystem;

namespace {

const fs::path sharedModels = fs::path(CURVENET_SHARED_DATA_DIR) / "transfinite-models";

/// Uniform random points strictly inside the domain polygon.
std::vector<Vec2> interiorPoints(const RegularDomain &domain, std::size_t count, std::mt19937 &rng) {
  std::uniform_real_distribution<double> coordinate(-1, 1);
  std::vector<Vec2> points;
  while (points.size() < count) {
    const Vec2 p{coordinate(rng), coordinate(rng)};
    bool inside = true;
    for (int i = 0; i < domain.sides(); ++i)
      inside = inside && cross(domain.corner(i + 1) - domain.corner(i), p - domain.corner(i)) > 1e-9;
    if (inside) points.push_back(p);
  }
  return points;
}

/// The unit inward normal of side i and its unit direction.
void sideDirections(const RegularDomain &domain, int i, Vec2 &along, Vec2 &inward) {
  const Vec2 e = domain.corner(i + 1) - domain.corner(i);
  along = e / std::sqrt(dot(e, e));
  inward = {-along.y, along.x};
}

double directional(const Dual &x, const Vec2 &direction) { return x.du * direction.x + x.dv * direction.y; }

} // namespace

TEST(TriangleSweep, IsolinesNeverCrossAndTheMapKeepsItsOrientation) {
  // The map (s_i, Δ_i) ↦ (u, v) has Jacobian ∂s_i/∂(along side i) / |side|
  // in side i's frame: positive at every interior point, so no point lies on
  // two sweeplines. (The cubic Hermite lines of eq. 20 cross at two thirds
  // of the height in a triangle.) Values stay inside (0, 1).
  const RegularDomain domain(3);
  std::mt19937 rng(11);
  double slowest = INFINITY;
  for (const Vec2 &p : interiorPoints(domain, 20000, rng))
    for (int i = 0; i < 3; ++i) {
      Vec2 along, inward;
      sideDirections(domain, i, along, inward);
      const Dual s = domain.triangleSweep(i, Dual::u(p.x), Dual::vCoord(p.y));
      ASSERT_GT(s.v, 0.0);
      ASSERT_LT(s.v, 1.0);
      slowest = std::min(slowest, directional(s, along));
    }
  // Along a parallel at height c the radial t grows at 1 / (side (1 − c))
  // and ∂s/∂t ≥ 1 − c: s grows at least at 1 / side = 1/√3, the fraction's
  // own rate on side i.
  std::printf("slowest growth of s along its side: %.4f per unit length\n", slowest);
  EXPECT_GE(slowest, 1 / std::sqrt(3.0) - 1e-9);
}

TEST(TriangleSweep, BoundaryValuesAndFirstOrderAgreementAcrossEverySide) {
  // On side i: s_i is the fraction along it, s_{i−1} = 1, s_{i+1} = 0, and
  // the two corner interpolants' distances of ribbon i, s_{i+1} and
  // 1 − s_{i−1}, rise from it at the same rate (eq. 19 to first order, what
  // G² across the side needs), equal to the cubic Hermite sweep's rate.
  const RegularDomain domain(3);
  for (int i = 0; i < 3; ++i) {
    Vec2 along, inward;
    sideDirections(domain, i, along, inward);
    for (double x : {0.01, 0.1, 0.3, 0.5, 0.77, 0.99}) {
      const Vec2 p = domain.pointOnSide(i, x);
      const Dual u = Dual::u(p.x), v = Dual::vCoord(p.y);
      const Dual own = domain.triangleSweep(i, u, v), previous = domain.triangleSweep(i - 1, u, v),
                 next = domain.triangleSweep(i + 1, u, v);
      EXPECT_NEAR(own.v, x, 1e-14);
      EXPECT_NEAR(previous.v, 1.0, 1e-14);
      EXPECT_NEAR(next.v, 0.0, 1e-14);
      const double rise = directional(next, inward), fall = directional(previous, inward);
      EXPECT_NEAR(rise, -fall, 1e-10) << "side " << i << " at " << x;
      // The rate is 1 / height: 2/3 per unit length for the unit-circumradius triangle.
      EXPECT_NEAR(rise, 2.0 / 3.0, 1e-12);
    }
  }
}

TEST(TriangleSweep, SecondOrderFormAgreesWithTheFirstAndItsDifferences) {
  const RegularDomain domain(3);
  std::mt19937 rng(5);
  constexpr double h = 1e-6;
  for (const Vec2 &p : interiorPoints(domain, 500, rng))
    for (int i = 0; i < 3; ++i) {
      const Dual2 s2 = domain.triangleSweep2(i, Dual2::u(p.x), Dual2::vCoord(p.y));
      const Dual s = domain.triangleSweep(i, Dual::u(p.x), Dual::vCoord(p.y));
      ASSERT_NEAR(s2.v, s.v, 1e-15);
      ASSERT_NEAR(s2.du, s.du, 1e-12 * (1 + std::abs(s.du)));
      ASSERT_NEAR(s2.dv, s.dv, 1e-12 * (1 + std::abs(s.dv)));
      const Dual su = domain.triangleSweep(i, Dual::u(p.x + h), Dual::vCoord(p.y)),
                 sd = domain.triangleSweep(i, Dual::u(p.x - h), Dual::vCoord(p.y));
      const Dual sv = domain.triangleSweep(i, Dual::u(p.x), Dual::vCoord(p.y + h)),
                 sw = domain.triangleSweep(i, Dual::u(p.x), Dual::vCoord(p.y - h));
      const double scale = 1 + std::abs(s2.duu) + std::abs(s2.dvv) + std::abs(s2.duv);
      ASSERT_NEAR(s2.duu, (su.du - sd.du) / (2 * h), 1e-5 * scale);
      ASSERT_NEAR(s2.duv, (su.dv - sd.dv) / (2 * h), 1e-5 * scale);
      ASSERT_NEAR(s2.dvv, (sv.dv - sw.dv) / (2 * h), 1e-5 * scale);
    }
}

TEST(BoundedPatch, TorusTrianglesDoNotFoldUnderG2) {
  // The two torus-mixed triangles that folded with the crossing sweeplines.
  SurfaceOptions g2;
  g2.scheme = Scheme::GregoryG2;
  const Surface surface = Surface::build(Network::build(builtinNetwork("torus-mixed")), g2);
  EXPECT_TRUE(surface.foldedFaces().empty()) << surface.foldedFaces().size() << " folded faces";
}

TEST(BoundedPatch, CrossDerivativesStayWithinTheirEndsOnPocket3sided) {
  // pocket3sided's sides run up to 1.7 times faster mid-way than at their
  // ends. Blended in the unit frame, |T| never exceeds the larger end
  // target (with α, β as coefficients of D and P' it reached 1.3–1.6 times
  // the reference library's mid-side values), and no G¹ scheme folds.
  if (!fs::exists(sharedModels)) GTEST_SKIP() << "shared models not present at " << sharedModels;
  const std::string path = (sharedModels / "pocket3sided.lop").string();
  const Network network = Network::build(readNetworkFile(path), path);
  for (Scheme scheme : {Scheme::GregoryG1, Scheme::CompositeRibbon}) {
    SurfaceOptions options;
    options.scheme = scheme;
    const Surface surface = Surface::build(network, options);
    EXPECT_TRUE(surface.foldedFaces().empty()) << schemeName(scheme);
    const Patch &patch = *SurfaceAccess::patch(surface, 0);
    for (int side = 0; side < 3; ++side) {
      const LinearRibbon &ribbon = patch.ribbon(side);
      const double bound = std::max(norm(ribbon.at(0.0).T), norm(ribbon.at(1.0).T));
      double largest = 0;
      for (int k = 0; k <= 200; ++k) largest = std::max(largest, norm(ribbon.at(k / 200.0).T));
      EXPECT_LE(largest, bound * (1 + 1e-12)) << schemeName(scheme) << " side " << side;
    }
  }
}

TEST(BoundedPatch, HighOrderCornerTermsMeetInTheTangentPlane) {
  // matchCornerTerms on the ribbons of a saddle-nodes quad, rebuilt from
  // the curves and fences alone: at every corner the tangential parts of
  // W₂₂ (the two C''), W₂₁ and W₁₂ (T'' against the other ribbon's C')
  // agree, and what the ribbons
  // carry at the corner to first order (P, T, the twist T', C) is unchanged.
  SurfaceOptions options;
  options.scheme = Scheme::GregoryG2;
  const Surface surface = Surface::build(Network::build(builtinNetwork("saddle-nodes")), options);
  const Patch &patch = *SurfaceAccess::patch(surface, 0);
  const int n = patch.domain().sides();
  std::vector<LinearRibbon> ribbons;
  for (int i = 0; i < n; ++i) {
    ribbons.push_back(patch.ribbon(i));
    ribbons.back().setEndCurvatures({}, {});
  }
  const TransversalCurvature kappa(std::vector<double>(9, 0.7));
  auto build = [&](const LinearRibbon &r) {
    return ParabolicRibbon(r, std::vector<const TransversalCurvature *>(r.pieces().size(), &kappa));
  };
  std::vector<ParabolicRibbon> before;
  for (const LinearRibbon &r : ribbons) before.push_back(build(r));
  const std::vector<ParabolicRibbon> after = matchCornerTerms(ribbons, build);
  auto tangential = [](const Vec3 &v, const Vec3 &normal) { return v - normal * dot(v, normal); };
  double largest = 0;
  for (int i = 0; i < n; ++i) {
    const int prev = (i + n - 1) % n;
    const Vec3 normal = ribbons[i].secondJet(0.0).N;
    const SideEndData &b0 = before[i].start(), &a0 = before[prev].end();
    const SideEndData &b1 = after[i].start(), &a1 = after[prev].end();
    const double scale = norm(b0.ddC) + norm(a0.ddC) + norm(b0.ddT) + norm(a0.dC) + 1;
    // W₂₂: a = C_{i−1}''(1), b = C_i''(0).
    EXPECT_LE(norm(tangential(a1.ddC - b1.ddC, normal)), 1e-7 * scale) << "corner " << i;
    // W₂₁: a = −C_{i−1}'(1), b = T_i''(0); W₁₂: a = T_{i−1}''(1), b = C_i'(0).
    const Vec3 w21Before = tangential(b0.ddT + a0.dC, normal), w21After = tangential(b1.ddT + a1.dC, normal);
    const Vec3 w12Before = tangential(a0.ddT - b0.dC, normal), w12After = tangential(a1.ddT - b1.dC, normal);
    EXPECT_LE(norm(w21After), 1e-9 * scale) << "corner " << i;
    EXPECT_LE(norm(w12After), 1e-9 * scale) << "corner " << i;
    largest = std::max({largest, norm(w21Before), norm(w12Before)});
    for (const auto &[x, y] : {std::pair{b0, b1}, std::pair{a0, a1}}) {
      EXPECT_LE(norm(x.P - y.P) + norm(x.T - y.T) + norm(x.dT - y.dT) + norm(x.C - y.C), 1e-12 * scale)
          << "corner " << i;
    }
  }
  EXPECT_GT(largest, 0.1); // the quad's ribbons did disagree there
}

namespace {

/// The blend shares of every gregory-g2 face of `surface`.
std::vector<double> allBlendShares(const Surface &surface) {
  std::vector<double> shares;
  for (int f = 0; f < surface.faceCount(); ++f) {
    const std::vector<double> &face = SurfaceAccess::patch(surface, f)->blendShares();
    shares.insert(shares.end(), face.begin(), face.end());
  }
  return shares;
}

SurfaceOptions g2() {
  SurfaceOptions options;
  options.scheme = Scheme::GregoryG2;
  return options;
}

} // namespace

TEST(BoundedPatch, TheCorrectionPatchGivesWayOnlyWhereTheRibbonsDisagree) {
  // On networks whose ribbons agree at the corners the nine-term correction
  // patch stays alone (μ = 0: [SV14] eq. 17, figures unchanged); on
  // saddle-nodes, whose corner terms disagree, some corners take a share of
  // the two-ribbon blend, some all of it.
  for (const char *name : {"pentagon", "sphere-dodecahedron", "ellipsoid-truncated-icosahedron", "torus-mixed"}) {
    const std::vector<double> shares = allBlendShares(Surface::build(Network::build(builtinNetwork(name), name), g2()));
    EXPECT_EQ(*std::max_element(shares.begin(), shares.end()), 0.0) << name;
  }
  // gregory-g1: no built-in has an end twist that departs from its side.
  for (const BuiltinInfo &info : builtinNetworks()) {
    const std::vector<double> shares =
        allBlendShares(Surface::build(Network::build(builtinNetwork(info.name), info.name), SurfaceOptions{}));
    ASSERT_FALSE(shares.empty()) << info.name;
    EXPECT_EQ(*std::max_element(shares.begin(), shares.end()), 0.0) << info.name;
  }
  const std::vector<double> saddle =
      allBlendShares(Surface::build(Network::build(builtinNetwork("saddle-nodes"), "saddle-nodes"), g2()));
  const auto partial = std::count_if(saddle.begin(), saddle.end(), [](double mu) { return mu > 0 && mu < 1; });
  const auto whole = std::count(saddle.begin(), saddle.end(), 1.0);
  std::printf("saddle-nodes: %td of %zu corners blended in part, %td wholly\n", partial, saddle.size(), whole);
  EXPECT_GT(partial, 0);
  EXPECT_GT(whole, 0);
  for (double mu : saddle) EXPECT_TRUE(mu >= 0 && mu <= 1) << mu;
}

TEST(BoundedPatch, BlendedCornersAgreeAcrossEvaluationPathsAndOrders) {
  // saddle-nodes' faces mix μ = 0, partial and whole shares: the batched
  // jets (ribbon tables and the SIMD kernel) agree with the pointwise Dual
  // evaluation, the hyper-dual evaluation has the same first derivatives,
  // and its second derivatives are the central differences of the first.
  const Surface surface = Surface::build(Network::build(builtinNetwork("saddle-nodes"), "saddle-nodes"), g2());
  std::mt19937 rng(5);
  double worstJet = 0, worstFirst = 0, worstSecondPlain = 0, worstSecondBlended = 0;
  for (int f = 0; f < surface.faceCount(); ++f) {
    const Patch &patch = *SurfaceAccess::patch(surface, f);
    const std::vector<double> &shares = patch.blendShares();
    const bool blended = *std::max_element(shares.begin(), shares.end()) > 0;
    const std::vector<Vec2> points = interiorPoints(patch.domain(), 64, rng);
    std::vector<double> us, vs;
    for (const Vec2 &p : points) us.push_back(p.x), vs.push_back(p.y);
    std::vector<DualVec3> jets(points.size());
    patch.evaluateJets(points.size(), us.data(), vs.data(), jets.data());
    for (std::size_t k = 0; k < points.size(); ++k) {
      const DualVec3 exact = patch.evaluate(us[k], vs[k]);
      const double scale = 1 + norm(exact.du) + norm(exact.dv);
      worstJet = std::max({worstJet, norm(jets[k].v - exact.v) / (1 + norm(exact.v)),
                           (norm(jets[k].du - exact.du) + norm(jets[k].dv - exact.dv)) / scale});
      const Dual2Vec3 second = patch.evaluateSecondOrder(us[k], vs[k]);
      worstFirst = std::max(worstFirst, (norm(second.du - exact.du) + norm(second.dv - exact.dv)) / scale);
      constexpr double h = 1e-5;
      const DualVec3 uPlus = patch.evaluate(us[k] + h, vs[k]), uMinus = patch.evaluate(us[k] - h, vs[k]);
      const DualVec3 vPlus = patch.evaluate(us[k], vs[k] + h), vMinus = patch.evaluate(us[k], vs[k] - h);
      const Vec3 duu = (uPlus.du - uMinus.du) / (2 * h), duv = (vPlus.du - vMinus.du) / (2 * h);
      const Vec3 dvv = (vPlus.dv - vMinus.dv) / (2 * h);
      const double secondScale = 1 + norm(second.duu) + norm(second.duv) + norm(second.dvv);
      double &worst = blended ? worstSecondBlended : worstSecondPlain;
      worst = std::max(worst, (norm(second.duu - duu) + norm(second.duv - duv) + norm(second.dvv - dvv)) / secondScale);
    }
  }
  std::printf("saddle-nodes G²: jets %.2e, hyper-dual first %.2e, second against differences %.2e (faces "
              "without blend shares: %.2e)\n",
              worstJet, worstFirst, worstSecondBlended, worstSecondPlain);
  EXPECT_LE(worstJet, 1e-10);
  EXPECT_LE(worstFirst, 1e-12);
  // The ribbons' C'' is a fourth-order difference (ParabolicRibbon::
  // secondOrder), which bounds the agreement on every face; the blended
  // corners add no error of their own beyond it.
  EXPECT_GT(worstSecondPlain, 0.0);
  EXPECT_LE(worstSecondPlain, 1e-3);
  EXPECT_LE(worstSecondBlended, 5 * worstSecondPlain);
}
