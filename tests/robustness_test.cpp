// The robustness corpus: built-in networks broken the way drawn networks
// are, and the real files of ../shared/data, each through gregory-g1,
// composite-ribbon and gregory-g2, with the vertex repair on (the default)
// and off.
//
//  (a) every curve's end tangents turned by 0.5°, 1° and 3° in seeded random
//      directions (the second control point from each end rotated about the
//      end point; drawn sketches leave their tangent planes by 2.6–7.5°);
//  (b) a smooth space warp of 1 % and 5 % of the diagonal applied to every
//      control point (connectivity kept; tangent planes and curvature
//      compatibility broken slightly at the nodes);
//  (c) X-nodes skewed by 1° and 5° (one curve end of each four-valent node
//      turned about the vertex normal), so that they are only nearly X;
//  (d) the .lop files of ../shared/data/transfinite-models;
//  (e) the sketches of ../shared/data/sketches, through the curve-graph
//      reader (faces found, curves fitted).
//
// Properties: folded faces, the tessellation's bounding-box diagonal over
// the network's, the curvature jump across edges whose vertices are both
// G²-admissible (gregory-g2), the largest normal angle. The expectations are
// a table, one row per case and scheme: tightening a bound is a one-line
// change. CURVENET_CORPUS_TABLE=1 prints every figure measured.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <set>

#include "analysis/editable_curve.hpp"
#include "bezier/bezier_surface.hpp"
#include "curvenet/analysis.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/continuity.hpp"
#include "curvenet/curvature_jump.hpp"
#include "curvenet/io.hpp"
#include "curvenet/shape.hpp"
#include "curvenet/sketch.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"
#include "approximation/triangle_bvh.hpp"
#include "patches/corner_grid.hpp"
#include "patches/crossing.hpp"
#include "patches/patch.hpp"

using namespace curvenet;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double inf = std::numeric_limits<double>::infinity();

// ---- perturbations -------------------------------------------------------------

BSplineCurve withPoints(const BSplineCurve &c, std::vector<Vec3> points) {
  return BSplineCurve(c.degree(), c.knots(), std::move(points), c.weights());
}

/// v rotated by `angle` about unit `axis` (Rodrigues).
Vec3 rotated(const Vec3 &v, const Vec3 &axis, double angle) {
  return v * std::cos(angle) + cross(axis, v) * std::sin(angle) + axis * (dot(axis, v) * (1 - std::cos(angle)));
}

/// A unit vector perpendicular to `d`, in a seeded random direction.
Vec3 randomPerpendicular(const Vec3 &d, std::mt19937 &rng) {
  std::normal_distribution<double> gauss;
  for (;;) {
    const Vec3 r{gauss(rng), gauss(rng), gauss(rng)};
    const Vec3 p = r - d * (dot(r, d) / squaredNorm(d));
    if (squaredNorm(p) > 1e-6) return normalized(p);
  }
}

/// (a): both end tangents of every curve turned by `degrees`.
NetworkDescription turnEndTangents(NetworkDescription d, double degrees, unsigned seed) {
  std::mt19937 rng(seed);
  for (BSplineCurve &c : d.curves) {
    std::vector<Vec3> p = c.controlPoints();
    if (p.size() < 4) continue; // the second point would also be the other end's
    for (int end = 0; end < 2; ++end) {
      const size_t at = end == 0 ? 0 : p.size() - 1, next = end == 0 ? 1 : p.size() - 2;
      const Vec3 arm = p[next] - p[at];
      p[next] = p[at] + rotated(arm, randomPerpendicular(arm, rng), degrees * pi / 180);
    }
    c = withPoints(c, std::move(p));
  }
  return d;
}

/// (b): x ↦ x + a·D·(sin(ωy + φ1), sin(ωz + φ2), sin(ωx + φ3)), D the
/// diagonal, a = `fraction`, one period over the model.
NetworkDescription warp(NetworkDescription d, double fraction) {
  const Network n = Network::build(d);
  const double D = n.diagonal(), w = 2 * pi / D;
  for (BSplineCurve &c : d.curves) {
    std::vector<Vec3> p = c.controlPoints();
    for (Vec3 &x : p)
      x = x + Vec3{std::sin(w * x.y + 0.3), std::sin(w * x.z + 1.1), std::sin(w * x.x + 2.3)} * (fraction * D);
    c = withPoints(c, std::move(p));
  }
  d.reference.reset(); // no longer the analytic surface
  return d;
}

/// (c): at every X-node (four-valent, opposite tangents collinear), one
/// end turned by `degrees` about the vertex normal: the second control
/// point from a curve end, or — for a curve passing through, after knot
/// insertion to multiplicity p — the neighbour of the vertex's point on one
/// side, which leaves the curve a corner there. `skewed` counts the nodes.
NetworkDescription skewXNodes(NetworkDescription d, double degrees, int &skewed) {
  const Network n = Network::build(d);
  const NetworkAnalysis analysis = analyzeNetwork(n);
  std::vector<char> turned(d.curves.size(), 0);
  skewed = 0;
  for (const VertexAnalysis &va : analysis.vertices) {
    if (va.valence != 4 || !va.formsX) continue;
    for (const CurveEnd &end : va.ends) {
      if (turned[end.sourceCurve]) continue;
      EditableCurve edit(d.curves[end.sourceCurve]);
      double t0 = end.sourceParameter;
      for (double u : edit.U)
        if (std::abs(u - t0) <= 1e-13) t0 = u;
      const double a = edit.U[edit.p], b = edit.U[edit.U.size() - edit.p - 1];
      int k = 0;
      if (t0 <= a) k = 0;
      else if (t0 >= b) k = edit.count() - 1;
      else {
        for (int r = edit.multiplicity(t0); r < edit.p; ++r) edit.insertKnot(t0);
        k = int(std::lower_bound(edit.U.begin(), edit.U.end(), t0) - edit.U.begin()) - 1;
      }
      const int j = end.towardsLargerParameter ? k + 1 : k - 1;
      if (j < 0 || j >= edit.count()) continue;
      const Vec3 centre = edit.wp[k] / edit.w[k], arm = edit.wp[j] / edit.w[j] - centre;
      edit.wp[j] = edit.w[j] * (centre + rotated(arm, va.normal, degrees * pi / 180));
      d.curves[end.sourceCurve] = edit.curve();
      turned[end.sourceCurve] = 1;
      ++skewed;
      break;
    }
  }
  d.reference.reset();
  return d;
}

// ---- measurement ---------------------------------------------------------------

struct Figures {
  int folds = 0;
  int cornerFolds = 0; ///< ShapeReport::cornerFolds: normals turning over near a corner, below the fold grid
  int intersections = 0; ///< ShapeReport::intersections: faces passing through each other or themselves
  double diagonalRatio = 0;
  double maxJump = 0;     ///< gregory-g2: across edges whose two vertices are G²-admissible
  double maxAngleDeg = 0; ///< normal angle across shared segments
  double excursion = 0;
  size_t repairMoves = 0;
};

