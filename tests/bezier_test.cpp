// Bézier schemes of [OSK11] (bezier-g1, coons-c0): G¹ across every edge of
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

// ---- Hand-made networks for the vertex G¹ systems -----------------------------

namespace {

BSplineCurve arc(const Vec3 &a0, const Vec3 &b0) {
  const Vec3 a = normalized(a0), b = normalized(b0);
  const double theta = angleBetween(a, b);
  const Vec3 t0 = normalized(b - dot(a, b) * a), t1 = -std::sin(theta) * a + std::cos(theta) * t0;
  const double k = 4.0 / 3.0 * std::tan(theta / 4);
  return BSplineCurve::bezier({a, a + k * t0, b - k * t1, b});
}

/// Quads of great-arc cubics between unit-sphere nodes, oriented outward.
NetworkDescription quadsOnSphere(const std::vector<Vec3> &nodes, std::vector<std::array<int, 4>> quads) {
  NetworkDescription net;
  net.name = "hand-made";
  std::map<std::pair<int, int>, int> curveOf;
  for (auto &q : quads) {
    const Vec3 c = normalized(nodes[q[0]] + nodes[q[1]] + nodes[q[2]] + nodes[q[3]]);
    if (dot(cross(nodes[q[1]] - nodes[q[0]], nodes[q[2]] - nodes[q[0]]), c) < 0) std::swap(q[1], q[3]);
    FaceDescription face;
    for (int k = 0; k < 4; ++k) {
      const int a = q[k], b = q[(k + 1) % 4];
      auto it = curveOf.find({std::min(a, b), std::max(a, b)});
      if (it == curveOf.end()) {
        net.curves.push_back(arc(nodes[std::min(a, b)], nodes[std::max(a, b)]));
        it = curveOf.insert({{std::min(a, b), std::max(a, b)}, static_cast<int>(net.curves.size()) - 1}).first;
      }
      face.sides.push_back(a < b ? SideDescription{it->second, 0, 1} : SideDescription{it->second, 1, 0});
    }
    net.faces.push_back(face);
  }
  net.reference = ReferenceSurface{ReferenceSurface::Kind::Ellipsoid, {}, {1, 1, 1}, nullptr};
  return net;
}

const bezier::VertexSystemReport &reportAt(const bezier::BezierSurfaceData &data, const Vec3 &p) {
  for (const auto &r : data.vertexSystems)
    if (norm(data.construction.vertices()[r.vertex].position - normalized(p)) < 1e-12) return r;
  throw std::runtime_error("no vertex system at the point");
}

} // namespace

TEST(VertexSystem, ValenceThreeIsRegularAndSolvedByLeastSquares) {
  // Three quads around the cube corner (1, 1, 1) projected on the sphere: a
  // closed circulant system with det ≠ 0 ([OSK11] table, case 3-a).
  const std::vector<Vec3> nodes = {normalized({1, 1, 1}), normalized({1, 1, 0.1}), normalized({1, 0.05, 0.1}),
                                   normalized({1, 0.05, 1}), normalized({0.2, 0.05, 1}), normalized({0.2, 1, 1}),
                                   normalized({0.2, 1, 0.1})};
  const Surface surface = Surface::build(Network::build(quadsOnSphere(nodes, {{0, 1, 2, 3}, {0, 3, 4, 5}, {0, 5, 6, 1}})),
                                         {Scheme::BezierG1});
  const auto &data = *SurfaceAccess::bezierData(surface);
  const auto &r = reportAt(data, {1, 1, 1});
  EXPECT_EQ(r.branch, bezier::VertexSystemReport::Branch::Regular);
  EXPECT_EQ(r.equations, 3);
  EXPECT_EQ(r.twists, 3);
  EXPECT_GT(std::abs(r.determinant), 1e-3);
  EXPECT_LE(r.residual, 1e-14);
  EXPECT_LE(bezierEdgeContinuity(surface).maxNormalAngleDeg, 1e-9);
  EXPECT_GT(bezierEdgeContinuity(Surface::build(surface.network(), {Scheme::CoonsC0})).maxNormalAngleDeg, 1.0);
}

