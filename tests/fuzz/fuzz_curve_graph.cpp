// libFuzzer harness: the curve-graph stage (curvenet/sketch.hpp) — an OBJ
// polyline / edge soup read by parseObjCurveGraph, welded, its nodes found,
// its strokes fitted and its faces traced (networkFromCurveGraph), then the
// network built and one face evaluated under gregory-g1. The seeds are the
// public sketches of ../shared/data/sketches and a cube's edge graph
// (tools/scripts/fuzz.sh writes them into the corpus). Bad input must end in InputError; anything
// else is a finding.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "curvenet/error.hpp"
#include "curvenet/network.hpp"
#include "curvenet/sketch.hpp"
#include "curvenet/surface.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
  using namespace curvenet;
  const std::string text(reinterpret_cast<const char *>(data), size);
  fuzz::refusedOrSound([&] {
    const CurveGraph graph = parseObjCurveGraph(text, "fuzz.obj");
    // Keep single inputs cheap so that the fuzzer explores breadth, not size.
    std::size_t points = 0;
    for (const auto &stroke : graph.strokes) points += stroke.size();
    if (graph.points.size() > 3000 || points > 6000) return;
    const SketchResult sketch = networkFromCurveGraph(graph, {}, "fuzz.obj");
    if (sketch.description.faces.empty() || sketch.description.faces.size() > 64) return;
    const Network network = Network::build(sketch.description);
    SurfaceOptions options;
    options.scheme = Scheme::GregoryG1;
    const Surface surface = Surface::build(network, options);
    const SurfacePoint p = surface.evaluate(0, surface.domainCorner(0, 0) * 0.5);
    if (!std::isfinite(p.point.x) || !std::isfinite(p.point.y) || !std::isfinite(p.point.z)) {
      std::fprintf(stderr, "finding: a non-finite point on an accepted sketch\n");
      std::abort();
    }
  });
  return 0;
}
