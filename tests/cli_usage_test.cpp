// The command line as a new user meets it (docs/design.md §6): names and numbers
// it does not accept get one short line naming the word, help shows every
// scheme and default, `-` is standard input or output, limits are checked
// before any work, and every kind of mesh file can be read and shown.
#include <gtest/gtest.h>

#include "cli_support.hpp"
#include "scratch.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "curvenet/io.hpp"
#include "curvenet/surface.hpp"

namespace fs = std::filesystem;
using curvenet::test::CliRun;
using curvenet::test::readFile;
using curvenet::test::runCli;

namespace {

class CliUsage : public ::testing::Test {
protected:
  void SetUp() override {
    if (std::string(CURVENET_CLI).empty()) GTEST_SKIP() << "the command-line program is not built";
    scratch.emplace();
    dir = scratch->path();
  }
  std::string path(const std::string &name) const { return "'" + (dir / name).string() + "'"; }
  std::optional<curvenet::test::ScratchDir> scratch;
  fs::path dir;
};

bool contains(const std::string &haystack, const std::string &needle) { return haystack.find(needle) != std::string::npos; }
std::size_t lineCount(const std::string &text) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')); }

} // namespace

TEST_F(CliUsage, UnknownSubcommandIsNamed) {
  const CliRun run = runCli("frobnicate");
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_TRUE(contains(run.err, "unknown subcommand 'frobnicate'")) << run.err;
  EXPECT_TRUE(contains(run.err, "tessellate")) << run.err; // the available ones follow
  EXPECT_EQ(lineCount(run.err), 1u) << run.err;
}

TEST_F(CliUsage, BadNumbersGetOneShortLineNamingTheWord) {
  struct Case {
    std::string arguments, word;
    int exitCode;
  };
  for (const Case &c : std::vector<Case>{
           {"check builtin:pentagon --threads abc", "'abc' is not a whole number", 2},
           {"check builtin:pentagon --threads -1", "-1 is not in [0, 1024]", 2},
           {"tessellate builtin:pentagon -o x.obj --resolution 99999999999999999999", "99999999999999999999", 2},
           {"render builtin:pentagon -o x.png --stripes 1e999", "'1e999' is not a number", 2},
           {"render builtin:pentagon -o x.png --size 100000x100000", "16384", 2},
       }) {
    const CliRun run = runCli(c.arguments);
    EXPECT_EQ(run.exitCode, c.exitCode) << c.arguments << "\n" << run.err;
    EXPECT_TRUE(contains(run.err, c.word)) << c.arguments << "\n" << run.err;
    EXPECT_EQ(lineCount(run.err), 1u) << c.arguments << "\n" << run.err;
    EXPECT_LT(run.err.size(), 160u) << c.arguments << "\n" << run.err;
  }
}

TEST_F(CliUsage, BadOptionValuesAreUsageErrorsNamingTheOption) {
  // Exit 2 as for an unknown option, one line naming the option and the word,
  // and nothing written: the values are checked before any work.
  struct Case {
    std::string arguments, option, word;
  };
  for (const Case &c : std::vector<Case>{
           {"tessellate builtin:pentagon -o " + path("t.obj") + " --scheme nope", "--scheme", "'nope'"},
           {"check builtin:pentagon --masters sideways", "--masters", "'sideways'"},
           {"check builtin:pentagon --curves bent", "--curves", "'bent'"},
           {"check builtin:pentagon --scheme gregory-g1 --masters kept-g1", "--masters", "gregory-g2"},
           {"render builtin:pentagon -o " + path("r.png") + " --mode x", "--mode", "'x'"},
           {"render builtin:pentagon -o " + path("r.png") + " --size 12by5", "--size", "'12by5'"},
           {"render builtin:pentagon -o " + path("r.png") + " --view north", "--view", "'north'"},
           {"tessellate builtin:pentagon --angle 5 --json", "--angle", "--tolerance"},
       }) {
    const CliRun run = runCli(c.arguments);
    EXPECT_EQ(run.exitCode, 2) << c.arguments << "\n" << run.err;
    EXPECT_TRUE(contains(run.err, "usage error: " + c.option)) << c.arguments << "\n" << run.err;
    EXPECT_TRUE(contains(run.err, c.word)) << c.arguments << "\n" << run.err;
    EXPECT_EQ(lineCount(run.err), 1u) << c.arguments << "\n" << run.err;
  }
  EXPECT_FALSE(fs::exists(dir / "t.obj"));
  EXPECT_FALSE(fs::exists(dir / "r.png"));
}

