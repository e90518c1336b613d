// Evaluation plans: rotation symmetry of the side parameters, the cache
// (one build per key under concurrent lookups), and plan-based tessellation
// against the pointwise Surface::evaluate path on every built-in and scheme.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <stdexcept>
#include <thread>

#include "curvenet/builtins.hpp"
#include "curvenet/error.hpp"
#include "curvenet/tessellate.hpp"
#include "patches/domain.hpp"
#include "plans/plan.hpp"

using namespace curvenet;

namespace {

// On the curves as given: the vertex repair would tweak the cubic Bézier
// built-ins under gregory-g2, and these tests compare evaluation paths.
std::vector<SurfaceOptions> schemes() {
  const CurveHandling kept = CurveHandling::Kept;
  return {{Scheme::GregoryG1, Sweepline::Radial, FenceNormals::Auto, EdgeCurvature::Direct, MasterFaces::Rebuilt, kept},
          {Scheme::GregoryG1, Sweepline::Hermite, FenceNormals::Auto, EdgeCurvature::Direct, MasterFaces::Rebuilt, kept},
          {Scheme::CompositeRibbon, Sweepline::Auto, FenceNormals::Auto, EdgeCurvature::Direct, MasterFaces::Rebuilt, kept},
          {Scheme::GregoryG2, Sweepline::Hermite, FenceNormals::Auto, EdgeCurvature::Direct, MasterFaces::Rebuilt, kept},
          {Scheme::GregoryG2, Sweepline::QuinticHermite, FenceNormals::Auto, EdgeCurvature::Direct, MasterFaces::Rebuilt,
           kept}};
}

std::string label(const SurfaceOptions &o) {
  return schemeName(o.scheme) + (o.sweepline == Sweepline::Radial ? "/radial"
                                 : o.sweepline == Sweepline::QuinticHermite ? "/quintic" : "/hermite");
}

} // namespace

TEST(EvaluationPlan, RotatedSideZeroDataIsEverySidesOwn) {
  // Side i at sample k computed directly equals side 0 at the rotated sample,
  // gradients turned: the n-fold symmetry that lets one solve serve n sides.
  for (int n = 3; n <= 8; ++n)
    for (const SurfaceOptions &o : schemes()) {
      if (o.scheme == Scheme::CompositeRibbon) continue;
      const PlanKey key = planKey(o, n, 9);
      const EvaluationPlan plan(key);
      const RegularDomain domain(n);
      const bool quintic = key.sweepline == Sweepline::QuinticHermite;
      for (std::size_t k = 0; k < plan.size(); ++k) {
        const Dual u = Dual::u(plan.samples()[k].x), v = Dual::vCoord(plan.samples()[k].y);
        for (int i = 0; i < n; ++i) {
          // (A triangle's cubic sweep is closed-form, see RegularDomain::triangleSideParameter.)
          const Dual direct = key.sweepline == Sweepline::Radial ? domain.radialSideParameter(i, u, v)
                              : n == 3 && !quintic               ? domain.triangleSweep(i, u, v)
                                                                 : domain.hermiteSweepByGrid(i, u, v, quintic).s;
          const Dual planned = plan.side(i, k);
          ASSERT_NEAR(planned.v, direct.v, 1e-12) << label(o) << " n=" << n << " k=" << k << " side " << i;
          ASSERT_NEAR(planned.du, direct.du, 1e-9 * (1 + std::abs(direct.du)));
          ASSERT_NEAR(planned.dv, direct.dv, 1e-9 * (1 + std::abs(direct.dv)));
          const Dual distance = domain.perpendicularDistance(i, u, v), planDistance = plan.distance(i, k);
          ASSERT_NEAR(planDistance.v, distance.v, 1e-13);
          ASSERT_NEAR(planDistance.du, distance.du, 1e-12);
        }
      }
    }
}

