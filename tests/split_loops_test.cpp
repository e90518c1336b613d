// Connection curves for unevenly spaced and many-sided loops ([SV14]
// Sec. 5.2, Fig. 9). Loops of 9–16 sides inscribed in an ellipse and the
// uneven loops (corners crowded on 100° of the turn) lie on the bowl
// z = 0.25x² + 0.15y², so the composite's distance to the bowl measures its
// shape. Each is split automatically and, independently, by hand: straight
// plan chords from corner 0, lifted onto the bowl, cutting the loop into the
// fewest parts of at most 8 sides (no split for 8 sides or fewer).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "builtins/builtin_support.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/continuity.hpp"
#include "curvenet/curvature_jump.hpp"
#include "curvenet/curvenet.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"

using namespace curvenet;

namespace {

constexpr double kBowlX = 0.25, kBowlY = 0.15; // as in builtins/composite.cpp

/// The plan (x, y) of loop corner k: where its side k starts.
Vec3 cornerOf(const NetworkDescription &d, int k) {
  const SideDescription &side = d.faces[0].sides[k];
  return d.curves[side.curve].point(side.from);
}

/// The loop split by hand: p − 1 chords from corner 0 to corners
/// round(j n / p), p the fewest parts of at most 8 sides, each chord the
/// straight plan line lifted onto the bowl (as the loop's own sides are).
/// Built as drawn (no connection curves of its own), its chords marked as
/// seams of one face, so gregory-g2 averages the G¹ curvatures on them as on
/// the hidden ones.
NetworkDescription splitByHand(const NetworkDescription &loop) {
  const int n = static_cast<int>(loop.faces[0].sides.size());
  // The largest of p parts: a run of ⌈n / p⌉ sides and its one or two chords.
  auto largestPart = [n](int p) { return p == 1 ? n : (n + p - 1) / p + (p > 2 ? 2 : 1); };
  int parts = 1;
  while (largestPart(parts) > 8) ++parts;
  NetworkDescription hand = loop;
  hand.connectionCurves = false;
  if (parts == 1) return hand;
  std::vector<int> ends{0}, chords{-1};
  for (int j = 1; j < parts; ++j) {
    const int k = static_cast<int>(std::lround(double(j) * n / parts));
    const Vec3 a = cornerOf(loop, 0), b = cornerOf(loop, k);
    auto lifted = [=](double t) {
      const double x = a.x + t * (b.x - a.x), y = a.y + t * (b.y - a.y);
      return Vec3{x, y, kBowlX * x * x + kBowlY * y * y};
    };
    hand.curves.push_back(builtin_detail::fitSurfaceCurve(lifted, 0, 1, 16, lifted(0), lifted(1)));
    ends.push_back(k);
    chords.push_back(static_cast<int>(hand.curves.size()) - 1);
    hand.edges.push_back({chords.back(), -1, true}); // a seam like the hidden ones
  }
  ends.push_back(n);
  chords.push_back(-1);
  hand.faces.clear();
  for (int j = 0; j < parts; ++j) {
    FaceDescription part;
    part.name = "part " + std::to_string(j);
    if (chords[j] >= 0) part.sides.push_back({chords[j], 0.0, 1.0}); // corner 0 out to corner ends[j]
    for (int k = ends[j]; k < ends[j + 1]; ++k) part.sides.push_back(loop.faces[0].sides[k]);
    if (chords[j + 1] >= 0) part.sides.push_back({chords[j + 1], 1.0, 0.0}); // back to corner 0
    hand.faces.push_back(part);
  }
  return hand;
}

struct Case {
  std::string name;
  NetworkDescription loop;
};

std::vector<Case> cases() {
  std::vector<Case> all;
  for (int n = 9; n <= 16; ++n)
    all.push_back({std::to_string(n) + "-sided", builtin_detail::manySidedLoop(n).network});
  all.push_back({"uneven 8-sided", builtin_detail::unevenLoop(8).network});
  all.push_back({"uneven-loop built-in", builtinNetwork("uneven-loop")});
  return all;
}

double seamJump(const Surface &surface) {
  double worst = 0;
  for (const CurvatureJumpSample &sample : measureCurvatureJump(surface).samples)
    if (surface.network().segments()[sample.segment].connection) worst = std::max(worst, sample.jump);
  return worst;
}

} // namespace

