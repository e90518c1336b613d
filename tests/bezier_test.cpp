// Bézier schemes of paper 003 (bezier-g1, coons-c0): G¹ across every edge of
// the four T-junction built-ins, the Coons baseline clearly worse, boundary
// curves reproduced, the vertex systems' branches on hand-made networks, and
// a 2-manifold mesh from the tessellator.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include <nlohmann/json.hpp>

#include "bezier/bezier_surface.hpp"
#include "curvenet/bezier.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/error.hpp"
#include "curvenet/tessellate.hpp"

using namespace curvenet;

namespace {

Surface buildSurface(const NetworkDescription &description, Scheme scheme) {
  return Surface::build(Network::build(description), {scheme});
}

class BezierBuiltin : public testing::TestWithParam<std::string> {};

} // namespace

TEST_P(BezierBuiltin, G1AcrossEveryEdgeAndCoonsClearlyWorse) {
  const NetworkDescription description = builtinNetwork(GetParam());
  const Surface g1 = buildSurface(description, Scheme::BezierG1);
  const Surface c0 = buildSurface(description, Scheme::CoonsC0);
  const EdgeContinuity a = bezierEdgeContinuity(g1, 64), b = bezierEdgeContinuity(c0, 64);
  std::printf("  %-22s bezier-g1 max %.3e deg mean %.3e deg (%d edges) | coons-c0 max %.3f deg mean %.3f deg | "
              "G1 equation residual %.1e\n",
              GetParam().c_str(), a.maxNormalAngleDeg, a.meanNormalAngleDeg, a.edges, b.maxNormalAngleDeg,
              b.meanNormalAngleDeg, SurfaceAccess::bezierData(g1)->maxEquationResidual);
  EXPECT_GT(a.edges, 0);
  EXPECT_LE(a.maxNormalAngleDeg, 1e-6);
  EXPECT_LE(a.meanNormalAngleDeg, 1e-7);
  EXPECT_GT(b.maxNormalAngleDeg, 1.0);
  EXPECT_GT(b.maxNormalAngleDeg, 100 * a.maxNormalAngleDeg);
  // C⁰ in both: the patches share the boundary curves exactly.
  EXPECT_LE(a.maxPositionGap, 1e-12 * g1.network().diagonal());
  EXPECT_LE(b.maxPositionGap, 1e-12 * c0.network().diagonal());
}

TEST_P(BezierBuiltin, BoundaryCurvesAreReproduced) {
  for (Scheme scheme : {Scheme::BezierG1, Scheme::CoonsC0}) {
    const Surface surface = buildSurface(builtinNetwork(GetParam()), scheme);
    const Network &net = surface.network();
    double worst = 0;
    for (int f = 0; f < surface.faceCount(); ++f)
      for (int k = 0; k < 4; ++k)
        for (int i = 0; i <= 50; ++i) {
          const double s = i / 50.0;
          const Vec3 p = surface.evaluate(f, surface.domainPointOnFaceSide(f, k, s)).point;
          worst = std::max(worst, norm(p - net.faces()[f].sides[k].curve.point(s)));
        }
    EXPECT_LE(worst, 1e-12 * net.diagonal()) << schemeName(scheme);
  }
}

TEST_P(BezierBuiltin, MeshIsATwoManifoldWithBorder) {
  const Surface surface = buildSurface(builtinNetwork(GetParam()), Scheme::BezierG1);
  const Mesh mesh = tessellate(surface, {12, 1});
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edgeUse, directed;
  for (const auto &t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      ASSERT_NE(a, b);
      ++edgeUse[{std::min(a, b), std::max(a, b)}];
      ++directed[{a, b}];
    }
  int border = 0;
  for (const auto &[e, n] : edgeUse) {
    EXPECT_LE(n, 2);
    border += n == 1;
  }
  for (const auto &[e, n] : directed) EXPECT_EQ(n, 1) << "edge used twice in one direction: inconsistent orientation";
  const bool closed = false; // every paper-003 built-in is an open sheet
  EXPECT_EQ(border > 0, !closed);
  for (const Vec3 &p : mesh.positions) EXPECT_TRUE(isFinite(p));
}

INSTANTIATE_TEST_SUITE_P(Paper003, BezierBuiltin,
                         testing::Values("hemisphere-tjunction", "tjunction-surrounded", "tjunction-vertex", "hull-like"),
                         [](const testing::TestParamInfo<std::string> &p) {
                           std::string s = p.param;
                           for (char &c : s)
                             if (c == '-') c = '_';
                           return s;
                         });
