// Every input the fuzzers ever found a fault with (tests/fuzz/regressions/
// <harness>/), replayed through the reader and the whole pipeline with every
// scheme and sweep: each must end either in a clean InputError or in finite
// output — never a crash (the sanitizer build runs this too), a hang or NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "curvenet/approximation.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "curvenet/network.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"
#include "scratch.hpp"

using namespace curvenet;
namespace fs = std::filesystem;

namespace {

const fs::path regressions = fs::path(CURVENET_TEST_DATA_DIR).parent_path() / "fuzz" / "regressions";

using test::readFile;

void exercise(const NetworkDescription &description, const std::string &name) {
  Network network;
  try {
    network = Network::build(description, name);
  } catch (const InputError &) {
    return;
  }
  const std::vector<SurfaceOptions> variants = {
      {Scheme::GregoryG1, Sweepline::Radial}, {Scheme::GregoryG1, Sweepline::Hermite},
      {Scheme::CompositeRibbon}, {Scheme::GregoryG2, Sweepline::Hermite}, {Scheme::BezierG1}};
  for (const SurfaceOptions &options : variants) {
    try {
      const Mesh mesh = tessellate(Surface::build(network, options), {3, 1});
      for (const Vec3 &p : mesh.positions) ASSERT_TRUE(std::isfinite(p.x + p.y + p.z)) << name;
      for (const Vec3 &n : mesh.normals) ASSERT_TRUE(std::isfinite(n.x + n.y + n.z)) << name;
    } catch (const InputError &) {
      // a clean refusal is a valid outcome
    }
  }
}

std::vector<fs::path> inputsOf(const std::string &harness) {
  std::vector<fs::path> files;
  if (fs::exists(regressions / harness))
    for (const auto &entry : fs::directory_iterator(regressions / harness)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

} // namespace

TEST(FuzzRegressions, LoopFiles) {
  const auto files = inputsOf("fuzz_lop");
  EXPECT_FALSE(files.empty());
  for (const fs::path &file : files) {
    SCOPED_TRACE(file.filename().string());
    try {
      exercise(parseLop(readFile(file), file.string()), file.string());
    } catch (const InputError &) {
    }
  }
}

TEST(FuzzRegressions, NativeFiles) {
  for (const fs::path &file : inputsOf("fuzz_network_json")) {
    SCOPED_TRACE(file.filename().string());
    try {
      exercise(parseNetworkJson(readFile(file), file.string()), file.string());
    } catch (const InputError &) {
    }
  }
}

TEST(FuzzRegressions, MeshFiles) {
  // As fuzz_mesh: the mesh read, then the pentagon's curves approximated
  // over it. The finding there is a mesh with an unreferenced vertex ~1e82
  // from the rest, whose grid cell overflowed a conversion (undefined: the
  // sanitizer build of this test reports it).
  const auto files = inputsOf("fuzz_mesh");
  EXPECT_FALSE(files.empty());
  const NetworkDescription curves = polylineNetwork(builtinNetwork("pentagon"), 8);
  for (const fs::path &file : files) {
    SCOPED_TRACE(file.filename().string());
    try {
      const Mesh mesh = parseMeshText(readFile(file), file.string());
      ApproximationOptions options;
      options.resolution = 3, options.curvatureSamples = 2, options.threads = 1;
      const ApproximationResult result = approximateMesh(mesh, curves, options);
      for (double figure : {result.g1Deviation.maxAbs, result.g2Deviation.maxAbs, result.curveDistance})
        EXPECT_FALSE(std::isnan(figure));
    } catch (const InputError &) {
    }
  }
}
