// The Python module `curvenet` (docs/design.md §8): the Model of
// curvenet/curvenet.hpp with numpy arrays in and out.
//
// Arrays and copies. Domain points (N, 2), positions (N, 3) and control
// points (P, 3) that are C-contiguous float64 are read in place as spans of
// Vec2 / Vec3 (two and three doubles, no padding); any other array is
// converted once. evaluate_positions writes straight into its result (or
// into `out=`), evaluate and evaluate_second_order into one (N, 4, 3) or
// (N, 7, 3) array whose slices are the fields of the result. A mesh is
// copied once, from the model into its numpy arrays (copyMesh), since the
// model keeps its own.
//
// The GIL is released around every call into the engine that can run long
// (loading, building, options, evaluation, tessellation, edits, check,
// render, bench). A model guards itself with a reader–writer lock, so Python
// threads may share it: evaluations run side by side, an edit waits for them.
//
// Errors. Every failed Status is raised as curvenet.Error (a ValueError)
// whose message is Status::toString(), with `code`, `file` and `element`
// attributes; the InputError that the report and render code throws
// becomes the same exception with code "invalid-input".
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "curvenet/builtins.hpp"
#include "curvenet/curvature.hpp"
#include "curvenet/curvenet.hpp"
#include "curvenet/error.hpp"
#include "render.hpp"
#include "report.hpp"

namespace py = pybind11;
using namespace curvenet;

namespace {

static_assert(sizeof(Vec2) == 2 * sizeof(double) && sizeof(Vec3) == 3 * sizeof(double),
              "domain points and positions are read and written in place as packed doubles");
static_assert(sizeof(SurfacePoint) == 4 * sizeof(Vec3) && sizeof(SurfacePoint2) == 7 * sizeof(Vec3),
              "surface points are written in place as rows of Vec3");

/// Arrays as the engine reads them: float64, C-contiguous (converted only
/// when the caller's array is not).
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// ---- Errors ----------------------------------------------------------------

PyObject *errorType = nullptr;

[[noreturn]] void raiseError(const std::string &message, const char *code, const std::string &file,
                             const std::string &element) {
  py::object error = py::reinterpret_borrow<py::object>(errorType)(message);
  error.attr("code") = code;
  error.attr("file") = file;
  error.attr("element") = element;
  PyErr_SetObject(errorType, error.ptr());
  throw py::error_already_set();
}

[[noreturn]] void raise(const Status &status) {
  raiseError(status.toString(), statusCodeName(status.code), status.file, status.element);
}

void check(const Status &status) {
  if (!status.ok()) raise(status);
}

template <class T> T take(Result<T> &&result) {
  if (!result) raise(result.status());
  return std::move(result).value();
}

/// An (N, columns) array's rows as a span of T (T = `columns` doubles).
template <class T> std::span<const T> rows(const DoubleArray &array, int columns, const char *name) {
  if (array.ndim() != 2 || array.shape(1) != columns)
    raiseError(std::string(name) + " must have shape (N, " + std::to_string(columns) + "), got " +
                   std::to_string(array.ndim()) + " dimensions",
               "invalid-argument", "", name);
  return {reinterpret_cast<const T *>(array.data()), static_cast<std::size_t>(array.shape(0))};
}

// ---- Options ---------------------------------------------------------------

SurfaceOptions surfaceOptions(const std::string &scheme, const std::optional<std::string> &edgeCurvature,
                              const std::optional<std::string> &masterFaces, SurfaceOptions options = {}) {
  if (auto s = schemeFromName(scheme)) options.scheme = *s;
  else {
    std::string known;
    for (Scheme available : availableSchemes()) known += (known.empty() ? "" : ", ") + schemeName(available);
    raiseError("unknown scheme '" + scheme + "'; available: " + known, "invalid-argument", "", "scheme");
  }
  if (edgeCurvature) {
    if (auto e = edgeCurvatureFromName(*edgeCurvature)) options.edgeCurvature = *e;
    else raiseError("unknown edge curvature '" + *edgeCurvature + "'", "invalid-argument", "", "edge_curvature");
  }
  if (masterFaces) {
    if (auto m = masterFacesFromName(*masterFaces)) options.masterFaces = *m;
    else raiseError("unknown master faces '" + *masterFaces + "' (rebuilt or kept-g1)", "invalid-argument", "",
                    "master_faces");
  }
  return options;
}

BatchOptions batchOptions(int threads) {
  BatchOptions batch;
  batch.threads = threads;
  return batch;
}

py::object jsonToPython(const nlohmann::json &json) {
  return py::module_::import("json").attr("loads")(json.dump());
}

// ---- Results ---------------------------------------------------------------

/// Surface points with first derivatives: views into one (N, 4, 3) array.
struct Evaluation {
  py::array_t<double> storage; ///< (N, 4, 3): point, du, dv, normal per row
  /// storage[:, k, :], a view.
  py::object field(int k) const {
    return storage.attr("__getitem__")(py::make_tuple(py::slice(0, storage.shape(0), 1), k));
  }
};

/// With second derivatives: views into one (N, 7, 3) array.
struct Evaluation2 : Evaluation {};

struct PyMesh {
  py::array vertices, normals, triangles, faceTriangleStart;
};

/// A numpy array over a vector's memory, which it keeps alive: no copy.
template <class Scalar, class T> py::array adopt(std::vector<T> &&values, std::vector<py::ssize_t> shape) {
  auto *owned = new std::vector<T>(std::move(values));
  py::capsule owner(owned, [](void *p) { delete static_cast<std::vector<T> *>(p); });
  return py::array_t<Scalar>(shape, reinterpret_cast<const Scalar *>(owned->data()), owner);
}

// ---- The model -------------------------------------------------------------

/// A Model and the lock that lets Python threads share it.
class PyModel {
  /// f() on the model under the shared lock, with the GIL released.
  template <class F> auto inspect(F &&f) const {
    py::gil_scoped_release unlocked;
    std::shared_lock shared(lock_);
    return f();
  }

