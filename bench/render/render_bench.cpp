// Render speed (issue: verification pictures): the 1024×1024 reflection-line
// image of the default network tessellated at resolution 64 per patch, as
// `curvenet render builtin:ellipsoid-truncated-icosahedron -o out.png
// --size 1024x1024 --resolution 64` does it, split into its two stages and
// measured at 1 and 2 threads in one run (report ratios, not absolute times:
// the machines are shared).
#include <benchmark/benchmark.h>

#include "curvenet/builtins.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"
#include "render.hpp"

using namespace curvenet;

namespace {

const Surface &defaultSurface() {
  static const Surface surface =
      Surface::build(Network::build(builtinNetwork(defaultBuiltinName()), "builtin:" + defaultBuiltinName()));
  return surface;
}

const Mesh &defaultMesh() {
  static const Mesh mesh = tessellate(defaultSurface(), {64, 0});
  return mesh;
}

void BM_Tessellate64(benchmark::State &state) {
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(tessellate(defaultSurface(), {64, threads}).positions.data());
  state.counters["triangles"] = static_cast<double>(defaultMesh().triangles.size());
}

void BM_Reflection1024(benchmark::State &state) {
  render::RenderOptions options;
  options.width = options.height = 1024;
  options.mode = render::Mode::Reflection;
  options.threads = static_cast<int>(state.range(0));
  const Mesh &mesh = defaultMesh();
  std::uint64_t rays = 0;
  for (auto _ : state) {
    const render::Image image = render::renderMesh(mesh, options);
    rays += image.rays;
    benchmark::DoNotOptimize(image.color.data());
  }
  state.counters["rays_per_second"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
}

} // namespace

BENCHMARK(BM_Tessellate64)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Reflection1024)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
