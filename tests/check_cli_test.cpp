// `curvenet check` end to end: the JSON fields of the vertex analysis on a
// built-in, the table's verdict line, and the `--tweak -o` round trip on a
// network with perturbed curvatures, read back and re-analysed here.
#include <gtest/gtest.h>

#include "cli_support.hpp"
#include "scratch.hpp"
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "curvenet/analysis.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/io.hpp"
#include "curvenet/network.hpp"
#include "quadric_fans.hpp"

using namespace curvenet;
using namespace curvenet::test;
namespace fs = std::filesystem;

namespace {

class CheckCli : public ::testing::Test {
protected:
  void SetUp() override {
    if (std::string(CURVENET_CLI).empty()) GTEST_SKIP() << "the curvenet program is not built";
    scratch.emplace();
    dir = scratch->path();
  }
  std::optional<ScratchDir> scratch;
  fs::path dir;
};

TEST_F(CheckCli, JsonCarriesTheVertexAnalysisOfABuiltin) {
  const CliRun run = runCli("check builtin:torus-mixed --json");
  ASSERT_EQ(run.exitCode, 0) << run.out;
  const auto report = nlohmann::json::parse(run.out);
  // The network keys stay.
  for (const char *key : {"patches", "segments", "faces_by_sides", "vertices", "diagonal"})
    EXPECT_TRUE(report.contains(key)) << key;
  EXPECT_EQ(report["analysis"]["verdict"], "G2-admissible");
  const Network network = Network::build(builtinNetwork("torus-mixed"));
  const NetworkAnalysis analysis = analyzeNetwork(network);
  ASSERT_EQ(report["vertices"].size(), network.vertices().size());
  for (const auto &v : report["vertices"]) {
    for (const char *key : {"index", "position", "kind", "boundary", "valence", "independent_curves",
                            "enclosure_residual", "euler_residual", "k1", "k2", "lambda", "tangent_residual_deg",
                            "forms_x", "verdict"})
      ASSERT_TRUE(v.contains(key)) << key;
    const VertexAnalysis &va = analysis.vertices.at(v["index"].get<size_t>());
    EXPECT_EQ(v["valence"].get<int>(), va.valence);
    EXPECT_EQ(v["independent_curves"].get<int>(), va.independentCurves);
    EXPECT_EQ(v["k1"].get<double>(), va.fit.tensor.k1);
    EXPECT_EQ(v["k2"].get<double>(), va.fit.tensor.k2);
    EXPECT_LE(v["euler_residual"].get<double>(), 1e-5);
    EXPECT_LE(v["enclosure_residual"].get<double>(), 1e-5);
    EXPECT_EQ(v["verdict"], "G2-admissible");
  }
}

TEST_F(CheckCli, TableEndsWithAOneLineVerdictAndListsWorstFirst) {
  const CliRun run = runCli("check builtin:saddle-nodes");
  ASSERT_EQ(run.exitCode, 0) << run.out;
  EXPECT_NE(run.out.find("worst first"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("verdict: G2-admissible (13 G2-admissible"), std::string::npos) << run.out;
}

TEST_F(CheckCli, TweakWritesARepairedNetworkAtomically) {
  NetworkDescription net;
  net.name = "bent-fan";
  const Quadric quadric;
  addFan(net, quadric, {0, 0, 1, {0, 80, 170, 250}, -1, {1, 1.4, 1, 1}});
  const fs::path input = dir / "bent.json", output = dir / "fixed.json";
  writeFileAtomically(input.string(), [&](std::ostream &out) { out << networkToJson(net); });

  const CliRun table = runCli("check " + input.string());
  ASSERT_EQ(table.exitCode, 0) << table.out;
  EXPECT_NE(table.out.find("verdict: needs-tweaking"), std::string::npos) << table.out;

  const CliRun run = runCli("check " + input.string() + " --tweak -o " + output.string() + " --json");
  ASSERT_EQ(run.exitCode, 0) << run.out;
  const auto report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["analysis"]["verdict"], "needs-tweaking"); // the input's
  const auto &tweak = report["tweak"];
  EXPECT_EQ(tweak["tweaked_vertices"], nlohmann::json::array({0}));
  EXPECT_EQ(tweak["moves"].size(), 4u);
  EXPECT_GT(tweak["max_move_relative"].get<double>(), 0);
  EXPECT_EQ(tweak["verdict_after"], "G2-admissible");
  EXPECT_LE(tweak["max_euler_residual_after"].get<double>(), 1e-10);
  // Only the output file, no temporary left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);

  const Network before = Network::build(net);
  const Network after = Network::build(readNetworkFile(output.string()));
  const VertexAnalysis centre = analyzeVertex(after, 0);
  EXPECT_LE(centre.eulerResidualRelative, 1e-10);
  EXPECT_LE(centre.enclosureResidualRelative, 1e-10);
  ASSERT_EQ(after.vertices().size(), before.vertices().size());
  for (size_t v = 0; v < before.vertices().size(); ++v) {
    EXPECT_LE(norm(after.vertices()[v].position - before.vertices()[v].position), 1e-12);
    for (size_t i = 0; i < before.vertices()[v].tangents.size(); ++i)
      EXPECT_LE(norm(after.vertices()[v].tangents[i] - before.vertices()[v].tangents[i]), 1e-12);
  }

  // Checking the repaired file says so.
  const CliRun again = runCli("check " + output.string());
  EXPECT_NE(again.out.find("verdict: G2-admissible"), std::string::npos) << again.out;
}

TEST_F(CheckCli, TweakNeedsAnOutputAndBadInputIsNamed) {
  EXPECT_EQ(runCli("check builtin:pentagon --tweak").exitCode, 2);
  EXPECT_EQ(runCli("check builtin:pentagon -o x.json").exitCode, 2);
  const CliRun missing = runCli("check " + (dir / "missing.json").string());
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_NE(missing.err.find("missing.json"), std::string::npos) << missing.err;
}

} // namespace