  /// inspect(f) for a valid face; Error for one out of range.
  template <class F> auto inspectFace(int face, F &&f) const {
    int faces = 0;
    auto value = inspect([&] {
      faces = model_.faceCount();
      return face >= 0 && face < faces ? std::optional(f()) : std::nullopt;
    });
    if (!value)
      raiseError("face " + std::to_string(face) + " out of range (the model has " + std::to_string(faces) + " faces)",
                 "invalid-argument", "", "face " + std::to_string(face));
    return *value;
  }

public:
  PyModel(Model model, std::string source) : model_(std::move(model)), source_(std::move(source)) {}

  /// `path`: a str or any os.PathLike (a pathlib.Path).
  static std::unique_ptr<PyModel> load(const py::object &path, const std::string &scheme,
                                       const std::optional<std::string> &edgeCurvature,
                                       const std::optional<std::string> &masterFaces) {
    const std::string source = py::str(py::module_::import("os").attr("fspath")(path));
    const SurfaceOptions options = surfaceOptions(scheme, edgeCurvature, masterFaces);
    std::optional<Result<Model>> model;
    {
      py::gil_scoped_release unlocked;
      model.emplace(Model::load(source, options));
    }
    return std::make_unique<PyModel>(take(std::move(*model)), source);
  }

  static std::unique_ptr<PyModel> build(const py::list &curves, const py::list &faces, const std::string &scheme, double tolerance,
                       const std::string &name) {
    NetworkDescription description;
    description.name = name;
    description.tolerance = tolerance;
    for (std::size_t c = 0; c < curves.size(); ++c) description.curves.push_back(curveFrom(curves[c], c));
    for (std::size_t f = 0; f < faces.size(); ++f) description.faces.push_back(faceFrom(faces[f], f, description));
    const SurfaceOptions options = surfaceOptions(scheme, std::nullopt, std::nullopt);
    std::optional<Result<Model>> model;
    {
      py::gil_scoped_release unlocked;
      model.emplace(Model::build(std::move(description), options));
    }
    return std::make_unique<PyModel>(take(std::move(*model)), name);
  }