TEST_F(CliUsage, HelpListsEverySchemeAndEveryDefault) {
  for (const std::string command : {"tessellate", "render", "check"}) {
    const CliRun run = runCli(command + " --help");
    ASSERT_EQ(run.exitCode, 0) << command;
    for (curvenet::Scheme scheme : curvenet::availableSchemes())
      EXPECT_TRUE(contains(run.out, curvenet::schemeName(scheme))) << command << " --help leaves out " << curvenet::schemeName(scheme);
    EXPECT_TRUE(contains(run.out, "=gregory-g1")) << command; // the default scheme
  }
  struct Default {
    std::string command, shown;
  };
  for (const Default &d : std::vector<Default>{{"tessellate", "=16"},
                                               {"render", "=32"},
                                               {"render", "=reflection"},
                                               {"render", "=800x600"},
                                               {"bench", "=256"},
                                               {"bench", "=builtin:pentagon"},
                                               {"demo", "=demo-output"},
                                               {"check", "=64"}}) {
    const CliRun run = runCli(d.command + " --help");
    EXPECT_TRUE(contains(run.out, d.shown)) << d.command << " --help does not show " << d.shown << "\n" << run.out;
  }
}

TEST_F(CliUsage, CheckAndApproximateRefuseWorkBeyondTheMachinesMemoryUpFront) {
  struct Case {
    std::string arguments, option;
  };
  for (const Case &c : std::vector<Case>{
           {"check builtin:torus-mixed --resolution 4096", "--resolution 4096"},
           {"approximate builtin:torus-mixed builtin:torus-mixed --resolution 1024 -o " + path("a.obj"), "--resolution 1024"},
       }) {
    const auto start = std::chrono::steady_clock::now();
    const CliRun run = runCli(c.arguments);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(run.exitCode, 1) << c.arguments << "\n" << run.err;
    EXPECT_TRUE(contains(run.err, "GiB")) << run.err; // the estimate
    EXPECT_TRUE(contains(run.err, c.option)) << run.err;
    EXPECT_LT(seconds, 20.0) << c.arguments << ": refused only after working";
  }
  EXPECT_FALSE(fs::exists(dir / "a.obj"));
}

TEST_F(CliUsage, DashIsStandardInputAndOutput) {
  // A mesh to standard output needs its format; the summary line moves to stderr.
  const CliRun noFormat = runCli("tessellate builtin:pentagon -o -");
  EXPECT_EQ(noFormat.exitCode, 1);
  EXPECT_TRUE(contains(noFormat.err, "--format")) << noFormat.err;
  const CliRun obj = runCli("tessellate builtin:pentagon --resolution 3 -o - --format obj");
  ASSERT_EQ(obj.exitCode, 0) << obj.err;
  const curvenet::Mesh piped = curvenet::parseObjMesh(obj.out, "stdout");
  EXPECT_TRUE(contains(obj.err, "triangles")) << obj.err;
  ASSERT_EQ(runCli("tessellate builtin:pentagon --resolution 3 -o " + path("file.obj")).exitCode, 0);
  const curvenet::Mesh file = curvenet::readMeshFile((dir / "file.obj").string());
  EXPECT_EQ(piped.positions.size(), file.positions.size());
  EXPECT_EQ(piped.triangles, file.triangles);
  // A network on standard input, native or .lop, gives the report of the file.
  for (const std::string name : {"quarter-sphere.json", "triangle.lop"}) {
    const std::string source = (fs::path(CURVENET_TEST_DATA_DIR) / name).string();
    const CliRun fromFile = runCli("check --json --samples 8 --resolution 4 '" + source + "'");
    const CliRun fromPipe = runCli("check --json --samples 8 --resolution 4 - < '" + source + "'");
    ASSERT_EQ(fromPipe.exitCode, 0) << name << ": " << fromPipe.err;
    auto a = nlohmann::json::parse(fromFile.out), b = nlohmann::json::parse(fromPipe.out);
    EXPECT_EQ(a["continuity"], b["continuity"]) << name;
    EXPECT_EQ(b["input"], "-");
  }
  // A mesh on standard input, its format read from the content.
  const CliRun render = runCli("render - -q -o " + path("r.png") + " --size 64x48 < " + path("file.obj"));
  EXPECT_EQ(render.exitCode, 0) << render.err;
  EXPECT_TRUE(contains(render.out, std::to_string(file.triangles.size()) + " triangles")) << render.out;
}

