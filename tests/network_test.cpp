// Network topology: every built-in's vertices, as classified by
// Network::build, agree with what the built-in's construction knows.
#include <gtest/gtest.h>

#include "input_errors.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/error.hpp"
#include "curvenet/network.hpp"

using namespace curvenet;

class BuiltinNetwork : public ::testing::TestWithParam<std::string> {};

TEST_P(BuiltinNetwork, VertexClassificationMatchesConstruction) {
  const Network network = Network::build(builtinNetwork(GetParam()));
  const auto facts = builtinVertexFacts(GetParam());
  ASSERT_EQ(network.vertices().size(), facts.size());
  const double tolerance = 1e-9 * network.diagonal();
  for (const BuiltinVertexFact &fact : facts) {
    const Vertex *match = nullptr;
    for (const Vertex &v : network.vertices())
      if (norm(v.position - fact.position) <= tolerance) match = &v;
    ASSERT_NE(match, nullptr) << "no vertex at the constructed position";
    EXPECT_EQ(match->valence, fact.valence);
    EXPECT_EQ(match->independentCurves, fact.independentCurves);
  }
}

TEST_P(BuiltinNetwork, EveryInteriorSegmentHasTwoOppositelyOrientedFaces) {
  const Network network = Network::build(builtinNetwork(GetParam()));
  for (const Segment &seg : network.segments()) {
    ASSERT_GE(seg.faces[0], 0);
    if (!seg.isBoundary()) {
      EXPECT_NE(seg.faces[0], seg.faces[1]);
    }
  }
  for (const Face &face : network.faces())
    for (int k = 0; k < face.sideCount(); ++k)
      EXPECT_EQ(face.sides[k].endVertex, face.sides[(k + 1) % face.sideCount()].startVertex);
}

INSTANTIATE_TEST_SUITE_P(AllBuiltins, BuiltinNetwork,
                         ::testing::Values("pentagon", "sphere-dodecahedron", "ellipsoid-truncated-icosahedron",
                                           "torus-mixed", "saddle-nodes", "setback-vertex-blend"),
                         [](const ::testing::TestParamInfo<std::string> &test) {
                           std::string name = test.param;
                           for (char &c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

TEST(Network, SaddleNodesHasXAndTNodesAndATwoSidedFace) {
  const Network network = Network::build(builtinNetwork("saddle-nodes"));
  int xNodes = 0, tNodes = 0, twoSided = 0, multiSegmentSides = 0;
  for (const Vertex &v : network.vertices()) {
    xNodes += v.kind == VertexKind::X;
    tNodes += v.kind == VertexKind::T && !v.onBoundary;
  }
  for (const Face &face : network.faces()) {
    twoSided += face.sideCount() == 2;
    for (const FaceSide &side : face.sides) multiSegmentSides += side.segments.size() > 1;
  }
  EXPECT_EQ(xNodes, 1);
  EXPECT_GE(tNodes, 1);
  EXPECT_EQ(twoSided, 1);
  EXPECT_GE(multiSegmentSides, 1) << "the face on the straight side of the T-node sees one side of two segments";
}

TEST(Network, RejectsLoopsWithMoreThanEightSides) {
  NetworkDescription d = builtinNetwork("pentagon");
  FaceDescription big;
  for (int k = 0; k < 9; ++k) big.sides.push_back(d.faces[0].sides[k % 5]);
  d.faces = {big};
  // With connection curves (the default) a loop of more than 8 sides is
  // split (tests/split_loops_test.cpp); this one does not close, which is
  // named on the user's face before any split.
  const InputError open = test::catchInputError([&] { Network::build(d, "nine.json"); });
  EXPECT_EQ(open.file(), "nine.json");
  EXPECT_EQ(open.element(), "face 0");
  EXPECT_NE(open.reason().find("does not close"), std::string::npos) << open.reason();
  d.connectionCurves = false;
  const InputError refused = test::catchInputError([&] { Network::build(d, "nine.json"); });
  EXPECT_EQ(refused.file(), "nine.json");
  EXPECT_EQ(refused.element(), "face 0");
  EXPECT_NE(refused.reason().find("2 to 8"), std::string::npos) << refused.reason();
}
