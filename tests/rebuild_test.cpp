// Surface construction in parallel and after edits: the same bits for any
// thread count, and a partial rebuild after moving a curve equal to a full
// build of the edited network, rebuilding only the faces near the edit.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "bezier/bezier_surface.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/error.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"

using namespace curvenet;

namespace {

/// Sample points of face f: the centre, points towards every corner and
/// along every side (inside the domain).
std::vector<Vec2> facePoints(const Surface &surface, int f) {
  std::vector<Vec2> points{{0, 0}};
  const int n = surface.domainSides(f);
  for (int i = 0; i < n; ++i) {
    const Vec2 a = surface.domainCorner(f, i), b = surface.domainCorner(f, i + 1);
    for (double w : {0.3, 0.7, 0.95}) points.push_back(a * w);
    for (double t : {0.25, 0.5}) points.push_back((a + (b - a) * t) * 0.9);
  }
  return points;
}

/// Every face's evaluation at facePoints, bit for bit.
void expectSameSurface(const Surface &a, const Surface &b, const std::string &what) {
  ASSERT_EQ(a.faceCount(), b.faceCount()) << what;
  for (int f = 0; f < a.faceCount(); ++f)
    for (const Vec2 &uv : facePoints(a, f)) {
      const SurfacePoint p = a.evaluate(f, uv), q = b.evaluate(f, uv);
      ASSERT_EQ(p.point, q.point) << what << " face " << f << " at (" << uv.x << ", " << uv.y << ")";
      ASSERT_EQ(p.du, q.du) << what << " face " << f;
      ASSERT_EQ(p.dv, q.dv) << what << " face " << f;
    }
  EXPECT_EQ(a.foldedFaces(), b.foldedFaces()) << what;
}

Surface buildWithThreads(const Network &network, const SurfaceOptions &options, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  return Surface::build(network, options);
}

/// The description with the interior control points of curve c moved by
/// `offset` (the ends stay, so the loops still close the same way), or only
/// its middle control point (a local change on a long spline that passes
/// through several vertices).
NetworkDescription movedCurve(NetworkDescription description, int c, const Vec3 &offset, bool middleOnly = false) {
  const BSplineCurve &curve = description.curves[c];
  std::vector<Vec3> points = curve.controlPoints();
  for (std::size_t k = 1; k + 1 < points.size(); ++k)
    if (!middleOnly || k == points.size() / 2) points[k] += offset;
  description.curves[c] = BSplineCurve(curve.degree(), curve.knots(), std::move(points), curve.weights());
  return description;
}

} // namespace

TEST(ParallelBuild, OneAndTwoThreadsGiveTheSameSurface) {
  for (const char *name : {"ellipsoid-truncated-icosahedron", "saddle-nodes", "concave-L"}) {
    const Network network = Network::build(builtinNetwork(name));
    for (SurfaceOptions options : {SurfaceOptions{Scheme::GregoryG1}, SurfaceOptions{Scheme::CompositeRibbon},
                                   SurfaceOptions{Scheme::GregoryG2},
                                   SurfaceOptions{Scheme::GregoryG2, Sweepline::Auto, FenceNormals::Curves,
                                                  EdgeCurvature::MasterSlave}}) {
      const std::string what = std::string(name) + " " + schemeName(options.scheme);
      expectSameSurface(buildWithThreads(network, options, 1), buildWithThreads(network, options, 2), what);
    }
  }
}