TEST(RegularDomain, AllSidesSweepsInOneBatchMatchTheIndependentSolver) {
  // hermiteSweepSides (every side of a point in one kernel call, its lanes
  // padded) against the grid solver side by side, on the resolution-9 plan
  // samples (corners, sides, spokes, interiors) and on random interior
  // points; values and gradients.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  for (int n = 3; n <= 8; ++n)
    for (bool quintic : {false, true}) {
      const RegularDomain domain(n);
      const EvaluationPlan plan(planKey({Scheme::GregoryG2, Sweepline::Hermite}, n, 9));
      std::vector<Vec2> points(plan.samples().begin(), plan.samples().end());
      while (points.size() < 2000) {
        const Vec2 p{coordinate(rng), coordinate(rng)};
        bool inside = true;
        for (int i = 0; i < n; ++i)
          inside = inside && cross(domain.corner(i + 1) - domain.corner(i), p - domain.corner(i)) > 0;
        if (inside) points.push_back(p);
      }
      for (const Vec2 &p : points) {
        const Dual u = Dual::u(p.x), v = Dual::vCoord(p.y);
        std::array<Dual, 8> batched;
        domain.hermiteSweepSides(u, v, quintic, batched);
        for (int i = 0; i < n; ++i) {
          const Dual direct =
              n == 3 && !quintic ? domain.triangleSweep(i, u, v) : domain.hermiteSweepByGrid(i, u, v, quintic).s;
          ASSERT_NEAR(batched[i].v, direct.v, 1e-12) << "n=" << n << " side " << i << " at " << p.x << ", " << p.y;
          ASSERT_NEAR(batched[i].du, direct.du, 1e-9 * (1 + std::abs(direct.du)));
          ASSERT_NEAR(batched[i].dv, direct.dv, 1e-9 * (1 + std::abs(direct.dv)));
        }
      }
    }
}

TEST(EvaluationPlan, BatchedSidesMatchTheRotation) {
  // sidesAndBlends (the batched reads: the plan's own arrays on runs that
  // every rotation keeps consecutive, gathered elsewhere, the gradients in
  // side 0's frame with their turn) equals side() and blend() on every
  // member of the rotation groups and on ranges straddling the spokes and
  // triangle boundaries.
  for (int n = 3; n <= 8; ++n)
    for (const SurfaceOptions &o : schemes()) {
      if (o.scheme == Scheme::CompositeRibbon) continue;
      const EvaluationPlan plan(planKey(o, n, 11));
      std::vector<std::pair<std::size_t, std::size_t>> ranges;
      for (const EvaluationPlan::Group &g : plan.groups(7))
        for (int m = 0; m < g.members; ++m) ranges.push_back({g.first + m * g.stride, g.count});
      const std::size_t spokesEnd = 1 + static_cast<std::size_t>(n) * 10;
      ranges.push_back({0, plan.size()});
      ranges.push_back({spokesEnd - 3, 9});
      ranges.push_back({plan.size() - 40, 40});
      std::vector<double> data(6 * plan.size());
      for (const auto &[first, count] : ranges)
        for (int i = 0; i < n; ++i) {
          double *const s[3] = {&data[0], &data[count], &data[2 * count]};
          double *const b[3] = {&data[3 * count], &data[4 * count], &data[5 * count]};
          const SideBlendArrays got = plan.sidesAndBlends(i, first, count, s, b);
          // Where the run is consecutive in every rotation, no copy is made.
          EXPECT_EQ(got.s[0] == s[0], count > plan.rotationRun(first)) << "n=" << n << " first " << first;
          auto turned = [](const double *const(&a)[3], const double (&turn)[2], std::size_t k) {
            return Dual{a[0][k], turn[0] * a[1][k] - turn[1] * a[2][k], turn[1] * a[1][k] + turn[0] * a[2][k]};
          };
          for (std::size_t k = 0; k < count; ++k) {
            const Dual side = plan.side(i, first + k), blend = plan.blend(i, first + k);
            const Dual gotSide = turned(got.s, got.sideTurn, k), gotBlend = turned(got.blend, got.blendTurn, k);
            ASSERT_EQ(gotSide.v, side.v);
            ASSERT_NEAR(gotSide.du, side.du, 1e-14 * (1 + std::abs(side.du)));
            ASSERT_NEAR(gotSide.dv, side.dv, 1e-14 * (1 + std::abs(side.dv)));
            ASSERT_EQ(gotBlend.v, blend.v);
            ASSERT_NEAR(gotBlend.du, blend.du, 1e-14 * (1 + std::abs(blend.du)));
            ASSERT_NEAR(gotBlend.dv, blend.dv, 1e-14 * (1 + std::abs(blend.dv)));
          }
        }
    }
}