Figures measure(const Network &network, Scheme scheme, CurveHandling curves) {
  SurfaceOptions options;
  options.scheme = scheme;
  options.curves = curves;
  const Surface surface = Surface::build(network, options);
  Figures f;
  f.folds = int(surface.foldedFaces().size());
  f.repairMoves = surface.repairMoves().size();
  const Mesh mesh = tessellate(surface, {4, 0});
  BoundingBox box;
  for (const Vec3 &p : mesh.positions) box.add(p);
  f.diagonalRatio = box.diagonal() / network.diagonal();
  f.maxAngleDeg = measureContinuity(surface, {8}).maxNormalAngleDeg;
  const ShapeReport shape = measureShape(surface, {2});
  f.excursion = shape.maxExcursion;
  f.cornerFolds = int(shape.cornerFolds.size());
  f.intersections = int(shape.intersections.size());
  if (scheme == Scheme::GregoryG2) {
    const Network &built = surface.network();
    const NetworkAnalysis analysis = analyzeNetwork(built);
    CurvatureJumpOptions jumpOptions;
    jumpOptions.samplesPerSegment = 5;
    for (const CurvatureJumpSample &s : measureCurvatureJump(surface, jumpOptions).samples) {
      const Segment &seg = built.segments()[size_t(s.segment)];
      if (analysis.vertices[size_t(seg.start)].verdict == VertexVerdict::G2Admissible &&
          analysis.vertices[size_t(seg.end)].verdict == VertexVerdict::G2Admissible)
        f.maxJump = std::max(f.maxJump, s.jump);
    }
  }
  return f;
}

// ---- the corpus and its expectations ---------------------------------------------

struct Expectation {
  int maxFolds;
  double maxDiagonalRatio;
  double maxJump; ///< gregory-g2 only
  double maxAngleDeg;
  int maxCornerFolds = 0;
  int maxIntersections = 0;
};

const char *const kBase = "sphere-dodecahedron";
const char *const kXBase = "saddle-nodes";

struct Case {
  std::string name;
  std::function<NetworkDescription()> make;
  // Repaired (the default), per scheme: gregory-g1, composite-ribbon, gregory-g2.
  Expectation g1, cr, g2;
};



// The expectations: what holds on this code, measured with the repair on.
// The goal for every row is {0, 1.05, 1e-4, 1e-6}; the rows that do
// not meet it yet say so, and tightening one is a change of that row only.
// Columns: max folds, max tessellation/network diagonal, max G² jump
// (gregory-g2, edges between G²-admissible vertices), max normal angle (°).
constexpr Expectation kGoal{0, 1.05, 1e-4, 1e-6};

std::vector<Case> corpus() {
  auto tangents = [](double degrees) { return [=] { return turnEndTangents(builtinNetwork(kBase), degrees, 26); }; };
  auto warped = [](double fraction) { return [=] { return warp(builtinNetwork(kBase), fraction); }; };
  auto skewed = [](double degrees) {
    return [=] {
      int nodes = 0;
      NetworkDescription d = skewXNodes(builtinNetwork(kXBase), degrees, nodes);
      EXPECT_GT(nodes, 0) << kXBase << " has X-nodes to skew";
      return d;
    };
  };
  return {
      //                                gregory-g1                composite-ribbon  gregory-g2
      {"tangents-0.5deg", tangents(0.5), kGoal, kGoal, kGoal},
      {"tangents-1deg", tangents(1.0), kGoal, kGoal, kGoal},
      {"tangents-3deg", tangents(3.0), kGoal, kGoal, kGoal},
      {"warp-1pct", warped(0.01), kGoal, kGoal, kGoal},
      {"warp-5pct", warped(0.05), kGoal, kGoal, kGoal},
      // saddle-nodes' G² quad 4, where the ribbons of its short sides have
      // rulings that cross a third of the way in, folds with its blend
      // shares but not with eq. 17 at every corner (the fallback of
      // buildFace); skewed by 5°, one quad folds with either corner form and
      // not with the cross-derivatives at 3/4 of their length.
      {"x-skew-1deg", skewed(1.0), kGoal, kGoal, kGoal},
      {"x-skew-5deg", skewed(5.0), kGoal, kGoal, kGoal},
  };
}

bool printTable() { return std::getenv("CURVENET_CORPUS_TABLE") != nullptr; }

void printRow(const std::string &name, Scheme scheme, const char *curves, const Figures &f) {
  std::printf("| %-18s | %-16s | %-8s | %5d | %5d | %5d | %8.4f | %9.3g | %9.3g | %9.3g | %5zu |\n", name.c_str(),
              schemeName(scheme).c_str(), curves, f.folds, f.cornerFolds, f.intersections, f.diagonalRatio, f.maxJump,
              f.maxAngleDeg, f.excursion, f.repairMoves);
}

void checkAgainst(const Figures &f, const Expectation &e) {
  EXPECT_LE(f.folds, e.maxFolds);
  EXPECT_LE(f.cornerFolds, e.maxCornerFolds);
  EXPECT_LE(f.intersections, e.maxIntersections);
  EXPECT_LE(f.diagonalRatio, e.maxDiagonalRatio);
  EXPECT_LE(f.maxJump, e.maxJump);
  EXPECT_LE(f.maxAngleDeg, e.maxAngleDeg);
}

void runCase(const std::string &name, const Network &network, const Expectation *expect) {
  const Scheme schemes[] = {Scheme::GregoryG1, Scheme::CompositeRibbon, Scheme::GregoryG2};
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(name + " " + schemeName(schemes[k]));
    const Figures repaired = measure(network, schemes[k], CurveHandling::Repaired);
    if (expect) checkAgainst(repaired, expect[k]);
    if (printTable()) {
      printRow(name, schemes[k], "repaired", repaired);
      printRow(name, schemes[k], "kept", measure(network, schemes[k], CurveHandling::Kept));
    }
  }
}

} // namespace

TEST(RobustnessCorpus, PerturbedBuiltins) {
  if (printTable())
    std::printf("| case | scheme | curves | folds | corner folds | intersections | diag ratio | max jump (G2-adm.) | max normal angle ° | "
                "excursion | moves |\n");
  for (const Case &c : corpus()) {
    const Network network = Network::build(c.make(), c.name);
    const Expectation expect[] = {c.g1, c.cr, c.g2};
    runCase(c.name, network, expect);
  }
}

TEST(RobustnessCorpus, RepairMakesPerturbedVerticesAdmissibleWithoutMovingThem) {
  const Network network = Network::build(turnEndTangents(builtinNetwork(kBase), 3.0, 26), "tangents-3deg");
  const RepairResult repair = repairNetwork(network);
  ASSERT_TRUE(repair.changed());
  const Network repaired = Network::build(repair.network, "repaired");
  ASSERT_EQ(repaired.vertices().size(), network.vertices().size());
  for (size_t v = 0; v < network.vertices().size(); ++v)
    EXPECT_EQ(norm(repaired.vertices()[v].position - network.vertices()[v].position), 0.0) << "vertex " << v;
  const NetworkAnalysis after = analyzeNetwork(repaired);
  EXPECT_LE(after.maxTangentResidual, 1e-9);
  EXPECT_EQ(after.verdict, VertexVerdict::G2Admissible);
  // Minimal: a tangent turned by at most the perturbation (3°) plus the plane's own tilt.
  for (const RepairMove &m : repair.moves) {
    if (m.kind == RepairKind::TangentPlane) {
      EXPECT_LE(m.angle, 6.0 * pi / 180);
    }
    EXPECT_LE(m.sizeRelative, 0.05);
  }
}

