// Engine phases and kernels. Names say what runs:
//   Tessellate/<scheme>/<model>/r<resolution>/<cold|warm>/t<threads>
//   Evaluate/<scheme>/<model>/r<resolution>/<cold|warm>/t<threads>
//     (evaluateFaceInteriors: positions of the face-interior samples; cold =
//     plan cache emptied and a freshly built surface, so plans and ribbon
//     tables are built inside the timing)
//   BatchPositions/<scheme>/<model>: Surface::evaluatePositions at random
//     domain points of face 0 (sweepline roots solved per point)
//   BatchJets/<scheme>/<model>: the same points with du, dv and normals
//     (Surface::evaluate on spans)
//   TessellateCpu/<scheme>/<model>/r256/t1[/reused]: the warm one-thread
//     tessellation on CPU time (the others of its kind on wall time); reused:
//     into one Mesh kept across runs (tessellate(surface, options, mesh))
//   Kernel<Name>/<width>
// <model> is a built-in network, or cagd86: the real 5-sided loop of
// ../shared/data/transfinite-models/cagd86.lop (its ribbons saturate, as on
// every real network tried), registered where that file is present.
// Each reports a points-per-second counter (items/s).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <random>

#include "curvenet/builtins.hpp"
#include "curvenet/io.hpp"
#include "curvenet/kernels/kernels.hpp"
#include "curvenet/tessellate.hpp"

using namespace curvenet;
namespace ck = curvenet::kernels;