TEST(VertexSystem, FourValentWithCollinearPairsIsSingularYetSolvable) {
  // A 3 × 3 node grid on the sphere: the centre is an X-node (two curves
  // passing through, case 4-c); det = Π λ̄ − Π λ = 0 and the system is
  // solvable only through the condition on μ₁, which the solve meets.
  std::vector<Vec3> nodes;
  const double ys[3] = {-0.7, 0.05, 0.6}, zs[3] = {-0.5, 0.1, 0.8};
  for (double z : zs)
    for (double y : ys) nodes.push_back(normalized({1, y, z}));
  const Surface surface = Surface::build(
      Network::build(quadsOnSphere(nodes, {{0, 1, 4, 3}, {1, 2, 5, 4}, {3, 4, 7, 6}, {4, 5, 8, 7}})), {Scheme::BezierG1});
  const auto &data = *SurfaceAccess::bezierData(surface);
  const auto &r = reportAt(data, {1, 0.05, 0.1});
  EXPECT_EQ(r.branch, bezier::VertexSystemReport::Branch::Singular);
  EXPECT_EQ(r.equations, 4);
  EXPECT_LE(std::abs(r.determinant), 1e-12);
  EXPECT_LE(r.residual, 1e-14);
  EXPECT_LE(data.maxEquationResidual, 1e-14);
  EXPECT_LE(bezierEdgeContinuity(surface).maxNormalAngleDeg, 1e-9);
  // Boundary vertices give open chains (minimum-norm branch).
  int chains = 0;
  for (const auto &v : data.vertexSystems) chains += v.branch == bezier::VertexSystemReport::Branch::Chain;
  EXPECT_EQ(chains, 4);
}

TEST(BezierSchemes, RefuseWhatTheMethodDoesNotCover) {
  try {
    Surface::build(Network::build(builtinNetwork("pentagon")), {Scheme::BezierG1});
    ADD_FAILURE() << "no error";
  } catch (const InputError &e) {
    EXPECT_EQ(e.element(), "face 0");
    EXPECT_NE(e.reason().find("4-sided"), std::string::npos);
  }
  NetworkDescription quintic = builtinNetwork("hemisphere-tjunction");
  std::vector<Vec3> p = quintic.curves[0].controlPoints();
  p = {p[0], 0.6 * p[0] + 0.4 * p[1], 0.2 * p[0] + 0.6 * p[1] + 0.2 * p[2], 0.4 * p[1] + 0.4 * p[2] + 0.2 * p[3],
       0.4 * p[2] + 0.6 * p[3], p[3]}; // exact degree-5 form of the same curve
  quintic.curves[0] = BSplineCurve::bezier(p);
  EXPECT_THROW(Surface::build(Network::build(quintic), {Scheme::CoonsC0}), InputError);
  EXPECT_THROW(controlNets(Surface::build(Network::build(builtinNetwork("hemisphere-tjunction")))), InputError);
}

TEST(BezierSchemes, ControlNetExportCarriesTheBoundaryCurves) {
  const Surface surface = buildSurface(builtinNetwork("tjunction-vertex"), Scheme::BezierG1);
  const nlohmann::json doc = nlohmann::json::parse(controlNetsJson(surface));
  EXPECT_EQ(doc["format"], "curvenet-quintic-nets");
  ASSERT_EQ(doc["faces"].size(), static_cast<size_t>(surface.faceCount()));
  int subdivided = 0;
  for (size_t f = 0; f < doc["faces"].size(); ++f) {
    const auto &face = doc["faces"][f];
    subdivided += face["patches"].size() == 3;
    for (const auto &patch : face["patches"]) ASSERT_EQ(patch["points"].size(), 36u);
    if (face["patches"].size() != 1) continue;
    // Row j = 0 is face side 0, elevated: its ends are the side's ends.
    const auto &pts = face["patches"][0]["points"];
    const FaceSide &side0 = surface.network().faces()[f].sides[0];
    for (int i : {0, 5}) {
      const Vec3 p{pts[i][0], pts[i][1], pts[i][2]};
      EXPECT_LE(norm(p - side0.curve.point(i / 5.0)), 1e-14);
    }
  }
  EXPECT_EQ(subdivided, 1); // the face running straight through the T
}
