// libFuzzer harness: random topology and geometry through the public API.
// The bytes choose a few vertex positions on a coarse lattice (so that
// coincident, collinear and degenerate configurations are common), cubic
// curves between them, and loops over those curves — mostly closed loops,
// sometimes with a second face running the same curves backwards, sometimes
// arbitrary side lists — and the result goes through the whole pipeline.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>

#include "fuzz_common.hpp"

using namespace curvenet;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  auto coordinate = [&] { return (in.ConsumeIntegralInRange<int>(-8, 8)) * in.PickValueInArray({0.25, 1.0, 1e-6, 1e6}); };
  auto point = [&] { return Vec3{coordinate(), coordinate(), coordinate()}; };

  const int vertexCount = in.ConsumeIntegralInRange(2, 8);
  std::vector<Vec3> vertices;
  for (int i = 0; i < vertexCount; ++i) vertices.push_back(point());

  NetworkDescription description;
  description.name = "fuzz";
  const int loopLength = in.ConsumeIntegralInRange(2, 9);
  std::vector<int> loop;
  for (int k = 0; k < loopLength; ++k) loop.push_back(in.ConsumeIntegralInRange(0, vertexCount - 1));
  for (int k = 0; k < loopLength; ++k) {
    const Vec3 a = vertices[loop[k]], b = vertices[loop[(k + 1) % loopLength]];
    const Vec3 d = b - a;
    const Vec3 bend = point() * 0.1;
    description.curves.push_back(BSplineCurve::bezier({a, a + d / 3 + bend, a + d * (2.0 / 3) + bend, b}));
  }
  FaceDescription face;
  for (int k = 0; k < loopLength; ++k) face.sides.push_back({k, 0.0, 1.0});
  description.faces.push_back(face);

  switch (in.ConsumeIntegralInRange(0, 2)) {
  case 1: { // the same loop from the other side: every curve shared by two faces
    FaceDescription back;
    for (int k = loopLength - 1; k >= 0; --k) back.sides.push_back({k, 1.0, 0.0});
    description.faces.push_back(back);
    break;
  }
  case 2: { // arbitrary extra sides: partial ranges, repeats, bad indices
    FaceDescription extra;
    const int sides = in.ConsumeIntegralInRange(0, 10);
    for (int k = 0; k < sides; ++k)
      extra.sides.push_back({in.ConsumeIntegralInRange(-1, loopLength), in.ConsumeFloatingPointInRange(-0.5, 1.5),
                             in.ConsumeFloatingPointInRange(-0.5, 1.5)});
    description.faces.push_back(extra);
    break;
  }
  default: break;
  }
  if (in.ConsumeBool()) description.tolerance = in.ConsumeFloatingPointInRange(-1.0, 1.0);
  fuzz::exercise(description);
  return 0;
}