namespace {

/// The real loop the benchmarks name cagd86.
const std::filesystem::path realLoop = std::filesystem::path(CURVENET_SHARED_DATA_DIR) / "transfinite-models" / "cagd86.lop";

NetworkDescription networkFor(const std::string &model) {
  return model == "cagd86" ? readNetworkFile(realLoop.string()) : builtinNetwork(model);
}

const Surface &surfaceFor(const std::string &model, Scheme scheme) {
  static std::map<std::pair<std::string, Scheme>, Surface> surfaces;
  auto it = surfaces.find({model, scheme});
  if (it == surfaces.end())
    it = surfaces.emplace(std::pair{model, scheme}, Surface::build(Network::build(networkFor(model)), {scheme})).first;
  return it->second;
}

void tessellateBench(benchmark::State &state, Scheme scheme, std::string model, int resolution, bool cold,
                     int threads, bool reuse) {
  const Surface &surface = surfaceFor(model, scheme);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::size_t points = 0;
  Mesh reused;
  for (auto _ : state) {
    if (cold) clearEvaluationPlans();
    if (reuse) {
      tessellate(surface, {resolution, threads}, reused);
      points = reused.positions.size();
      benchmark::DoNotOptimize(reused.positions.data());
      continue;
    }
    const Mesh mesh = tessellate(surface, {resolution, threads});
    points = mesh.positions.size();
    benchmark::DoNotOptimize(mesh.positions.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * points));
  state.counters["points"] = static_cast<double>(points);
}

void evaluateBench(benchmark::State &state, Scheme scheme, std::string model, int resolution, bool cold,
                   int threads) {
  const Network network = Network::build(networkFor(model));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::optional<Surface> surface = Surface::build(network, {scheme});
  std::size_t points = 0;
  for (auto _ : state) {
    if (cold) {
      state.PauseTiming();
      surface = Surface::build(network, {scheme});
      clearEvaluationPlans();
      state.ResumeTiming();
    }
    const std::vector<Vec3> p = evaluateFaceInteriors(*surface, {resolution, threads});
    points = p.size();
    benchmark::DoNotOptimize(p.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * points));
  state.counters["points"] = static_cast<double>(points);
}

/// 65 536 random points of face 0's domain in one batch, positions alone
/// (Surface::evaluatePositions) or with du, dv and normals (the jets:
/// Surface::evaluate on spans).
void batchBench(benchmark::State &state, Scheme scheme, std::string model, bool jets) {
  const Surface &surface = surfaceFor(model, scheme);
  const int n = surface.domainSides(0);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Vec2> uv(1 << 16);
  for (Vec2 &p : uv) {
    const int k = static_cast<int>(unit(rng) * n) % n;
    double a = unit(rng), b = unit(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    p = surface.domainCorner(0, k) * a + surface.domainCorner(0, k + 1) * b;
  }
  std::vector<Vec3> out(uv.size());
  std::vector<SurfacePoint> points(jets ? uv.size() : 0);
  surface.evaluatePositions(0, uv, out); // the face's ribbon tables
  for (auto _ : state) {
    if (jets) {
      surface.evaluate(0, uv, points);
      benchmark::DoNotOptimize(points.data());
    } else {
      surface.evaluatePositions(0, uv, out);
      benchmark::DoNotOptimize(out.data());
    }
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * uv.size()));
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

/// The whole G² position kernel for a pentagon over random per-side data,
/// `batch` samples per call (the engine's plan evaluation calls it on 128,
/// its per-side arrays in the cache); with sharedWeights the corners'
/// weights computed beforehand, as a plan's rotation group supplies them.
void kernelGregoryBench(benchmark::State &state, std::int64_t width, std::size_t batch, bool sharedWeights) {
  constexpr int n = 5;
  KernelData in(n * 11, batch), out(3, batch), weights(8 * n, batch);
  ck::GregorySamples samples;
  samples.sides = n, samples.parabolic = true;
  for (int i = 0; i < n; ++i) {
    samples.s[i] = in.at(11 * i, batch), samples.blend[i] = in.at(11 * i + 1, batch);
    for (int c = 0; c < 3; ++c)
      samples.P[i][c] = in.at(11 * i + 2 + c, batch), samples.T[i][c] = in.at(11 * i + 5 + c, batch),
      samples.C[i][c] = in.at(11 * i + 8 + c, batch);
  }
  std::vector<ck::GregoryCorner> corners(n);
  for (auto &corner : corners)
    for (auto &v : corner.v) v[0] = 0.3, v[1] = -0.2, v[2] = 0.1;
  double *o[3] = {out.at(0, batch), out.at(1, batch), out.at(2, batch)};
  if (sharedWeights) {
    // As a plan's rotation group supplies them: computed once, outside.
    for (int i = 0; i < n; ++i) {
      samples.weights[i] = weights.at(8 * i, batch);
      ck::gregoryCornerWeights(batch, samples.s[i], samples.s[(i + n - 1) % n], weights.at(8 * i, batch), batch, width);
    }
    samples.weightStride = batch;
  }
  for (auto _ : state) {
    ck::gregoryPositions(batch, samples, corners.data(), o, width);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * batch));
}

/// The eight G² corner weights of one corner.
void kernelCornerWeightsBench(benchmark::State &state, std::int64_t width) {
  KernelData in(2, kBatch), out(8, kBatch);
  for (auto _ : state) {
    ck::gregoryCornerWeights(kBatch, in.at(0, kBatch), in.at(1, kBatch), out.at(0, kBatch), kBatch, width);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kBatch));
}

/// The whole Composite Ribbon kernel for a pentagon (points, or points with
/// their domain derivatives) over random per-side data.
void kernelCompositeBench(benchmark::State &state, std::int64_t width, bool jets) {
  constexpr int n = 5, perSide = 9 + 36;
  KernelData in(n * perSide, kBatch), out(9, kBatch);
  ck::CompositeSamples samples;
  samples.sides = n;
  for (int i = 0; i < n; ++i) {
    for (int part = 0; part < 3; ++part)
      samples.s[i][part] = in.at(perSide * i + part, kBatch), samples.d[i][part] = in.at(perSide * i + 3 + part, kBatch),
      samples.blend[i][part] = in.at(perSide * i + 6 + part, kBatch);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        const std::size_t base = perSide * i + 9 + 12 * r;
        samples.P[i][r][c] = in.at(base + c, kBatch), samples.T[i][r][c] = in.at(base + 3 + c, kBatch);
        samples.dP[i][r][c] = in.at(base + 6 + c, kBatch), samples.dT[i][r][c] = in.at(base + 9 + c, kBatch);
      }
  }
  std::vector<ck::GregoryCorner> corners(n);
  for (auto &corner : corners)
    for (auto &v : corner.v) v[0] = 0.3, v[1] = -0.2, v[2] = 0.1;
  double *o[9];
  for (int j = 0; j < 9; ++j) o[j] = out.at(j, kBatch);
  for (auto _ : state) {
    if (jets)
      ck::compositeRibbonJets(kBatch, samples, corners.data(), corners.data(),
                              {{o[0], o[1], o[2]}, {o[3], o[4], o[5]}, {o[6], o[7], o[8]}}, width);
    else ck::compositeRibbonPositions(kBatch, samples, corners.data(), corners.data(), o, width);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kBatch));
}

