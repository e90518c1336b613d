// The C interface (curvenet/curvenet.h): a thin translation onto the Model
// facade of curvenet/curvenet.hpp. This file only converts C arrays and
// enums to the C++ types and Status values back; every check and every
// computation lives in the facade.
#include "curvenet/curvenet.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>
#include <optional>
#include <type_traits>
#include <vector>

#include "curvenet/curvenet.hpp"

using namespace curvenet;

struct curvenet_model {
  Model model;
};

static_assert(static_cast<int>(StatusCode::OutOfMemory) == CURVENET_OUT_OF_MEMORY &&
              static_cast<int>(StatusCode::NoMesh) == CURVENET_NO_MESH);
static_assert(static_cast<int>(CurveHandling::Repaired) == CURVENET_CURVES_REPAIRED &&
              static_cast<int>(CurveHandling::Kept) == CURVENET_CURVES_KEPT);
static_assert(static_cast<int>(Scheme::CoonsC0) == CURVENET_COONS_C0 &&
              static_cast<int>(Sweepline::QuinticHermite) == CURVENET_SWEEPLINE_QUINTIC_HERMITE &&
              static_cast<int>(FenceNormals::Reference) == CURVENET_FENCE_REFERENCE &&
              static_cast<int>(EdgeCurvature::Reference) == CURVENET_EDGE_CURVATURE_REFERENCE);

namespace {

void copyTruncated(char *to, std::size_t capacity, const std::string &from) {
  const std::size_t n = std::min(from.size(), capacity - 1);
  std::memcpy(to, from.data(), n);
  to[n] = '\0';
}

/// Fills the caller's status (if any) and returns the code.
curvenet_status_code report(const Status &status, curvenet_status *out) {
  const auto code = static_cast<curvenet_status_code>(status.code);
  if (out) {
    out->code = code;
    copyTruncated(out->element, sizeof out->element, status.element);
    copyTruncated(out->message, sizeof out->message, status.ok() ? std::string() : status.toString());
  }
  return code;
}

curvenet_status_code fail(StatusCode code, const std::string &element, const std::string &message,
                          curvenet_status *out) {
  return report(Status{code, {}, element, message}, out);
}

curvenet_status_code nullArgument(const char *name, curvenet_status *out) {
  return fail(StatusCode::InvalidArgument, name, "must not be NULL", out);
}

/// Runs `body` (which returns a curvenet_status_code) and maps what the C
/// layer's own allocations may throw; the facade itself does not throw.
template <class Body>
curvenet_status_code guarded(curvenet_status *status, Body &&body) noexcept {
  try {
    return body();
  } catch (const std::bad_alloc &) {
    return fail(StatusCode::OutOfMemory, {}, "out of memory", status);
  } catch (...) {
    return fail(StatusCode::Internal, {}, "unexpected exception in the C interface", status);
  }
}

SurfaceOptions toOptions(const curvenet_surface_options *options) {
  if (!options) return {};
  return {static_cast<Scheme>(options->scheme), static_cast<Sweepline>(options->sweepline),
          static_cast<FenceNormals>(options->fence_normals), static_cast<EdgeCurvature>(options->edge_curvature),
          static_cast<MasterFaces>(options->master_faces), static_cast<CurveHandling>(options->curves)};
}

/// Enum values outside their range would reach the engine as invalid enums.
/// A C caller may store any int in these fields; reading one through the
/// enum type is undefined in C++ when it is out of range, so the raw bits
/// are copied into an int first.
template <typename Enum> int rawValue(const Enum &field) {
  static_assert(sizeof(Enum) == sizeof(int), "C enums are int-sized here");
  int raw;
  std::memcpy(&raw, &field, sizeof raw);
  return raw;
}

bool validOptions(const curvenet_surface_options *o) {
  if (!o) return true;
  const int scheme = rawValue(o->scheme), sweepline = rawValue(o->sweepline);
  const int fence = rawValue(o->fence_normals), curvature = rawValue(o->edge_curvature);
  const int masters = rawValue(o->master_faces), curves = rawValue(o->curves);
  return scheme >= CURVENET_GREGORY_G1 && scheme <= CURVENET_COONS_C0 && sweepline >= CURVENET_SWEEPLINE_AUTO &&
         sweepline <= CURVENET_SWEEPLINE_QUINTIC_HERMITE && fence >= CURVENET_FENCE_AUTO &&
         fence <= CURVENET_FENCE_REFERENCE && curvature >= CURVENET_EDGE_CURVATURE_MASTER_SLAVE &&
         curvature <= CURVENET_EDGE_CURVATURE_REFERENCE && masters >= CURVENET_MASTER_FACES_REBUILT &&
         masters <= CURVENET_MASTER_FACES_KEPT_G1 && curves >= CURVENET_CURVES_REPAIRED &&
         curves <= CURVENET_CURVES_KEPT;
}

std::vector<Vec3> toPoints(const double *xyz, std::size_t count) {
  std::vector<Vec3> points(count);
  for (std::size_t k = 0; k < count; ++k) points[k] = {xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]};
  return points;
}

