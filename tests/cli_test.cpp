// End-to-end tests of the `curvenet` program (docs/design.md §6): the JSON
// report's figures, mesh output, and clear failures on bad input that leave
// no output file behind.
#include <gtest/gtest.h>

#include "cli_support.hpp"
#include "scratch.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <csignal>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

namespace fs = std::filesystem;
using curvenet::test::CliRun;
using curvenet::test::runCli;
using curvenet::test::runCliOnTerminal;
using curvenet::test::readFile;

namespace {

class Cli : public ::testing::Test {
protected:
  void SetUp() override {
    if (std::string(CURVENET_CLI).empty()) GTEST_SKIP() << "the command-line program is not built";
    scratch.emplace();
    dir = scratch->path();
  }
  std::optional<curvenet::test::ScratchDir> scratch;
  fs::path dir;
};

} // namespace

TEST_F(Cli, CheckReportsContinuityAndReferenceFigures) {
  for (const std::string scheme : {"gregory-g1", "composite-ribbon"}) {
    const CliRun run = runCli("check builtin:sphere-dodecahedron --json --samples 16 --resolution 8 --scheme " + scheme);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    EXPECT_EQ(report["scheme"], scheme);
    EXPECT_EQ(report["patches"], 12);
    EXPECT_EQ(report["vertices"].size(), 20u);
    EXPECT_LE(report["continuity"]["max_position_gap"].get<double>(), 1e-12);
    EXPECT_LE(report["continuity"]["max_normal_angle_deg"].get<double>(), 1e-6);
    EXPECT_GE(report["continuity"]["mean_normal_angle_deg"].get<double>(), 0.0);
    EXPECT_EQ(report["continuity"]["shared_segments"], 30);
    const double deviation = report["reference"]["max_deviation"].get<double>();
    EXPECT_GT(deviation, 0.0);
    EXPECT_LT(deviation, 0.05);
    EXPECT_LE(report["reference"]["mean_deviation"].get<double>(), deviation);
    EXPECT_NE(report["reference"]["sampling"].get<std::string>().find("resolution 8"), std::string::npos);
  }
}

TEST_F(Cli, TessellateWritesAClosedMesh) {
  const fs::path out = dir / "torus.obj";
  const CliRun run = runCli("tessellate builtin:torus-mixed --resolution 3 -o '" + out.string() + "'");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  std::ifstream in(out);
  std::string line;
  std::size_t vertices = 0, faces = 0;
  while (std::getline(in, line)) {
    vertices += line.rfind("v ", 0) == 0;
    faces += line.rfind("f ", 0) == 0;
  }
  EXPECT_GT(faces, 0u);
  // A closed triangle mesh of genus 1: V − E + F = 0 with E = 3F/2.
  EXPECT_EQ(static_cast<long>(vertices) - static_cast<long>(faces) / 2, 0);
}

TEST_F(Cli, TessellateToAToleranceReportsWhatItMeasured) {
  const fs::path out = dir / "ellipsoid.obj";
  const CliRun run = runCli("tessellate builtin:ellipsoid-truncated-icosahedron --tolerance 2e-3 --json -o '" +
                            out.string() + "'");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const auto report = nlohmann::json::parse(run.out);
  EXPECT_LE(report["deviation"].get<double>(), 2e-3);
  EXPECT_GT(report["deviation"].get<double>(), 0.0);
  EXPECT_LT(report["triangles"].get<std::size_t>(), report["uniform_triangles"].get<std::size_t>());
  EXPECT_TRUE(fs::exists(out));
  EXPECT_NE(runCli("tessellate builtin:pentagon --angle 5 --json").exitCode, 0); // --angle needs --tolerance
  EXPECT_NE(runCli("tessellate builtin:pentagon").exitCode, 0);                  // neither -o nor --json
}