  int faceCount() const {
    return inspect([&] { return model_.faceCount(); });
  }
  int curveCount() const {
    return inspect([&] { return model_.curveCount(); });
  }
  int surfaceCount() const {
    return inspect([&] { return model_.surfaceCount(); });
  }
  const std::string &source() const { return source_; }

  int domainSides(int face) const {
    return inspectFace(face, [&] { return model_.domainSides(face); });
  }

  py::array_t<double> domainCorners(int face) const {
    const std::vector<Vec2> corners = inspectFace(face, [&] {
      std::vector<Vec2> c;
      for (int k = 0; k < model_.domainSides(face); ++k) c.push_back(*model_.domainCorner(face, k));
      return c;
    });
    py::array_t<double> out({static_cast<py::ssize_t>(corners.size()), py::ssize_t(2)});
    std::memcpy(out.mutable_data(), corners.data(), corners.size() * sizeof(Vec2));
    return out;
  }

  std::string faceScheme(int face) const {
    return inspectFace(face, [&] { return schemeName(model_.faceOptions(face).scheme); });
  }

  bool hasExactSecondDerivatives(int face) const {
    return inspectFace(face, [&] { return model_.hasExactSecondDerivatives(face); });
  }

  std::vector<int> lastEditedFaces() const {
    return inspect([&] { return model_.lastEditedFaces(); });
  }

  void setFaceOptions(std::optional<int> face, const std::string &scheme,
                      const std::optional<std::string> &edgeCurvature, const std::optional<std::string> &masterFaces) {
    const int target = face.value_or(Model::allFaces);
    const SurfaceOptions options = surfaceOptions(scheme, edgeCurvature, masterFaces);
    Status status;
    {
      py::gil_scoped_release unlocked;
      std::unique_lock exclusive(lock_);
      status = model_.setFaceOptions(target, options);
    }
    check(status);
  }

  void setControlPoints(int curve, const DoubleArray &points) {
    const std::span<const Vec3> p = rows<Vec3>(points, 3, "points");
    Status status;
    {
      py::gil_scoped_release unlocked;
      std::unique_lock exclusive(lock_);
      status = model_.setControlPoints(curve, p);
    }
    check(status);
  }

  py::array evaluatePositions(int face, const DoubleArray &uv, int threads, std::optional<py::array> out) const {
    const std::span<const Vec2> points = rows<Vec2>(uv, 2, "uv");
    py::array result = out ? *out : py::array_t<double>({static_cast<py::ssize_t>(points.size()), py::ssize_t(3)});
    if (out && (!result.dtype().is(py::dtype::of<double>()) || result.ndim() != 2 ||
                result.shape(0) != static_cast<py::ssize_t>(points.size()) || result.shape(1) != 3 ||
                !(result.flags() & py::array::c_style) || !result.writeable()))
      raiseError("out must be a writeable C-contiguous float64 array of shape (N, 3) for N = " +
                     std::to_string(points.size()) + " points",
                 "invalid-argument", "", "out");
    const std::span<Vec3> positions(reinterpret_cast<Vec3 *>(result.mutable_data()), points.size());
    check(inspect([&] { return model_.evaluatePositions(face, points, positions, batchOptions(threads)); }));
    return result;
  }

  Evaluation evaluate(int face, const DoubleArray &uv, int threads) const {
    const std::span<const Vec2> points = rows<Vec2>(uv, 2, "uv");
    Evaluation e{py::array_t<double>({static_cast<py::ssize_t>(points.size()), py::ssize_t(4), py::ssize_t(3)})};
    const std::span<SurfacePoint> out(reinterpret_cast<SurfacePoint *>(e.storage.mutable_data()), points.size());
    check(inspect([&] { return model_.evaluate(face, points, out, batchOptions(threads)); }));
    return e;
  }

