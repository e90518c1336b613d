// Engine phases and kernels. Names say what runs:
//   Tessellate/<scheme>/<model>/r<resolution>/<cold|warm>/t<threads>
//   PlanBuild/<scheme>/n<sides>/r<resolution>
//   Kernel<Name>/<width>
// Each reports a points-per-second counter (items/s).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>
#include <map>
#include <optional>
#include <random>

#include "curvenet/builtins.hpp"
#include "curvenet/kernels/kernels.hpp"
#include "curvenet/tessellate.hpp"

using namespace curvenet;
namespace ck = curvenet::kernels;

namespace {

const Surface &surfaceFor(const std::string &model, Scheme scheme) {
  static std::map<std::pair<std::string, Scheme>, Surface> surfaces;
  auto it = surfaces.find({model, scheme});
  if (it == surfaces.end())
    it = surfaces.emplace(std::pair{model, scheme}, Surface::build(Network::build(builtinNetwork(model)), {scheme})).first;
  return it->second;
}

void tessellateBench(benchmark::State &state, Scheme scheme, std::string model, int resolution, bool cold,
                     int threads) {
  const Surface &surface = surfaceFor(model, scheme);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::size_t points = 0;
  for (auto _ : state) {
    if (cold) clearEvaluationPlans();
    const Mesh mesh = tessellate(surface, {resolution, threads});
    points = mesh.positions.size();
    benchmark::DoNotOptimize(mesh.positions.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * points));
  state.counters["points"] = static_cast<double>(points);
}

void surfaceBuildBench(benchmark::State &state, Scheme scheme, std::string model, int threads) {
  const Network network = Network::build(builtinNetwork(model));
  std::optional<tbb::global_control> limit;
  if (threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, threads);
  for (auto _ : state) benchmark::DoNotOptimize(Surface::build(network, {scheme}));
}

/// One edge curve of the model moved (interior control points), then the
/// surface rebuilt after the edit (Surface::rebuildAfterEdit) and, with
/// resolution > 0, its whole-network mesh re-tessellated on the changed
/// faces (retessellateFaces); resolution 0 times the rebuild alone.
void surfaceEditBench(benchmark::State &state, Scheme scheme, std::string model, int resolution) {
  const NetworkDescription description = builtinNetwork(model);
  const Network network = Network::build(description);
  NetworkDescription moved = description;
  const int c = network.segments()[0].sourceCurve;
  std::vector<Vec3> points = moved.curves[c].controlPoints();
  for (std::size_t k = 1; k + 1 < points.size(); ++k) points[k].z += 0.02;
  moved.curves[c] = BSplineCurve(moved.curves[c].degree(), moved.curves[c].knots(), points, moved.curves[c].weights());
  const Network edited = Network::build(moved);
  const Surface before = Surface::build(network, {scheme});
  const TessellationOptions options{.resolution = std::max(resolution, 1)};
  const Mesh original = resolution > 0 ? tessellate(before, options) : Mesh{};
  Mesh mesh;
  for (auto _ : state) {
    SurfaceEdit edit = before.rebuildAfterEdit(edited);
    if (resolution > 0) {
      state.PauseTiming();
      mesh = original;
      state.ResumeTiming();
      retessellateFaces(edit.surface, edit.changedFaces, mesh, options);
    }
    benchmark::DoNotOptimize(edit);
  }
}

struct KernelData {
  std::vector<double> data;
  explicit KernelData(std::size_t arrays, std::size_t n) : data(arrays * n) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.05, 0.95);
    for (double &x : data) x = u(rng);
  }
  double *at(std::size_t a, std::size_t n) { return data.data() + a * n; }
};

constexpr std::size_t kBatch = 4096;

void kernelRibbonBench(benchmark::State &state, std::int64_t width) {
  KernelData in(24, kBatch), out(9, kBatch);
  ck::RibbonJets j;
  for (int c = 0; c < 3; ++c)
    j.P[c] = in.at(c, kBatch), j.dP[c] = in.at(3 + c, kBatch), j.T[c] = in.at(6 + c, kBatch),
    j.dT[c] = in.at(9 + c, kBatch), j.C[c] = in.at(12 + c, kBatch), j.dC[c] = in.at(15 + c, kBatch);
  const ck::DualSpan sigma{in.at(18, kBatch), in.at(19, kBatch), in.at(20, kBatch)};
  const ck::DualSpan delta{in.at(21, kBatch), in.at(22, kBatch), in.at(23, kBatch)};
  ck::DualVec3Span o{{out.at(0, kBatch), out.at(1, kBatch), out.at(2, kBatch)},
                     {out.at(3, kBatch), out.at(4, kBatch), out.at(5, kBatch)},
                     {out.at(6, kBatch), out.at(7, kBatch), out.at(8, kBatch)}};
  for (auto _ : state) {
    ck::ribbonPoints(kBatch, j, sigma, delta, o, width);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kBatch));
}

