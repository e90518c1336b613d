// Ribbon tables and the position-only planned evaluation: the quintic
// Hermite table against functions it must reproduce exactly and against the
// exact ribbons of every built-in; planned positions against the pointwise
// Surface path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <random>

#include "bezier/bezier_surface.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/curvenet.hpp"
#include "curvenet/error.hpp"
#include "curvenet/tessellate.hpp"
#include "patches/patch.hpp"
#include "plans/face_errors.hpp"
#include "plans/plan.hpp"
#include "ribbons/ribbon_table.hpp"

using namespace curvenet;

namespace {
// A test name part for a scheme: gtest allows letters, digits and '_'.
std::string schemeParamName(const testing::TestParamInfo<SurfaceOptions> &info) {
  std::string name = std::to_string(info.index) + "_" + schemeName(info.param.scheme);
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}
} // namespace

TEST(RibbonTable, ReproducesQuinticsAndKinksAtBreaks) {
  // Two coordinates: a quintic (a quintic Hermite interpolant is exact for
  // it) and a function whose derivative jumps at the declared break 0.3.
  auto exact = [](std::span<const double> s, double *values, double *slopes) {
    for (std::size_t k = 0; k < s.size(); ++k) {
      const double x = s[k];
      values[2 * k] = ((((3 * x - 2) * x + 1) * x - 4) * x + 0.5) * x + 2;
      slopes[2 * k] = (((15 * x - 8) * x + 3) * x - 8) * x + 0.5;
      values[2 * k + 1] = x <= 0.3 ? std::sin(x) : std::sin(0.3) + 2 * (x - 0.3) * (x - 0.3) + 3 * (x - 0.3);
      slopes[2 * k + 1] = x <= 0.3 ? std::cos(x) : 4 * (x - 0.3) + 3;
    }
  };
  const RibbonTable table(2, {0.3}, exact);
  EXPECT_LE(table.valueError(), 1e-13);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  double worst = 0, worstSlope = 0;
  for (int k = 0; k < 20000; ++k) {
    const double s = k < 3 ? 0.3 * k : u(rng);
    double want[2], wantSlope[2], got[2], gotSlope[2];
    exact(std::span<const double>(&s, 1), want, wantSlope);
    table.evaluate(s, got, gotSlope);
    for (int c = 0; c < 2; ++c) {
      worst = std::max(worst, std::abs(got[c] - want[c]));
      worstSlope = std::max(worstSlope, std::abs(gotSlope[c] - wantSlope[c]));
    }
  }
  EXPECT_LE(worst, 5e-13);
  EXPECT_LE(worstSlope, 1e-10);
  // Without the break the kink cannot be resolved to the tolerance.
  const RibbonTable blind(2, {}, exact);
  EXPECT_GT(blind.intervals(), table.intervals());
}

// Exact functions whose derivative disagrees with their values (a factor
// of 2, as a wrong term of a derivative would) can never be tabulated to the
// tolerance: building stops with an error saying so, after a bounded number
// of evaluations, instead of refining everywhere and keeping a wrong table.
TEST(RibbonTable, ADerivativeThatDisagreesWithItsValuesIsAnErrorAtBoundedCost) {
  std::size_t evaluations = 0;
  auto inconsistent = [&](std::span<const double> s, double *values, double *slopes) {
    evaluations += s.size();
    for (std::size_t k = 0; k < s.size(); ++k) values[k] = std::sin(3 * s[k]), slopes[k] = 2 * 3 * std::cos(3 * s[k]);
  };
  const std::vector<double> breaks = {0.25, 0.5, 0.75};
  try {
    const RibbonTable table(1, breaks, inconsistent);
    ADD_FAILURE() << "built a table of " << table.intervals() << " intervals with value error " << table.valueError();
  } catch (const InternalError &e) {
    EXPECT_NE(std::string(e.what()).find("disagree"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("gap"), std::string::npos) << e.what();
  }
  // At most the depth limit (2^10 intervals below each of the 4 break
  // intervals), a dozen evaluations each, doubled for the levels above.
  EXPECT_LE(evaluations, std::size_t(4) * 1024 * 12 * 2);
  // The consistent functions are tabulated as before.
  auto consistent = [](std::span<const double> s, double *values, double *slopes) {
    for (std::size_t k = 0; k < s.size(); ++k) values[k] = std::sin(3 * s[k]), slopes[k] = 3 * std::cos(3 * s[k]);
  };
  EXPECT_LE(RibbonTable(1, breaks, consistent).valueError(), 1e-13);
}

// A table that cannot be built while a face is evaluated names the face as
// well as the table's own complaint, and nothing else is caught.
TEST(RibbonTable, ATableThatCannotBeBuiltForAFaceNamesTheFace) {
  auto inconsistent = [](std::span<const double> s, double *values, double *slopes) {
    for (std::size_t k = 0; k < s.size(); ++k) values[k] = std::sin(3 * s[k]), slopes[k] = 2 * 3 * std::cos(3 * s[k]);
  };
  try {
    namingFace(7, [&] { return RibbonTable(1, {0.5}, inconsistent); });
    ADD_FAILURE() << "the inconsistent table was built";
  } catch (const InternalError &e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("face 7: ribbon table: ", 0), 0u) << message;
    EXPECT_NE(message.find("disagree"), std::string::npos) << message;
  }
  EXPECT_THROW(namingFace(7, [] { throw InputError("", "curve 1", "bad"); }), InputError);
  // A side's input error (a table the curves keep from its tolerances) gets the face in its element.
  try {
    namingFace(7, [] { throw InputError("", "side 2", "ribbon table: too steep"); });
    ADD_FAILURE() << "nothing thrown";
  } catch (const InputError &e) {
    EXPECT_EQ(e.element(), "face 7 side 2");
    EXPECT_EQ(e.reason(), "ribbon table: too steep");
  }
  EXPECT_EQ(namingFace(7, [] { return 42; }), 42);
}