TEST(EvaluationPlan, RotatedSampleIsTheSampleTurnedBackBySideAngle) {
  // Side i's data at sample k are side 0's at rotated(i, k): the domain
  // point that the turn taking side 0 onto side i maps to sample k. Checked
  // against the sample positions themselves, not the layout's arithmetic.
  for (int n = 3; n <= 8; ++n)
    for (int r : {1, 2, 3, 4, 11}) {
      const EvaluationPlan plan(planKey({Scheme::GregoryG2}, n, r));
      for (int i = 0; i < n; ++i) {
        const double angle = 2 * std::numbers::pi * i / n, c = std::cos(angle), s = std::sin(angle);
        for (std::size_t k = 0; k < plan.size(); ++k) {
          const std::size_t j = plan.rotated(i, k);
          ASSERT_LT(j, plan.size()) << "n=" << n << " r=" << r << " i=" << i << " k=" << k;
          const Vec2 p = plan.samples()[j], q = plan.samples()[k];
          ASSERT_NEAR(c * p.x - s * p.y, q.x, 1e-12) << "n=" << n << " r=" << r << " i=" << i << " k=" << k;
          ASSERT_NEAR(s * p.x + c * p.y, q.y, 1e-12) << "n=" << n << " r=" << r << " i=" << i << " k=" << k;
        }
      }
    }
}

TEST(EvaluationPlan, GroupsCoverEverySampleOnceAndRotateMemberOntoMember) {
  // Side i's data on member m of a group are side 0's on member m − i at
  // the same offsets: rotated() says so for every sample.
  for (int n = 3; n <= 8; ++n)
    for (int r : {1, 2, 3, 11}) {
      const EvaluationPlan plan(planKey({Scheme::GregoryG2}, n, r));
      std::vector<int> covered(plan.size(), 0);
      for (std::size_t maxCount : {std::size_t{4}, std::size_t{1000}})
        for (const EvaluationPlan::Group &g : plan.groups(maxCount)) {
          ASSERT_GE(g.count, 1u);
          ASSERT_LE(g.count, maxCount);
          ASSERT_TRUE(g.members == 1 || g.members == n) << "n=" << n << " r=" << r;
          for (int m = 0; m < g.members; ++m)
            for (std::size_t o = 0; o < g.count; ++o) {
              const std::size_t k = g.first + m * g.stride + o;
              if (maxCount == 4) ++covered.at(k);
              for (int i = 0; i < n; ++i) {
                const int from = g.source(m, i);
                ASSERT_EQ(plan.rotated(i, k), g.first + from * g.stride + o) << "n=" << n << " r=" << r << " k=" << k;
              }
            }
        }
      for (std::size_t k = 0; k < plan.size(); ++k) ASSERT_EQ(covered[k], 1) << "n=" << n << " r=" << r << " sample " << k;
    }
}

TEST(EvaluationPlan, RotationRunsReadEverySideFromSideZero) {
  // Within a rotation run every side's samples are consecutive samples of
  // side 0's (the position path reads side 0's arrays there), and a run ends
  // where the next sample leaves that: the plan stores one side's values.
  for (int n = 3; n <= 8; ++n)
    for (const SurfaceOptions &o : schemes()) {
      if (o.scheme == Scheme::CompositeRibbon) continue;
      for (int r : {1, 2, 3, 11}) {
        const EvaluationPlan plan(planKey(o, n, r));
        for (std::size_t k = 0; k < plan.size(); ++k) {
          const std::size_t run = plan.rotationRun(k);
          ASSERT_GE(run, 1u);
          ASSERT_LE(k + run, plan.size());
          for (int i = 0; i < n; ++i) {
            const double *side = plan.sideValuesFrom(i, k), *blend = plan.blendValuesFrom(i, k);
            for (std::size_t m = 0; m < run; ++m) {
              ASSERT_EQ(plan.rotated(i, k + m), plan.rotated(i, k) + m) << label(o) << " n=" << n << " r=" << r;
              ASSERT_EQ(side[m], plan.sideValue(i, k + m)) << label(o) << " n=" << n << " r=" << r << " k=" << k;
              ASSERT_EQ(blend[m], plan.blendValue(i, k + m)) << label(o) << " n=" << n << " r=" << r << " k=" << k;
            }
          }
          if (k + run < plan.size()) {
            bool ends = false;
            for (int i = 1; i < n; ++i) ends = ends || plan.rotated(i, k + run) != plan.rotated(i, k) + run;
            EXPECT_TRUE(ends) << "n=" << n << " r=" << r << " k=" << k << ": the run could go on";
          }
        }
      }
    }
}