  Evaluation2 evaluateSecondOrder(int face, const DoubleArray &uv, int threads, double step) const {
    const std::span<const Vec2> points = rows<Vec2>(uv, 2, "uv");
    Evaluation2 e;
    e.storage = py::array_t<double>({static_cast<py::ssize_t>(points.size()), py::ssize_t(7), py::ssize_t(3)});
    const std::span<SurfacePoint2> out(reinterpret_cast<SurfacePoint2 *>(e.storage.mutable_data()), points.size());
    BatchOptions batch = batchOptions(threads);
    batch.step = step;
    check(inspect([&] { return model_.evaluateSecondOrder(face, points, out, batch); }));
    return e;
  }

  PyMesh tessellate(int resolution, int threads, std::optional<int> face) {
    TessellationOptions options;
    options.resolution = resolution;
    options.threads = threads;
    std::optional<Status> failed;
    std::vector<Vec3> vertices, normals;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<std::uint32_t> starts;
    {
      py::gil_scoped_release unlocked;
      std::unique_lock exclusive(lock_);
      const Result<MeshSize> size = model_.tessellate(options, face.value_or(Model::allFaces));
      if (!size) failed = size.status();
      else {
        vertices.resize(size->vertices), normals.resize(size->vertices), triangles.resize(size->triangles);
        if (Status copied = model_.copyMesh(vertices, normals, triangles); !copied.ok()) failed = copied;
        starts = model_.mesh().faceTriangleStart;
      }
    }
    if (failed) raise(*failed);
    const auto v = static_cast<py::ssize_t>(vertices.size()), t = static_cast<py::ssize_t>(triangles.size()),
               f = static_cast<py::ssize_t>(starts.size());
    return {adopt<double>(std::move(vertices), {v, 3}), adopt<double>(std::move(normals), {v, 3}),
            adopt<std::uint32_t>(std::move(triangles), {t, 3}), adopt<std::uint32_t>(std::move(starts), {f})};
  }

  py::object checkReport(const std::optional<std::string> &scheme, int samples, int resolution) const {
    std::shared_lock shared(lock_, std::defer_lock);
    cli::CheckOptions options;
    options.samples = samples;
    options.resolution = resolution;
    if (scheme) options.surface = surfaceOptions(*scheme, std::nullopt, std::nullopt);
    else if (model_.surfaceCount() == 1) options.surface = model_.faceOptions(0);
    else
      raiseError("the faces use different schemes: name the one to check (check(scheme=...))", "invalid-argument",
                 "", "scheme");
    nlohmann::json report;
    {
      py::gil_scoped_release unlocked;
      shared.lock();
      report = cli::checkReport(model_.network(), source_, options);
    }
    return jsonToPython(report);
  }