TEST(RobustnessCorpus, SharedDataFiles) {
  const std::filesystem::path dir = std::filesystem::path(CURVENET_SHARED_DATA_DIR) / "transfinite-models";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << dir << " is absent: no real networks to run";
  int files = 0;
  for (const auto &entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".lop") continue;
    ++files;
    const Network network = Network::build(loadNetworkInput(entry.path().string()), entry.path().string());
    // Known files have their row (what holds today; the goal is kGoal for
    // every scheme); another file is measured and printed only.
    const std::string name = entry.path().filename().string();
    const std::map<std::string, std::array<Expectation, 3>> known = {
        {"pocket3sided.lop", {{kGoal, kGoal, kGoal}}},
        {"cagd86.lop", {{kGoal, kGoal, kGoal}}},
    };
    const auto row = known.find(name);
    runCase(name, network, row != known.end() ? row->second.data() : nullptr);
  }
  EXPECT_GT(files, 0);
}

// The public sketches of ../shared/data/sketches through the curve-graph
// reader (curvenet/sketch.hpp), each scheme, repaired. The rows are what
// holds today; the goal is kGoal. Normal angles are over the G¹ segments
// (crease segments are sharp by design).
TEST(RobustnessCorpus, SharedSketches) {
  const std::filesystem::path dir = std::filesystem::path(CURVENET_SHARED_DATA_DIR) / "sketches";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << dir << " is absent: no sketches to run";
  // Columns as in corpus(): gregory-g1, composite-ribbon, gregory-g2.
  // Measured: every sketch meets the goal under every scheme. What it
  // took (docs/surfaces.md, Folds): faces that fold under eq. 17's corners
  // take the two-ribbon blend or shorter cross-derivatives (gregory-g2: 49
  // folded faces before the direct transversal curvature stopped taking up
  // curvature spikes of the curves, 10 before folded faces took shorter
  // cross-derivatives too); sewing_machine's L-shaped strips are split at a
  // quarter point; iron's two hexagons pleated over a V of its strokes are
  // cut along the fold (they folded under every scheme and met at 180°);
  // doghead's faces 7 and 18 folded under gregory-g2 (18 under
  // composite-ribbon too) beside an X-node the weld had made one sample
  // short of a junction, and its 7-sided face 1 under composite-ribbon, a
  // part of an 8-sided face that a tie among equally even splits cut into a
  // quad and a 7-gon (its mirror image into two hexagons). G¹ segments
  // ending at a crease are exactly G¹ (≤ 1.1e-8°; 6.5–7.7° before vertex
  // repair turned each fan's G¹ curves into the plane of its crease curves).
  // gregory-g2's folds near corners, closer to them than the fold grid
  // samples (ShapeReport::cornerFolds, turned-over normals within
  // 3e-4–2e-3 of the diagonal: doghead 2 corners, dress 4, bathtub 4), are
  // gone since such corners take the two-ribbon blend (buildFace).
  // Faces passing through each other without folding in their own
  // parameters (ShapeReport::intersections), where a gregory-g2 patch
  // curled over a thin part — doghead's ear stalks (faces 10 and 11, 34
  // and 35) and bathtub's faces 1 and 20 — are gone since one face of such
  // a pair takes a variant (separateCrossingFaces); bathtub's faces 47 and
  // 48, which crossed under every variant of either, since fences no longer
  // turn at crease vertices' tensors (G2SidesStayNearTheG1TangentPlanes-
  // AtCreaseVertices). A face through itself is rebuilt by the variant search
  // (patchSelfCrossing): bathtub's face 34 under gregory-g2 and
  // sewing_machine's faces 10, 11 and 36 under gregory-g1 did so before.
  // composite-ribbon, the .lop files and the built-ins have none.
  const std::map<std::string, std::array<Expectation, 3>> rows = {
      {"doghead.obj", {{kGoal, kGoal, kGoal}}},
      {"spherecylinder.obj", {{kGoal, kGoal, kGoal}}},
      {"sewing_machine.obj", {{kGoal, kGoal, kGoal}}},
      {"box.obj", {{kGoal, kGoal, kGoal}}},
      {"dress.obj", {{kGoal, kGoal, kGoal}}},
      {"ellipsetorus.obj", {{kGoal, kGoal, kGoal}}},
      {"iron.obj", {{kGoal, kGoal, kGoal}}},
      {"bathtub.obj", {{kGoal, kGoal, kGoal}}},
  };

  int files = 0;
  for (const auto &[name, expect] : rows) {
    const std::string path = (dir / name).string();
    if (!std::filesystem::exists(path)) continue;
    ++files;
    const Network network = Network::build(networkFromCurveGraph(readCurveGraphFile(path), {}, path).description, path);
    runCase(name, network, expect.data());
  }
  EXPECT_GT(files, 0);
}

