// G¹ surfaces (issue: normal fences, linear ribbons, Gregory and Composite
// Ribbon patches, watertight tessellation). One fixture runs every built-in
// through every G¹ scheme and asserts the continuity figures of docs/design.md §5,
// boundary reproduction and a manifold mesh; further tests check planar
// reproduction, exact derivatives against central differences, the Coons
// boundary correspondence of 4-sided patches and thread-independent output.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <random>

#include "curvenet/builtins.hpp"
#include "curvenet/continuity.hpp"
#include "curvenet/error.hpp"
#include "curvenet/network.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"

using namespace curvenet;

namespace {

struct Case {
  std::string builtin;
  SurfaceOptions options;
};

std::string caseName(const Case &c) {
  std::string name = c.builtin + "_" + schemeName(c.options.scheme);
  if (c.options.scheme == Scheme::GregoryG1)
    name += c.options.sweepline == Sweepline::Radial ? "_radial" : "_hermite";
  for (char &ch : name)
    if (ch == '-') ch = '_';
  return name;
}

std::vector<Case> allCases() {
  std::vector<Case> cases;
  for (const BuiltinInfo &info : builtinNetworks()) {
    cases.push_back({info.name, {Scheme::GregoryG1, Sweepline::Hermite}});
    cases.push_back({info.name, {Scheme::GregoryG1, Sweepline::Radial}});
    cases.push_back({info.name, {Scheme::CompositeRibbon, Sweepline::Hermite}});
  }
  return cases;
}

bool inside(const Surface &surface, int face, const Vec2 &uv, double margin) {
  const int n = surface.domainSides(face);
  for (int i = 0; i < n; ++i) {
    const Vec2 p = surface.domainCorner(face, i), q = surface.domainCorner(face, i + 1);
    if (cross(q - p, uv - p) / norm(q - p) < margin) return false;
  }
  return true;
}

/// Random domain points strictly inside face f's polygon.
std::vector<Vec2> interiorPoints(const Surface &surface, int face, int count, unsigned seed, double margin = 0.05) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  std::vector<Vec2> points;
  while (static_cast<int>(points.size()) < count) {
    const Vec2 uv{coordinate(rng), coordinate(rng)};
    if (inside(surface, face, uv, margin)) points.push_back(uv);
  }
  return points;
}

} // namespace

class G1Surface : public ::testing::TestWithParam<Case> {
protected:
  Network network = Network::build(builtinNetwork(GetParam().builtin));
  Surface surface = Surface::build(network, GetParam().options);
};

TEST_P(G1Surface, NeighbouringPatchesJoinWithCommonTangentPlanes) {
  const ContinuityReport report = measureContinuity(surface, {32});
  std::size_t interiorSegments = 0;
  for (const Segment &seg : network.segments()) interiorSegments += !seg.isBoundary();
  EXPECT_EQ(static_cast<std::size_t>(report.sharedSegments), interiorSegments);
  EXPECT_LE(report.maxPositionGap, 1e-12);
  EXPECT_LE(report.maxNormalAngleDeg, 1e-6) << "worst segment " << report.worstNormalSegment;
  EXPECT_LE(report.maxBoundaryDeviation, 1e-12);
}

TEST_P(G1Surface, EvaluationIsFiniteOnCornersSidesAndInside) {
  for (int f = 0; f < surface.faceCount(); ++f) {
    const int n = surface.domainSides(f);
    std::vector<Vec2> points = interiorPoints(surface, f, 8, 17u + f, 0.0);
    for (int i = 0; i < n; ++i)
      for (double t : {0.0, 1e-9, 0.5, 1.0 - 1e-9})
        points.push_back(surface.domainCorner(f, i) + (surface.domainCorner(f, i + 1) - surface.domainCorner(f, i)) * t);
    points.push_back({0, 0});
    for (const Vec2 &uv : points) {
      const SurfacePoint p = surface.evaluate(f, uv);
      for (double c : {p.point.x, p.point.y, p.point.z, p.du.x, p.du.y, p.du.z, p.dv.x, p.dv.y, p.dv.z})
        ASSERT_TRUE(std::isfinite(c)) << "face " << f << " at (" << uv.x << ", " << uv.y << ")";
      ASSERT_NEAR(norm(p.normal), 1.0, 1e-12) << "face " << f << " at (" << uv.x << ", " << uv.y << ")";
    }
  }
}

