// libFuzzer harness: edits of a built model through the embedding API.
// The bytes pick a small built-in, a scheme and edge-curvature source, then
// up to three control-point edits (small and huge moves, a NaN or infinite
// point, a point dropped, a curve collapsed to a point, a curve number out of
// range). curvenet.hpp promises what is checked after each edit:
//   * no call throws;
//   * a refused edit leaves the model as it was: the same description and
//     the same bits at every probe point;
//   * an accepted edit (a partial rebuild, Surface::rebuildAfterEdit) gives
//     the bits of a model built afresh from the edited description.
// Any other outcome aborts, which libFuzzer reports as a finding.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "curvenet/builtins.hpp"
#include "curvenet/curvenet.hpp"

using namespace curvenet;

namespace {

[[noreturn]] void finding(const std::string &what) {
  std::fprintf(stderr, "finding: %s\n", what.c_str());
  std::abort();
}

/// Every face evaluated at its centre and halfway to each corner: the
/// outcome (status code) and the bytes of the point and normal.
std::vector<unsigned char> probe(const Model &model) {
  std::vector<unsigned char> bytes;
  auto append = [&](const void *data, std::size_t size) {
    bytes.insert(bytes.end(), static_cast<const unsigned char *>(data), static_cast<const unsigned char *>(data) + size);
  };
  for (int f = 0; f < model.faceCount(); ++f) {
    std::vector<Vec2> points{{0, 0}};
    for (int k = 0; k < model.domainSides(f); ++k)
      if (const Result<Vec2> corner = model.domainCorner(f, k)) points.push_back(*corner * 0.5);
    for (const Vec2 &uv : points) {
      const Result<SurfacePoint> p = model.evaluate(f, uv);
      const int code = static_cast<int>(p.status().code);
      append(&code, sizeof code);
      if (p) append(&p->point, sizeof p->point), append(&p->normal, sizeof p->normal);
    }
  }
  return bytes;
}

bool sameCurves(const NetworkDescription &a, const NetworkDescription &b) {
  if (a.curves.size() != b.curves.size()) return false;
  for (std::size_t c = 0; c < a.curves.size(); ++c) {
    const auto &p = a.curves[c].controlPoints(), &q = b.curves[c].controlPoints();
    if (p.size() != q.size() || std::memcmp(p.data(), q.data(), p.size() * sizeof(Vec3)) != 0) return false;
  }
  return true;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  // Small built-ins: every kind of node, face and scheme, each built in well
  // under a second.
  const char *name = in.PickValueInArray({"pentagon", "saddle-nodes", "sphere-dodecahedron", "hemisphere-tjunction",
                                          "tjunction-vertex", "concave-L", "ring", "setback-vertex-blend"});
  SurfaceOptions options;
  options.scheme = in.PickValueInArray(
      {Scheme::GregoryG1, Scheme::CompositeRibbon, Scheme::GregoryG2, Scheme::BezierG1, Scheme::CoonsC0});
  if (options.scheme == Scheme::GregoryG2) {
    options.edgeCurvature = in.PickValueInArray({EdgeCurvature::Direct, EdgeCurvature::MasterSlave});
    options.masterFaces = in.PickValueInArray({MasterFaces::Rebuilt, MasterFaces::KeptG1});
  }
  Result<Model> built = Model::build(builtinNetwork(name), options);
  if (!built) {
    // Refused for a reason (e.g. bezier-g1 over a network that is not
    // 4-sided Bézier), never by an internal error.
    if (built.status().code == StatusCode::Internal) finding("a built-in failed to build: " + built.status().toString());
    return 0;
  }
  Model &model = *built;

  for (int edit = in.ConsumeIntegralInRange(1, 3); edit > 0 && in.remaining_bytes() > 0; --edit) {
    const int curve = in.ConsumeIntegralInRange(-1, model.curveCount());
    std::vector<Vec3> points;
    if (curve >= 0 && curve < model.curveCount()) points = model.description().curves[curve].controlPoints();
    if (points.empty()) points.resize(4);
    const int which = in.ConsumeIntegralInRange(0, static_cast<int>(points.size()) - 1);
    switch (in.ConsumeIntegralInRange(0, 5)) {
    case 0: // move every point a little, or a lot
    case 1: {
      const double scale = in.PickValueInArray({1e-9, 1e-3, 0.1, 1.0, 1e6});
      for (Vec3 &p : points)
        p = p + Vec3{double(in.ConsumeIntegralInRange(-4, 4)), double(in.ConsumeIntegralInRange(-4, 4)),
                     double(in.ConsumeIntegralInRange(-4, 4))} *
                    scale;
      break;
    }
    case 2:
      points[which].y = in.ConsumeBool() ? std::numeric_limits<double>::quiet_NaN()
                                         : std::numeric_limits<double>::infinity();
      break;
    case 3:
      points.pop_back();
      break;
    case 4:
      for (Vec3 &p : points) p = points[which];
      break;
    default:
      points[which] = points[in.ConsumeIntegralInRange(0, static_cast<int>(points.size()) - 1)];
      break;
    }

    const NetworkDescription before = model.description();
    const std::vector<unsigned char> evaluatedBefore = probe(model);
    const Status status = model.setControlPoints(curve, points);
    if (!status.ok()) {
      if (!sameCurves(before, model.description())) finding("a refused edit changed the description");
      if (probe(model) != evaluatedBefore) finding("a refused edit changed the surfaces: " + status.toString());
      continue;
    }
    const Result<Model> fresh = Model::build(model.description(), options);
    if (!fresh) finding("an accepted edit gave a description a full build refuses: " + fresh.status().toString());
    if (probe(model) != probe(*fresh)) finding("the partial rebuild differs from a full build");
  }
  return 0;
}