// Corner folds (docs/surfaces.md, Corner folds) are real and avoided: on
// doghead.obj's gregory-g2 surface, a corner that takes the two-ribbon blend
// (share 1) and would fold with eq. 17's corner interpolant there (share 0,
// the rest of the patch as built) on the corner grid that chose the blend
// folds as well on a square grid along the corner's two sides, while the
// surface as built folds on neither and the shape report names no corner
// fold. No corner of a built-in folds.
TEST(RobustnessCorpus, CornersThatWouldFoldTakeTheTwoRibbonBlend) {
  for (const char *name : {"sphere-dodecahedron", "ellipsoid-truncated-icosahedron", "torus-mixed"})
    EXPECT_TRUE(measureShape(Surface::build(Network::build(builtinNetwork(name)), {Scheme::GregoryG2})).cornerFolds.empty())
        << name;
  const std::string path = std::string(CURVENET_SHARED_DATA_DIR) + "/sketches/doghead.obj";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent: no sketch with corner folds";
  const Network network = Network::build(networkFromCurveGraph(readCurveGraphFile(path), {}, path).description, path);
  const Surface surface = Surface::build(network, {Scheme::GregoryG2});
  EXPECT_TRUE(measureShape(surface).cornerFolds.empty());
  // Whether the patch's normals turn over on a square grid of 120² samples
  // spanning 3 % of the corner's two sides, and on the corner grid.
  auto squareGridFolds = [](const Patch &patch, int corner) {
    const RegularDomain &domain = patch.domain();
    const Vec2 c = domain.corner(corner), along = domain.corner(corner + 1) - c, back = domain.corner(corner - 1) - c;
    constexpr int kSteps = 120;
    std::vector<Vec3> normals;
    for (int i = 1; i <= kSteps; ++i)
      for (int j = 1; j <= kSteps; ++j) {
        const Vec2 uv = c + along * (0.03 * i / kSteps) + back * (0.03 * j / kSteps);
        const DualVec3 r = patch.evaluate(uv.x, uv.y);
        normals.push_back(cross(r.du, r.dv));
      }
    for (int i = 0; i < kSteps; ++i)
      for (int j = 0; j < kSteps; ++j) {
        const std::size_t k = static_cast<std::size_t>(i * kSteps + j);
        if (j + 1 < kSteps && dot(normals[k], normals[k + 1]) <= 0) return true;
        if (i + 1 < kSteps && dot(normals[k], normals[k + kSteps]) <= 0) return true;
      }
    return false;
  };
  auto cornerGridFolds = [](const Patch &patch, int corner) {
    const RegularDomain &domain = patch.domain();
    std::vector<Vec3> normals;
    for (int i = 0; i < CornerGrid::kRings; ++i)
      for (int j = 0; j < CornerGrid::kRays; ++j) {
        const Vec2 uv = CornerGrid::point(domain.corner(corner), domain.corner(corner - 1), domain.corner(corner + 1), i, j);
        const DualVec3 r = patch.evaluate(uv.x, uv.y);
        normals.push_back(cross(r.du, r.dv));
      }
    return CornerGrid::folds(normals);
  };
  int avoided = 0;
  for (int f = 0; f < surface.faceCount(); ++f) {
    const Patch &patch = *SurfaceAccess::patch(surface, f);
    for (int k = 0; k < patch.domain().sides(); ++k) {
      if (patch.blendShares()[k] != 1) continue;
      std::vector<double> shares = patch.blendShares();
      shares[k] = 0;
      std::vector<LinearRibbon> ribbons;
      for (int i = 0; i < patch.domain().sides(); ++i) ribbons.push_back(patch.ribbon(i));
      const Patch eq17(std::move(ribbons), patch.options(), patch.parabolicRibbons(), std::move(shares));
      if (!cornerGridFolds(eq17, k)) continue;
      SCOPED_TRACE("face " + std::to_string(f) + " corner " + std::to_string(k));
      ++avoided;
      EXPECT_TRUE(squareGridFolds(eq17, k));
      EXPECT_FALSE(squareGridFolds(patch, k));
      EXPECT_FALSE(cornerGridFolds(patch, k));
    }
  }
  EXPECT_GE(avoided, 2);
}

// The overlap traversal of TriangleBvh gives exactly the brute-force pairs of
// triangles whose boxes overlap, on random triangles of mixed sizes; so do
// BoundingBox::meets, and BoundingBox::intersection is non-empty exactly
// for those pairs, with the larger minimum and smaller maximum per axis.
TEST(SelfIntersection, OverlappingPairsAreTheBruteForcePairs) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Vec3> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (int t = 0; t < 400; ++t) {
    const Vec3 centre{unit(random), unit(random), unit(random)};
    const double size = t % 10 == 0 ? 0.3 : 0.04;
    for (int k = 0; k < 3; ++k)
      positions.push_back(centre + Vec3{unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5} * size);
    triangles.push_back({std::uint32_t(3 * t), std::uint32_t(3 * t + 1), std::uint32_t(3 * t + 2)});
  }
  auto box = [&](int t) {
    BoundingBox b;
    for (std::uint32_t v : triangles[t]) b.add(positions[v]);
    return b;
  };
  std::set<std::pair<int, int>> expected, found;
  for (int a = 0; a < 400; ++a)
    for (int b = a + 1; b < 400; ++b) {
      const BoundingBox A = box(a), B = box(b);
      bool overlap = true;
      for (int i = 0; i < 3; ++i) overlap = overlap && A.min[i] <= B.max[i] && B.min[i] <= A.max[i];
      if (overlap) expected.insert({a, b});
      EXPECT_EQ(A.meets(B), overlap) << a << " " << b;
      const BoundingBox both = A.intersection(B);
      bool nonEmpty = true;
      for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(both.min[i], std::max(A.min[i], B.min[i]));
        EXPECT_EQ(both.max[i], std::min(A.max[i], B.max[i]));
        nonEmpty = nonEmpty && both.min[i] <= both.max[i];
      }
      EXPECT_EQ(nonEmpty, overlap) << a << " " << b;
    }
  TriangleBvh(positions, triangles).forEachOverlappingPair([&](int a, int b) {
    EXPECT_LT(a, b);
    EXPECT_TRUE(found.insert({a, b}).second) << a << " " << b << " visited twice";
  });
  EXPECT_GT(expected.size(), 50u);
  EXPECT_EQ(found, expected);
}

// trianglesCross: a triangle pierced by another, one passing through the
// other's middle like a chain's links, apart, side by side in one plane, and
// meeting only at a shared edge or corner (not a crossing).
TEST(SelfIntersection, TrianglesCrossWhereAnEdgeOfOnePassesThroughTheOther) {
  const std::array<Vec3, 3> flat{Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{0, 2, 0}};
  const std::array<Vec3, 3> pierce{Vec3{0.5, 0.5, -1}, Vec3{0.5, 0.5, 1}, Vec3{3, 3, 0.5}};
  const std::optional<Vec3> x = trianglesCross(flat, pierce);
  ASSERT_TRUE(x.has_value());
  EXPECT_NEAR(norm(*x - Vec3{0.5, 0.5, 0}), 0, 1e-15);
  EXPECT_TRUE(trianglesCross(pierce, flat).has_value());
  const std::array<Vec3, 3> link{Vec3{0.5, 0.5, -1}, Vec3{0.5, 0.5, 1}, Vec3{-3, -3, 0}};
  EXPECT_TRUE(trianglesCross(flat, link).has_value());
  const std::array<Vec3, 3> above{Vec3{0, 0, 1}, Vec3{2, 0, 1}, Vec3{0, 2, 1.5}};
  EXPECT_FALSE(trianglesCross(flat, above).has_value());
  const std::array<Vec3, 3> beside{Vec3{3, 0, 0}, Vec3{5, 0, 0}, Vec3{3, 2, 0}};
  EXPECT_FALSE(trianglesCross(flat, beside).has_value());
  const std::array<Vec3, 3> hinged{Vec3{2, 0, 0}, Vec3{0, 2, 0}, Vec3{0, 0, 1}};
  EXPECT_FALSE(trianglesCross(flat, hinged).has_value());
  const std::array<Vec3, 3> cornered{Vec3{0, 0, 0}, Vec3{-1, 0, 1}, Vec3{0, -1, 1}};
  EXPECT_FALSE(trianglesCross(flat, cornered).has_value());
}