TEST_F(CheckCli, ThreadCountDoesNotChangeTheReport) {
  const CliRun one = runCli("check builtin:pentagon --json --threads 1");
  const CliRun two = runCli("check builtin:pentagon --json --threads 2");
  ASSERT_EQ(one.exitCode, 0) << one.out;
  ASSERT_EQ(two.exitCode, 0) << two.out;
  EXPECT_EQ(one.out, two.out);
  EXPECT_NE(runCli("check builtin:pentagon --threads -1").exitCode, 0);
}

namespace {

/// The sphere dodecahedron with both end tangents of curve 0 turned 2° out
/// of their vertex planes (the second control point rotated about the end).
NetworkDescription turnedDodecahedron() {
  NetworkDescription d = builtinNetwork("sphere-dodecahedron");
  BSplineCurve &c = d.curves[0];
  std::vector<Vec3> p = c.controlPoints();
  const double angle = 2 * std::numbers::pi / 180;
  for (size_t at : {size_t(0), p.size() - 1}) {
    const size_t next = at == 0 ? 1 : p.size() - 2;
    const Vec3 arm = p[next] - p[at], normal = normalized(p[at]); // the sphere's normal
    const Vec3 axis = normalized(cross(arm, normal));
    p[next] = p[at] + arm * std::cos(angle) + cross(axis, arm) * std::sin(angle);
  }
  c = BSplineCurve(c.degree(), c.knots(), std::move(p), c.weights());
  d.reference.reset();
  return d;
}

} // namespace