  py::array_t<std::uint8_t> render(const std::string &mode, std::pair<int, int> size, int resolution,
                                   std::pair<double, double> view, double stripes, bool boundaries, int threads) {
    render::RenderOptions options;
    if (auto m = render::modeFromName(mode)) options.mode = *m;
    else raiseError("unknown mode '" + mode + "'; available: reflection, isophote, mean, gauss", "invalid-argument",
                    "", "mode");
    options.width = size.first, options.height = size.second;
    options.azimuth = view.first, options.elevation = view.second;
    options.stripes = stripes;
    options.boundaries = boundaries;
    options.threads = threads;
    const bool curvatureMode = options.mode == render::Mode::Mean || options.mode == render::Mode::Gauss;
    if (curvatureMode && model_.surfaceCount() != 1)
      raiseError("mean and gauss maps need one scheme for every face", "invalid-argument", "", "mode");
    TessellationOptions t;
    t.resolution = resolution;
    t.threads = threads;
    t.recordDomainPoints = curvatureMode;
    render::Image image;
    std::optional<Status> status;
    {
      py::gil_scoped_release unlocked;
      std::unique_lock exclusive(lock_);
      const Result<MeshSize> tessellated = model_.tessellate(t);
      if (!tessellated) status = tessellated.status();
      else {
        std::vector<double> values;
        if (curvatureMode) {
          CurvatureOptions c;
          c.threads = threads;
          for (const CurvatureSample &s : meshCurvature(*model_.surface(0), model_.mesh(), c))
            values.push_back(options.mode == render::Mode::Mean ? s.mean : s.gauss);
        }
        image = render::renderMesh(model_.mesh(), options, values);
      }
    }
    if (status) raise(*status);
    const std::vector<std::uint8_t> bytes = render::srgbBytes(image);
    py::array_t<std::uint8_t> pixels({image.height, image.width, 3});
    std::memcpy(pixels.mutable_data(), bytes.data(), bytes.size());
    return pixels;
  }

private:
  /// A curve of Model.build: an (P, 3) array of Bézier control points, or a
  /// dict with `points`, `degree`, `knots` and optional `weights`.
  static BSplineCurve curveFrom(const py::handle &item, std::size_t index) {
    auto pointsOf = [&](const py::handle &array) {
      const DoubleArray a = DoubleArray::ensure(array);
      if (!a) raiseError("not an array of points", "invalid-argument", "", "curve " + std::to_string(index));
      const std::span<const Vec3> p = rows<Vec3>(a, 3, ("curve " + std::to_string(index)).c_str());
      return std::vector<Vec3>(p.begin(), p.end());
    };
    std::optional<Result<BSplineCurve>> curve;
    if (py::isinstance<py::dict>(item)) {
      const py::dict d = py::reinterpret_borrow<py::dict>(item);
      if (!d.contains("points") || !d.contains("degree") || !d.contains("knots"))
        raiseError("a B-spline curve needs 'points', 'degree' and 'knots'", "invalid-argument", "",
                   "curve " + std::to_string(index));
      std::vector<double> weights;
      if (d.contains("weights")) weights = d["weights"].cast<std::vector<double>>();
      curve.emplace(makeCurve(d["degree"].cast<int>(), d["knots"].cast<std::vector<double>>(), pointsOf(d["points"]),
                        std::move(weights)));
    } else {
      curve.emplace(makeBezier(pointsOf(item)));
    }
    if (!*curve) {
      Status status = curve->status();
      if (status.element.empty()) status.element = "curve " + std::to_string(index);
      raise(status);
    }
    return std::move(*curve).value();
  }

  /// A face of Model.build: a list of sides, each a curve index (the whole
  /// curve, start to end) or a (curve, from, to) tuple.
  static FaceDescription faceFrom(const py::handle &item, std::size_t index, const NetworkDescription &description) {
    FaceDescription face;
    for (const py::handle side : item) {
      SideDescription s;
      if (py::isinstance<py::int_>(side)) {
        s.curve = side.cast<int>();
        if (s.curve < 0 || s.curve >= static_cast<int>(description.curves.size()))
          raiseError("side refers to curve " + std::to_string(s.curve) + " of " +
                         std::to_string(description.curves.size()),
                     "invalid-argument", "", "face " + std::to_string(index));
        s.from = description.curves[s.curve].domainStart();
        s.to = description.curves[s.curve].domainEnd();
      } else {
        const auto [curve, from, to] = side.cast<std::tuple<int, double, double>>();
        s = {curve, from, to};
      }
      face.sides.push_back(s);
    }
    return face;
  }

  Model model_;
  std::string source_;
  mutable std::shared_mutex lock_;
};

} // namespace