/// The smallest distance (relative to the diagonal) from `point` to a place
/// where triangles of faces a and b within 3 % of the diagonal of it cross,
/// by brute force over every such pair of `mesh` (no hierarchy); infinity
/// where none do.
double nearestCrossing(const Mesh &mesh, int faceA, int faceB, const Vec3 &point, double diagonal) {
  auto corners = [&](std::uint32_t t) {
    const auto &tri = mesh.triangles[t];
    return std::array<Vec3, 3>{mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]};
  };
  auto near = [&](int face) {
    std::vector<std::uint32_t> found;
    for (std::uint32_t t = mesh.faceTriangleStart[face]; t < mesh.faceTriangleStart[face + 1]; ++t)
      if (norm(mesh.positions[mesh.triangles[t][0]] - point) < 0.03 * diagonal) found.push_back(t);
    return found;
  };
  double nearest = std::numeric_limits<double>::infinity();
  for (const std::uint32_t s : near(faceA))
    for (const std::uint32_t t : near(faceB)) {
      const auto &a = mesh.triangles[s], &b = mesh.triangles[t];
      if (std::any_of(a.begin(), a.end(), [&](std::uint32_t v) { return v == b[0] || v == b[1] || v == b[2]; }))
        continue;
      if (const std::optional<Vec3> crossing = trianglesCross(corners(s), corners(t)))
        nearest = std::min(nearest, norm(*crossing - point) / diagonal);
    }
  return nearest;
}

// Faces that pass through each other (ShapeReport::intersections) do so on
// a finer mesh too, where they truly cross: two flat rectangles linked like
// a chain's links (each has an edge through the other's middle), whose
// patches cross along x = 1, z = 0, 1 ≤ y ≤ 2 under every scheme and no
// variant can take apart. The shape report names the pair, near that line;
// a brute-force search over every pair of the two faces' triangles near the
// reported point at 64 intervals per segment finds crossing triangles
// within 2 % of the diagonal of it.
TEST(SelfIntersection, FacesPassingThroughEachOtherAreFoundAgainOnAFinerMesh) {
  const std::array<std::array<Vec3, 4>, 2> loops{{{Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{2, 2, 0}, Vec3{0, 2, 0}},
                                                  {Vec3{1, 1, -1}, Vec3{1, 3, -1}, Vec3{1, 3, 1}, Vec3{1, 1, 1}}}};
  NetworkDescription links;
  for (const auto &loop : loops) {
    FaceDescription face;
    for (std::size_t i = 0; i < 4; ++i) {
      links.curves.push_back(BSplineCurve::bezier({loop[i], loop[(i + 1) % 4]}));
      face.sides.push_back({static_cast<int>(links.curves.size()) - 1, 0, 1});
    }
    links.faces.push_back(face);
  }
  const Network network = Network::build(links);
  for (Scheme scheme : {Scheme::GregoryG1, Scheme::CompositeRibbon, Scheme::GregoryG2}) {
    SCOPED_TRACE(schemeName(scheme));
    const Surface surface = Surface::build(network, {scheme});
    const ShapeReport shape = measureShape(surface);
    ASSERT_EQ(shape.intersections.size(), 1u);
    const FaceIntersection &x = shape.intersections[0];
    EXPECT_EQ(std::min(x.faceA, x.faceB), 0);
    EXPECT_EQ(std::max(x.faceA, x.faceB), 1);
    EXPECT_LE(std::hypot(x.point.x - 1, x.point.z), 0.02 * network.diagonal());
    EXPECT_GE(x.point.y, 1 - 0.02 * network.diagonal());
    EXPECT_LE(x.point.y, 2 + 0.02 * network.diagonal());
    for (const FaceShape &face : shape.faces) EXPECT_TRUE(face.intersects) << face.face;
    EXPECT_FALSE(shape.acceptable());
    EXPECT_LE(nearestCrossing(tessellate(surface, {64, 0}), x.faceA, x.faceB, x.point, network.diagonal()), 0.02);
  }
}

// gregory-g2's fences turn about their curve at the rates the end vertices'
// curvature tensors give (N' = −S(P')), except at crease vertices, whose one
// tensor is fitted across the crease and describes neither side: from it a
// wall's fence under bathtub.obj's rim turned 90° mid-edge into the rim's
// plane, and its patch curled under the rim through the strip there (faces
// 47 and 48). Along every side of the sketches where that happened
// (bathtub, doghead, sewing_machine: 103°, 66° and 22° before) the G²
// patches' normals now stay within 30° of the G¹ patches' (whose fences
// turn only from one end normal to the other), and no bathtub faces pass
// through each other under any scheme.
TEST(RobustnessCorpus, G2SidesStayNearTheG1TangentPlanesAtCreaseVertices) {
  for (const char *name : {"bathtub", "doghead", "sewing_machine"}) {
    const std::string path = std::string(CURVENET_SHARED_DATA_DIR) + "/sketches/" + name + ".obj";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent: no sketch with crease vertices";
    SCOPED_TRACE(name);
    const Network network = Network::build(networkFromCurveGraph(readCurveGraphFile(path), {}, path).description, path);
    const Surface g1 = Surface::build(network, {Scheme::GregoryG1}), g2 = Surface::build(network, {Scheme::GregoryG2});
    double worst = 0;
    for (int f = 0; f < g1.faceCount(); ++f) {
      const int n = g1.domainSides(f);
      ASSERT_EQ(g2.domainSides(f), n);
      for (int i = 0; i < n; ++i)
        for (int k = 1; k < 20; ++k) {
          const double z = k / 20.0;
          auto at = [&](const Surface &s) { return s.domainCorner(f, i) * (1 - z) + s.domainCorner(f, i + 1) * z; };
          const double angle = angleBetween(g1.evaluate(f, at(g1)).normal, g2.evaluate(f, at(g2)).normal);
          worst = std::max(worst, angle);
          EXPECT_LE(angle, 30 * std::numbers::pi / 180) << "face " << f << " side " << i << " at " << z;
        }
    }
    std::printf("%s: largest angle between the G1 and G2 normals along a side %.1f deg\n", name, worst * 180 / std::numbers::pi);
    if (std::string(name) == "bathtub") {
      EXPECT_TRUE(measureShape(g1).intersections.empty());
      EXPECT_TRUE(measureShape(g2).intersections.empty());
      EXPECT_TRUE(measureShape(Surface::build(network, {Scheme::CompositeRibbon})).intersections.empty());
    }
  }
}

