// libFuzzer harness: the C interface (curvenet/curvenet.h) as a foreign
// caller drives it — raw ints in the enum fields, counts that disagree with
// degrees, NaN and infinite numbers, NULL pointers where the header allows
// them and where it does not, indices out of range, buffers smaller than the
// mesh. The bytes pick how the model is made (a small built-in, one loop of
// curves, or a network of faces, curves partly arbitrary, with or without
// holes, edge settings and a reference surface), then up to eight
// calls on it. The header's promises are what is checked after every call:
//   * the returned code is one of curvenet_status_code, never
//     CURVENET_INTERNAL, and equals status.code; the element and message are
//     NUL-terminated within their arrays; a failure carries a message;
//   * a failed call leaves the model as it was (curve and face counts and the
//     bits at a probe point of every face);
//   * evaluations that succeed give finite numbers; points reported outside
//     the domain are NaN; a copied mesh's triangles index its vertices.
// Anything else aborts, which libFuzzer reports as a finding.
#include <fuzzer/FuzzedDataProvider.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "curvenet/curvenet.h"

namespace {

[[noreturn]] void finding(const std::string &what) {
  std::fprintf(stderr, "finding: %s\n", what.c_str());
  std::abort();
}

/// The header's contract for one call's outcome; returns the code.
curvenet_status_code checked(const char *call, curvenet_status_code code, const curvenet_status *status) {
  const int raw = static_cast<int>(code);
  if (raw < CURVENET_OK || raw > CURVENET_OUT_OF_MEMORY) finding(std::string(call) + ": code out of range");
  if (code == CURVENET_INTERNAL)
    finding(std::string(call) + ": internal error: " + (status ? status->message : "(no status)"));
  if (!status) return code;
  if (status->code != code) finding(std::string(call) + ": status.code differs from the returned code");
  if (!std::memchr(status->element, '\0', sizeof status->element) ||
      !std::memchr(status->message, '\0', sizeof status->message))
    finding(std::string(call) + ": element or message not NUL-terminated");
  if (code != CURVENET_OK && status->message[0] == '\0') finding(std::string(call) + ": a failure without a message");
  return code;
}

/// A double from the bytes: mostly small lattice values, sometimes extreme.
double number(FuzzedDataProvider &in) {
  switch (in.ConsumeIntegralInRange(0, 7)) {
  case 0: return std::numeric_limits<double>::quiet_NaN();
  case 1: return in.ConsumeBool() ? INFINITY : -INFINITY;
  case 2: return in.PickValueInArray({1e-300, 1e300, -1e300, 5e-324, 0.0, -0.0});
  case 3: return in.ConsumeFloatingPoint<double>();
  default: return in.ConsumeIntegralInRange(-8, 8) * 0.25;
  }
}

/// A curve's arrays, owned here; view() is what the C interface reads.
struct CurveData {
  int degree = 3;
  std::vector<double> knots, points, weights; ///< no weights: a polynomial curve
  curvenet_curve view() const {
    return {degree, knots.data(), knots.size(), points.data(), points.size() / 3,
            weights.empty() ? nullptr : weights.data()};
  }
};

/// A Bézier curve from a to b with interior points near the chord, or (when
/// the bytes say so) arbitrary degree, knots, points and weights.
CurveData curveFrom(FuzzedDataProvider &in, const double a[3], const double b[3]) {
  CurveData c;
  c.degree = in.ConsumeIntegralInRange(1, 4);
  const int count = c.degree + 1;
  for (int k = 0; k < count; ++k) {
    const double t = static_cast<double>(k) / c.degree;
    for (int x = 0; x < 3; ++x) c.points.push_back(a[x] + (b[x] - a[x]) * t);
  }
  for (int k = 1; k + 1 < count; ++k)
    for (int x = 0; x < 3; ++x) c.points[3 * k + x] += in.ConsumeIntegralInRange(-2, 2) * 0.25;
  c.knots.assign(count, 0.0);
  c.knots.resize(2 * count, 1.0);
  switch (in.ConsumeIntegralInRange(0, 9)) {
  case 0: c.degree = in.ConsumeIntegralInRange(-1, 17); break;                     // degree disagrees with the counts
  case 1: c.knots.resize(in.ConsumeIntegralInRange(0, 12), 0.5); break;            // knot count disagrees
  case 2: c.knots[in.ConsumeIntegralInRange(0, 2 * count - 1)] = number(in); break; // a bad knot
  case 3: c.points[in.ConsumeIntegralInRange(0, 3 * count - 1)] = number(in); break; // a bad point
  case 4:
    for (int k = 0; k < count; ++k) c.weights.push_back(in.ConsumeBool() ? 1.0 : number(in));
    break;
  case 5: c.points.clear(), c.knots.clear(); break; // no data at all
  default: break;
  }
  return c;
}

/// Curve and face counts and the bits at one point of every face: what a
/// failed call must leave unchanged.
std::vector<unsigned char> snapshot(const curvenet_model *model) {
  std::vector<unsigned char> bytes;
  auto append = [&](const void *data, std::size_t size) {
    bytes.insert(bytes.end(), static_cast<const unsigned char *>(data), static_cast<const unsigned char *>(data) + size);
  };
  const int faces = curvenet_model_face_count(model), curves = curvenet_model_curve_count(model);
  append(&faces, sizeof faces), append(&curves, sizeof curves);
  for (int f = 0; f < faces; ++f) {
    const double uv[2] = {0.1, -0.05};
    curvenet_point p;
    const int code = curvenet_model_evaluate(model, f, uv, 1, &p, nullptr, nullptr);
    append(&code, sizeof code);
    if (code == CURVENET_OK) append(&p, sizeof p);
  }
  return bytes;
}

curvenet_surface_options options(FuzzedDataProvider &in) {
  curvenet_surface_options o;
  curvenet_surface_options_init(&o);
  if (in.ConsumeBool()) return o;
  // Any int, as a C caller may store one: copied in as raw bits.
  const int raw[5] = {in.ConsumeIntegralInRange(-1, 5), in.ConsumeIntegralInRange(-1, 4),
                      in.ConsumeIntegralInRange(-1, 3), in.ConsumeIntegralInRange(-1, 4),
                      in.ConsumeIntegralInRange(-1, 2)};
  std::memcpy(&o.scheme, &raw[0], sizeof(int));
  std::memcpy(&o.sweepline, &raw[1], sizeof(int));
  std::memcpy(&o.fence_normals, &raw[2], sizeof(int));
  std::memcpy(&o.edge_curvature, &raw[3], sizeof(int));
  std::memcpy(&o.master_faces, &raw[4], sizeof(int));
  return o;
}

/// A model made one of three ways, or NULL when the bytes make none.
curvenet_model *makeModel(FuzzedDataProvider &in, std::vector<CurveData> &curves) {
  curvenet_model *model = nullptr;
  curvenet_status status;
  const curvenet_surface_options o = options(in);
  const curvenet_surface_options *chosen = in.ConsumeBool() ? &o : nullptr;
  switch (in.ConsumeIntegralInRange(0, 2)) {
  case 0: {
    const char *name = in.PickValueInArray({"builtin:pentagon", "builtin:saddle-nodes", "builtin:hemisphere-tjunction",
                                            "builtin:concave-L", "builtin:no-such-network", "no-such-file.json"});
    checked("model_load", curvenet_model_load(name, chosen, &model, &status), &status);
    break;
  }
  case 1: {
    // One loop: corners on a coarse lattice, curve k from corner k to k + 1.
    const int n = in.ConsumeIntegralInRange(1, 6);
    std::vector<std::array<double, 3>> corners(n);
    for (int k = 0; k < n; ++k) {
      const double angle = 2 * std::numbers::pi * k / n;
      corners[k] = {std::cos(angle), std::sin(angle), in.ConsumeIntegralInRange(-2, 2) * 0.25};
    }
    for (int k = 0; k < n; ++k) curves.push_back(curveFrom(in, corners[k].data(), corners[(k + 1) % n].data()));
    std::vector<curvenet_curve> views;
    for (const CurveData &c : curves) views.push_back(c.view());
    checked("model_from_loop", curvenet_model_from_loop(views.data(), views.size(), chosen, &model, &status), &status);
    break;
  }
  default: {
    // A network: curves between lattice points, faces of arbitrary sides.
    const int vertices = in.ConsumeIntegralInRange(2, 6);
    std::vector<std::array<double, 3>> points(vertices);
    for (auto &p : points)
      p = {in.ConsumeIntegralInRange(-2, 2) * 0.5, in.ConsumeIntegralInRange(-2, 2) * 0.5,
           in.ConsumeIntegralInRange(-1, 1) * 0.25};
    for (int k = in.ConsumeIntegralInRange(0, 8); k > 0; --k) {
      const int a = in.ConsumeIntegralInRange(0, vertices - 1), b = in.ConsumeIntegralInRange(0, vertices - 1);
      curves.push_back(curveFrom(in, points[a].data(), points[b].data()));
    }
    std::vector<curvenet_curve> views;
    for (const CurveData &c : curves) views.push_back(c.view());
    std::vector<std::vector<curvenet_side>> sides(in.ConsumeIntegralInRange(0, 3));
    std::vector<curvenet_face> faces;
    for (auto &face : sides) {
      for (int k = in.ConsumeIntegralInRange(0, 6); k > 0; --k) {
        const bool forward = in.ConsumeBool();
        face.push_back({in.ConsumeIntegralInRange(-1, static_cast<int>(curves.size())),
                        in.ConsumeBool() ? (forward ? 0.0 : 1.0) : number(in), forward ? 1.0 : 0.0});
      }
      faces.push_back({face.empty() && in.ConsumeBool() ? nullptr : face.data(), face.size()});
    }
    if (!in.ConsumeBool()) {
      checked("model_build",
              curvenet_model_build(views.empty() && in.ConsumeBool() ? nullptr : views.data(), views.size(),
                                   faces.data(), faces.size(), chosen, &model, &status),
              &status);
      break;
    }
    // The same network with what only curvenet_model_build_network says:
    // holes (another face's loop, or a NULL array), names, edge settings with
    // any indices, a reference surface of any kind and size, any tolerance.
    std::vector<curvenet_loop> holes;
    for (const curvenet_face &f : faces) holes.push_back({f.sides, f.side_count});
    std::vector<curvenet_network_face> full;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      // One hole (the next face's loop), two (refused: at most one), or a
      // NULL array with a hole claimed.
      const std::size_t holeCount = in.ConsumeBool() ? (holes.size() >= 2 && in.ConsumeBool() ? 2 : 1) : 0;
      const bool nullHoles = holeCount > 0 && in.ConsumeIntegralInRange(0, 7) == 0;
      const curvenet_loop *hole = holeCount == 2 ? holes.data() : &holes[(f + 1) % holes.size()];
      full.push_back({{faces[f].sides, faces[f].side_count}, nullHoles ? nullptr : hole, holeCount,
                      in.ConsumeBool() ? "face" : nullptr});
    }
    std::vector<curvenet_edge> edges;
    for (int k = in.ConsumeIntegralInRange(0, 3); k > 0; --k)
      edges.push_back({in.ConsumeIntegralInRange(-1, static_cast<int>(curves.size())),
                       in.ConsumeIntegralInRange(-2, static_cast<int>(faces.size())), in.ConsumeIntegralInRange(0, 2)});
    curvenet_network network;
    curvenet_network_init(&network);
    network.curves = views.data();
    network.curve_count = views.size();
    network.faces = full.data();
    network.face_count = full.size();
    network.edges = edges.empty() && in.ConsumeBool() ? nullptr : edges.data();
    network.edge_count = edges.size();
    const int kind = in.ConsumeIntegralInRange(-1, 4); // raw bits, as a C caller may store any int
    std::memcpy(&network.reference.kind, &kind, sizeof kind);
    for (int i = 0; i < 3; ++i) network.reference.center[i] = number(in), network.reference.size[i] = number(in);
    if (in.ConsumeBool()) network.tolerance = number(in);
    network.connection_curves = in.ConsumeIntegralInRange(0, 2);
    checked("model_build_network", curvenet_model_build_network(&network, chosen, &model, &status), &status);
    break;
  }
  }
  if ((model == nullptr) != (status.code != CURVENET_OK)) finding("a model handle disagrees with the status");
  return model;
}