void fromVec(const Vec3 &v, double out[3]) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
}

void fromPoint(const SurfacePoint &p, curvenet_point &out) {
  fromVec(p.point, out.point);
  fromVec(p.du, out.du);
  fromVec(p.dv, out.dv);
  fromVec(p.normal, out.normal);
}

void fromPoint(const SurfacePoint2 &p, curvenet_point2 &out) {
  fromVec(p.point, out.point);
  fromVec(p.du, out.du);
  fromVec(p.dv, out.dv);
  fromVec(p.normal, out.normal);
  fromVec(p.duu, out.duu);
  fromVec(p.duv, out.duv);
  fromVec(p.dvv, out.dvv);
}

/// A C curve as a BSplineCurve (the facade validates the data).
Result<BSplineCurve> toCurve(const curvenet_curve &c, int index) {
  const std::string element = "curve " + std::to_string(index);
  if ((!c.knots && c.knot_count) || (!c.points && c.point_count))
    return Status{StatusCode::InvalidArgument, {}, element, "knots or points are NULL"};
  std::vector<double> weights;
  if (c.weights) weights.assign(c.weights, c.weights + c.point_count);
  Result<BSplineCurve> curve =
      makeCurve(c.degree, {c.knots, c.knots + c.knot_count}, toPoints(c.points, c.point_count), std::move(weights));
  if (!curve.ok()) {
    Status status = curve.status();
    status.element = element;
    return status;
  }
  return curve;
}

/// The C curves as BSplineCurves, or the first one's error.
Result<std::vector<BSplineCurve>> toCurves(const curvenet_curve *curves, std::size_t count) {
  std::vector<BSplineCurve> result;
  result.reserve(count);
  for (std::size_t c = 0; c < count; ++c) {
    Result<BSplineCurve> curve = toCurve(curves[c], static_cast<int>(c));
    if (!curve) return curve.status();
    result.push_back(std::move(curve).value());
  }
  return result;
}

/// A C loop of sides, or an error naming `element` when its array is NULL.
Result<std::vector<SideDescription>> toSides(const curvenet_side *sides, std::size_t count,
                                             const std::string &element) {
  if (count && !sides) return Status{StatusCode::InvalidArgument, {}, element, "sides are NULL"};
  std::vector<SideDescription> loop;
  for (std::size_t k = 0; k < count; ++k) loop.push_back({sides[k].curve, sides[k].from, sides[k].to});
  return loop;
}

/// The network of C curves and faces (shared by the build calls).
Result<NetworkDescription> toDescription(const curvenet_curve *curves, std::size_t curve_count,
                                         const curvenet_face *faces, std::size_t face_count) {
  NetworkDescription description;
  description.name = "network";
  Result<std::vector<BSplineCurve>> converted = toCurves(curves, curve_count);
  if (!converted) return converted.status();
  description.curves = std::move(converted).value();
  for (std::size_t f = 0; f < face_count; ++f) {
    Result<std::vector<SideDescription>> sides =
        toSides(faces[f].sides, faces[f].side_count, "face " + std::to_string(f));
    if (!sides) return sides.status();
    description.faces.push_back({std::move(sides).value()});
  }
  return description;
}