// forEachLatticeCrossing: a face's lattice (halved: the same as one at half
// the rows) crosses its copy turned a quarter
// turn about a line through its middle, and not its copy moved away; the
// sphere-dodecahedron's faces, which meet along curves and at corners, do
// not cross one another once triangles that both touch their boundaries
// are left out between faces that share a vertex (and do where they are not).
TEST(SelfIntersection, LatticesCrossWhereTheirPatchesDo) {
  const Surface sphere = Surface::build(Network::build(builtinNetwork("sphere-dodecahedron")), {Scheme::GregoryG2});
  const PatchLattice face = patchLattice(*SurfaceAccess::patch(sphere, 0), 24);
  // Every other point of the 24-row lattice is the 12-row one (the build
  // searches all faces at 12 rows from the lattices it made at 24).
  const PatchLattice half = halved(face), twelve = patchLattice(*SurfaceAccess::patch(sphere, 0), 12);
  ASSERT_EQ(half.positions.size(), twelve.positions.size());
  for (std::size_t p = 0; p < half.positions.size(); ++p) // the batch evaluates them in other lanes
    EXPECT_LE(norm(half.positions[p] - twelve.positions[p]), 1e-12 * face.box.diagonal()) << p;
  EXPECT_EQ(half.triangles, twelve.triangles);
  EXPECT_EQ(half.onBoundary, twelve.onBoundary);
  const Vec3 middle = face.box.center();
  PatchLattice turned = face, moved = face;
  for (Vec3 &p : turned.positions) {
    const Vec3 q = p - middle; // a quarter turn about the x axis through the middle
    p = middle + Vec3{q.x, -q.z, q.y};
  }
  turned.box = {};
  for (const Vec3 &p : turned.positions) turned.box.add(p);
  for (Vec3 &p : moved.positions) p += Vec3{3, 0, 0};
  moved.box = {};
  for (const Vec3 &p : moved.positions) moved.box.add(p);
  auto crossings = [](std::vector<const PatchLattice *> lattices, bool touching) {
    std::set<std::pair<int, int>> found;
    forEachLatticeCrossing(lattices, [&](int, int) { return touching; },
                           [&](int a, int b, const Vec3 &) { EXPECT_TRUE(found.insert({a, b}).second); });
    return found;
  };
  EXPECT_EQ(crossings({&face, &turned}, false), (std::set<std::pair<int, int>>{{0, 1}}));
  EXPECT_TRUE(crossings({&face, &moved}, false).empty());
  std::vector<PatchLattice> faces;
  for (int f = 0; f < sphere.faceCount(); ++f) faces.push_back(patchLattice(*SurfaceAccess::patch(sphere, f), 24));
  std::vector<const PatchLattice *> all;
  for (const PatchLattice &l : faces) all.push_back(&l);
  EXPECT_TRUE(crossings(all, true).empty());
  // Counted, neighbours' boundary chords do cross (30 pairs here).
  EXPECT_FALSE(crossings(all, false).empty());
}

// A face passing through a neighbour takes a variant (separateCrossingFaces):
// bathtub.obj's gregory-g2 face 20, which with the blend shares its ribbons
// ask curled through face 1 near this point, has no crossing triangles with
// it there at 64 intervals per segment (brute force), and the shape report,
// on the tessellation rather than the build's lattices, finds no faces
// passing through each other. The face took a uniform variant of the
// corner shares and does not fold. (doghead.obj's ear stalks, faces 11 and
// 35, did the same until the crease vertices stopped turning their fences:
// G2SidesStayNearTheG1TangentPlanesAtCreaseVertices.)
TEST(SelfIntersection, FacesPassingThroughANeighbourTakeAVariant) {
  const std::string path = std::string(CURVENET_SHARED_DATA_DIR) + "/sketches/bathtub.obj";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent: no sketch whose faces intersected";
  const Network network = Network::build(networkFromCurveGraph(readCurveGraphFile(path), {}, path).description, path);
  const Surface surface = Surface::build(network, {Scheme::GregoryG2});
  const ShapeReport shape = measureShape(surface);
  EXPECT_TRUE(shape.intersections.empty());
  EXPECT_TRUE(shape.foldedFaces.empty());
  const Mesh mesh = tessellate(surface, {64, 0});
  const std::array<int, 2> faces{1, 20};
  const Vec3 before{0.3111, 0.02714, -0.7684};
  EXPECT_EQ(nearestCrossing(mesh, faces[0], faces[1], before, network.diagonal()), std::numeric_limits<double>::infinity());
  const std::vector<double> &shares = SurfaceAccess::patch(surface, faces[1])->blendShares();
  EXPECT_TRUE(std::all_of(shares.begin(), shares.end(), [&](double s) { return s == shares.front(); }));
}

// A model far from the origin is translated to its centre before anything
// else, the vertex repair included: doghead.obj moved 10 diagonals away is
// repaired and surfaced as the same sketch at its centre. (With the repair
// in world coordinates, the second derivatives at the ends of its split
// curves lost digits to the coordinates' size: at 4.4 diagonals 34 moves
// instead of 28, and 2 folded gregory-g2 faces.)
TEST(RobustnessCorpus, FarFromTheOriginIsRepairedAsAtTheCentre) {
  const std::filesystem::path path = std::filesystem::path(CURVENET_SHARED_DATA_DIR) / "sketches" / "doghead.obj";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
  const NetworkDescription sketch = networkFromCurveGraph(readCurveGraphFile(path.string()), {}, path.string()).description;
  const Network original = Network::build(sketch);
  const Vec3 centre = original.bounds().center();
  const double diagonal = norm(original.bounds().max - original.bounds().min);
  auto moved = [&](const Vec3 &by) {
    NetworkDescription d = sketch;
    for (BSplineCurve &c : d.curves) {
      std::vector<Vec3> p = c.controlPoints();
      for (Vec3 &q : p) q += by;
      c = withPoints(c, std::move(p));
    }
    return Network::build(d);
  };
  SurfaceOptions g2;
  g2.scheme = Scheme::GregoryG2;
  const Surface atCentre = Surface::build(moved(-centre), g2);
  const Surface far = Surface::build(moved(Vec3{10, -4, 3} * (diagonal / norm(Vec3{10, -4, 3})) * 10 - centre), g2);
  ASSERT_EQ(far.repairMoves().size(), atCentre.repairMoves().size());
  for (std::size_t k = 0; k < far.repairMoves().size(); ++k) {
    const RepairMove &a = far.repairMoves()[k], &b = atCentre.repairMoves()[k];
    EXPECT_EQ(a.vertex, b.vertex);
    EXPECT_EQ(a.curve, b.curve);
    EXPECT_NEAR(a.sizeRelative, b.sizeRelative, 1e-9);
  }
  EXPECT_TRUE(far.foldedFaces().empty());
  EXPECT_EQ(far.foldedFaces(), atCentre.foldedFaces());
  // The surface's network is the repaired one, where the model is.
  EXPECT_LT(norm(far.network().bounds().center() - far.origin()), 0.1 * diagonal);
  EXPECT_GT(norm(far.origin()), 9 * diagonal);
}