TEST(RibbonTable, MatchesExactRibbonsOfEveryBuiltin) {
  for (const BuiltinInfo &info : builtinNetworks()) {
    const Network network = Network::build(builtinNetwork(info.name));
    for (Scheme scheme : {Scheme::GregoryG1, Scheme::GregoryG2}) {
      const Surface surface = Surface::build(network, {scheme});
      std::size_t intervals = 0, sides = 0;
      for (int f = 0; f < surface.faceCount(); ++f) {
        const Patch &patch = *SurfaceAccess::patch(surface, f);
        for (const RibbonTable &t : patch.tables().sides) {
          EXPECT_LE(t.valueError(), 1e-13) << info.name << " face " << f;
          EXPECT_LE(t.slopeError(), 1e-10) << info.name << " face " << f;
          intervals += t.intervals(), ++sides;
        }
      }
      // Compact: a few hundred intervals per side at most on the built-ins.
      EXPECT_LE(intervals, 400 * sides) << info.name;
      std::printf("%-36s %s: %.0f intervals per side\n", info.name.c_str(), schemeName(scheme).c_str(),
                  double(intervals) / double(sides));
    }
  }
}

// The tables sample each breakpoint interval one ulp inside its ends and
// rely on the exact ribbon taking there the piece of the side it is asked
// from. Curves fitted to a sketch carry many interior knots at arbitrary
// parameters, and their sides run against their segments (reversed pieces):
// a segment's knot mapped to the side parameter lands a few ulps off the
// side curve's own, where the ribbon's second derivatives actually jump. So
// one ulp beside every listed breakpoint the ribbon must already be on that
// side: its second derivatives there agree with those a little further in.
TEST(RibbonTable, RibbonsTakeTheSideOfEveryBreakpointTheyAreAskedFrom) {
  const std::filesystem::path sketch = std::filesystem::path(CURVENET_SHARED_DATA_DIR) / "sketches" / "doghead.obj";
  if (!std::filesystem::is_regular_file(sketch)) GTEST_SKIP() << sketch << " is not there (shared data absent)";
  auto model = Model::load(sketch.string(), {.scheme = Scheme::GregoryG2});
  ASSERT_TRUE(model.ok()) << model.status().toString();
  std::size_t checked = 0;
  for (int f = 0; f < model->faceCount(); ++f) {
    const Patch &patch = *SurfaceAccess::patch(*model->surface(f), f);
    for (int side = 0; side < patch.domain().sides(); ++side) {
      const LinearRibbon &ribbon = patch.ribbon(side);
      for (double b : ribbon.breakpoints()) {
        for (double towards : {0.0, 1.0}) {
          const double inside = std::nextafter(b, towards), further = b + (towards - b) * 1e-9;
          if (!(further != inside) || b <= 0 || b >= 1) continue;
          const LinearRibbon::SecondJet at = ribbon.secondJet(inside), beyond = ribbon.secondJet(further);
          // Within 1e-9 of the interval the third derivatives move ddT by
          // far less than this; a jump at a knot moves it by its own size.
          const double size = norm(beyond.ddT) + norm(beyond.dT) + norm(beyond.T);
          EXPECT_LE(norm(at.ddT - beyond.ddT), 1e-5 * size)
              << "face " << f << " side " << side << " breakpoint " << b << (towards > b ? " from above" : " from below");
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 100u);
}

// Curves fitted to sketches carry knots within 2e-6 of a curve end: the
// breakpoint interval there is ~1e-6 wide, where the difference of two
// ribbon values loses the digits a slope needs. Such a side is tabulated to
// the same tolerances as any other (and the table builder's strict check,
// which stops on any interval that cannot reach them, lets it through).
TEST(RibbonTable, ABreakpointIntervalOneMillionthWideMeetsTheTolerances) {
  const double bump = 0.2;
  auto bezier = [&](Vec3 a, Vec3 b) {
    const Vec3 lift{0, 0, bump};
    return std::vector<Vec3>{a, a + (b - a) / 3.0 + lift, b + (a - b) / 3.0 + lift, b};
  };
  const Vec3 corner[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  NetworkDescription d;
  d.name = "near-end knot";
  for (int k = 0; k < 4; ++k) {
    const std::vector<Vec3> b = bezier(corner[k], corner[(k + 1) % 4]);
    if (k > 0) {
      d.curves.push_back(BSplineCurve(3, {0, 0, 0, 0, 1, 1, 1, 1}, b));
      continue;
    }
    // Curve 0: the Bézier with the knot u = 1 − 1e-6 inserted (Boehm), as a
    // fit leaves a knot near a curve end: the shape is smooth, the
    // breakpoint interval [u, 1] a millionth wide.
    const double u = 1 - 1e-6;
    std::vector<Vec3> q{b[0]};
    for (int i = 1; i <= 3; ++i) q.push_back(u * b[i] + (1 - u) * b[i - 1]);
    q.push_back(b[3]);
    d.curves.push_back(BSplineCurve(3, {0, 0, 0, 0, u, 1, 1, 1, 1}, q));
  }
  d.faces.push_back({{{0, 0, 1}, {1, 0, 1}, {2, 0, 1}, {3, 0, 1}}});
  const Network network = Network::build(d);
  for (Scheme scheme : {Scheme::GregoryG1, Scheme::GregoryG2}) {
    const Surface surface = Surface::build(network, {.scheme = scheme, .curves = CurveHandling::Kept});
    const Patch &patch = *SurfaceAccess::patch(surface, 0);
    double breakInterval = 1;
    for (int side = 0; side < 4; ++side) {
      const std::vector<double> breaks = patch.ribbon(side).breakpoints();
      for (std::size_t k = 0; k + 1 < breaks.size(); ++k)
        breakInterval = std::min(breakInterval, breaks[k + 1] - breaks[k]);
      for (double b : breaks) breakInterval = std::min({breakInterval, b > 0 ? b : 1.0, b < 1 ? 1 - b : 1.0});
    }
    EXPECT_LT(breakInterval, 2e-6) << "the side lost its near-end breakpoint";
    ASSERT_EQ(patch.tables().sides.size(), 4u);
    for (int side = 0; side < 4; ++side) {
      EXPECT_LE(patch.tables().sides[side].valueError(), 1e-13) << schemeName(scheme) << " side " << side;
      EXPECT_LE(patch.tables().sides[side].slopeError(), 1e-10) << schemeName(scheme) << " side " << side;
    }
  }
}

// Every public sketch (through the curve-graph reader) tabulates every side
// under gregory-g2 to the tables' tolerances: the builder's strict check
// stops on any side that cannot reach them.
TEST(RibbonTable, EverySketchSideIsTabulatedToTheTolerancesUnderGregoryG2) {
  const std::filesystem::path sketches = std::filesystem::path(CURVENET_SHARED_DATA_DIR) / "sketches";
  if (!std::filesystem::is_directory(sketches)) GTEST_SKIP() << sketches << " is not there (shared data absent)";
  std::size_t tables = 0;
  for (const char *name : {"bathtub", "box", "doghead", "dress", "ellipsetorus", "iron", "sewing_machine",
                           "spherecylinder"}) {
    const std::string path = (sketches / (std::string(name) + ".obj")).string();
    auto model = Model::load(path, {.scheme = Scheme::GregoryG2, .curves = CurveHandling::Kept});
    ASSERT_TRUE(model.ok()) << model.status().toString();
    double valueError = 0, slopeError = 0;
    for (int f = 0; f < model->faceCount(); ++f) {
      try {
        for (const RibbonTable &t : SurfaceAccess::patch(*model->surface(f), f)->tables().sides) {
          valueError = std::max(valueError, t.valueError());
          slopeError = std::max(slopeError, t.slopeError());
          ++tables;
        }
      } catch (const InternalError &e) {
        ADD_FAILURE() << name << " face " << f << ": " << e.what();
      }
    }
    EXPECT_LE(valueError, 1e-13) << name;
    EXPECT_LE(slopeError, 1e-10) << name;
  }
  EXPECT_GT(tables, 800u);
}

// One test per scheme, so that the suite's parallel runner (and the slow
// sanitizer builds) can spread them over its jobs.
class PlannedPositions : public testing::TestWithParam<SurfaceOptions> {};

TEST_P(PlannedPositions, MatchPointwiseEvaluationOnEveryBuiltin) {
  SurfaceOptions o = GetParam();
  o.curves = CurveHandling::Kept; // the curves as given: this compares evaluation paths, not repairs
  for (const BuiltinInfo &info : builtinNetworks()) {
    const Network network = Network::build(builtinNetwork(info.name));
    {
      const Surface surface = Surface::build(network, o);
      BoundingBox box;
      for (const Vertex &v : network.vertices()) box.add(v.position);
      double worst = 0, worstPlanned = 0, worstSlope = 0;
      // r = 40: ribbons through the tables; r = 9: exactly.
      for (int f = 0; f < 2 * surface.faceCount(); ++f) {
        const Patch &patch = *SurfaceAccess::patch(surface, f / 2);
        const auto plan = evaluationPlan(planKey(surface.options(), surface.domainSides(f / 2), f % 2 ? 9 : 40));
        std::vector<double> x(plan->size()), y(plan->size()), z(plan->size());
        double *out[3] = {x.data(), y.data(), z.data()};
        patch.evaluatePlannedPositions(*plan, 0, plan->size(), out);
        // By rotation groups (G²: the corner weights shared): the numbers of
        // the members evaluated one by one (the same blocks of samples).
        std::vector<double> grouped(3 * plan->size()), single(3 * plan->size());
        const PositionSink groupedSink = PositionSink::soa(std::array<double *, 3>{
            &grouped[0], &grouped[plan->size()], &grouped[2 * plan->size()]}.data());
        const PositionSink singleSink = PositionSink::soa(std::array<double *, 3>{
            &single[0], &single[plan->size()], &single[2 * plan->size()]}.data());
        for (const EvaluationPlan::Group &g : plan->groups(f % 2 ? 5 : 200)) {
          patch.evaluatePlannedGroup(*plan, g, groupedSink.from(g.first));
          for (int m = 0; m < g.members; ++m)
            patch.evaluatePlannedPositions(*plan, g.first + m * g.stride, g.count,
                                           singleSink.from(g.first + m * g.stride));
        }
        std::size_t mismatches = 0;
        for (std::size_t k = 0; k < grouped.size(); ++k) mismatches += grouped[k] != single[k];
        EXPECT_EQ(mismatches, 0u) << info.name << " face " << f / 2 << " " << schemeName(o.scheme);
        // The jets the same way (the tessellator's pass, G²'s weights and
        // their partials shared): the numbers of the members one by one.
        std::vector<double> groupedJets(9 * plan->size()), singleJets(9 * plan->size());
        auto into = [&](std::vector<double> &to, std::size_t first) {
          return [&to, first, &plan](std::size_t at, std::size_t size, const double *const jet[9]) {
            for (int c = 0; c < 9; ++c)
              for (std::size_t k = 0; k < size; ++k) to[c * plan->size() + first + at + k] = jet[c][k];
          };
        };
        for (const EvaluationPlan::Group &g : plan->groups(f % 2 ? 5 : 200)) {
          patch.evaluatePlannedGroup(*plan, g, [&](int m, std::size_t at, std::size_t size, const double *const jet[9]) {
            into(groupedJets, g.first + m * g.stride)(at, size, jet);
          });
          for (int m = 0; m < g.members; ++m)
            patch.evaluatePlanned(*plan, g.first + m * g.stride, g.count, into(singleJets, g.first + m * g.stride));
        }
        mismatches = 0;
        for (std::size_t k = 0; k < groupedJets.size(); ++k) mismatches += groupedJets[k] != singleJets[k];
        EXPECT_EQ(mismatches, 0u) << info.name << " face " << f / 2 << " " << schemeName(o.scheme) << " (jets)";
        std::vector<DualVec3> planned(plan->size());
        patch.evaluatePlanned(*plan, 0, plan->size(), planned.data());
        for (std::size_t k = 0; k < plan->size(); k += 23) {
          const DualVec3 p = patch.evaluate(plan->samples()[k].x, plan->samples()[k].y);
          worst = std::max(worst, norm(Vec3{x[k], y[k], z[k]} - p.v));
          worstPlanned = std::max(worstPlanned, norm(planned[k].v - p.v));
          // Relative to the derivatives themselves: on triangles they grow
          // without bound towards the corners' opposite sides' sweep poles.
          const double size = box.diagonal() + norm(p.du) + norm(p.dv);
          worstSlope = std::max({worstSlope, norm(planned[k].du - p.du) / size, norm(planned[k].dv - p.dv) / size});
        }
      }
      EXPECT_LE(worst, 1e-12 * box.diagonal()) << info.name << " " << schemeName(o.scheme);
      EXPECT_LE(worstPlanned, 1e-12 * box.diagonal()) << info.name << " " << schemeName(o.scheme);
      EXPECT_LE(worstSlope, 1e-9) << info.name << " " << schemeName(o.scheme);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Schemes, PlannedPositions,
                         testing::Values(SurfaceOptions{Scheme::GregoryG1, Sweepline::Radial},
                                         SurfaceOptions{Scheme::GregoryG2, Sweepline::Hermite},
                                         SurfaceOptions{Scheme::CompositeRibbon}),
                         schemeParamName);

class BatchEvaluation : public testing::TestWithParam<SurfaceOptions> {};

TEST_P(BatchEvaluation, MatchesPointwiseEvaluationAtRandomDomainPoints) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(0, 1);
  const SurfaceOptions o = GetParam();
  for (const BuiltinInfo &info : builtinNetworks()) {
    const Network network = Network::build(builtinNetwork(info.name));
    {
      const Surface surface = Surface::build(network, o);
      BoundingBox box;
      for (const Vertex &v : network.vertices()) box.add(v.position);
      double worst = 0, worstJet = 0;
      for (int f = 0; f < surface.faceCount(); ++f) {
        const Patch &patch = *SurfaceAccess::patch(surface, f);
        const int n = surface.domainSides(f);
        // Uniform points of the fan triangles (centre, corner j, corner j + 1), the centre itself first.
        std::vector<double> u{0.0}, v{0.0};
        for (int k = 0; k < 600; ++k) {
          const int j = static_cast<int>(unit(rng) * n) % n;
          double a = unit(rng), b = unit(rng);
          if (a + b > 1) a = 1 - a, b = 1 - b;
          const Vec2 p = surface.domainCorner(f, j) * a + surface.domainCorner(f, j + 1) * b;
          u.push_back(p.x), v.push_back(p.y);
        }
        std::vector<double> x(u.size()), y(u.size()), z(u.size());
        double *out[3] = {x.data(), y.data(), z.data()};
        patch.evaluatePositions(u.size(), u.data(), v.data(), out);
        std::vector<DualVec3> jets(u.size());
        patch.evaluateBatch(u.size(), u.data(), v.data(), jets.data());
        for (std::size_t k = 0; k < u.size(); ++k) {
          const DualVec3 p = patch.evaluate(u[k], v[k]);
          worst = std::max(worst, norm(Vec3{x[k], y[k], z[k]} - p.v));
          worstJet = std::max({worstJet, norm(jets[k].v - p.v), norm(jets[k].du - p.du) / (1 + norm(p.du)),
                               norm(jets[k].dv - p.dv) / (1 + norm(p.dv))});
        }
      }
      EXPECT_LE(worst, 1e-12 * box.diagonal()) << info.name << " " << schemeName(o.scheme);
      EXPECT_LE(worstJet, 1e-11 * (1 + box.diagonal())) << info.name << " " << schemeName(o.scheme) << " (with derivatives)";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Schemes, BatchEvaluation,
                         testing::Values(SurfaceOptions{Scheme::GregoryG1, Sweepline::Radial},
                                         SurfaceOptions{Scheme::GregoryG1, Sweepline::Hermite},
                                         SurfaceOptions{Scheme::GregoryG2, Sweepline::Hermite},
                                         SurfaceOptions{Scheme::CompositeRibbon}),
                         schemeParamName);
