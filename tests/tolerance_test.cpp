// Tessellation to a chordal tolerance (TessellationOptions::tolerance):
// the mesh meets the tolerance by an independent measurement, stays
// watertight where neighbouring faces take different resolutions, needs
// fewer triangles than the uniform resolution that meets the same
// tolerance, and that uniform resolution is the smallest that does.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>

#include "curvenet/builtins.hpp"
#include "curvenet/error.hpp"
#include "curvenet/network.hpp"
#include "curvenet/sketch.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"

using namespace curvenet;

namespace {

struct Case {
  std::string builtin;
  Scheme scheme;
  double tolerance, angle;
};

std::string caseName(const testing::TestParamInfo<Case> &info) {
  std::string name = info.param.builtin + "_" + schemeName(info.param.scheme) + (info.param.angle > 0 ? "_angle" : "");
  for (char &c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

class ToleranceTessellation : public testing::TestWithParam<Case> {};

TEST_P(ToleranceTessellation, MeetsTheToleranceWatertightWithFewerTrianglesThanUniform) {
  const Case c = GetParam();
  const Network network = Network::build(builtinNetwork(c.builtin));
  const Surface surface = Surface::build(network, {c.scheme});
  TessellationOptions options;
  options.tolerance = c.tolerance, options.angle = c.angle, options.recordDomainPoints = true;
  TessellationReport report;
  const Mesh mesh = tessellate(surface, options, report);
  const double target = c.tolerance * network.diagonal();

  EXPECT_LE(report.deviation, c.tolerance);
  if (c.angle > 0) EXPECT_LE(report.angle, c.angle);
  EXPECT_EQ(report.triangles, mesh.triangles.size());
  // Faces of different resolutions meet, so the watertightness below covers them.
  EXPECT_LT(report.minResolution, report.maxResolution);

  // Independently of the report: the exact surface at the centroid of every
  // triangle whose vertices all carry its own face's domain points (the
  // interior ones), against the mesh.
  double centroidDeviation = 0;
  std::size_t checked = 0;
  for (int f = 0; f < surface.faceCount(); ++f)
    for (std::uint32_t t = mesh.faceTriangleStart[f]; t < mesh.faceTriangleStart[f + 1]; ++t) {
      const auto &tri = mesh.triangles[t];
      if (mesh.domainPoints[tri[0]].face != f || mesh.domainPoints[tri[1]].face != f ||
          mesh.domainPoints[tri[2]].face != f)
        continue;
      const Vec2 centre =
          (mesh.domainPoints[tri[0]].uv + mesh.domainPoints[tri[1]].uv + mesh.domainPoints[tri[2]].uv) * (1.0 / 3);
      const Vec3 flat = (mesh.positions[tri[0]] + mesh.positions[tri[1]] + mesh.positions[tri[2]]) * (1.0 / 3);
      centroidDeviation = std::max(centroidDeviation, norm(surface.evaluate(f, centre).point - flat));
      ++checked;
    }
  EXPECT_GT(checked, mesh.triangles.size() / 2);
  EXPECT_LE(centroidDeviation, target);

  // Watertight: the network is closed, so every edge joins exactly two
  // triangles, which run it in opposite directions.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses, forward;
  for (const auto &t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
      if (a < b) ++forward[{a, b}];
    }
  for (const auto &[edge, count] : uses) {
    ASSERT_EQ(count, 2) << "edge " << edge.first << "-" << edge.second;
    ASSERT_EQ(forward[edge], 1) << "edge " << edge.first << "-" << edge.second;
  }

  // The uniform comparison: fewer triangles here; its count is that of the
  // uniform mesh, which meets the limits, and one resolution less does not.
  EXPECT_LT(report.triangles, report.uniformTriangles);
  TessellationReport uniform, coarser;
  EXPECT_EQ(tessellate(surface, {report.uniformResolution}, uniform).triangles.size(), report.uniformTriangles);
  EXPECT_LE(uniform.deviation, c.tolerance);
  tessellate(surface, {report.uniformResolution - 1}, coarser);
  EXPECT_TRUE(coarser.deviation > c.tolerance || (c.angle > 0 && coarser.angle > c.angle))
      << coarser.deviation << " at uniform resolution " << report.uniformResolution - 1;
}

INSTANTIATE_TEST_SUITE_P(Builtins, ToleranceTessellation,
                         testing::Values(Case{"ellipsoid-truncated-icosahedron", Scheme::GregoryG1, 1e-3, 0},
                                         Case{"ellipsoid-truncated-icosahedron", Scheme::GregoryG2, 2e-3, 0},
                                         Case{"ellipsoid-truncated-icosahedron", Scheme::CompositeRibbon, 2e-3, 0},
                                         Case{"torus-mixed", Scheme::GregoryG1, 1e-2, 30}),
                         caseName);

// A real sketch whose faces meet at creases (box.obj: a box's 90° edges
// among its segments). A vertex on a crease is shared by both faces and
// carries one face's normal; measured against it, the other face's
// neighbouring normals differ by the crease's angle at every resolution,
// and the tolerance loop once drove such faces towards resolution 4096
// until the memory ran out. The angle is each face's own: the limit is met
// with no face given up on, within the memory, and the crease is really
// there in the mesh's normals.
TEST(ToleranceTessellation, CreasesOfARealSketchAreNotNormalAngles) {
  const std::string box = std::string(CURVENET_SHARED_DATA_DIR) + "/sketches/box.obj";
  if (!std::filesystem::exists(box)) GTEST_SKIP() << box << " is absent: no sketch with creases";
  const Network network = Network::build(networkFromCurveGraph(readCurveGraphFile(box), {}, box).description);
  const Surface surface = Surface::build(network, {Scheme::GregoryG1});
  TessellationOptions options;
  options.tolerance = 1e-3, options.angle = 15, options.recordDomainPoints = true;
  TessellationReport report;
  const Mesh mesh = tessellate(surface, options, report);
  EXPECT_TRUE(report.met);
  EXPECT_FALSE(report.memoryLimited);
  EXPECT_TRUE(report.angleUnreachableFaces.empty());
  EXPECT_LE(report.deviation, options.tolerance);
  EXPECT_LE(report.angle, options.angle);
  EXPECT_LT(report.maxResolution, 256);
  EXPECT_LT(report.triangles, report.uniformTriangles);
  // Independently: between two vertices of one face's interior, the mesh's
  // own normals keep the limit; across the creases they do not.
  double inside = 0, across = 0;
  for (int f = 0; f < surface.faceCount(); ++f)
    for (std::uint32_t t = mesh.faceTriangleStart[f]; t < mesh.faceTriangleStart[f + 1]; ++t)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
        const double angle = std::acos(std::clamp(dot(mesh.normals[a], mesh.normals[b]), -1.0, 1.0)) * 180 / std::numbers::pi;
        const bool own = mesh.domainPoints[a].face == f && mesh.domainPoints[b].face == f;
        (own ? inside : across) = std::max(own ? inside : across, angle);
      }
  EXPECT_LE(inside, options.angle);
  EXPECT_GT(across, 45.0) << "the sketch's creases";
}

TEST(ToleranceTessellation, BadLimitsAreRefused) {
  const Surface surface = Surface::build(Network::build(builtinNetwork("pentagon")));
  TessellationOptions options;
  options.tolerance = 2;
  EXPECT_THROW(tessellate(surface, options), InputError);
  options.tolerance = 1e-3, options.angle = 120;
  EXPECT_THROW(tessellate(surface, options), InputError);
}

} // namespace