// An edit that turns a tangent out of its plane is repaired on the way, and
// the rebuild stays partial: the repaired edit differs from the repaired
// surface's network near the edited curve only. The result is a full build's.
TEST(RobustnessCorpus, RepairedEditRebuildsPartially) {
  const NetworkDescription description = builtinNetwork(kBase);
  const Network network = Network::build(description);
  const Surface before = Surface::build(network, {Scheme::GregoryG1});
  ASSERT_TRUE(before.repairMoves().empty());
  NetworkDescription turned = description;
  std::mt19937 rng(7);
  BSplineCurve &c = turned.curves[0];
  std::vector<Vec3> p = c.controlPoints();
  p[1] = p[0] + rotated(p[1] - p[0], randomPerpendicular(p[1] - p[0], rng), 2 * pi / 180);
  c = withPoints(c, std::move(p));
  const Network edited = Network::build(turned);
  const SurfaceEdit edit = before.rebuildAfterEdit(edited);
  EXPECT_TRUE(edit.partial);
  EXPECT_LT(edit.changedFaces.size(), size_t(network.faces().size()));
  EXPECT_FALSE(edit.surface.repairMoves().empty());
  const Surface full = Surface::build(edited, {Scheme::GregoryG1});
  EXPECT_EQ(edit.surface.repairMoves().size(), full.repairMoves().size());
  for (int f = 0; f < full.faceCount(); ++f)
    for (const Vec2 &uv : {Vec2{0, 0}, Vec2{0.3, 0.2}, Vec2{-0.4, 0.1}}) {
      const SurfacePoint a = edit.surface.evaluate(f, uv), b = full.evaluate(f, uv);
      EXPECT_EQ(norm(a.point - b.point), 0.0) << "face " << f;
      EXPECT_EQ(norm(a.normal - b.normal), 0.0) << "face " << f;
    }
  EXPECT_LE(measureContinuity(edit.surface, {8}).maxNormalAngleDeg, 1e-6);
}

// With end tangents turned by 3°, corners of both Gregory schemes take the
// two-ribbon blend (Patch::blendShares; gregory-g1: end twists the turned
// curves' first spans bend, gregory-g2: disagreeing corner terms). The
// batched jets (ribbon tables, the SIMD kernel) still agree with the
// pointwise evaluation on those faces.
TEST(RobustnessCorpus, BlendedCornersKeepTheBatchedPathsExact) {
  const Network network = Network::build(turnEndTangents(builtinNetwork(kBase), 3.0, 26), "tangents-3deg");
  for (Scheme scheme : {Scheme::GregoryG1, Scheme::GregoryG2}) {
    SurfaceOptions options;
    options.scheme = scheme;
    const Surface surface = Surface::build(network, options);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> coordinate(-0.6, 0.6);
    int blended = 0;
    double worst = 0;
    for (int f = 0; f < surface.faceCount(); ++f) {
      const Patch &patch = *SurfaceAccess::patch(surface, f);
      blended += int(std::count_if(patch.blendShares().begin(), patch.blendShares().end(), [](double mu) { return mu > 0; }));
      std::vector<double> us, vs;
      while (us.size() < 64) {
        const double u = coordinate(rng), v = coordinate(rng);
        bool inside = true;
        for (int i = 0; i < patch.domain().sides(); ++i) {
          const Vec2 a = patch.domain().corner(i), b = patch.domain().corner(i + 1);
          inside = inside && (b.x - a.x) * (v - a.y) - (b.y - a.y) * (u - a.x) > 1e-9;
        }
        if (inside) us.push_back(u), vs.push_back(v);
      }
      std::vector<DualVec3> jets(us.size());
      patch.evaluateJets(us.size(), us.data(), vs.data(), jets.data());
      for (std::size_t k = 0; k < us.size(); ++k) {
        const DualVec3 exact = patch.evaluate(us[k], vs[k]);
        worst = std::max({worst, norm(jets[k].v - exact.v) / (1 + norm(exact.v)),
                          (norm(jets[k].du - exact.du) + norm(jets[k].dv - exact.dv)) /
                              (1 + norm(exact.du) + norm(exact.dv))});
      }
    }
    std::printf("%s: %d blended corners, batched jets within %.2e of pointwise\n", schemeName(scheme).c_str(), blended,
                worst);
    EXPECT_GT(blended, 0) << schemeName(scheme);
    EXPECT_LE(worst, 1e-10) << schemeName(scheme);
  }
}

// Domain samples (a 81 × 81 grid) where a planar patch in z = const turns
// over: its Jacobian's z component has the sign opposite to `orientation`.
int reversedSamples(const Patch &p, double orientation) {
  int count = 0;
  for (int r = -40; r <= 40; ++r)
    for (int q = -40; q <= 40; ++q) {
      const double u = q / 40.0, v = r / 40.0;
      bool inside = true;
      for (int i = 0; i < p.domain().sides(); ++i) inside = inside && p.domain().perpendicularDistance(i, Dual(u), Dual(v)).v > 1e-3;
      if (!inside) continue;
      const DualVec3 x = p.evaluate(u, v);
      count += cross(x.du, x.dv).z * orientation < 0;
    }
  return count;
}

// A planar triangle with right angles at both ends of its short side and a
// bent long side (box.obj's three-sided faces are of this kind): eq. 17's
// corner interpolants extrapolate right-angled corners into a 60° domain
// and the gregory-g1 patch folds with them; the two-ribbon blend at every
// corner does not. The surface takes the blend, and stays G¹ to its corners.
TEST(RobustnessCorpus, TriangleFoldingUnderEq17TakesTheTwoRibbonBlend) {
  auto cubic = [](Vec3 a, Vec3 b, Vec3 c, Vec3 d) { return BSplineCurve(3, {0, 0, 0, 0, 1, 1, 1, 1}, {a, b, c, d}); };
  const Vec3 a{0, 0, 0}, b{0.29, 0, 0}, c{0.29, 1.2, 0};
  const double turn = 40 * pi / 180; // the long side leaves the top corner 40° off the right side
  NetworkDescription d;
  d.curves = {cubic(a, a + (b - a) / 3.0, a + (b - a) * (2 / 3.0), b), cubic(b, b + (c - b) / 3.0, b + (c - b) * (2 / 3.0), c),
              cubic(c, c + Vec3{-std::sin(turn), -std::cos(turn), 0} * 0.3, a + Vec3{0, 0.3, 0}, a)};
  d.faces = {{{{0, 0, 1}, {1, 0, 1}, {2, 0, 1}}, "triangle"}};
  const Surface surface = Surface::build(Network::build(d), {Scheme::GregoryG1});
  EXPECT_TRUE(surface.foldedFaces().empty());
  const Patch &patch = *SurfaceAccess::patch(surface, 0);
  for (double mu : patch.blendShares()) EXPECT_EQ(mu, 1.0);
  // The same ribbons with eq. 17's corners: the Jacobian turns over.
  std::vector<LinearRibbon> ribbons;
  for (int i = 0; i < 3; ++i) ribbons.push_back(patch.ribbon(i));
  const Patch eq17(ribbons, {Scheme::GregoryG1}, {}, std::vector<double>(3, 0.0));
  EXPECT_GT(reversedSamples(eq17, 1), 0); // the loop runs counter-clockwise about +z
  EXPECT_EQ(reversedSamples(patch, 1), 0);
  // At the corners, where the blend's weight turns with the direction, the
  // normal is the plane's.
  for (int i = 0; i < 3; ++i)
    for (const Vec2 &uv : {patch.domain().corner(i), patch.domain().pointOnSide(i - 1, 1.0), patch.domain().pointOnSide(i, 0.0)})
      EXPECT_NEAR(std::abs(surface.evaluate(0, uv).normal.z), 1.0, 1e-9) << "corner " << i;
}