/// Table evaluation, 9 coordinates (a G² ribbon: P, T, C), 256 intervals.
void kernelTableBench(benchmark::State &state, std::int64_t width, bool slopes) {
  constexpr std::size_t intervals = 256, dims = 9, padded = 8; // the G² layout: rows of 8, a tail of one
  std::vector<double> starts(intervals), ends(intervals), inverse(intervals, double(intervals));
  for (std::size_t j = 0; j < intervals; ++j) starts[j] = double(j) / intervals, ends[j] = double(j + 1) / intervals;
  KernelData coefficients(intervals * 7, padded), in(1, kBatch), out(2 * dims, kBatch); // 6 rows + the tail
  // Four cells an interval, each with its first interval's end: one read a
  // lookup, as the engine's tables (RibbonTable, steps ≤ 1) have it.
  std::vector<std::uint32_t> first(4 * intervals);
  std::vector<double> firstEnd(first.size());
  for (std::size_t c = 0; c < first.size(); ++c)
    first[c] = static_cast<std::uint32_t>(c / 4), firstEnd[c] = first[c] + 1 < intervals ? ends[first[c]] : INFINITY;
  ck::PolynomialTable table;
  table.dims = dims, table.paddedDims = padded, table.steps = 1, table.intervals = intervals, table.cells = first.size();
  table.starts = starts.data(), table.ends = ends.data(), table.inverseWidths = inverse.data();
  table.coefficients = coefficients.data.data(), table.cellFirst = first.data(), table.cellFirstEnd = firstEnd.data();
  double *values[dims], *derivatives[dims];
  for (std::size_t d = 0; d < dims; ++d) values[d] = out.at(d, kBatch), derivatives[d] = out.at(dims + d, kBatch);
  for (auto _ : state) {
    ck::evaluateTable(kBatch, table, in.at(0, kBatch), values, slopes ? derivatives : nullptr, width);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kBatch));
}