curvenet_status_code adopt(Result<Model> model, curvenet_model **out, curvenet_status *status) {
  if (!model) return report(model.status(), status);
  *out = new curvenet_model{std::move(model).value()};
  return report({}, status);
}

/// Evaluates in chunks: the C arrays are converted to Vec2 / SurfacePoint
/// through buffers of bounded size, each chunk evaluated as one facade batch
/// (first or second order, or positions alone, by the point type).
template <class Point, class CPoint> void storePoint(const Point &p, CPoint *out, std::size_t i) { fromPoint(p, out[i]); }
inline void storePoint(const Vec3 &p, double *out, std::size_t i) {
  out[3 * i] = p.x, out[3 * i + 1] = p.y, out[3 * i + 2] = p.z;
}

template <class Point, class CPoint>
curvenet_status_code evaluateChunks(const curvenet_model *model, int face, const double *uv, std::size_t count,
                                    CPoint *out, const curvenet_batch_options *batch, curvenet_status *status) {
  if (!model) return nullArgument("model", status);
  if (count && (!uv || !out)) return nullArgument(!uv ? "uv" : "out", status);
  BatchOptions options;
  if (batch) options = {batch->threads, batch->parallel_threshold, batch->step};
  // With the automatic policy a whole batch above the threshold is parallel;
  // chunks must not fall below it and turn serial.
  if (options.threads == 0 && count >= options.parallelThreshold) options.parallelThreshold = 0;
  constexpr std::size_t chunk = 1 << 16;
  std::vector<Vec2> in(std::min(count, chunk));
  std::vector<Point> result(in.size());
  Status first;
  for (std::size_t begin = 0; begin < count || (count == 0 && begin == 0); begin += chunk) {
    const std::size_t n = std::min(chunk, count - begin);
    for (std::size_t k = 0; k < n; ++k) in[k] = {uv[2 * (begin + k)], uv[2 * (begin + k) + 1]};
    const std::span<const Vec2> chunkIn(in.data(), n);
    const std::span<Point> chunkOut(result.data(), n);
    Status s;
    if constexpr (std::is_same_v<Point, SurfacePoint2>)
      s = model->model.evaluateSecondOrder(face, chunkIn, chunkOut, options);
    else if constexpr (std::is_same_v<Point, Vec3>)
      s = model->model.evaluatePositions(face, chunkIn, chunkOut, options);
    else
      s = model->model.evaluate(face, chunkIn, chunkOut, options);
    if (s.code != StatusCode::Ok && s.code != StatusCode::OutOfDomain) return report(s, status);
    if (!s.ok() && first.ok()) {
      // The facade numbers points within the chunk; name the batch index.
      first = s;
      const std::size_t local = std::stoul(s.element.substr(s.element.find(' ') + 1));
      first.element = "point " + std::to_string(begin + local);
      first.message = "lies outside the domain of face " + std::to_string(face) + "; such points are set to NaN";
    }
    for (std::size_t k = 0; k < n; ++k) storePoint(result[k], out, begin + k);
    if (count == 0) break;
  }
  return report(first, status);
}

/// Tessellates `face` (or all faces) of the model and reports the mesh size:
/// the common end of both tessellation entry points.
curvenet_status_code tessellateModel(curvenet_model &model, const TessellationOptions &options, int face,
                                     size_t *vertex_count, size_t *triangle_count, curvenet_status *status) {
  const Result<MeshSize> size = model.model.tessellate(options, face);
  if (!size) return report(size.status(), status);
  if (vertex_count) *vertex_count = size->vertices;
  if (triangle_count) *triangle_count = size->triangles;
  return report({}, status);
}

// ---- Network input: holes, reference surface, edge settings -------------