// A planar half disc with a wavy rim (dress.obj's two-sided faces: radius
// 0.8 at the ends and the top of the rim, 0.49 between): a 2-sided face,
// evaluated as a quad with straight corners at the diameter's middle and
// the rim's top. The ribbons' cross-derivatives take the rim's parameter
// speed (1.25 at its top, where the diameter lies 0.8 away) and reach past
// the diameter: the patch folds with either corner form. With shorter
// cross-derivatives it does not, and its normal along the boundary is
// still the plane's.
TEST(RobustnessCorpus, HalfDiscWithAWavyRimTakesShorterCrossDerivatives) {
  std::vector<double> params;
  std::vector<Vec3> rim;
  for (int k = 0; k <= 32; ++k) {
    const double theta = pi * k / 32, r = 0.8 - 0.31 * std::pow(std::sin(2 * theta), 2);
    params.push_back(k / 32.0);
    rim.push_back({r * std::cos(theta), r * std::sin(theta), 0});
  }
  NetworkDescription d;
  d.curves = {BSplineCurve::interpolate(3, params, rim),
              BSplineCurve::bezier({{-0.8, 0, 0}, {-0.8 / 3, 0, 0}, {0.8 / 3, 0, 0}, {0.8, 0, 0}})};
  d.faces = {{{{0, 0, 1}, {1, 0, 1}}, "half-disc"}};
  const Surface surface = Surface::build(Network::build(d), {Scheme::GregoryG1});
  EXPECT_TRUE(surface.foldedFaces().empty());
  const Patch &patch = *SurfaceAccess::patch(surface, 0);
  ASSERT_EQ(patch.domain().sides(), 4);
  EXPECT_EQ(reversedSamples(patch, 1), 0);
  // The ribbons with their full end targets: the neighbours' tangents, the
  // fence direction where the loop runs straight on.
  std::vector<LinearRibbon> full;
  for (int i = 0; i < 4; ++i) {
    LinearRibbon ribbon = patch.ribbon(i);
    const Vec3 before = patch.ribbon(i - 1).curve().derivatives(1.0)[1], after = patch.ribbon(i + 1).curve().derivatives(0.0)[1];
    const bool straightStart = angleBetween(ribbon.curve().derivatives(0.0)[1], before) < 1e-2;
    const bool straightEnd = angleBetween(ribbon.curve().derivatives(1.0)[1], after) < 1e-2;
    ribbon.setEndConditions(straightStart ? ribbon.fenceDirection(0.0) : -before, straightEnd ? ribbon.fenceDirection(1.0) : after);
    EXPECT_LT(norm(patch.ribbon(i).at(0.5).T), norm(ribbon.at(0.5).T)) << "side " << i;
    full.push_back(std::move(ribbon));
  }
  for (double mu : {0.0, 1.0}) EXPECT_GT(reversedSamples(Patch(full, {Scheme::GregoryG1}, {}, std::vector<double>(4, mu)), 1), 0) << mu;
  for (int i = 0; i < 4; ++i)
    for (double s : {0.0, 0.3, 0.7, 1.0}) {
      const Vec2 uv = patch.domain().pointOnSide(i, s);
      EXPECT_NEAR(std::abs(surface.evaluate(0, uv).normal.z), 1.0, 1e-9) << "side " << i << " at " << s;
    }
}

// Two half discs with wavy rims on the paraboloid z = c (x² + y²), split by
// their common diameter (dress.obj's two faces, bent, with rims of unequal
// waves). Under gregory-g2 the upper one folds with its ribbons' full
// cross-derivatives, with either corner form; it is rebuilt with shorter
// ones (buildFace), whose parabolic ribbons carry the same second
// fundamental form along every side (C = II(T, T) N of the shorter T). The
// lower one folds at full length too, at two corners with eq. 17's corners
// (the corner grid) and inside with the two-ribbon blend, and takes a
// length of its own, so the curvature jump across the diameter compares
// faces rebuilt with different cross-derivatives.
TEST(RobustnessCorpus, BentHalfDiscTakesShorterG2CrossDerivativesAndStaysG2) {
  const double c = 0.6;
  auto lifted = [c](double x, double y) { return Vec3{x, y, c * (x * x + y * y)}; };
  std::vector<double> params;
  std::vector<Vec3> upper, lower;
  for (int k = 0; k <= 32; ++k) {
    params.push_back(k / 32.0);
    for (int half = 0; half < 2; ++half) {
      const double theta = pi * (k / 32.0 + half), r = 0.8 - (half ? 0.2 : 0.31) * std::pow(std::sin(2 * theta), 2);
      (half ? lower : upper).push_back(lifted(r * std::cos(theta), r * std::sin(theta)));
    }
  }
  NetworkDescription d;
  // The diameter z = c x² over y = 0: a parabola, exactly a quadratic Bézier.
  d.curves = {BSplineCurve::interpolate(3, params, upper), BSplineCurve::interpolate(3, params, lower),
              BSplineCurve::bezier({lifted(-0.8, 0), {0, 0, -c * 0.64}, lifted(0.8, 0)})};
  d.faces = {{{{0, 0, 1}, {2, 0, 1}}, "upper"}, {{{1, 0, 1}, {2, 1, 0}}, "lower"}};
  const Surface surface = Surface::build(Network::build(d), {Scheme::GregoryG2});
  EXPECT_TRUE(surface.foldedFaces().empty());
  // How much shorter than its end targets ask a face's cross-derivatives
  // are: the upper face's by 3/4 or 1/2, the lower face's not at all.
  auto shortening = [&](int face) {
    const Patch &patch = *SurfaceAccess::patch(surface, face);
    EXPECT_EQ(patch.domain().sides(), 4);
    double shortest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < patch.domain().sides(); ++i) {
      LinearRibbon full = patch.ribbon(i);
      const Vec3 before = patch.ribbon(i - 1).curve().derivatives(1.0)[1], after = patch.ribbon(i + 1).curve().derivatives(0.0)[1];
      const bool straightStart = angleBetween(full.curve().derivatives(0.0)[1], before) < 1e-2;
      const bool straightEnd = angleBetween(full.curve().derivatives(1.0)[1], after) < 1e-2;
      full.setEndConditions(straightStart ? full.fenceDirection(0.0) : -before,
                            straightEnd ? full.fenceDirection(1.0) : after, LinearRibbon::ScalarBlend::Quintic);
      shortest = std::min(shortest, norm(full.at(0.0).T) / norm(patch.ribbon(i).at(0.0).T));
    }
    return shortest;
  };
  EXPECT_GT(shortening(0), 1.2);
  EXPECT_GT(shortening(1), 1.2);
  EXPECT_GT(std::abs(shortening(0) - shortening(1)), 0.1);
  EXPECT_TRUE(measureShape(surface).cornerFolds.empty());
  // G² and G¹ across the diameter, between the rebuilt face and the other.
  EXPECT_LE(measureCurvatureJump(surface).maxJump, 1e-9);
  EXPECT_LE(measureContinuity(surface, {8}).maxNormalAngleDeg, 1e-9);
}