// Every loop is split into parts of 4 to 8 sides that report as the user's
// face, and each scheme surfaces them watertight and G¹ without a fold;
// under gregory-g2 the hidden seams are curvature continuous to rounding.
// Reference deviation against the loop split by hand (its chords seams of
// one face, averaged under gregory-g2 as the hidden ones are), within 2%
// (two tessellations' sampling): no worse under every scheme. Measured, of
// the diagonal: on 9–16 sides gregory-g1 0.21–2.5% (hand 1.8–4.1%),
// gregory-g2 0.20–1.6% (hand 2.2–6.3%); the uneven 8-gon, whose hand
// "split" is the loop itself as one patch: 2.9%, 2.8%, 1.7% under
// gregory-g1, composite-ribbon, gregory-g2 (one patch: 3.6%, 3.7%, 2.3%);
// the uneven 10-gon 1.8%, 1.5%, 1.2% (hand 2.6%, 2.6%, 8.4%). Seam jumps
// under gregory-g2 ≤ 2.7e-14 on all of them (4.6e-11 and 7.7e-11 on the
// uneven loops while seam points within an ulp of a side's end were not
// taken as that end, see Patch::evaluateSecondOrder).
TEST(SplitLoops, ManySidedAndUnevenLoopsAreSplitAndSurfaced) {
  for (const Case &c : cases()) {
    SCOPED_TRACE(c.name);
    const Network net = Network::build(c.loop);
    const Network hand = Network::build(splitByHand(c.loop));
    ASSERT_GE(net.faces().size(), 2u);
    for (const Face &face : net.faces()) {
      EXPECT_EQ(face.partOf, 0);
      EXPECT_LE(face.sideCount(), 8);
      EXPECT_GE(face.sideCount(), 4);
    }
    int seams = 0;
    for (const Segment &seg : net.segments()) seams += seg.connection;
    EXPECT_GE(seams, static_cast<int>(net.faces().size()) - 1);
    std::printf("%-22s %zu parts (sides", c.name.c_str(), net.faces().size());
    for (const Face &face : net.faces()) std::printf(" %d", face.sideCount());
    std::printf("), hand %zu parts\n", hand.faces().size());
    for (Scheme scheme : {Scheme::GregoryG1, Scheme::CompositeRibbon, Scheme::GregoryG2}) {
      SurfaceOptions options;
      options.scheme = scheme;
      const Surface surface = Surface::build(net, options), byHand = Surface::build(hand, options);
      EXPECT_TRUE(surface.foldedFaces().empty()) << schemeName(scheme);
      const ContinuityReport continuity = measureContinuity(surface, {16});
      EXPECT_LE(continuity.maxPositionGap, 1e-12) << schemeName(scheme);
      EXPECT_LE(continuity.maxNormalAngleDeg, 1e-6) << schemeName(scheme);
      const double deviation = measureReferenceDeviation(surface, 16)->maxDeviation;
      const double handDeviation = measureReferenceDeviation(byHand, 16)->maxDeviation;
      const double jump = seamJump(surface);
      std::printf("  %-16s deviation %.3e (hand %.3e), seam jump %.2e\n", schemeName(scheme).c_str(), deviation,
                  handDeviation, jump);
      EXPECT_LE(deviation, 1.02 * handDeviation) << schemeName(scheme);
      if (scheme == Scheme::GregoryG2) {
        EXPECT_LE(jump, 1e-12);
      }
    }
  }
}

// The split description is explicit and idempotent: written and read back,
// it builds the same network without a further split.
TEST(SplitLoops, SplitDescriptionRoundTrips) {
  for (const std::string name : {"many-sided", "uneven-loop"}) {
    SCOPED_TRACE(name);
    const Network net = Network::build(builtinNetwork(name));
    const NetworkDescription back = parseNetworkJson(networkToJson(net.description()));
    EXPECT_EQ(back.faces.size(), net.faces().size());
    const Network again = Network::build(back);
    EXPECT_EQ(again.faces().size(), net.faces().size());
    EXPECT_EQ(again.segments().size(), net.segments().size());
    EXPECT_EQ(again.description().curves.size(), back.curves.size());
  }
}

// Loops of more than 8 sides are refused by name when connection curves are
// switched off.
TEST(SplitLoops, ManySidedLoopsNeedConnectionCurves) {
  NetworkDescription d = builtin_detail::manySidedLoop(12).network;
  d.connectionCurves = false;
  try {
    Network::build(d);
    ADD_FAILURE() << "a 12-sided loop was built as one patch";
  } catch (const InputError &e) {
    EXPECT_EQ(e.element(), "face 0") << e.what();
  }
}