TEST(PartialRebuild, MovingOneEdgeRebuildsTheFourFacesAroundIt) {
  // On the truncated icosahedron every vertex has valence 3: moving one edge
  // curve changes its two end vertices, the five segments there and the four
  // faces touching them (the two along the edge and one more at each end).
  const NetworkDescription description = builtinNetwork("ellipsoid-truncated-icosahedron");
  const Network network = Network::build(description);
  const int curve = network.segments()[0].sourceCurve;
  int segmentsOfCurve = 0;
  for (const Segment &seg : network.segments()) segmentsOfCurve += seg.sourceCurve == curve;
  ASSERT_EQ(segmentsOfCurve, 1) << "the test edits one edge";
  const Network edited = Network::build(movedCurve(description, curve, {0.0, 0.0, 0.02}));

  for (SurfaceOptions options : {SurfaceOptions{Scheme::GregoryG2}, SurfaceOptions{Scheme::GregoryG1},
                                 SurfaceOptions{Scheme::CompositeRibbon}}) {
    // On the curves as given: the move turns the edge's end tangents out of
    // their planes, and the vertex repair would mend its neighbours too.
    options.curves = CurveHandling::Kept;
    const std::string what = schemeName(options.scheme);
    const Surface before = Surface::build(network, options);
    const SurfaceEdit edit = before.rebuildAfterEdit(edited);
    EXPECT_TRUE(edit.partial) << what;

    std::set<int> expected;
    const Segment &seg = network.segments()[0];
    for (int v : {seg.start, seg.end})
      for (int e : network.vertices()[v].segments)
        for (int f : network.segments()[e].faces) expected.insert(f);
    EXPECT_EQ(expected.size(), 4u);
    EXPECT_EQ(std::vector<int>(expected.begin(), expected.end()), edit.changedFaces) << what;

    // Unchanged faces keep the old patch object; changed ones have a new one.
    for (int f = 0; f < before.faceCount(); ++f) {
      const bool reused = SurfaceAccess::patch(before, f) == SurfaceAccess::patch(edit.surface, f);
      EXPECT_EQ(reused, !expected.count(f)) << what << " face " << f;
    }
    // Bit for bit what a full build of the edited network gives, and not
    // the old surface (the edit is visible).
    expectSameSurface(edit.surface, Surface::build(edited, options), what);
    const int f = *expected.begin();
    EXPECT_NE(before.evaluate(f, {0, 0}).point, edit.surface.evaluate(f, {0, 0}).point) << what;
  }
}

TEST(PartialRebuild, MeasuredEdgeCurvatureReachesOneRingFurther) {
  // Master–slave measures κ_D on the G¹ patches: a segment's curvature
  // changes when a G¹ patch next to it does, so the faces around those
  // patches are rebuilt too — and the result is still a full build's.
  const NetworkDescription description = builtinNetwork("ellipsoid-truncated-icosahedron");
  const Network network = Network::build(description);
  const int curve = network.segments()[0].sourceCurve;
  const Network edited = Network::build(movedCurve(description, curve, {0.0, 0.0, 0.02}));
  // On the curves as given (see MovingOneEdgeRebuildsTheFourFacesAroundIt).
  const CurveHandling kept = CurveHandling::Kept;
  const SurfaceOptions options{Scheme::GregoryG2,       Sweepline::Auto,      FenceNormals::Curves,
                               EdgeCurvature::MasterSlave, MasterFaces::Rebuilt, kept};
  const Surface before = Surface::build(network, options);
  const SurfaceEdit edit = before.rebuildAfterEdit(edited);
  ASSERT_TRUE(edit.partial);
  const SurfaceEdit direct =
      Surface::build(network, {Scheme::GregoryG2, Sweepline::Auto, FenceNormals::Auto, EdgeCurvature::Direct,
                               MasterFaces::Rebuilt, kept})
          .rebuildAfterEdit(edited);
  EXPECT_GT(edit.changedFaces.size(), direct.changedFaces.size());
  EXPECT_LT(static_cast<int>(edit.changedFaces.size()), before.faceCount() + 1);
  expectSameSurface(edit.surface, Surface::build(edited, options), "master-slave");
}

// One test per network, so that the suite's parallel runner can spread them.
class PartialRebuildOf : public testing::TestWithParam<const char *> {};

