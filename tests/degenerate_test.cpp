// Degenerate geometry (issue: reliability, item 3): every case is either
// handled with the documented result or refused with an InputError naming
// the face, vertex or curve at fault.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "curvenet/analysis.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/continuity.hpp"
#include "curvenet/error.hpp"
#include "curvenet/network.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"

using namespace curvenet;

namespace {

/// A curve over the surface z = f(x, y) from (x0, y0) to (x1, y1): a cubic
/// interpolating 9 points of the straight plan-view segment lifted onto f,
/// so that curves meeting at a point share f's tangent plane there.
BSplineCurve lifted(const std::function<double(double, double)> &f, double x0, double y0, double x1, double y1) {
  std::vector<double> params;
  std::vector<Vec3> points;
  for (int k = 0; k <= 8; ++k) {
    const double t = k / 8.0, x = x0 + (x1 - x0) * t, y = y0 + (y1 - y0) * t;
    params.push_back(t);
    points.push_back({x, y, f(x, y)});
  }
  return BSplineCurve::interpolate(3, params, points);
}

double bump(double x, double y) { return 0.15 * (x * x - 0.5 * y * y) + 0.05 * x * y; }

const std::vector<SurfaceOptions> &everyTransfiniteScheme() {
  static const std::vector<SurfaceOptions> all = {{Scheme::GregoryG1}, {Scheme::CompositeRibbon}, {Scheme::GregoryG2}};
  return all;
}

/// Expects InputError whose message names `element` and contains `words`.
void expectRefused(const std::function<void()> &action, const std::string &element, const std::string &words) {
  try {
    action();
    ADD_FAILURE() << "accepted; expected a refusal naming " << element;
  } catch (const InputError &e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(element), std::string::npos) << message;
    EXPECT_NE(message.find(words), std::string::npos) << message;
  }
}

} // namespace

// A T-node seen from one face as a straight angle, with the through curve
// listed as two sides: handled — the corner's cross-derivative follows the
// normal fence (docs/network-format.md) and the faces join G¹.
TEST(Degenerate, StraightAngleCornerListedAsTwoSides) {
  NetworkDescription d;
  // Bottom face [0,2]×[0,1]; two top faces over [0,1]×[1,2] and [1,2]×[1,2].
  const auto c = [&](double x0, double y0, double x1, double y1) {
    d.curves.push_back(lifted(bump, x0, y0, x1, y1));
    return static_cast<int>(d.curves.size()) - 1;
  };
  const int b0 = c(0, 0, 2, 0), r0 = c(2, 0, 2, 1), m1 = c(2, 1, 1, 1), m0 = c(1, 1, 0, 1), l0 = c(0, 1, 0, 0);
  const int v = c(1, 1, 1, 2), t0 = c(0, 2, 1, 2), t1 = c(1, 2, 2, 2), l1 = c(0, 1, 0, 2), r1 = c(2, 1, 2, 2);
  d.faces.push_back({{{b0, 0, 1}, {r0, 0, 1}, {m1, 0, 1}, {m0, 0, 1}, {l0, 0, 1}}, "bottom, straight angle at (1,1)"});
  d.faces.push_back({{{m0, 1, 0}, {v, 0, 1}, {t0, 1, 0}, {l1, 1, 0}}, "top left"});
  d.faces.push_back({{{m1, 1, 0}, {r1, 0, 1}, {t1, 1, 0}, {v, 1, 0}}, "top right"});
  const Network network = Network::build(d);
  for (const SurfaceOptions &options : everyTransfiniteScheme()) {
    const Surface surface = Surface::build(network, options);
    const ContinuityReport report = measureContinuity(surface, {16});
    EXPECT_LE(report.maxNormalAngleDeg, 1e-6) << schemeName(options.scheme);
    EXPECT_LE(report.maxBoundaryDeviation, 1e-12) << schemeName(options.scheme);
    EXPECT_TRUE(surface.foldedFaces().empty()) << schemeName(options.scheme);
  }
}