/// One evaluation call of the three kinds on face `face` at `count` points.
void evaluate(FuzzedDataProvider &in, const curvenet_model *model, int face) {
  const int sides = curvenet_model_domain_sides(model, face);
  const std::size_t count = in.ConsumeIntegralInRange<std::size_t>(0, 16);
  std::vector<double> uv;
  for (std::size_t k = 0; k < count; ++k) {
    if (in.ConsumeBool() && sides > 0) {
      // Inside: a convex combination of the centre and a corner.
      double corner[2] = {0, 0};
      checked("domain_corner", curvenet_model_domain_corner(model, face, in.ConsumeIntegral<int>(), corner, nullptr),
              nullptr);
      const double t = in.ConsumeIntegralInRange(0, 9) * 0.1;
      uv.push_back(t * corner[0]), uv.push_back(t * corner[1]);
    } else {
      uv.push_back(number(in)), uv.push_back(number(in));
    }
  }
  curvenet_batch_options batch;
  curvenet_batch_options_init(&batch);
  const bool withBatch = in.ConsumeBool();
  if (withBatch) {
    batch.threads = in.ConsumeIntegralInRange(-2, 3);
    batch.parallel_threshold = in.ConsumeIntegralInRange<std::size_t>(0, 8);
    batch.step = in.ConsumeBool() ? 1e-5 : number(in);
  }
  curvenet_status status;
  const bool noPoints = count > 0 && in.ConsumeIntegralInRange(0, 15) == 0; // a NULL array with points claimed
  const double *points = noPoints ? nullptr : uv.data();
  std::vector<double> values;
  curvenet_status_code code;
  switch (in.ConsumeIntegralInRange(0, 2)) {
  case 0: {
    std::vector<curvenet_point> out(count);
    code = checked("evaluate", curvenet_model_evaluate(model, face, points, count, out.data(),
                                                       withBatch ? &batch : nullptr, &status), &status);
    for (const curvenet_point &p : out)
      for (int x = 0; x < 3; ++x) values.insert(values.end(), {p.point[x], p.du[x], p.dv[x], p.normal[x]});
    break;
  }
  case 1: {
    std::vector<curvenet_point2> out(count);
    code = checked("evaluate_second_order",
                   curvenet_model_evaluate_second_order(model, face, points, count, out.data(),
                                                        withBatch ? &batch : nullptr, &status),
                   &status);
    for (const curvenet_point2 &p : out)
      for (int x = 0; x < 3; ++x) values.insert(values.end(), {p.point[x], p.duu[x], p.duv[x], p.dvv[x]});
    break;
  }
  default: {
    std::vector<double> out(3 * count);
    code = checked("evaluate_positions", curvenet_model_evaluate_positions(model, face, points, count, out.data(),
                                                                           withBatch ? &batch : nullptr, &status),
                   &status);
    values = out;
    break;
  }
  }
  if (code == CURVENET_OK)
    for (double v : values)
      if (!std::isfinite(v)) finding("an evaluation reported ok gave a non-finite number");
  if (code == CURVENET_OUT_OF_DOMAIN) {
    bool anyNaN = false;
    for (double v : values) anyNaN |= std::isnan(v);
    if (!anyNaN) finding("points reported outside the domain are not NaN");
  }
}