static_assert(CURVENET_REFERENCE_ELLIPSOID == static_cast<int>(ReferenceSurface::Kind::Ellipsoid) + 1 &&
              CURVENET_REFERENCE_TORUS == static_cast<int>(ReferenceSurface::Kind::Torus) + 1 &&
              CURVENET_REFERENCE_GRAPH == static_cast<int>(ReferenceSurface::Kind::Graph) + 1);

/// The reference surface, held to the rules the native reader applies to
/// its "reference" object (finite data, surfaces that are surfaces).
Result<std::optional<ReferenceSurface>> toReference(const curvenet_reference &r) {
  const int kind = rawValue(r.kind);
  if (kind == CURVENET_REFERENCE_NONE) return std::optional<ReferenceSurface>();
  const auto refuse = [](const std::string &reason) {
    return Status{StatusCode::InvalidInput, {}, "reference", reason};
  };
  if (kind < CURVENET_REFERENCE_ELLIPSOID || kind > CURVENET_REFERENCE_GRAPH)
    return Status{StatusCode::InvalidArgument, {}, "reference", "kind " + std::to_string(kind) + " is out of range"};
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(r.center[i]) || !std::isfinite(r.size[i])) return refuse("center and size must be finite");
  ReferenceSurface reference;
  reference.kind = static_cast<ReferenceSurface::Kind>(kind - 1);
  reference.center = {r.center[0], r.center[1], r.center[2]};
  reference.size = {r.size[0], r.size[1], r.size[2]};
  const Vec3 &s = reference.size;
  if (reference.kind == ReferenceSurface::Kind::Ellipsoid && !(s.x > 0 && s.y > 0 && s.z > 0))
    return refuse("ellipsoid semi-axes must be positive");
  if (reference.kind == ReferenceSurface::Kind::Torus && !(s.y > 0 && s.x > s.y))
    return refuse("torus needs ring radius size[0] > tube radius size[1] > 0");
  return std::optional<ReferenceSurface>(reference);
}

/// A face with its holes and name.
Result<FaceDescription> toFace(const curvenet_network_face &f, std::size_t index) {
  const std::string element = "face " + std::to_string(index);
  if (f.hole_count && !f.holes) return Status{StatusCode::InvalidArgument, {}, element, "holes are NULL"};
  FaceDescription face;
  Result<std::vector<SideDescription>> outer = toSides(f.outer.sides, f.outer.side_count, element);
  if (!outer) return outer.status();
  face.sides = std::move(outer).value();
  for (std::size_t h = 0; h < f.hole_count; ++h) {
    Result<std::vector<SideDescription>> hole =
        toSides(f.holes[h].sides, f.holes[h].side_count, element + " hole " + std::to_string(h));
    if (!hole) return hole.status();
    face.holes.push_back(std::move(hole).value());
  }
  if (f.name) face.name = f.name;
  return face;
}

/// The whole C network as a NetworkDescription; Network::build checks the
/// topology, the edge settings and the tolerance.
Result<NetworkDescription> toNetwork(const curvenet_network &n) {
  const auto null = [](const char *what) { return Status{StatusCode::InvalidArgument, {}, what, "must not be NULL"}; };
  if (n.curve_count && !n.curves) return null("curves");
  if (n.face_count && !n.faces) return null("faces");
  if (n.edge_count && !n.edges) return null("edges");
  NetworkDescription d;
  d.name = n.name ? n.name : "network";
  Result<std::vector<BSplineCurve>> curves = toCurves(n.curves, n.curve_count);
  if (!curves) return curves.status();
  d.curves = std::move(curves).value();
  for (std::size_t f = 0; f < n.face_count; ++f) {
    Result<FaceDescription> face = toFace(n.faces[f], f);
    if (!face) return face.status();
    d.faces.push_back(std::move(face).value());
  }
  for (std::size_t e = 0; e < n.edge_count; ++e)
    d.edges.push_back({n.edges[e].curve, n.edges[e].master_face, n.edges[e].connection != 0});
  Result<std::optional<ReferenceSurface>> reference = toReference(n.reference);
  if (!reference) return reference.status();
  d.reference = *reference;
  d.tolerance = n.tolerance;
  d.connectionCurves = n.connection_curves != 0;
  return d;
}