TEST_F(CliUsage, FileSystemMistakesAreErrorsNotInternalOnes) {
  std::ofstream(dir / "a-file") << "x";
  const CliRun demo = runCli("demo -q --out " + path("a-file"));
  EXPECT_EQ(demo.exitCode, 1);
  EXPECT_TRUE(contains(demo.err, "a-file")) << demo.err;
  EXPECT_FALSE(contains(demo.err, "internal")) << demo.err;
  const CliRun tweak = runCli("check builtin:pentagon --tweak -o " + path("x.obj"));
  EXPECT_EQ(tweak.exitCode, 1);
  EXPECT_TRUE(contains(tweak.err, ".json")) << tweak.err;
  EXPECT_FALSE(fs::exists(dir / "x.obj"));
}

TEST_F(CliUsage, ApproximateReadsItsOwnPlyOutputAndStl) {
  const std::string base = "approximate builtin:hemisphere-tjunction builtin:hemisphere-tjunction --resolution 6 -q";
  ASSERT_EQ(runCli(base + " -o " + path("g2.ply")).exitCode, 0);
  const curvenet::Mesh g2 = curvenet::readMeshFile((dir / "g2.ply").string());
  EXPECT_GT(g2.triangles.size(), 100u);
  // As STL (ASCII) too: the triangles' corners merge back into shared vertices.
  std::ofstream stl(dir / "g2.stl");
  stl.precision(17);
  stl << "solid g2\n";
  for (const auto &t : g2.triangles) {
    stl << "facet normal 0 0 0\nouter loop\n";
    for (std::uint32_t v : t) stl << "vertex " << g2.positions[v].x << ' ' << g2.positions[v].y << ' ' << g2.positions[v].z << '\n';
    stl << "endloop\nendfacet\n";
  }
  stl << "endsolid g2\n";
  stl.close();
  for (const std::string input : {"g2.ply", "g2.stl"}) {
    const CliRun run = runCli("approximate " + path(input) + " builtin:hemisphere-tjunction --resolution 6 -q -o " +
                              path("again.obj") + " --report " + path("again.json"));
    ASSERT_EQ(run.exitCode, 0) << input << ": " << run.err;
    const auto report = nlohmann::json::parse(readFile(dir / "again.json"));
    EXPECT_EQ(report["mesh"]["triangles"].get<std::size_t>(), g2.triangles.size()) << input;
    EXPECT_GT(report["g2"]["deviation"]["samples"].get<std::size_t>(), 0u) << input;
  }
}

TEST_F(CliUsage, ApproximateWarnsWhenCurvesAndMeshAreApartAndRefusesNoSamples) {
  const std::string write = "approximate builtin:hemisphere-tjunction builtin:hemisphere-tjunction --resolution 4 -q "
                            "--write-inputs " + path("in") + " -o " + path("ignored.obj");
  ASSERT_EQ(runCli(write).exitCode, 0);
  const fs::path meshFile = dir / "in" / "hemisphere-tjunction-mesh.obj", curves = dir / "in" / "hemisphere-tjunction-curves.json";
  ASSERT_TRUE(fs::exists(meshFile) && fs::exists(curves));
  const curvenet::Mesh mesh = curvenet::readMeshFile(meshFile.string());
  auto moved = [&](double dz, const std::string &name) {
    curvenet::Mesh m = mesh;
    for (curvenet::Vec3 &p : m.positions) p.z += dz;
    curvenet::writeMeshFile(m, (dir / name).string());
    return runCli("approximate " + path(name) + " '" + curves.string() + "' --resolution 4 -q -o " + path(name + ".out.obj"));
  };
  const CliRun near = moved(0, "near.obj");
  ASSERT_EQ(near.exitCode, 0) << near.err;
  EXPECT_FALSE(contains(near.err, "warning")) << near.err;
  const CliRun apart = moved(0.05, "apart.obj"); // the hemisphere's diagonal is about 2.4
  EXPECT_EQ(apart.exitCode, 0) << apart.err;
  EXPECT_TRUE(contains(apart.err, "warning") && contains(apart.err, "away from the mesh")) << apart.err;
  const CliRun far = moved(100, "far.obj");
  EXPECT_EQ(far.exitCode, 1) << far.out;
  EXPECT_TRUE(contains(far.err, "0 samples") && contains(far.err, "far.obj")) << far.err;
  EXPECT_FALSE(fs::exists(dir / "far.obj.out.obj"));
}

