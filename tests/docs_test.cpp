// The examples of docs/network-format.md are real files: each one parses,
// builds a network and surfaces that do not fold, and an example that names
// a reference surface has its curves on that surface.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "curvenet/continuity.hpp"
#include "curvenet/io.hpp"
#include "curvenet/master_contact.hpp"
#include "curvenet/network.hpp"
#include "curvenet/surface.hpp"

namespace fs = std::filesystem;
using namespace curvenet;

namespace {

const fs::path formatDocument = fs::path(CURVENET_TEST_DATA_DIR).parent_path().parent_path() / "docs" / "network-format.md";

struct Example {
  std::string language; ///< the fence's info string: json or lop
  std::string text;
  int line = 0;         ///< where the fence opens, 1-based
};

/// Every fenced block of the document whose info string is json or lop.
std::vector<Example> examples() {
  std::ifstream in(formatDocument);
  EXPECT_TRUE(in) << "cannot read " << formatDocument;
  std::vector<Example> found;
  std::optional<Example> open;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (open) {
      if (line == "```") found.push_back(*open), open.reset();
      else open->text += line + "\n";
    } else if (line == "```json" || line == "```lop") {
      open = Example{line.substr(3), {}, number};
    }
  }
  EXPECT_FALSE(open) << "unterminated example at line " << open->line;
  return found;
}

NetworkDescription parse(const Example &example) {
  const std::string where = "docs/network-format.md line " + std::to_string(example.line);
  return example.language == "json" ? parseNetworkJson(example.text, where) : parseLop(example.text, where);
}

} // namespace

TEST(NetworkFormatDocument, HasAnExampleOfEachFormat) {
  int json = 0, lop = 0;
  for (const Example &example : examples()) (example.language == "json" ? json : lop) += 1;
  EXPECT_GE(json, 1);
  EXPECT_GE(lop, 1);
}

TEST(NetworkFormatDocument, EveryExampleBuildsSurfacesThatDoNotFold) {
  for (const Example &example : examples()) {
    SCOPED_TRACE("example at line " + std::to_string(example.line));
    const Network network = Network::build(parse(example));
    for (Scheme scheme : {Scheme::GregoryG1, Scheme::CompositeRibbon, Scheme::GregoryG2}) {
      const Surface surface = Surface::build(network, {scheme});
      EXPECT_TRUE(surface.foldedFaces().empty()) << schemeName(scheme);
      EXPECT_LT(measureContinuity(surface).maxBoundaryDeviation, 1e-12) << schemeName(scheme);
    }
  }
}

// The example's curves are exact arcs of its reference surface, and the
// G² patch over them lies closer to it than the G¹ patch (the flat lens this
// example once was lay on no sphere at all).
TEST(NetworkFormatDocument, ExamplesWithAReferenceLieOnIt) {
  int withReference = 0;
  for (const Example &example : examples()) {
    const Network network = Network::build(parse(example));
    if (!network.reference()) continue;
    ++withReference;
    SCOPED_TRACE("example at line " + std::to_string(example.line));
    for (const Segment &segment : network.segments())
      for (int k = 0; k <= 64; ++k)
        EXPECT_LT(std::abs(network.reference()->signedDistance(segment.curve.point(k / 64.0))),
                  1e-12 * network.diagonal());
    const double g1 = measureReferenceDeviation(Surface::build(network, {Scheme::GregoryG1}))->maxDeviation;
    const double g2 = measureReferenceDeviation(Surface::build(network, {Scheme::GregoryG2}))->maxDeviation;
    EXPECT_LT(g2, g1);
  }
  EXPECT_GE(withReference, 1);
}

// An example that names master surfaces: its faces meet each master with
// the master's tangent plane under every transfinite scheme, and with its
// curvature under gregory-g2 (measured against the surface itself).
TEST(NetworkFormatDocument, ExamplesWithMasterSurfacesMeetThem) {
  int withMasters = 0;
  for (const Example &example : examples()) {
    const Network network = Network::build(parse(example));
    if (network.description().surfaces.empty()) continue;
    ++withMasters;
    SCOPED_TRACE("example at line " + std::to_string(example.line));
    for (Scheme scheme : {Scheme::GregoryG1, Scheme::CompositeRibbon, Scheme::GregoryG2}) {
      const std::vector<MasterSurfaceContact> contacts = measureMasterSurfaceContact(Surface::build(network, {scheme}));
      EXPECT_FALSE(contacts.empty());
      for (const MasterSurfaceContact &c : contacts) {
        EXPECT_LE(c.maxNormalAngleDeg, 1e-6) << schemeName(scheme);
        EXPECT_LE(c.maxDistance, 1e-12) << schemeName(scheme);
        if (scheme == Scheme::GregoryG2) EXPECT_LE(c.maxCurvatureJump, 1e-4);
      }
    }
  }
  EXPECT_GE(withMasters, 1);
}