PYBIND11_MODULE(curvenet, m) {
  m.doc() = "Transfinite G1/G2 surfaces over 3D curve networks: evaluation, tessellation, analysis and pictures.\n\n"
            "Domain points are (N, 2) float64 arrays in a face's domain polygon (the regular n-gon with corners on\n"
            "the unit circle, Model.domain_corners); points, derivatives and normals come back as (N, 3) float64,\n"
            "triangles as (T, 3) uint32. Every failure raises curvenet.Error.";
  m.attr("__version__") = versionString();

  errorType = PyErr_NewExceptionWithDoc(
      "curvenet.Error",
      "A failed curvenet call. str() is 'file: element: reason'; attributes: code (e.g. 'invalid-input', "
      "'out-of-domain'), file and element (e.g. 'curve 3', 'point 17'), empty when not known.",
      PyExc_ValueError, nullptr);
  m.attr("Error") = py::handle(errorType);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError &e) {
      try {
        raiseError(e.what(), "invalid-input", "", "");
      } catch (py::error_already_set &error) {
        error.restore();
      }
    } catch (const InternalError &e) {
      try {
        raiseError(e.what(), "internal", "", "");
      } catch (py::error_already_set &error) {
        error.restore();
      }
    }
  });

  m.def("builtins", [] {
    std::vector<std::string> names;
    for (const BuiltinInfo &b : builtinNetworks()) names.push_back(b.name);
    return names;
  }, "The names of the built-in networks, for Model.load('builtin:NAME').");

  m.def(
      "bench",
      [](const std::string &source, int resolution, int points, int threads) {
        nlohmann::json report;
        {
          py::gil_scoped_release unlocked;
          report = cli::benchReport({source, resolution, points, threads});
        }
        return jsonToPython(report);
      },
      py::arg("source") = "builtin:pentagon", py::arg("resolution") = 256, py::arg("points") = 4000,
      py::arg("threads") = 0,
      "G1 against G2 evaluation cost of a network (file or 'builtin:NAME'): the dict that\n"
      "`curvenet bench --json` prints (per scheme build, pointwise, face-interior and tessellation timings, and\n"
      "the G2/G1 ratios). Takes seconds at the default resolution 256.");

  py::class_<Evaluation>(m, "Evaluation", "Surface points with exact first derivatives and unit normals.")
      .def_property_readonly("points", [](const Evaluation &e) { return e.field(0); }, "(N, 3) positions")
      .def_property_readonly("du", [](const Evaluation &e) { return e.field(1); }, "(N, 3) derivative along u")
      .def_property_readonly("dv", [](const Evaluation &e) { return e.field(2); }, "(N, 3) derivative along v")
      .def_property_readonly("normals", [](const Evaluation &e) { return e.field(3); }, "(N, 3) unit normals")
      .def("__len__", [](const Evaluation &e) { return e.storage.shape(0); }, "N, the number of points");

  py::class_<Evaluation2, Evaluation>(m, "Evaluation2", "An Evaluation with second derivatives.")
      .def_property_readonly("duu", [](const Evaluation2 &e) { return e.field(4); }, "(N, 3) second derivative uu")
      .def_property_readonly("duv", [](const Evaluation2 &e) { return e.field(5); }, "(N, 3) mixed derivative uv")
      .def_property_readonly("dvv", [](const Evaluation2 &e) { return e.field(6); }, "(N, 3) second derivative vv");

  py::class_<PyMesh>(m, "Mesh", "A triangle mesh with exact vertex normals.")
      .def_readonly("vertices", &PyMesh::vertices, "(V, 3) float64 positions")
      .def_readonly("normals", &PyMesh::normals, "(V, 3) float64 unit normals")
      .def_readonly("triangles", &PyMesh::triangles, "(T, 3) uint32 vertex indices, counter-clockwise")
      .def_readonly("face_triangle_start", &PyMesh::faceTriangleStart,
                    "(F + 1,) uint32: triangles face_triangle_start[f] up to face_triangle_start[f + 1] are face f's");

  py::class_<PyModel, std::unique_ptr<PyModel>>(m, "Model",
                      "A curve network and the transfinite surfaces over its faces (curvenet::Model).\n\n"
                      "Const calls (evaluation, inspection, check) may run from several Python threads at once;\n"
                      "calls that change the model wait for them.")
      .def_static("load", &PyModel::load, py::arg("source"), py::arg("scheme") = "gregory-g1",
                  py::arg("edge_curvature") = py::none(), py::arg("master_faces") = py::none(),
                  "Loads 'builtin:NAME' or a network file (.json, .lop; a str or os.PathLike) and builds every face\n"
                  "with `scheme` "
                  "(gregory-g1, composite-ribbon, gregory-g2, bezier-g1, coons-c0).")
      .def_static("build", &PyModel::build, py::arg("curves"), py::arg("faces"), py::arg("scheme") = "gregory-g1",
                  py::arg("tolerance") = 1e-7, py::arg("name") = "",
                  "Builds a network from curves and faces. A curve is a (P, 3) array of Bezier control points or a\n"
                  "dict(points=(P, 3), degree=int, knots=[...], weights=[...] optional). A face is a list of sides in\n"
                  "loop order, each a curve index (the whole curve, start to end) or (curve, from, to).")
      .def_property_readonly("face_count", &PyModel::faceCount,
                             "Faces of the network (connection curves may split a given face into several).")
      .def_property_readonly("curve_count", &PyModel::curveCount, "Curves of the network description.")
      .def_property_readonly("surface_count", &PyModel::surfaceCount, "Distinct option sets (surfaces built).")
      .def_property_readonly("source", &PyModel::source, "What the model was loaded from (the name for build).")
      .def_property_readonly("last_edited_faces", &PyModel::lastEditedFaces,
                             "Faces the last set_control_points rebuilt.")
      .def("domain_sides", &PyModel::domainSides, py::arg("face"), "Sides of the face's domain polygon.")
      .def("domain_corners", &PyModel::domainCorners, py::arg("face"), "(n, 2) corners of the face's domain polygon.")
      .def("face_scheme", &PyModel::faceScheme, py::arg("face"), "The scheme face `face` is built with.")
      .def("has_exact_second_derivatives", &PyModel::hasExactSecondDerivatives, py::arg("face"),
           "True when evaluate_second_order is exact for the face (gregory-g2), false when it differences.")
      .def("set_face_options", &PyModel::setFaceOptions, py::arg("face") = py::none(),
           py::arg("scheme") = "gregory-g1", py::arg("edge_curvature") = py::none(),
           py::arg("master_faces") = py::none(),
           "Sets the scheme (and gregory-g2 options) of one face, or of every face with face=None, and rebuilds\n"
           "the surfaces that changed.")
      .def("set_control_points", &PyModel::setControlPoints, py::arg("curve"), py::arg("points"),
           "New (P, 3) control points for a curve (same count); rebuilds the faces around it.")
      .def("evaluate_positions", &PyModel::evaluatePositions, py::arg("face"), py::arg("uv"), py::arg("threads") = 0,
           py::arg("out") = py::none(),
           "(N, 3) positions of face `face` at the (N, 2) domain points uv: the fast path. `out`: an (N, 3)\n"
           "C-contiguous float64 array to write into (and return). threads: 0 automatic, 1 serial, k at most k.")
      .def("evaluate", &PyModel::evaluate, py::arg("face"), py::arg("uv"), py::arg("threads") = 0,
           "Points, exact first derivatives and unit normals at the (N, 2) domain points uv.")
      .def("evaluate_second_order", &PyModel::evaluateSecondOrder, py::arg("face"), py::arg("uv"),
           py::arg("threads") = 0, py::arg("step") = 1e-5,
           "As evaluate, with second derivatives (exact for gregory-g2; differenced with `step` otherwise).")
      .def("tessellate", &PyModel::tessellate, py::arg("resolution") = 16, py::arg("threads") = 0,
           py::arg("face") = py::none(),
           "The watertight mesh of the whole network (or of one face) at `resolution` intervals per segment.")
      .def("check", &PyModel::checkReport, py::arg("scheme") = py::none(), py::arg("samples") = 64,
           py::arg("resolution") = 32,
           "The network analysis and continuity report: the dict `curvenet check --json` prints for the same\n"
           "network and scheme (default: the model's, when every face has the same).")
      .def("render", &PyModel::render, py::arg("mode") = "reflection", py::arg("size") = std::pair{640, 480},
           py::arg("resolution") = 32, py::arg("view") = std::pair{30.0, 30.0}, py::arg("stripes") = 8.0,
           py::arg("boundaries") = false, py::arg("threads") = 0,
           "A ray-traced picture, (height, width, 3) uint8 sRGB: mode reflection, isophote, mean or gauss;\n"
           "size (width, height); view (azimuth, elevation) in degrees; the mesh at `resolution`.")
      .def("__repr__", [](const PyModel &model) {
        return "<curvenet.Model '" + model.source() + "': " + std::to_string(model.faceCount()) + (model.faceCount() == 1 ? " face>" : " faces>");
      });
}