// Two sides leaving a corner in the same direction: refused, naming the face.
TEST(Degenerate, CuspCornerIsRefused) {
  NetworkDescription d;
  d.curves.push_back(BSplineCurve::bezier({{0, 0, 0}, {1, 0, 0}, {2, 0.5, 0}, {3, 1, 0}}));
  d.curves.push_back(BSplineCurve::bezier({{3, 1, 0}, {2, 1.2, 0}, {1, 0, 0}, {0, 0, 0}}));
  d.faces.push_back({{{0, 0, 1}, {1, 0, 1}}, "lens with a cusp"});
  // The second curve ends travelling along −x and the first leaves along +x:
  // at (0,0) the two sides leave the corner in the same direction.
  expectRefused([&] { Surface::build(Network::build(d), {}); }, "face 0", "cusp");
}

TEST(Degenerate, ZeroLengthCurveIsRefused) {
  NetworkDescription d = builtinNetwork("pentagon");
  const Vec3 p = d.curves[0].point(0.0);
  d.curves.push_back(BSplineCurve::bezier({p, p, p, p}));
  d.faces.push_back({{{static_cast<int>(d.curves.size()) - 1, 0, 1}, {0, 0, 0}}, "degenerate"});
  expectRefused([&] { Network::build(d); }, "curve", "");
}

TEST(Degenerate, CurveFoldingBackOnItselfIsRefused) {
  NetworkDescription d;
  // Runs out along the x axis to x = 1.5 and back over itself to x = 1: the
  // tangent vanishes and reverses at the turn.
  d.curves.push_back(BSplineCurve::bezier({{0, 0, 0}, {2, 0, 0}, {2, 0, 0}, {1, 0, 0}}));
  d.curves.push_back(BSplineCurve::bezier({{1, 0, 0}, {1, 0.5, 0}, {0.5, 1, 0}, {0, 1, 0}}));
  d.curves.push_back(BSplineCurve::bezier({{0, 1, 0}, {0, 0.5, 0}, {0, 0, 0}}));
  d.faces.push_back({{{0, 0, 1}, {1, 0, 1}, {2, 0, 1}}, "a"});
  expectRefused([&] { Network::build(d); }, "curve 0", "folds back");
}

// Three curves whose tangents at a vertex are not coplanar: handled — the
// least-squares plane is the vertex normal, its residual angle is reported,
// the analysis says so, and the continuity report shows the normal mismatch
// that the patches' own corner tangent planes cannot avoid.
/// Three triangles around the origin vertex; the first spoke rises by
/// `rise` out of the plane of the other two.
NetworkDescription spokesAroundTheOrigin(double rise) {
  NetworkDescription d;
  const double pi = std::acos(-1.0);
  std::vector<Vec3> spoke;
  for (int k = 0; k < 3; ++k) spoke.push_back({std::cos(2 * pi * k / 3), std::sin(2 * pi * k / 3), 0});
  spoke[0].z = rise;
  for (int k = 0; k < 3; ++k) d.curves.push_back(BSplineCurve::bezier({{0, 0, 0}, spoke[k] * 0.5, spoke[k]}));
  for (int k = 0; k < 3; ++k) {
    const Vec3 a = spoke[k], b = spoke[(k + 1) % 3];
    d.curves.push_back(BSplineCurve::bezier({a, (a + b) * 0.5 + Vec3{0, 0, 0.05}, b}));
  }
  for (int k = 0; k < 3; ++k) d.faces.push_back({{{k, 0, 1}, {3 + k, 0, 1}, {(k + 1) % 3, 1, 0}}, ""});
  return d;
}

int originVertex(const Network &network) {
  for (size_t v = 0; v < network.vertices().size(); ++v)
    if (norm(network.vertices()[v].position) < 1e-12) return static_cast<int>(v);
  return -1;
}