void kernelAccumulateBench(benchmark::State &state, std::int64_t width) {
  KernelData in(12, kBatch), out(9, kBatch);
  const ck::DualSpan w{in.at(0, kBatch), in.at(1, kBatch), in.at(2, kBatch)};
  const ck::ConstDualVec3Span x{{in.at(3, kBatch), in.at(4, kBatch), in.at(5, kBatch)},
                                {in.at(6, kBatch), in.at(7, kBatch), in.at(8, kBatch)},
                                {in.at(9, kBatch), in.at(10, kBatch), in.at(11, kBatch)}};
  ck::DualVec3Span o{{out.at(0, kBatch), out.at(1, kBatch), out.at(2, kBatch)},
                     {out.at(3, kBatch), out.at(4, kBatch), out.at(5, kBatch)},
                     {out.at(6, kBatch), out.at(7, kBatch), out.at(8, kBatch)}};
  for (auto _ : state) {
    ck::accumulate(kBatch, w, x, o, width);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kBatch));
}

void kernelSweepBench(benchmark::State &state, std::int64_t width) {
  // Side 0 of the regular pentagon, points in its centre–side triangle.
  const double angle = 3 * 3.141592653589793 / 5; // the pentagon's interior angle
  ck::SweepFrame frame{-std::cos(angle) * -1, std::sin(angle), 0, 0};
  frame.ax = std::cos(angle), frame.bx = -std::cos(angle), frame.by = std::sin(angle);
  const double alpha = frame.by / (frame.ax * frame.by - frame.ay * frame.bx); // cross((1,0), b) / cross(a, b)
  frame.apexX = frame.ax * alpha, frame.apexY = frame.ay * alpha;
  KernelData in(2, kBatch), out(2, kBatch);
  for (std::size_t k = 0; k < kBatch; ++k) in.at(1, kBatch)[k] *= 0.6;
  for (auto _ : state) {
    ck::hermiteSweepRoots(kBatch, frame, in.at(0, kBatch), in.at(1, kBatch), out.at(0, kBatch), out.at(1, kBatch),
                          width);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kBatch));
}

int registerAll() {
  const std::pair<Scheme, const char *> schemes[] = {
      {Scheme::GregoryG1, "gregory-g1"}, {Scheme::GregoryG2, "gregory-g2"}, {Scheme::CompositeRibbon, "composite-ribbon"}};
  for (const auto &[scheme, name] : schemes) {
    for (int r : {64, 256})
      for (bool cold : {true, false})
        for (int threads : {1, 2})
          benchmark::RegisterBenchmark(("Tessellate/" + std::string(name) + "/pentagon/r" + std::to_string(r) + "/" +
                                        (cold ? "cold" : "warm") + "/t" + std::to_string(threads))
                                           .c_str(),
                                       tessellateBench, scheme, std::string("pentagon"), r, cold, threads)
              ->Unit(benchmark::kMillisecond)
              ->UseRealTime();
    benchmark::RegisterBenchmark(("SurfaceBuild/" + std::string(name) + "/ellipsoid-truncated-icosahedron").c_str(),
                                 surfaceBuildBench, scheme, std::string("ellipsoid-truncated-icosahedron"), 0)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("SurfaceBuild/" + std::string(name) + "/ellipsoid-truncated-icosahedron/t1").c_str(),
                                 surfaceBuildBench, scheme, std::string("ellipsoid-truncated-icosahedron"), 1)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    for (int r : {0, 64})
      benchmark::RegisterBenchmark(("SurfaceEdit/" + std::string(name) + "/ellipsoid-truncated-icosahedron/one-curve/" +
                                    (r ? "retessellate-r" + std::to_string(r) : std::string("rebuild")))
                                       .c_str(),
                                   surfaceEditBench, scheme, std::string("ellipsoid-truncated-icosahedron"), r)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
  }
  for (const ck::Width &w : ck::availableWidths()) {
    const std::string suffix = "/" + w.name + "x" + std::to_string(w.lanes);
    benchmark::RegisterBenchmark(("KernelRibbonPoints" + suffix).c_str(), kernelRibbonBench, w.id);
    benchmark::RegisterBenchmark(("KernelAccumulate" + suffix).c_str(), kernelAccumulateBench, w.id);
    benchmark::RegisterBenchmark(("KernelHermiteSweep" + suffix).c_str(), kernelSweepBench, w.id);
  }
  return 0;
}
const int registered = registerAll();

} // namespace