TEST_P(G1Surface, TessellationIsAManifoldWithTheNetworkBoundaryAsBorder) {
  const Mesh mesh = tessellate(surface, {6, 0});
  ASSERT_EQ(mesh.positions.size(), mesh.normals.size());
  ASSERT_EQ(mesh.faceTriangleStart.size(), network.faces().size() + 1);
  // Every undirected edge: how many triangles use it, and in which directions.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses, forward;
  for (const auto &t : mesh.triangles) {
    ASSERT_TRUE(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) << "degenerate triangle";
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      ASSERT_LT(std::max(a, b), mesh.positions.size());
      ++uses[{std::min(a, b), std::max(a, b)}];
      if (a < b) ++forward[{a, b}];
    }
  }
  // Border edges lie on boundary segments of the network; all others are
  // shared by exactly two triangles running it in opposite directions.
  std::size_t borderEdges = 0;
  for (const auto &[edge, count] : uses) {
    ASSERT_LE(count, 2) << "edge in more than two triangles";
    if (count == 1) ++borderEdges;
    else EXPECT_EQ(forward[edge], 1) << "inconsistent orientation across an edge";
  }
  std::size_t boundarySegments = 0;
  for (const Segment &seg : network.segments()) boundarySegments += seg.isBoundary();
  EXPECT_EQ(borderEdges, boundarySegments * 6);
  // Every vertex is used (no stray samples).
  std::vector<char> used(mesh.positions.size(), 0);
  for (const auto &t : mesh.triangles)
    for (std::uint32_t v : t) used[v] = 1;
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
}

TEST_P(G1Surface, TessellationRowsTileEachDomainCounterClockwise) {
  // Inside the first row of samples (level 1 − 1/r of the domain polygon,
  // the face's own samples), the triangles between rows run
  // counter-clockwise in the domain and tile the polygon that row bounds:
  // their areas sum to (1 − 1/r)² of the domain's. Without recomputing the
  // strips: wrong or flipped triangles change the sum or the signs.
  for (int r : {2, 3, 7, 12}) {
    TessellationOptions options{r, 0};
    options.recordDomainPoints = true;
    const Mesh mesh = tessellate(surface, options);
    for (int f = 0; f < surface.faceCount(); ++f) {
      const int n = surface.domainSides(f);
      std::vector<Vec2> corner(n);
      for (int i = 0; i < n; ++i) corner[i] = surface.domainCorner(f, i);
      double area = 0;
      for (int i = 0; i < n; ++i) area += cross(corner[i], corner[(i + 1) % n]) / 2;
      // A domain point's level: 1 on the polygon, 0 at the centre.
      auto level = [&](Vec2 p) {
        double worst = 0;
        for (int i = 0; i < n; ++i) {
          const Vec2 e = corner[(i + 1) % n] - corner[i], outward{e.y, -e.x};
          worst = std::max(worst, dot(p, outward) / dot(corner[i], outward));
        }
        return worst;
      };
      double inner = 0;
      for (std::uint32_t t = mesh.faceTriangleStart[f]; t < mesh.faceTriangleStart[f + 1]; ++t) {
        const auto &tri = mesh.triangles[t];
        bool inside = true;
        for (std::uint32_t v : tri)
          inside = inside && mesh.domainPoints[v].face == f && level(mesh.domainPoints[v].uv) < 1 - 0.5 / r;
        if (!inside) continue;
        const Vec2 a = mesh.domainPoints[tri[0]].uv, b = mesh.domainPoints[tri[1]].uv, c = mesh.domainPoints[tri[2]].uv;
        const double twice = cross(b - a, c - a);
        ASSERT_GT(twice, 0) << "face " << f << " r " << r << " triangle " << t << " is clockwise or flat";
        inner += twice / 2;
      }
      EXPECT_NEAR(inner, (1 - 1.0 / r) * (1 - 1.0 / r) * area, 1e-12 * area) << "face " << f << " r " << r;
    }
  }
}