TEST(EvaluationPlan, CacheBuildsEachKeyOnceUnderConcurrentLookups) {
  clearEvaluationPlans();
  const PlanKey key{Scheme::GregoryG2, Sweepline::Hermite, 5, 40};
  std::vector<std::shared_ptr<const EvaluationPlan>> got(8);
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t) threads.emplace_back([&, t] { got[t] = evaluationPlan(key); });
  for (auto &t : threads) t.join();
  for (const auto &p : got) EXPECT_EQ(p.get(), got[0].get());
  EXPECT_EQ(evaluationPlanCache().plans, 1u);
  EXPECT_GT(evaluationPlanCache().bytes, got[0]->size() * 72);
  clearEvaluationPlans();
  EXPECT_EQ(evaluationPlanCache().plans, 0u);
  EXPECT_NE(evaluationPlan(key).get(), got[0].get()); // rebuilt after clearing
}

TEST(PlannedTessellation, MatchesPointwiseEvaluationOnEveryBuiltinAndScheme) {
  for (const BuiltinInfo &info : builtinNetworks()) {
    const Network network = Network::build(builtinNetwork(info.name));
    for (const SurfaceOptions &o : schemes()) {
      const Surface surface = Surface::build(network, o);
      TessellationOptions planned{7, 0, false, true}, pointwise{7, 0, false, false};
      const Mesh a = tessellate(surface, planned), b = tessellate(surface, pointwise);
      ASSERT_EQ(a.positions.size(), b.positions.size());
      ASSERT_EQ(a.triangles, b.triangles);
      BoundingBox box;
      for (const Vec3 &p : b.positions) box.add(p);
      double worst = 0, worstNormal = 0;
      for (size_t k = 0; k < a.positions.size(); ++k) {
        worst = std::max(worst, norm(a.positions[k] - b.positions[k]));
        worstNormal = std::max(worstNormal, norm(a.normals[k] - b.normals[k]));
      }
      EXPECT_LE(worst, 1e-12 * box.diagonal()) << info.name << " " << label(o);
      EXPECT_LE(worstNormal, 1e-9) << info.name << " " << label(o);
    }
  }
}

TEST(PlannedTessellation, BytesDoNotDependOnThreads) {
  const Network network = Network::build(builtinNetwork("pentagon"));
  for (const SurfaceOptions &o : schemes()) {
    const Surface surface = Surface::build(network, o);
    // Large enough for the parallel path and several tiles per face.
    const Mesh one = tessellate(surface, {48, 1}), two = tessellate(surface, {48, 2}), all = tessellate(surface, {48, 0});
    ASSERT_EQ(one.positions.size(), two.positions.size());
    EXPECT_EQ(0, std::memcmp(one.positions.data(), two.positions.data(), one.positions.size() * sizeof(Vec3)))
        << label(o);
    EXPECT_EQ(0, std::memcmp(one.normals.data(), two.normals.data(), one.normals.size() * sizeof(Vec3))) << label(o);
    EXPECT_EQ(0, std::memcmp(one.positions.data(), all.positions.data(), one.positions.size() * sizeof(Vec3)));
    EXPECT_EQ(one.triangles, two.triangles);
  }
}

// tessellate into a Mesh that held something else (another surface, a
// larger resolution, domain points, every value overwritten with garbage)
// gives the bytes of a fresh tessellation: nothing of the old mesh survives.
TEST(PlannedTessellation, ReusedMeshGivesTheBytesOfAFreshOne) {
  const Surface other = Surface::build(Network::build(builtinNetwork("pentagon")), {Scheme::GregoryG1});
  for (const char *name : {"pentagon", "torus-mixed"})
    for (const SurfaceOptions &o : schemes()) {
      if (name != std::string("pentagon") && o.scheme != Scheme::GregoryG2) continue; // several faces: one scheme
      const Surface surface = Surface::build(Network::build(builtinNetwork(name)), o);
      for (bool record : {false, true}) {
        TessellationOptions options{20, 2, record};
        Mesh reused = tessellate(other, {33, 1, !record});
        std::fill(reused.positions.begin(), reused.positions.end(), Vec3{7, 7, 7});
        std::fill(reused.normals.begin(), reused.normals.end(), Vec3{7, 7, 7});
        std::fill(reused.triangles.begin(), reused.triangles.end(), std::array<std::uint32_t, 3>{7, 7, 7});
        std::fill(reused.domainPoints.begin(), reused.domainPoints.end(), MeshDomainPoint{7, {7, 7}});
        tessellate(surface, options, reused);
        const Mesh fresh = tessellate(surface, options);
        ASSERT_EQ(reused.positions.size(), fresh.positions.size()) << name << " " << label(o);
        ASSERT_EQ(reused.normals.size(), fresh.normals.size());
        ASSERT_EQ(reused.domainPoints.size(), fresh.domainPoints.size());
        EXPECT_EQ(0, std::memcmp(reused.positions.data(), fresh.positions.data(), fresh.positions.size() * sizeof(Vec3)))
            << name << " " << label(o);
        EXPECT_EQ(0, std::memcmp(reused.normals.data(), fresh.normals.data(), fresh.normals.size() * sizeof(Vec3)))
            << name << " " << label(o);
        for (std::size_t k = 0; k < fresh.domainPoints.size(); ++k) {
          EXPECT_EQ(reused.domainPoints[k].face, fresh.domainPoints[k].face);
          EXPECT_EQ(reused.domainPoints[k].uv, fresh.domainPoints[k].uv);
        }
        EXPECT_EQ(reused.triangles, fresh.triangles);
        EXPECT_EQ(reused.faceTriangleStart, fresh.faceTriangleStart);
      }
    }
}