TEST_F(CheckCli, RepairedCurvesListEveryMoveAndKeptCurvesNone) {
  const fs::path input = dir / "turned.json";
  writeFileAtomically(input.string(), [&](std::ostream &out) { out << networkToJson(turnedDodecahedron()); });
  const CliRun repaired = runCli("check " + input.string() + " --json --scheme gregory-g2");
  ASSERT_EQ(repaired.exitCode, 0) << repaired.err;
  const auto report = nlohmann::json::parse(repaired.out);
  EXPECT_EQ(report["analysis"]["verdict"], "no-tangent-plane"); // the input's
  const auto &moves = report["repair"]["moves"];
  ASSERT_FALSE(moves.empty());
  bool tangent = false, curvature = false;
  for (const auto &m : moves) {
    for (const char *key : {"vertex", "curve", "kind", "size", "size_relative"}) ASSERT_TRUE(m.contains(key)) << key;
    tangent |= m["kind"] == "tangent-plane";
    curvature |= m["kind"] == "curvature";
    EXPECT_LE(m["size_relative"].get<double>(), 0.01);
  }
  EXPECT_TRUE(tangent);
  // Three curves fit Euler's formula exactly, so gregory-g2 needs no tweak here.
  EXPECT_FALSE(curvature);
  // The continuity figures are those of the repaired network: G¹ holds.
  EXPECT_LE(report["continuity"]["max_normal_angle_deg"].get<double>(), 1e-6);

  const CliRun g1 = runCli("check " + input.string() + " --json");
  ASSERT_EQ(g1.exitCode, 0) << g1.err;
  const auto g1Report = nlohmann::json::parse(g1.out); // named: a range-for keeps no temporary alive
  for (const auto &m : g1Report["repair"]["moves"]) EXPECT_EQ(m["kind"], "tangent-plane");

  const CliRun kept = runCli("check " + input.string() + " --json --curves kept");
  ASSERT_EQ(kept.exitCode, 0) << kept.err;
  const auto keptReport = nlohmann::json::parse(kept.out);
  EXPECT_TRUE(keptReport["repair"]["moves"].empty());
  EXPECT_EQ(keptReport["repair"]["curves"], "kept");
  // Without a tangent plane at two vertices the surface cannot be G¹ there.
  EXPECT_GT(keptReport["continuity"]["max_normal_angle_deg"].get<double>(), 0.1);
  EXPECT_NE(runCli("check builtin:pentagon --curves bent").exitCode, 0);
}

TEST_F(CheckCli, ShapeReportAndStrictRefusal) {
  const CliRun good = runCli("check builtin:sphere-dodecahedron --json --scheme gregory-g2");
  ASSERT_EQ(good.exitCode, 0) << good.err;
  const auto goodReport = nlohmann::json::parse(good.out);
  const auto &shape = goodReport["shape"];
  EXPECT_TRUE(shape["acceptable"].get<bool>());
  ASSERT_EQ(shape["faces"].size(), 12u);
  for (const auto &f : shape["faces"]) {
    EXPECT_FALSE(f["folded"].get<bool>());
    EXPECT_LE(f["excursion"].get<double>(), 0.05);
    // gregory-g2 reproduces the sphere caps: κ1² + κ2² = 2/R² against the
    // great circles' 1/R² (gregory-g1's corner twists give 3.7).
    EXPECT_NEAR(f["fairness"].get<double>(), 2.0, 0.1);
  }
  EXPECT_EQ(runCli("check builtin:sphere-dodecahedron --strict").exitCode, 0);

  // The turned network on its curves as given, under gregory-g2: whatever the
  // report says, --strict must agree with it and write nothing on refusal.
  const fs::path input = dir / "turned.json", mesh = dir / "turned.obj";
  writeFileAtomically(input.string(), [&](std::ostream &out) { out << networkToJson(turnedDodecahedron()); });
  const std::string args = input.string() + " --scheme gregory-g2 --curves kept";
  const CliRun report = runCli("check " + args + " --json");
  ASSERT_EQ(report.exitCode, 0) << report.err;
  const bool acceptable = nlohmann::json::parse(report.out)["shape"]["acceptable"].get<bool>();
  const CliRun strict = runCli("tessellate " + args + " --strict --resolution 4 -o " + mesh.string());
  EXPECT_EQ(strict.exitCode, acceptable ? 0 : 1) << strict.err;
  EXPECT_EQ(fs::exists(mesh), acceptable);
  if (!acceptable) {
    EXPECT_NE(strict.err.find("--strict writes nothing"), std::string::npos) << strict.err;
    const CliRun lenient = runCli("tessellate " + args + " --resolution 4 -o " + mesh.string());
    EXPECT_EQ(lenient.exitCode, 0) << lenient.err;
    EXPECT_NE(lenient.err.find("warning"), std::string::npos);
    EXPECT_TRUE(fs::exists(mesh));
    EXPECT_EQ(runCli("check " + args + " --strict").exitCode, 1);
  }
}
