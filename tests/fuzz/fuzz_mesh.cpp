// libFuzzer harness: the triangle-mesh readers (parseMeshText: PLY, OFF or
// STL when the text starts like one, OBJ otherwise), then mesh approximation ([SV14] Sec. 5.3) of the
// pentagon built-in's curves, as polylines, over the mesh read: the mesh
// becomes the reference surface (local quadric fits), both surfaces are
// built and every mesh vertex measured against them. The seeds are the
// pentagon's own tessellation in all four formats (fuzz_seed_corpus), so
// mutations start from a mesh the curves lie on. Bad input must end in
// InputError; anything else is a finding.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "curvenet/approximation.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
  using namespace curvenet;
  const std::string text(reinterpret_cast<const char *>(data), size);
  Mesh mesh;
  try {
    mesh = parseMeshText(text, "fuzz-mesh");
  } catch (const InputError &) {
    return 0;
  }
  for (const auto &t : mesh.triangles)
    for (std::uint32_t v : t)
      if (v >= mesh.positions.size()) std::abort(); // the readers promise indices in range
  // Keep single inputs cheap so that the fuzzer explores breadth, not size.
  if (mesh.positions.size() > 4000 || mesh.triangles.size() > 8000) return 0;
  static const NetworkDescription curves = polylineNetwork(builtinNetwork("pentagon"), 8);
  fuzz::refusedOrSound([&] {
    ApproximationOptions options;
    options.resolution = 3, options.curvatureSamples = 2, options.threads = 1;
    const ApproximationResult result = approximateMesh(mesh, curves, options);
    for (double figure : {result.g1Deviation.maxAbs, result.g2Deviation.maxAbs, result.curveDistance})
      if (std::isnan(figure)) {
        std::fprintf(stderr, "finding: a NaN figure from an accepted mesh\n");
        std::abort();
      }
  });
  return 0;
}