TEST_P(G1Surface, ExactDerivativesAgreeWithCentralDifferences) {
  const double h = 1e-5;
  for (int f = 0; f < surface.faceCount(); f += std::max(1, surface.faceCount() / 7)) {
    for (const Vec2 &uv : interiorPoints(surface, f, 4, 101u + f, 0.1)) {
      const SurfacePoint p = surface.evaluate(f, uv);
      const Vec3 du = (surface.evaluate(f, {uv.x + h, uv.y}).point - surface.evaluate(f, {uv.x - h, uv.y}).point) / (2 * h);
      const Vec3 dv = (surface.evaluate(f, {uv.x, uv.y + h}).point - surface.evaluate(f, {uv.x, uv.y - h}).point) / (2 * h);
      const double scale = std::max(norm(p.du), norm(p.dv));
      EXPECT_LE(norm(p.du - du), 1e-6 * scale) << "face " << f << " at (" << uv.x << ", " << uv.y << ")";
      EXPECT_LE(norm(p.dv - dv), 1e-6 * scale) << "face " << f << " at (" << uv.x << ", " << uv.y << ")";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllBuiltins, G1Surface, ::testing::ValuesIn(allCases()),
                         [](const ::testing::TestParamInfo<Case> &test) { return caseName(test.param); });

namespace {

/// A planar network: a pentagon of curved planar cubics in z = 0 split into
/// a triangle and a quadrilateral by one inner curve, so that one edge is shared.
NetworkDescription planarNetwork() {
  NetworkDescription desc;
  desc.name = "planar";
  std::vector<Vec3> corners;
  for (int i = 0; i < 5; ++i) {
    const double a = 2 * M_PI * i / 5 + 0.3;
    corners.push_back({std::cos(a) * (1 + 0.1 * i), std::sin(a) * (1 - 0.05 * i), 0});
  }
  auto bulged = [](const Vec3 &p, const Vec3 &q, double bulge) {
    const Vec3 d = q - p, side{-d.y, d.x, 0};
    return BSplineCurve::bezier({p, p + d / 3 + side * bulge, p + d * (2.0 / 3) - side * (bulge * 0.5), q});
  };
  for (int i = 0; i < 5; ++i) desc.curves.push_back(bulged(corners[i], corners[(i + 1) % 5], 0.15 - 0.05 * i));
  desc.curves.push_back(bulged(corners[0], corners[2], 0.08)); // inner curve 5
  desc.faces.push_back({{{0, 0, 1}, {1, 0, 1}, {5, 1, 0}}, "triangle"});
  desc.faces.push_back({{{5, 0, 1}, {2, 0, 1}, {3, 0, 1}, {4, 0, 1}}, "quadrilateral"});
  return desc;
}

} // namespace

TEST(G1Surface, PlanarNetworkGivesPlanarPatches) {
  const Network network = Network::build(planarNetwork());
  for (const Case &c : allCases()) {
    if (c.builtin != "pentagon") continue; // one entry per scheme variant
    const Surface surface = Surface::build(network, c.options);
    for (int f = 0; f < surface.faceCount(); ++f)
      for (const Vec2 &uv : interiorPoints(surface, f, 50, 7u + f, 0.0)) {
        const SurfacePoint p = surface.evaluate(f, uv);
        EXPECT_NEAR(p.point.z, 0.0, 1e-13) << caseName(c);
        EXPECT_NEAR(std::abs(p.normal.z), 1.0, 1e-12) << caseName(c);
      }
    EXPECT_LE(measureContinuity(surface, {16}).maxNormalAngleDeg, 1e-9) << caseName(c);
  }
}

TEST(G1Surface, FourSidedPatchesInterpolateTheCoonsBoundaryData) {
  // The bilinearly blended Coons patch of a 4-sided loop interpolates the
  // four curves with side k ↔ domain side k, running in the loop direction.
  // Both schemes must put the same curve point at each boundary point of the
  // domain, with the same tangent along the side.
  for (const std::string name : {"torus-mixed", "saddle-nodes"}) {
    const Network network = Network::build(builtinNetwork(name));
    for (Scheme scheme : {Scheme::GregoryG1, Scheme::CompositeRibbon}) {
      const Surface surface = Surface::build(network, {scheme});
      int quads = 0;
      for (int f = 0; f < surface.faceCount(); ++f) {
        const Face &face = network.faces()[f];
        if (face.sideCount() != 4) continue;
        ++quads;
        // Coons: C(x, y) on [0,1]² with bottom c0(x), right c1(y), top c2(1−x), left c3(1−y).
        auto coons = [&](double x, double y) {
          const auto c = [&](int k, double t) { return face.sides[k].curve.point(t); };
          const Vec3 p00 = c(0, 0), p10 = c(1, 0), p11 = c(2, 0), p01 = c(3, 0);
          return c(0, x) * (1 - y) + c(2, 1 - x) * y + c(3, 1 - y) * (1 - x) + c(1, y) * x -
                 (p00 * ((1 - x) * (1 - y)) + p10 * (x * (1 - y)) + p11 * (x * y) + p01 * ((1 - x) * y));
        };
        const double h = 1e-6;
        for (int k = 0; k < 4; ++k)
          for (double t : {0.0, 0.2, 0.5, 0.9, 1.0}) {
            const double x[4] = {t, 1, 1 - t, 0}, y[4] = {0, t, 1, 1 - t};
            const Vec2 p0 = surface.domainCorner(f, k), p1 = surface.domainCorner(f, k + 1);
            const SurfacePoint p = surface.evaluate(f, p0 + (p1 - p0) * t);
            EXPECT_LE(norm(p.point - coons(x[k], y[k])), 1e-12 * network.diagonal()) << name << " face " << f;
            // Tangent along the side: the patch's directional derivative along the
            // domain side equals the Coons patch's along the unit-square side.
            const Vec2 e = p1 - p0;
            const Vec3 along = p.du * e.x + p.dv * e.y;
            const double dx[4] = {1, 0, -1, 0}, dy[4] = {0, 1, 0, -1};
            const double t0 = std::clamp(t, h, 1 - h);
            const double xa = x[k] + dx[k] * (t0 - t), ya = y[k] + dy[k] * (t0 - t);
            const Vec3 coonsAlong = (coons(xa + dx[k] * h, ya + dy[k] * h) - coons(xa - dx[k] * h, ya - dy[k] * h)) / (2 * h);
            EXPECT_LE(norm(along - coonsAlong), 1e-5 * norm(coonsAlong)) << name << " face " << f << " side " << k;
          }
      }
      EXPECT_GT(quads, 0);
    }
  }
}

TEST(G1Surface, TessellationBytesDoNotDependOnThreads) {
  const Network network = Network::build(builtinNetwork("torus-mixed"));
  for (Scheme scheme : {Scheme::GregoryG1, Scheme::CompositeRibbon}) {
    const Surface surface = Surface::build(network, {scheme});
    const Mesh one = tessellate(surface, {9, 1}), two = tessellate(surface, {9, 2});
    ASSERT_EQ(one.positions.size(), two.positions.size());
    ASSERT_EQ(one.triangles.size(), two.triangles.size());
    EXPECT_EQ(std::memcmp(one.positions.data(), two.positions.data(), one.positions.size() * sizeof(Vec3)), 0);
    EXPECT_EQ(std::memcmp(one.normals.data(), two.normals.data(), one.normals.size() * sizeof(Vec3)), 0);
    EXPECT_EQ(one.triangles, two.triangles);
  }
}

// Mesh vertex indices are 32-bit: a resolution whose mesh would need more
// is refused up front (before the int arithmetic of the layout could
// overflow, and before any allocation), and the estimate used for memory
// checks saturates instead of wrapping.
TEST(G1Surface, ResolutionsBeyondThirtyTwoBitMeshesAreRefused) {
  const Surface surface = Surface::build(Network::build(builtinNetwork("pentagon")), {});
  // One pentagon: 1 + 5 (r − 1) + 5 (r − 1)(r − 2) / 2 interior samples,
  // 5 r boundary samples: 40 000 fits 32 bits, 42 000 does not.
  EXPECT_EQ(faceInteriorPoints(surface, 3), 1u + 5 * 2 + 5 * 2 * 1 / 2);
  EXPECT_EQ(estimateMeshVertices(surface, 40000), 5u + 5 * 40000 + 1 + 5 * 39999 + 5ull * 39999 * 39998 / 2);
  for (int r : {42000, 1 << 20, std::numeric_limits<int>::max()}) {
    EXPECT_THROW(tessellate(surface, {r, 1}), InputError) << r;
    EXPECT_THROW(faceInteriorPoints(surface, r), InputError) << r;
  }
  EXPECT_GT(estimateMeshVertices(surface, std::numeric_limits<int>::max()), 1ull << 62);
}

TEST(G1Surface, ReferenceDeviationShrinksWithSmallerPatches) {
  // Two closed convex networks: 12 large pentagons on a sphere vs 32 smaller
  // faces on an ellipsoid of similar size.
  // Linear ribbons interpolate first-order data, so the error must fall
  // markedly when the faces shrink — a regression guard on the ribbons and
  // blends, which would stall the convergence if a term were wrong.
  const Network coarse = Network::build(builtinNetwork("sphere-dodecahedron"));
  const Network fine = Network::build(builtinNetwork("ellipsoid-truncated-icosahedron"));
  for (Scheme scheme : {Scheme::GregoryG1, Scheme::CompositeRibbon}) {
    const auto a = measureReferenceDeviation(Surface::build(coarse, {scheme}), 12);
    const auto b = measureReferenceDeviation(Surface::build(fine, {scheme}), 12);
    ASSERT_TRUE(a && b);
    EXPECT_LT(b->maxDeviation, 0.75 * a->maxDeviation) << schemeName(scheme);
    EXPECT_LT(a->maxDeviation, 0.03) << schemeName(scheme);
  }
}