// Uneven 8-gons with straight sides between corners on the bowl above the
// ellipse x = 1.5 cos θ, y = sin θ, crowded on part of the turn: several
// cuts give the worse part the same side ratio (its longest and shortest
// pieces stay the same whichever of several points the cut leaves from).
// The split takes the one whose larger part has the fewest sides, so each
// loop is cut alike (4 + 5 + 5) from whichever corner its side list starts
// and in either direction. The order among the ties used to be the sort's:
// the first loop came out as 4 + 4 + 7 or 4 + 4 + 8, the second in six
// different ways, by where the list started.
TEST(SplitLoops, EquallyEvenCutsSplitALoopAlikeWhereverItsListStarts) {
  const std::vector<std::vector<double>> loops = {{33.4, 186.5, 257.7, 280.2, 289.0, 298.5, 311.4, 338.1},
                                                  {33.0, 36.8, 83.4, 84.1, 100.2, 103.9, 183.5, 348.4}};
  auto line = [](Vec3 a, Vec3 b) { return BSplineCurve::bezier({a, a + (b - a) / 3.0, a + (b - a) * (2 / 3.0), b}); };
  for (const std::vector<double> &degrees : loops) {
    const int n = static_cast<int>(degrees.size());
    std::vector<int> first;
    for (const bool mirrored : {false, true})
      for (int start = 0; start < n; ++start) {
        SCOPED_TRACE("from corner " + std::to_string(start) + (mirrored ? ", mirrored" : ""));
        std::vector<Vec3> corners;
        for (double angle : degrees) {
          const double x = 1.5 * std::cos(angle * std::numbers::pi / 180), y = std::sin(angle * std::numbers::pi / 180);
          corners.push_back({x, mirrored ? -y : y, kBowlX * x * x + kBowlY * y * y});
        }
        if (mirrored) std::reverse(corners.begin(), corners.end()); // counter-clockwise again
        std::rotate(corners.begin(), corners.begin() + start, corners.end());
        NetworkDescription d;
        FaceDescription face;
        for (int k = 0; k < n; ++k) {
          d.curves.push_back(line(corners[k], corners[(k + 1) % n]));
          face.sides.push_back({k, 0, 1});
        }
        d.faces.push_back(face);
        const Network network = Network::build(d);
        std::vector<int> parts;
        for (const Face &f : network.faces()) parts.push_back(f.sideCount());
        std::sort(parts.begin(), parts.end());
        EXPECT_GT(parts.size(), 1u) << "the loop is uneven";
        if (first.empty()) first = parts;
        EXPECT_EQ(parts, first);
      }
  }
}

// A planar strip 15 times longer than wide whose long side bends concavely
// by 90° into a foot at its end (sewing_machine.obj's L-shaped faces): every
// cut between corners and side midpoints leaves the bend in a part that
// cannot fan from its centre, so none is taken, and the unsplit patch folds.
// A cut from a quarter point splits the foot off; no part folds.
TEST(SplitLoops, ConcavelyBentStripIsSplitAtAQuarterPoint) {
  auto bezier = [](std::vector<Vec3> p) { return BSplineCurve::bezier(std::move(p)); };
  auto line = [&](Vec3 a, Vec3 b) { return bezier({a, a + (b - a) / 3.0, a + (b - a) * (2 / 3.0), b}); };
  const Vec3 c0{0, 0, 0}, c1{0, 1.5, 0}, c2{0.1, 1.5, 0}, c3{0.4, 0.12, 0}, c4{0.4, 0, 0};
  NetworkDescription d;
  d.curves = {line(c0, c1), line(c1, c2), bezier({c2, {0.1, 0.3, 0}, {0.12, 0.12, 0}, c3}), line(c3, c4), line(c4, c0)};
  d.faces = {{{{0, 0, 1}, {1, 0, 1}, {2, 0, 1}, {3, 0, 1}, {4, 0, 1}}, "strip"}};
  NetworkDescription whole = d;
  whole.connectionCurves = false;
  const Network unsplit = Network::build(whole);
  EXPECT_EQ(Surface::build(unsplit, {Scheme::GregoryG1}).foldedFaces().size(), 1u);
  const Network split = Network::build(d);
  ASSERT_GT(split.faces().size(), 1u);
  for (const Face &face : split.faces()) EXPECT_EQ(face.partOf, 0);
  for (Scheme scheme : {Scheme::GregoryG1, Scheme::CompositeRibbon, Scheme::GregoryG2}) {
    SCOPED_TRACE(schemeName(scheme));
    EXPECT_TRUE(Surface::build(split, {scheme}).foldedFaces().empty());
  }
}