TEST_F(Cli, BadInputFailsClearlyAndWritesNothing) {
  const fs::path out = dir / "out.obj";
  const fs::path broken = dir / "broken.json";
  std::ofstream(broken) << R"({"curves": [], "faces": [{"sides": [{"curve": 3, "from": 0, "to": 1}]}]})";
  struct Expectation {
    std::string arguments, mentions;
  };
  for (const Expectation &e : std::vector<Expectation>{
           {"tessellate builtin:no-such-network -o '" + out.string() + "'", "no-such-network"},
           {"tessellate builtin:pentagon --scheme no-such-scheme -o '" + out.string() + "'", "no-such-scheme"},
           {"tessellate builtin:pentagon -o '" + (dir / "out.xyz").string() + "'", "out.xyz"},
           {"tessellate '" + broken.string() + "' -o '" + out.string() + "'", "broken.json"},
           {"check '" + (dir / "missing.json").string() + "'", "missing.json"},
       }) {
    const CliRun run = runCli(e.arguments);
    EXPECT_NE(run.exitCode, 0) << e.arguments;
    EXPECT_NE(run.err.find(e.mentions), std::string::npos) << e.arguments << "\nstderr: " << run.err;
    EXPECT_FALSE(fs::exists(out)) << e.arguments;
    EXPECT_FALSE(fs::exists(dir / "out.xyz")) << e.arguments;
  }
}