TEST_F(CliUsage, RenderShowsAMeshFile) {
  ASSERT_EQ(runCli("tessellate builtin:hemisphere-tjunction --resolution 6 -o " + path("h.ply")).exitCode, 0);
  const CliRun run = runCli("render " + path("h.ply") + " -o " + path("h.png") + " --size 96x72 -q");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_TRUE(fs::exists(dir / "h.png"));
  EXPECT_TRUE(contains(run.out, "triangles")) << run.out;
  const CliRun curvature = runCli("render " + path("h.ply") + " -o " + path("m.png") + " --mode mean");
  EXPECT_EQ(curvature.exitCode, 1);
  EXPECT_TRUE(contains(curvature.err, "needs a network")) << curvature.err;
}

TEST_F(CliUsage, ListAlignsItsColumnsAndSpeaksJson) {
  const CliRun table = runCli("list");
  ASSERT_EQ(table.exitCode, 0);
  std::istringstream lines(table.out);
  std::string line;
  std::optional<std::size_t> facesEnd;
  std::size_t rows = 0;
  while (std::getline(lines, line)) {
    if (!line.starts_with("builtin:")) continue;
    // The faces column ends where the two spaces before "sides: faces" begin.
    const std::size_t end = line.find("  ", line.find_first_not_of(' ', line.find(' ')));
    if (!facesEnd) facesEnd = end;
    EXPECT_EQ(end, *facesEnd) << line;
    ++rows;
  }
  const CliRun json = runCli("list --json");
  ASSERT_EQ(json.exitCode, 0);
  const auto list = nlohmann::json::parse(json.out);
  EXPECT_EQ(list["builtins"].size(), rows);
  for (const auto &b : list["builtins"]) {
    int faces = 0;
    for (const auto &[sides, count] : b["faces_by_sides"].items()) faces += count.get<int>();
    EXPECT_EQ(faces, b["faces"].get<int>()) << b["input"];
  }
}

// The patches refuse a face's geometry naming the face; the command adds the file.
TEST_F(CliUsage, AFaceRefusedByItsGeometryNamesTheFile) {
  // Three collinear lines: the loop folds back on itself at a corner (a cusp).
  std::ofstream(dir / "flat.lop") << "3\n1\n4 0 0 1 1\n2 0 0 0 1 0 0\n1\n4 0 0 1 1\n2 1 0 0 2 0 0\n"
                                      "1\n4 0 0 1 1\n2 2 0 0 0 0 0\n";
  for (const std::string &command : std::vector<std::string>{"check", "tessellate -o " + path("f.obj"), "render -o " + path("f.png")}) {
    const CliRun run = runCli(command + " " + path("flat.lop"));
    EXPECT_EQ(run.exitCode, 1) << command;
    EXPECT_TRUE(contains(run.err, "flat.lop: face 0") && contains(run.err, "cusp")) << command << "\n" << run.err;
  }
}

// The vertex analysis refuses a curve end without speed naming the vertex; check adds the file.
TEST_F(CliUsage, AVertexRefusedByTheAnalysisNamesTheFile) {
  // Curve 0 starts with a repeated control point: zero speed at vertex 0.
  std::ofstream(dir / "still.lop") << "3\n3\n8 0 0 0 0 1 1 1 1\n4 0 0 0 0 0 0 0.6 0.1 0 1 0 0\n"
                                       "1\n4 0 0 1 1\n2 1 0 0 0.5 1 0\n1\n4 0 0 1 1\n2 0.5 1 0 0 0 0\n";
  const CliRun run = runCli("check " + path("still.lop"));
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_TRUE(contains(run.err, "still.lop: vertex 0") && contains(run.err, "zero speed")) << run.err;
}

TEST_F(CliUsage, CountsAgreeWithTheirNouns) {
  const CliRun run = runCli("check builtin:pentagon --samples 4 --resolution 2");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_TRUE(contains(run.out, "1 patch,")) << run.out;
  EXPECT_FALSE(contains(run.out, "1 patches")) << run.out;
}