TEST(Degenerate, VertexWithoutCommonTangentPlane) {
  // A spoke ~2° out of the others' plane: a drawing error. By default the
  // spokes' end tangents are turned into the fitted plane (the vertex stays
  // put), and the surface is G¹ there.
  {
    const Network network = Network::build(spokesAroundTheOrigin(0.05));
    const int centre = originVertex(network);
    ASSERT_GE(centre, 0);
    SurfaceOptions kept{Scheme::GregoryG1};
    kept.curves = CurveHandling::Kept;
    const Surface surface = Surface::build(network, kept);
    EXPECT_GT(surface.vertexResidualAngle(centre), 0.01);
    EXPECT_FALSE(surface.isCreaseVertex(centre));
    EXPECT_EQ(analyzeVertex(network, centre).verdict, VertexVerdict::NoTangentPlane);
    EXPECT_GT(measureContinuity(surface, {8}).maxNormalAngleDeg, 0.1);
    const Surface repaired = Surface::build(network, {Scheme::GregoryG1});
    EXPECT_FALSE(repaired.repairMoves().empty());
    EXPECT_LE(repaired.vertexResidualAngle(centre), 1e-12);
    EXPECT_EQ(norm(repaired.network().vertices()[size_t(centre)].position), 0.0);
    EXPECT_LE(measureContinuity(repaired, {8}).maxNormalAngleDeg, 1e-6);
  }
  // ~25° out: a crease, meant sharp. Repair leaves it alone, each face
  // corner keeps its own plane, and nothing folds.
  {
    const Network network = Network::build(spokesAroundTheOrigin(0.6));
    const int centre = originVertex(network);
    ASSERT_GE(centre, 0);
    const Surface surface = Surface::build(network, {Scheme::GregoryG1});
    EXPECT_GT(surface.vertexResidualAngle(centre), 0.1); // radians
    EXPECT_TRUE(surface.isCreaseVertex(centre));
    EXPECT_TRUE(surface.repairMoves().empty());
    EXPECT_TRUE(surface.foldedFaces().empty());
    int creases = 0;
    for (int e = 0; e < static_cast<int>(network.segments().size()); ++e) creases += surface.isCreaseSegment(e) ? 1 : 0;
    EXPECT_GE(creases, 2); // the raised spoke's faces fold away from the flat one
    EXPECT_EQ(measureContinuity(surface, {8}).creaseSegments, creases);
  }
}

// A 2-sided face: handled as a 4-sided patch split at the curves' middles.
TEST(Degenerate, TwoSidedFaceIsAHandledLens) {
  NetworkDescription d;
  d.curves.push_back(BSplineCurve::bezier({{-1, 0, bump(-1, 0)}, {-0.3, 0.8, 0.1}, {0.3, 0.8, 0.1}, {1, 0, bump(1, 0)}}));
  d.curves.push_back(BSplineCurve::bezier({{1, 0, bump(1, 0)}, {0.3, -0.8, 0.1}, {-0.3, -0.8, 0.1}, {-1, 0, bump(-1, 0)}}));
  d.faces.push_back({{{0, 0, 1}, {1, 0, 1}}, "lens"});
  const Network network = Network::build(d);
  for (const SurfaceOptions &options : everyTransfiniteScheme()) {
    const Surface surface = Surface::build(network, options);
    EXPECT_EQ(surface.domainSides(0), 4);
    const Mesh mesh = tessellate(surface, {6, 1});
    for (const Vec3 &n : mesh.normals) ASSERT_TRUE(std::isfinite(n.x + n.y + n.z));
    EXPECT_LE(measureContinuity(surface, {16}).maxBoundaryDeviation, 1e-12);
  }
}

