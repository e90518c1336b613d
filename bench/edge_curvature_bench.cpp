// The transversal-curvature sources of gregory-g2 compared on the default
// network ([SV14] Sec. 3.3 and 5.3): build time of the whole surface and
// its deviation from the network's reference surface.
//   EdgeCurvature/<source>: counters max_dev_pct and mean_dev_pct (all vertices
//   of the resolution-32 tessellation vs the reference, percent of the
//   bounding-box diagonal), folded (faces whose normal turns over), and the
//   wall time of Surface::build.
#include <benchmark/benchmark.h>

#include <cmath>
#include <optional>

#include "curvenet/builtins.hpp"
#include "curvenet/tessellate.hpp"

using namespace curvenet;

namespace {

const Network &defaultNetwork() {
  static const Network network = Network::build(builtinNetwork(defaultBuiltinName()));
  return network;
}

void buildBench(benchmark::State &state, Scheme scheme, EdgeCurvature source) {
  const Network &net = defaultNetwork();
  SurfaceOptions options;
  options.scheme = scheme;
  options.edgeCurvature = source;
  std::optional<Surface> surface;
  for (auto _ : state) {
    surface.emplace(Surface::build(net, options));
    benchmark::DoNotOptimize(&*surface);
  }
  const Mesh mesh = tessellate(*surface, {32, 1});
  double worst = 0, sum = 0;
  for (const Vec3 &p : mesh.positions) {
    const double d = std::abs(net.reference()->signedDistance(p));
    worst = std::max(worst, d), sum += d;
  }
  state.counters["max_dev_pct"] = 100 * worst / net.diagonal();
  state.counters["mean_dev_pct"] = 100 * sum / mesh.positions.size() / net.diagonal();
  state.counters["folded"] = double(surface->foldedFaces().size());
}

} // namespace

BENCHMARK_CAPTURE(buildBench, gregory_g1, Scheme::GregoryG1, EdgeCurvature::Direct)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(buildBench, averaging, Scheme::GregoryG2, EdgeCurvature::Averaging)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(buildBench, direct, Scheme::GregoryG2, EdgeCurvature::Direct)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(buildBench, reference, Scheme::GregoryG2, EdgeCurvature::Reference)->Unit(benchmark::kMillisecond);