// ---- End of network input: holes, reference surface, edge settings ------

} // namespace

extern "C" {

const char *curvenet_status_code_name(curvenet_status_code code) {
  return statusCodeName(static_cast<StatusCode>(code));
}

const char *curvenet_version(void) { return versionString(); }

void curvenet_surface_options_init(curvenet_surface_options *options) {
  if (!options) return;
  const SurfaceOptions d;
  *options = {static_cast<curvenet_scheme>(d.scheme), static_cast<curvenet_sweepline>(d.sweepline),
              static_cast<curvenet_fence_normals>(d.fenceNormals),
              static_cast<curvenet_edge_curvature>(d.edgeCurvature), static_cast<curvenet_master_faces>(d.masterFaces),
              static_cast<curvenet_curves>(d.curves)};
}

void curvenet_batch_options_init(curvenet_batch_options *options) {
  if (!options) return;
  const BatchOptions d;
  *options = {d.threads, d.parallelThreshold, d.step};
}

curvenet_status_code curvenet_model_build(const curvenet_curve *curves, size_t curve_count,
                                          const curvenet_face *faces, size_t face_count,
                                          const curvenet_surface_options *options, curvenet_model **model,
                                          curvenet_status *status) {
  if (!model) return nullArgument("model", status);
  *model = nullptr;
  if (curve_count && !curves) return nullArgument("curves", status);
  if (face_count && !faces) return nullArgument("faces", status);
  if (!validOptions(options)) return fail(StatusCode::InvalidArgument, "options", "enum value out of range", status);
  return guarded(status, [&] {
    Result<NetworkDescription> description = toDescription(curves, curve_count, faces, face_count);
    if (!description) return report(description.status(), status);
    return adopt(Model::build(std::move(description).value(), toOptions(options)), model, status);
  });
}

// ---- Master surfaces given from outside ([SV14] Sec. 5.1) ----------------

// C++ linkage: the helper returns a C++ type (this block is inside extern "C").
extern "C++" {
namespace {

/// A C master surface as a BSplineSurface (the facade validates the data).
Result<BSplineSurface> toSurface(const curvenet_master_surface &m, std::size_t index) {
  const std::string element = "surfaces[" + std::to_string(index) + "]";
  const std::size_t count = m.count_u * m.count_v;
  if ((!m.knots_u && m.knot_u_count) || (!m.knots_v && m.knot_v_count) || (!m.points && count))
    return Status{StatusCode::InvalidArgument, {}, element, "knots or points are NULL"};
  if (m.count_u > std::size_t(INT32_MAX) || m.count_v > std::size_t(INT32_MAX))
    return Status{StatusCode::InvalidArgument, {}, element, "control net too large"};
  std::vector<double> weights;
  if (m.weights) weights.assign(m.weights, m.weights + count);
  Result<BSplineSurface> surface =
      makeSurface(m.degree_u, m.degree_v, {m.knots_u, m.knots_u + m.knot_u_count}, {m.knots_v, m.knots_v + m.knot_v_count},
                  int(m.count_u), int(m.count_v), toPoints(m.points, count), std::move(weights));
  if (!surface.ok()) {
    Status status = surface.status();
    status.element = element;
    return status;
  }
  return surface;
}

} // namespace
} // extern "C++"

curvenet_status_code curvenet_model_build_with_masters(const curvenet_curve *curves, size_t curve_count,
                                                       const curvenet_face *faces, size_t face_count,
                                                       const curvenet_master_surface *surfaces, size_t surface_count,
                                                       const curvenet_master_edge *edges, size_t edge_count,
                                                       const curvenet_surface_options *options,
                                                       curvenet_model **model, curvenet_status *status) {
  if (!model) return nullArgument("model", status);
  *model = nullptr;
  if (curve_count && !curves) return nullArgument("curves", status);
  if (face_count && !faces) return nullArgument("faces", status);
  if (surface_count && !surfaces) return nullArgument("surfaces", status);
  if (edge_count && !edges) return nullArgument("edges", status);
  if (!validOptions(options)) return fail(StatusCode::InvalidArgument, "options", "enum value out of range", status);
  return guarded(status, [&] {
    Result<NetworkDescription> description = toDescription(curves, curve_count, faces, face_count);
    if (!description) return report(description.status(), status);
    NetworkDescription network = std::move(description).value();
    for (std::size_t k = 0; k < surface_count; ++k) {
      Result<BSplineSurface> surface = toSurface(surfaces[k], k);
      if (!surface) return report(surface.status(), status);
      network.surfaces.push_back(std::move(surface).value());
    }
    // Network::build checks the indices and that each curve lies on its surface.
    for (std::size_t k = 0; k < edge_count; ++k) {
      EdgeDescription edge;
      edge.curve = edges[k].curve;
      edge.masterSurface = edges[k].surface;
      network.edges.push_back(edge);
    }
    return adopt(Model::build(std::move(network), toOptions(options)), model, status);
  });
}

// ---- end of master surfaces --------------------------------------------------

curvenet_status_code curvenet_model_from_loop(const curvenet_curve *curves, size_t curve_count,
                                              const curvenet_surface_options *options, curvenet_model **model,
                                              curvenet_status *status) {
  if (!model) return nullArgument("model", status);
  *model = nullptr;
  if (curve_count && !curves) return nullArgument("curves", status);
  if (!validOptions(options)) return fail(StatusCode::InvalidArgument, "options", "enum value out of range", status);
  return guarded(status, [&] {
    Result<std::vector<BSplineCurve>> loop = toCurves(curves, curve_count);
    if (!loop) return report(loop.status(), status);
    return adopt(Model::fromLoop(std::move(loop).value(), toOptions(options)), model, status);
  });
}

curvenet_status_code curvenet_model_load(const char *input, const curvenet_surface_options *options,
                                         curvenet_model **model, curvenet_status *status) {
  if (!model) return nullArgument("model", status);
  *model = nullptr;
  if (!input) return nullArgument("input", status);
  if (!validOptions(options)) return fail(StatusCode::InvalidArgument, "options", "enum value out of range", status);
  return guarded(status, [&] { return adopt(Model::load(input, toOptions(options)), model, status); });
}

void curvenet_model_destroy(curvenet_model *model) { delete model; }

int curvenet_model_face_count(const curvenet_model *model) { return model ? model->model.faceCount() : 0; }
int curvenet_model_curve_count(const curvenet_model *model) { return model ? model->model.curveCount() : 0; }
int curvenet_model_domain_sides(const curvenet_model *model, int face) {
  return model ? model->model.domainSides(face) : 0;
}

curvenet_status_code curvenet_model_domain_corner(const curvenet_model *model, int face, int corner, double uv[2],
                                                  curvenet_status *status) {
  if (!model || !uv) return nullArgument(!model ? "model" : "uv", status);
  const Result<Vec2> c = model->model.domainCorner(face, corner);
  if (!c) return report(c.status(), status);
  uv[0] = c->x;
  uv[1] = c->y;
  return report({}, status);
}

curvenet_status_code curvenet_model_set_face_options(curvenet_model *model, int face,
                                                     const curvenet_surface_options *options,
                                                     curvenet_status *status) {
  if (!model || !options) return nullArgument(!model ? "model" : "options", status);
  if (!validOptions(options)) return fail(StatusCode::InvalidArgument, "options", "enum value out of range", status);
  return report(model->model.setFaceOptions(face, toOptions(options)), status);
}

curvenet_status_code curvenet_model_evaluate(const curvenet_model *model, int face, const double *uv, size_t count,
                                             curvenet_point *out, const curvenet_batch_options *batch,
                                             curvenet_status *status) {
  return guarded(status, [&] { return evaluateChunks<SurfacePoint>(model, face, uv, count, out, batch, status); });
}

curvenet_status_code curvenet_model_evaluate_second_order(const curvenet_model *model, int face, const double *uv,
                                                          size_t count, curvenet_point2 *out,
                                                          const curvenet_batch_options *batch,
                                                          curvenet_status *status) {
  return guarded(status, [&] { return evaluateChunks<SurfacePoint2>(model, face, uv, count, out, batch, status); });
}

curvenet_status_code curvenet_model_evaluate_positions(const curvenet_model *model, int face, const double *uv,
                                                       size_t count, double *xyz, const curvenet_batch_options *batch,
                                                       curvenet_status *status) {
  return guarded(status, [&] { return evaluateChunks<Vec3>(model, face, uv, count, xyz, batch, status); });
}

curvenet_status_code curvenet_model_shape(const curvenet_model *model, curvenet_shape *shape,
                                          curvenet_status *status) {
  if (!model || !shape) return nullArgument(!model ? "model" : "shape", status);
  return guarded(status, [&] {
    const Result<ShapeReport> r = model->model.shape();
    if (!r) return report(r.status(), status);
    const std::vector<RepairMove> moves = model->model.repairMoves();
    double largest = 0;
    for (const RepairMove &m : moves) largest = std::max(largest, m.sizeRelative);
    *shape = {r->foldedFaces.size(), r->rejectedFaces.size(), r->maxExcursion, r->worstExcursionFace, kExcursionBound,
              r->fairness, r->maxFairness, r->worstFairnessFace, moves.size(), largest};
    return report({}, status);
  });
}

curvenet_status_code curvenet_model_face_shape(const curvenet_model *model, int face, int *folded,
                                               double *excursion, double *fairness, curvenet_status *status) {
  if (!model) return nullArgument("model", status);
  if (face < 0 || face >= model->model.faceCount())
    return report(Status{StatusCode::InvalidArgument, {}, "face " + std::to_string(face), "no such face"}, status);
  return guarded(status, [&] {
    const Result<ShapeReport> r = model->model.shape();
    if (!r) return report(r.status(), status);
    const FaceShape &f = r->faces[static_cast<std::size_t>(face)];
    if (folded) *folded = f.folded ? 1 : 0;
    if (excursion) *excursion = f.excursion;
    if (fairness) *fairness = f.fairness;
    return report({}, status);
  });
}

curvenet_status_code curvenet_model_tessellate(curvenet_model *model, int face, int resolution, int threads,
                                               size_t *vertex_count, size_t *triangle_count,
                                               curvenet_status *status) {
  if (!model) return nullArgument("model", status);
  TessellationOptions options;
  options.resolution = resolution;
  options.threads = threads;
  return tessellateModel(*model, options, face, vertex_count, triangle_count, status);
}

curvenet_status_code curvenet_model_tessellate_to_tolerance(curvenet_model *model, int face, double tolerance,
                                                            double angle_deg, int threads, size_t *vertex_count,
                                                            size_t *triangle_count, curvenet_status *status) {
  if (!model) return nullArgument("model", status);
  if (!(tolerance > 0 && tolerance < 1))
    return report({StatusCode::InvalidArgument, "", "tolerance", "must lie in (0, 1) (relative to the diagonal)"},
                  status);
  TessellationOptions options;
  options.tolerance = tolerance;
  options.angle = angle_deg;
  options.threads = threads;
  return tessellateModel(*model, options, face, vertex_count, triangle_count, status);
}

curvenet_status_code curvenet_model_copy_mesh(const curvenet_model *model, double *positions,
                                              size_t position_capacity, double *normals, size_t normal_capacity,
                                              uint32_t *triangles, size_t triangle_capacity,
                                              curvenet_status *status) {
  if (!model) return nullArgument("model", status);
  if (!positions || !triangles) return nullArgument(!positions ? "positions" : "triangles", status);
  return guarded(status, [&] {
    // Staging buffers of the claimed capacities (at most the mesh's sizes):
    // the facade's copyMesh then judges whether they suffice.
    const Mesh &mesh = model->model.mesh();
    std::vector<Vec3> p(std::min(position_capacity, mesh.positions.size()));
    std::vector<Vec3> n(normals ? std::min(normal_capacity, mesh.normals.size()) : 0);
    std::vector<std::array<std::uint32_t, 3>> t(std::min(triangle_capacity, mesh.triangles.size()));
    const Status s = model->model.copyMesh(p, normals ? std::span<Vec3>(n) : std::span<Vec3>(), t);
    if (!s.ok()) return report(s, status);
    for (std::size_t k = 0; k < p.size(); ++k) fromVec(p[k], positions + 3 * k);
    for (std::size_t k = 0; k < n.size(); ++k) fromVec(n[k], normals + 3 * k);
    for (std::size_t k = 0; k < t.size(); ++k) std::copy(t[k].begin(), t[k].end(), triangles + 3 * k);
    return report({}, status);
  });
}

curvenet_status_code curvenet_model_face_triangle_ranges(const curvenet_model *model, uint32_t *starts,
                                                         size_t capacity, size_t *count, curvenet_status *status) {
  if (!model) return nullArgument("model", status);
  if (!starts && capacity) return nullArgument("starts", status);
  return guarded(status, [&] {
    const std::vector<std::uint32_t> &ranges = model->model.mesh().faceTriangleStart;
    if (ranges.empty()) return fail(StatusCode::NoMesh, "mesh", "tessellate first", status);
    if (count) *count = ranges.size();
    if (!starts) return report({}, status);
    if (capacity < ranges.size())
      return fail(StatusCode::BufferTooSmall, "starts",
                  "holds " + std::to_string(capacity) + ", the mesh needs " + std::to_string(ranges.size()), status);
    std::copy(ranges.begin(), ranges.end(), starts);
    return report({}, status);
  });
}

curvenet_status_code curvenet_model_write_mesh(const curvenet_model *model, const char *path,
                                               curvenet_status *status) {
  if (!model || !path) return nullArgument(!model ? "model" : "path", status);
  return guarded(status, [&] { return report(model->model.writeMesh(path), status); });
}

curvenet_status_code curvenet_model_set_curve(curvenet_model *model, int curve, const curvenet_curve *replacement,
                                              curvenet_status *status) {
  if (!model || !replacement) return nullArgument(!model ? "model" : "replacement", status);
  return guarded(status, [&] {
    Result<BSplineCurve> c = toCurve(*replacement, curve);
    if (!c) return report(c.status(), status);
    return report(model->model.setCurve(curve, std::move(c).value()), status);
  });
}

curvenet_status_code curvenet_model_set_control_points(curvenet_model *model, int curve, const double *points,
                                                       size_t point_count, curvenet_status *status) {
  if (!model || (!points && point_count)) return nullArgument(!model ? "model" : "points", status);
  return guarded(status, [&] {
    const std::vector<Vec3> p = toPoints(points, point_count);
    return report(model->model.setControlPoints(curve, p), status);
  });
}

// ---- Network input: holes, reference surface, edge settings -------------

void curvenet_network_init(curvenet_network *network) {
  if (!network) return;
  const NetworkDescription d;
  *network = {};
  network->tolerance = d.tolerance;
  network->connection_curves = d.connectionCurves ? 1 : 0;
}

curvenet_status_code curvenet_model_build_network(const curvenet_network *network,
                                                  const curvenet_surface_options *options, curvenet_model **model,
                                                  curvenet_status *status) {
  if (!model) return nullArgument("model", status);
  *model = nullptr;
  if (!network) return nullArgument("network", status);
  if (!validOptions(options)) return fail(StatusCode::InvalidArgument, "options", "enum value out of range", status);
  return guarded(status, [&] {
    Result<NetworkDescription> description = toNetwork(*network);
    if (!description) return report(description.status(), status);
    return adopt(Model::build(std::move(description).value(), toOptions(options)), model, status);
  });
}

// ---- End of network input: holes, reference surface, edge settings ------

} // extern "C"