// Progress reports come on the calling thread only (the callback needs no
// locking), never decrease, start at 0 and end at exactly 1, and do not
// change the mesh — on the planned and the pointwise path, with 2 threads.
TEST(PlannedTessellation, ProgressReportsOnTheCallingThreadAndKeepTheBytes) {
  const Network network = Network::build(builtinNetwork("pentagon"));
  const Surface surface = Surface::build(network, {Scheme::GregoryG2});
  for (bool usePlans : {true, false}) {
    std::vector<double> fractions;
    bool otherThread = false;
    const auto caller = std::this_thread::get_id();
    TessellationOptions options{64, 2, false, usePlans};
    options.progress = [&](double fraction) {
      otherThread |= std::this_thread::get_id() != caller;
      fractions.push_back(fraction);
    };
    const Mesh reported = tessellate(surface, options);
    const Mesh plain = tessellate(surface, {64, 2, false, usePlans});
    EXPECT_FALSE(otherThread);
    ASSERT_GE(fractions.size(), 2u);
    EXPECT_EQ(fractions.front(), 0.0);
    EXPECT_EQ(fractions.back(), 1.0);
    for (std::size_t k = 1; k < fractions.size(); ++k) EXPECT_LE(fractions[k - 1], fractions[k]);
    ASSERT_EQ(reported.positions.size(), plain.positions.size());
    EXPECT_EQ(0, std::memcmp(reported.positions.data(), plain.positions.data(), plain.positions.size() * sizeof(Vec3)));
    EXPECT_EQ(reported.triangles, plain.triangles);
  }
  // A callback that throws (a cancelled call) aborts the tessellation.
  TessellationOptions cancelled{64, 2};
  cancelled.progress = [](double) { throw std::runtime_error("cancelled"); };
  EXPECT_THROW(tessellate(surface, cancelled), std::runtime_error);
}

TEST(FaceInteriors, AreTheTessellationsInteriorPointsAndIgnoreTheThreadCount) {
  // evaluateFaceInteriors (positions kernel, points written with the origin)
  // against the interior vertices tessellate() places (jet kernel), on
  // networks with several faces and n-gons; the caller-buffer form gives the
  // same bytes for one and two threads and refuses a short buffer.
  for (const char *name : {"pentagon", "torus-mixed"}) {
    const Network network = Network::build(builtinNetwork(name));
    BoundingBox box;
    for (const Vertex &v : network.vertices()) box.add(v.position);
    for (const SurfaceOptions &o : schemes()) {
      const Surface surface = Surface::build(network, o);
      const TessellationOptions options{36, 1};
      const std::vector<Vec3> points = evaluateFaceInteriors(surface, options);
      const Mesh mesh = tessellate(surface, options);
      ASSERT_EQ(points.size(), faceInteriorPoints(surface, 36)) << name << " " << label(o);
      ASSERT_LE(points.size(), mesh.positions.size());
      const std::size_t base = mesh.positions.size() - points.size();
      double worst = 0;
      for (std::size_t k = 0; k < points.size(); ++k) worst = std::max(worst, norm(points[k] - mesh.positions[base + k]));
      EXPECT_LE(worst, 1e-12 * box.diagonal()) << name << " " << label(o);

      std::vector<Vec3> two(points.size());
      EXPECT_EQ(evaluateFaceInteriors(surface, two, {36, 2}), points.size());
      EXPECT_EQ(std::memcmp(two.data(), points.data(), points.size() * sizeof(Vec3)), 0) << name << " " << label(o);
      std::vector<Vec3> shorter(points.size() - 1);
      EXPECT_THROW(evaluateFaceInteriors(surface, shorter, options), InputError);
    }
  }
}