/// A tessellation and a copy of the mesh into buffers of claimed capacities.
void tessellateAndCopy(FuzzedDataProvider &in, curvenet_model *model) {
  curvenet_status status;
  std::size_t vertices = 0, triangles = 0;
  const int face = in.ConsumeIntegralInRange(-2, curvenet_model_face_count(model));
  // Small resolutions, or now and then one no machine holds (refused up front).
  const int resolution = in.ConsumeIntegralInRange(0, 15) == 0
                             ? in.PickValueInArray({1 << 16, 1 << 24, std::numeric_limits<int>::max()})
                             : in.ConsumeIntegralInRange(-1, 6);
  const int threads = in.ConsumeIntegralInRange(-1, 2);
  const curvenet_status_code code = checked(
      "tessellate", curvenet_model_tessellate(model, face, resolution, threads, &vertices, &triangles, &status),
      &status);
  if (code == CURVENET_OK && vertices == 0) finding("an empty mesh reported ok");
  // Capacities: the sizes, or fewer, or more (a stale size query).
  auto claimed = [&](std::size_t size) {
    const int how = in.ConsumeIntegralInRange(0, 3);
    return how == 0 && size > 0 ? size - 1 : how == 1 ? size + 3 : size;
  };
  const std::size_t positionCapacity = claimed(vertices), triangleCapacity = claimed(triangles);
  const bool withNormals = in.ConsumeBool();
  std::vector<double> positions(3 * positionCapacity + 1), normals(3 * positionCapacity + 1);
  std::vector<std::uint32_t> indices(3 * triangleCapacity + 1);
  const curvenet_status_code copied =
      checked("copy_mesh",
              curvenet_model_copy_mesh(model, positions.data(), positionCapacity, withNormals ? normals.data() : nullptr,
                                       positionCapacity, indices.data(), triangleCapacity, &status),
              &status);
  // After a failed tessellation a mesh kept from before may still be
  // copied; its sizes are not known here.
  if (copied == CURVENET_OK && code == CURVENET_OK) {
    for (std::size_t k = 0; k < 3 * triangles; ++k)
      if (indices[k] >= vertices) finding("a copied triangle indexes past the vertices");
    for (std::size_t k = 0; k < 3 * vertices; ++k)
      if (!std::isfinite(positions[k])) finding("a copied position is not finite");
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  // NULL handles and arguments: refused with a code, never dereferenced.
  curvenet_status status;
  curvenet_model *model = nullptr;
  checked("model_load", curvenet_model_load(nullptr, nullptr, &model, &status), &status);
  checked("model_from_loop", curvenet_model_from_loop(nullptr, 3, nullptr, &model, &status), &status);
  if (model) finding("a refused call returned a model");
  if (curvenet_model_face_count(nullptr) != 0 || curvenet_model_domain_sides(nullptr, 0) != 0)
    finding("a NULL model has faces");
  checked("evaluate", curvenet_model_evaluate(nullptr, 0, nullptr, 0, nullptr, nullptr, nullptr), nullptr);
  checked("tessellate", curvenet_model_tessellate(nullptr, 0, 1, 1, nullptr, nullptr, &status), &status);
  curvenet_model_destroy(nullptr);

  std::vector<CurveData> curves; // the arrays the model was made from (loops and networks)
  model = makeModel(in, curves);
  if (!model) return 0;

  for (int call = in.ConsumeIntegralInRange(1, 8); call > 0 && in.remaining_bytes() > 0; --call) {
    const int faces = curvenet_model_face_count(model), curveCount = curvenet_model_curve_count(model);
    const int kind = in.ConsumeIntegralInRange(0, 5);
    if (kind <= 1) {
      evaluate(in, model, in.ConsumeIntegralInRange(-1, faces));
      continue;
    }
    if (kind == 3) {
      tessellateAndCopy(in, model);
      continue;
    }
    // The calls that change the model: a failure must leave it as it was.
    const std::vector<unsigned char> before = snapshot(model);
    curvenet_status_code code = CURVENET_OK;
    switch (kind) {
    case 2: {
      const curvenet_surface_options o = options(in);
      const int face = in.ConsumeBool() ? CURVENET_ALL_FACES : in.ConsumeIntegralInRange(-2, faces);
      code = checked("set_face_options", curvenet_model_set_face_options(model, face, &o, &status), &status);
      break;
    }
    case 4: {
      // A replacement: one of the model's own curves moved, or an arbitrary one.
      const int curve = in.ConsumeIntegralInRange(-1, curveCount);
      CurveData replacement;
      if (curve >= 0 && curve < static_cast<int>(curves.size()) && in.ConsumeBool()) {
        replacement = curves[curve];
        if (!replacement.points.empty())
          replacement.points[in.ConsumeIntegralInRange<std::size_t>(0, replacement.points.size() - 1)] +=
              in.ConsumeIntegralInRange(-2, 2) * 0.125;
      } else {
        const double a[3] = {number(in), 0, 0}, b[3] = {1, number(in), 0};
        replacement = curveFrom(in, a, b);
      }
      const curvenet_curve view = replacement.view();
      code = checked("set_curve", curvenet_model_set_curve(model, curve, &view, &status), &status);
      if (code == CURVENET_OK && curve < static_cast<int>(curves.size())) curves[curve] = replacement;
      break;
    }
    default: {
      const int curve = in.ConsumeIntegralInRange(-1, curveCount);
      std::vector<double> points;
      if (curve >= 0 && curve < static_cast<int>(curves.size())) points = curves[curve].points;
      if (points.empty() || in.ConsumeIntegralInRange(0, 7) == 0)
        points.resize(3 * in.ConsumeIntegralInRange<std::size_t>(0, 6), 0.5);
      if (!points.empty()) points[in.ConsumeIntegralInRange<std::size_t>(0, points.size() - 1)] += number(in);
      code = checked("set_control_points",
                     curvenet_model_set_control_points(model, curve, points.empty() ? nullptr : points.data(),
                                                       points.size() / 3, &status),
                     &status);
      if (code == CURVENET_OK && curve < static_cast<int>(curves.size())) curves[curve].points = points;
      break;
    }
    }
    if (code != CURVENET_OK && snapshot(model) != before) finding("a failed call changed the model");
  }
  curvenet_model_destroy(model);
  return 0;
}