TEST_P(PartialRebuildOf, CurvesOfTransfiniteBuiltinsMatchAFullBuild) {
  // A moved control point anywhere (T-nodes, X-nodes, 2-sided faces,
  // connection curves, boundaries, long splines through several vertices):
  // the rebuild equals a full one. Edits that change the topology (a curve
  // no longer meeting another where it did) fall back to a full build; each
  // network must see some partial ones.
  {
    const char *name = GetParam();
    const NetworkDescription description = builtinNetwork(name);
    const Network network = Network::build(description);
    const Surface before = Surface::build(network, {Scheme::GregoryG2});
    int partial = 0;
    const int curves = static_cast<int>(description.curves.size()), step = curves > 12 ? 3 : 1;
    for (int c = 0; c < curves; c += step) {
      std::optional<Network> edited;
      try {
        edited = Network::build(movedCurve(description, c, {0.0, 0.0, 0.003}, true));
      } catch (const InputError &) {
        continue; // the move broke a loop: no surface to compare
      }
      const SurfaceEdit edit = before.rebuildAfterEdit(*edited);
      if (edit.partial) {
        ++partial;
        if (before.faceCount() > 4) {
          EXPECT_LT(static_cast<int>(edit.changedFaces.size()), before.faceCount()) << name << " curve " << c;
        }
      }
      expectSameSurface(edit.surface, Surface::build(*edited, {Scheme::GregoryG2}),
                        std::string(name) + " curve " + std::to_string(c));
    }
    EXPECT_GT(partial, 0) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(Builtins, PartialRebuildOf,
                         testing::Values("saddle-nodes", "concave-L", "sphere-dodecahedron", "torus-mixed"),
                         [](const testing::TestParamInfo<const char *> &param) {
                           std::string name = param.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(PartialRebuild, TopologyChangeFallsBackToAFullBuild) {
  const NetworkDescription description = builtinNetwork("pentagon");
  const Network network = Network::build(description);
  const Surface before = Surface::build(network, {Scheme::GregoryG1});
  const SurfaceEdit edit = before.rebuildAfterEdit(Network::build(builtinNetwork("sphere-dodecahedron")));
  EXPECT_FALSE(edit.partial);
  EXPECT_EQ(edit.changedFaces.size(), 12u);
  EXPECT_EQ(edit.surface.faceCount(), 12);
}

TEST(PartialRebuild, RetessellatingTheChangedFacesEqualsAFullTessellation) {
  // saddle-nodes has T-nodes, an X-node and a 2-sided face; each edit keeps
  // the topology, and the updated mesh equals a fresh one byte for byte.
  const NetworkDescription description = builtinNetwork("saddle-nodes");
  const Network network = Network::build(description);
  for (SurfaceOptions options : {SurfaceOptions{Scheme::GregoryG2}, SurfaceOptions{Scheme::CompositeRibbon}}) {
    const Surface before = Surface::build(network, options);
    for (int c : {2, 7, 8}) {
      const Network edited = Network::build(movedCurve(description, c, {0.0, 0.0, 0.003}, true));
      const SurfaceEdit edit = before.rebuildAfterEdit(edited);
      ASSERT_TRUE(edit.partial);
      for (bool record : {false, true}) {
        const TessellationOptions tess{.resolution = 12, .threads = 2, .recordDomainPoints = record};
        Mesh mesh = tessellate(before, tess);
        retessellateFaces(edit.surface, edit.changedFaces, mesh, tess);
        const Mesh fresh = tessellate(Surface::build(edited, options), tess);
        EXPECT_EQ(mesh.positions, fresh.positions) << schemeName(options.scheme) << " curve " << c;
        EXPECT_EQ(mesh.normals, fresh.normals) << schemeName(options.scheme) << " curve " << c;
        EXPECT_EQ(mesh.triangles, fresh.triangles) << schemeName(options.scheme) << " curve " << c;
        EXPECT_EQ(mesh.faceTriangleStart, fresh.faceTriangleStart);
        ASSERT_EQ(mesh.domainPoints.size(), fresh.domainPoints.size());
        for (std::size_t v = 0; v < mesh.domainPoints.size(); ++v)
          ASSERT_TRUE(mesh.domainPoints[v].face == fresh.domainPoints[v].face &&
                      mesh.domainPoints[v].uv == fresh.domainPoints[v].uv);
      }
    }
  }
}