TEST(Degenerate, MoreThanEightSidesIsRefused) {
  NetworkDescription d;
  const double pi = std::acos(-1.0);
  for (int k = 0; k < 9; ++k) {
    const Vec3 a{std::cos(2 * pi * k / 9), std::sin(2 * pi * k / 9), 0};
    const Vec3 b{std::cos(2 * pi * (k + 1) / 9), std::sin(2 * pi * (k + 1) / 9), 0};
    d.curves.push_back(BSplineCurve::bezier({a, b}));
  }
  FaceDescription face;
  for (int k = 0; k < 9; ++k) face.sides.push_back({k, 0, 1});
  d.faces.push_back(face);
  // By default connection curves split such a loop (tests/split_loops_test.cpp);
  // here the split is switched off.
  d.connectionCurves = false;
  expectRefused([&] { Network::build(d); }, "face 0", "8 sides");
}

// A loop with a concave corner folds on the regular n-gon domain: detected
// and reported (Surface::foldedFaces), never silent; a convex loop is not.
// (By default Network::build splits such a loop with a connection curve, see
// tests/apps_test.cpp; here the split is switched off.)
TEST(Degenerate, ConcaveLoopFoldIsDetected) {
  auto loop = [](const std::vector<Vec3> &corners) {
    NetworkDescription d;
    FaceDescription face;
    for (size_t k = 0; k < corners.size(); ++k) {
      const Vec3 a = corners[k], b = corners[(k + 1) % corners.size()];
      d.curves.push_back(BSplineCurve::bezier({a, a + (b - a) / 3, a + (b - a) * (2.0 / 3), b}));
      face.sides.push_back({static_cast<int>(k), 0, 1});
    }
    d.faces.push_back(face);
    d.connectionCurves = false; // the loop as drawn, without the automatic split
    return Network::build(d);
  };
  const Network lShape = loop({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}});
  const Network hexagon = loop({{0, 0, 0}, {2, 0, 0}, {3, 1, 0}, {2, 2, 0}, {0, 2, 0}, {-1, 1, 0}});
  for (const SurfaceOptions &options : everyTransfiniteScheme()) {
    EXPECT_EQ(Surface::build(lShape, options).foldedFaces(), std::vector<int>{0}) << schemeName(options.scheme);
    EXPECT_TRUE(Surface::build(hexagon, options).foldedFaces().empty()) << schemeName(options.scheme);
  }
}

// A part far from the origin and a tiny part keep their continuity figures
// relative to the diagonal (Surface::origin: the far one is built in its own
// frame). Only the rounding of the world coordinates themselves remains in
// the boundary figure.
TEST(Degenerate, HugeOffsetAndTinyModelKeepTheirFigures) {
  const NetworkDescription original = builtinNetwork("sphere-dodecahedron");
  auto transformed = [&](const std::function<Vec3(const Vec3 &)> &map) {
    NetworkDescription d = original;
    d.reference.reset();
    for (BSplineCurve &c : d.curves) {
      std::vector<Vec3> points = c.controlPoints();
      for (Vec3 &p : points) p = map(p);
      c = BSplineCurve(c.degree(), c.knots(), points, c.weights());
    }
    return Network::build(d);
  };
  const Network far = transformed([](const Vec3 &p) { return p + Vec3{1e6, -1e6, 1e6}; });
  const Network tiny = transformed([](const Vec3 &p) { return p * 1e-6; });
  for (const SurfaceOptions &options : everyTransfiniteScheme()) {
    const Surface farSurface = Surface::build(far, options), tinySurface = Surface::build(tiny, options);
    EXPECT_GT(norm(farSurface.origin()), 1e5);
    const ContinuityReport a = measureContinuity(farSurface, {8}), b = measureContinuity(tinySurface, {8});
    for (const ContinuityReport &r : {a, b}) {
      EXPECT_LE(r.maxNormalAngleDeg, 1e-6) << schemeName(options.scheme);
      EXPECT_LE(r.maxPositionGap, 1e-12) << schemeName(options.scheme);
    }
    EXPECT_LE(b.maxBoundaryDeviation, 1e-12);
    // 1e6 carries 2.3e-10 of rounding per coordinate: four ulps of the diagonal (2).
    EXPECT_LE(a.maxBoundaryDeviation, 4 * 2.4e-10 / far.diagonal());
  }
}