// Outputs are named only when complete (writeFileAtomically): a tessellation
// killed at any moment — while computing or while writing — leaves the
// output folder exactly as it was, with no partial mesh and no temporary.
TEST_F(Cli, KilledTessellateLeavesNoFile) {
  // One uninterrupted run first: its duration places the kills (tessellation
  // early, the file's writing late, on any machine), and its file is the only
  // thing a killed run may leave behind — the output is linked into place
  // whole, so a kill just after that finds the complete file, never a part.
  const fs::path work = dir / "work", reference = dir / "reference.obj", out = work / "big.obj";
  fs::create_directories(work);
  auto spawn = [&](const fs::path &target) {
    const std::string outPath = target.string();
    const char *argv[] = {CURVENET_CLI, "tessellate", "builtin:ellipsoid-truncated-icosahedron", "--resolution",
                          "64",         "-q",         "-o",  outPath.c_str(), nullptr};
    pid_t pid = 0;
    EXPECT_EQ(::posix_spawn(&pid, CURVENET_CLI, nullptr, nullptr, const_cast<char **>(argv), environ), 0);
    return pid;
  };
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  ::waitpid(spawn(reference), &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string whole = readFile(reference);
  for (double fraction : {0.05, 0.3, 0.6, 0.8, 0.95}) {
    const pid_t pid = spawn(out);
    ::usleep(static_cast<useconds_t>(fraction * seconds * 1e6));
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    if (WIFEXITED(status)) { // finished before the kill: nothing to learn from this one
      fs::remove_all(work), fs::create_directories(work);
      continue;
    }
    for (const auto &entry : fs::directory_iterator(work)) {
      EXPECT_EQ(entry.path(), out) << "after SIGKILL at " << fraction << " of a run the folder holds "
                                   << entry.path().filename();
      EXPECT_TRUE(readFile(entry.path()) == whole) << "after SIGKILL at " << fraction << " of a run "
                                                     << entry.path().filename() << " is not the whole file";
    }
    fs::remove_all(work), fs::create_directories(work);
  }
}

TEST_F(Cli, WorkBeyondTheMachinesMemoryIsRefusedUpFront) {
  const fs::path out = dir / "huge.obj";
  const CliRun run = runCli("tessellate builtin:torus-mixed --resolution 4000 -o '" + out.string() + "'");
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("GiB"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("--resolution 4000"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(out));
}

// Determinism (issue: reliability, item 5): every command that writes a file
// writes the same bytes for 1 and 2 threads, and again on a second run.
TEST_F(Cli, EveryWritingCommandIsDeterministic) {
  struct Case {
    std::string name, arguments, file;
  };
  const std::vector<Case> cases = {
      {"tessellate", "tessellate builtin:torus-mixed --scheme gregory-g2 --resolution 5", "mesh.ply"},
      {"render", "render builtin:pentagon --size 160x120 --resolution 8 --mode mean --boundaries", "picture.exr"},
      {"approximate", "approximate builtin:pentagon builtin:pentagon --resolution 4", "fit.obj"},
  };
  for (const Case &c : cases) {
    std::vector<std::string> outputs;
    for (const std::string threads : {"1", "2", "2"}) {
      const fs::path out = dir / (threads + "-" + std::to_string(outputs.size()) + "-" + c.file);
      const CliRun run = runCli(c.arguments + " --threads " + threads + " -o '" + out.string() + "'");
      ASSERT_EQ(run.exitCode, 0) << c.name << ": " << run.err;
      outputs.push_back(readFile(out));
      ASSERT_FALSE(outputs.back().empty()) << c.name;
    }
    EXPECT_TRUE(outputs[0] == outputs[1]) << c.name << ": 1 vs 2 threads";
    EXPECT_TRUE(outputs[1] == outputs[2]) << c.name << ": two runs";
  }
  // check --tweak writes a repaired network: the same bytes on every run.
  std::vector<std::string> tweaks;
  for (int run = 0; run < 2; ++run) {
    const fs::path out = dir / ("tweak-" + std::to_string(run) + ".json");
    const CliRun r = runCli("check builtin:torus-mixed --samples 2 --resolution 2 --tweak -o '" + out.string() + "'");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    tweaks.push_back(readFile(out));
  }
  EXPECT_TRUE(tweaks[0] == tweaks[1]);
}

// Progress display: a self-overwriting stderr line on a terminal only.
TEST_F(Cli, NoProgressWhenStderrIsNotATerminal) {
  const fs::path mesh = dir / "m.obj", image = dir / "i.png";
  const CliRun tess = runCli("tessellate builtin:pentagon --resolution 24 -o '" + mesh.string() + "'");
  ASSERT_EQ(tess.exitCode, 0) << tess.err;
  EXPECT_EQ(tess.err.find('%'), std::string::npos) << tess.err;
  EXPECT_EQ(tess.err.find('\r'), std::string::npos) << tess.err;
  const CliRun pic = runCli("render builtin:pentagon --size 64x48 --resolution 8 -o '" + image.string() + "'");
  ASSERT_EQ(pic.exitCode, 0) << pic.err;
  EXPECT_EQ(pic.err.find('%'), std::string::npos) << pic.err;
}

TEST_F(Cli, ProgressOnATerminal) {
  const fs::path mesh = dir / "m.obj", image = dir / "i.png";
  const CliRun tess = runCliOnTerminal("tessellate builtin:pentagon --resolution 24 -o '" + mesh.string() + "'");
  ASSERT_EQ(tess.exitCode, 0) << tess.out;
  // The first and the last report always show; the line is erased afterwards.
  EXPECT_NE(tess.out.find("\rtessellate   0%"), std::string::npos) << tess.out;
  EXPECT_NE(tess.out.find("\rtessellate 100%"), std::string::npos) << tess.out;
  EXPECT_NE(tess.out.find("\r\033[K"), std::string::npos) << tess.out;
  EXPECT_NE(tess.out.find("vertices"), std::string::npos) << tess.out; // the result line is still there
  const CliRun pic = runCliOnTerminal("render builtin:pentagon --size 64x48 --resolution 8 -o '" + image.string() + "'");
  ASSERT_EQ(pic.exitCode, 0) << pic.out;
  EXPECT_NE(pic.out.find("\rtessellate 100%"), std::string::npos) << pic.out;
  EXPECT_NE(pic.out.find("\rrender 100%"), std::string::npos) << pic.out;
}

TEST_F(Cli, QuietSilencesProgressOnATerminal) {
  const fs::path mesh = dir / "m.obj", image = dir / "i.png";
  const CliRun tess =
      runCliOnTerminal("tessellate builtin:pentagon --resolution 24 --quiet -o '" + mesh.string() + "'");
  ASSERT_EQ(tess.exitCode, 0) << tess.out;
  EXPECT_EQ(tess.out.find('%'), std::string::npos) << tess.out;
  EXPECT_NE(tess.out.find("vertices"), std::string::npos) << tess.out;
  const CliRun pic = runCliOnTerminal("render builtin:pentagon --size 64x48 --resolution 8 -q -o '" + image.string() + "'");
  ASSERT_EQ(pic.exitCode, 0) << pic.out;
  EXPECT_EQ(pic.out.find('%'), std::string::npos) << pic.out;
  // Every command accepts the flag, so scripts can pass it everywhere.
  for (const char *command : {"list -q", "check builtin:pentagon --quiet --samples 4 --resolution 4",
                              "bench builtin:pentagon --quiet --resolution 4 --points 10 --json"}) {
    const CliRun run = runCli(command);
    EXPECT_EQ(run.exitCode, 0) << command << "\n" << run.err;
  }
}