/// Side 0 of the regular pentagon, points (x, y) ∈ [0.05, 0.95] × [0.03, 0.57]
/// of its frame, all inside the domain. robust: the fallback solver alone.
void kernelSweepBench(benchmark::State &state, std::int64_t width, bool robust) {
  const double angle = 3 * 3.141592653589793 / 5; // the pentagon's interior angle
  ck::SweepFrame frame{std::cos(angle), std::sin(angle), -std::cos(angle), std::sin(angle)};
  const double alpha = frame.by / (frame.ax * frame.by - frame.ay * frame.bx); // cross((1,0), b) / cross(a, b)
  frame.apexX = frame.ax * alpha, frame.apexY = frame.ay * alpha;
  KernelData in(2, kBatch), out(2, kBatch);
  for (std::size_t k = 0; k < kBatch; ++k) in.at(1, kBatch)[k] *= 0.6;
  std::size_t fallbacks = 0;
  for (auto _ : state) {
    if (robust)
      ck::hermiteSweepRootsRobust(kBatch, frame, in.at(0, kBatch), in.at(1, kBatch), out.at(0, kBatch),
                                  out.at(1, kBatch), width);
    else
      fallbacks += ck::hermiteSweepRoots(kBatch, frame, in.at(0, kBatch), in.at(1, kBatch), out.at(0, kBatch),
                                         out.at(1, kBatch), width);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * kBatch));
  if (!robust) state.counters["fallback"] = static_cast<double>(fallbacks) / static_cast<double>(state.iterations() * kBatch);
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
                                       tessellateBench, scheme, std::string("pentagon"), r, cold, threads, false)
              ->Unit(benchmark::kMillisecond)
              ->UseRealTime();
    for (bool cold : {true, false})
      for (int threads : {1, 2})
        benchmark::RegisterBenchmark(("Evaluate/" + std::string(name) + "/pentagon/r256/" + (cold ? "cold" : "warm") +
                                      "/t" + std::to_string(threads))
                                         .c_str(),
                                     evaluateBench, scheme, std::string("pentagon"), 256, cold, threads)
            ->Unit(benchmark::kMillisecond)
            ->UseRealTime();
    if (std::filesystem::exists(realLoop))
      benchmark::RegisterBenchmark(("Evaluate/" + std::string(name) + "/cagd86/r256/warm/t1").c_str(), evaluateBench,
                                   scheme, std::string("cagd86"), 256, false, 1)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    benchmark::RegisterBenchmark(("BatchPositions/" + std::string(name) + "/pentagon").c_str(), batchBench, scheme,
                                 std::string("pentagon"), false)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BatchJets/" + std::string(name) + "/pentagon").c_str(), batchBench, scheme,
                                 std::string("pentagon"), true)
        ->Unit(benchmark::kMillisecond);
    // One thread on CPU time: the rate of the work itself on a machine
    // shared with other jobs, where wall-clock rates fall with their load.
    benchmark::RegisterBenchmark(("TessellateCpu/" + std::string(name) + "/pentagon/r256/t1").c_str(), tessellateBench,
                                 scheme, std::string("pentagon"), 256, false, 1, false)
        ->Unit(benchmark::kMillisecond);
    // The same into one reused Mesh (no fresh pages to fault in), and on a real loop.
    for (const char *model : {"pentagon", "cagd86"}) {
      if (model == std::string("cagd86") && !std::filesystem::exists(realLoop)) continue;
      benchmark::RegisterBenchmark(("TessellateCpu/" + std::string(name) + "/" + model + "/r256/t1/reused").c_str(),
                                   tessellateBench, scheme, std::string(model), 256, false, 1, true)
          ->Unit(benchmark::kMillisecond);
    }
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
    benchmark::RegisterBenchmark(("KernelGregoryPositionsG2n5" + suffix).c_str(), kernelGregoryBench, w.id, kBatch,
                                 false);
    benchmark::RegisterBenchmark(("KernelGregoryPositionsG2n5Block128" + suffix).c_str(), kernelGregoryBench, w.id,
                                 std::size_t{128}, false);
    benchmark::RegisterBenchmark(("KernelGregoryPositionsG2n5Block128SharedWeights" + suffix).c_str(),
                                 kernelGregoryBench, w.id, std::size_t{128}, true);
    benchmark::RegisterBenchmark(("KernelG2CornerWeights" + suffix).c_str(), kernelCornerWeightsBench, w.id);
    benchmark::RegisterBenchmark(("KernelCompositeRibbonn5" + suffix).c_str(), kernelCompositeBench, w.id, false);
    benchmark::RegisterBenchmark(("KernelCompositeRibbonJetsn5" + suffix).c_str(), kernelCompositeBench, w.id, true);
    benchmark::RegisterBenchmark(("KernelTable9" + suffix).c_str(), kernelTableBench, w.id, false);
    benchmark::RegisterBenchmark(("KernelTable9Slopes" + suffix).c_str(), kernelTableBench, w.id, true);
    benchmark::RegisterBenchmark(("KernelHermiteSweep" + suffix).c_str(), kernelSweepBench, w.id, false);
    benchmark::RegisterBenchmark(("KernelHermiteSweepRobust" + suffix).c_str(), kernelSweepBench, w.id, true);
  }
  return 0;
}
const int registered = registerAll();

} // namespace
