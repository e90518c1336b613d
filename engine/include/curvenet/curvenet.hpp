// curvenet/curvenet.hpp — the embedding API: one include, no exceptions.
//
// An embedding program (a CAD kernel, a renderer, a game tool) includes this
// header and works with one object, a Model: a curve network together with
// the transfinite surfaces over its faces. It can
//
//  * build the network in code (curves and loops of curve ranges) or load it
//    from a file or a built-in (Model::build, Model::fromLoop, Model::load);
//  * choose a scheme and its options for every face (setFaceOptions);
//  * evaluate a face at one domain point or at a batch of them, with first
//    and, on request, second derivatives and the unit normal (evaluate,
//    evaluateSecondOrder);
//  * tessellate one face or the whole network into a library-owned mesh or
//    into caller-provided buffers sized by a query first (tessellate, mesh,
//    copyMesh);
//  * move curves and re-evaluate (setCurve, setControlPoints): only the
//    faces near the moved curve are rebuilt.
//
// Errors. Nothing in this header throws. Every call that can fail returns a
// Status — or a Result<T>, a value or a Status — carrying a code, the
// element at fault ("curve 3", "face 2", "point 17") and the reason, in the
// manner of Manifold's status values. After a failed call the model is as
// it was before the call. (The lower-level classes this header re-exports —
// Network, Surface, BSplineCurve, the readers in io.hpp — report bad input by
// throwing InputError; use them directly only where that suits you.)
//
// Units. Positions are in the units of the input curves; domain points are
// in the face's domain polygon, the regular n-gon with corners on the unit
// circle (surface.hpp, "Domains"), so derivatives are per unit of domain
// length (circumradius 1).
//
// Threads. A Model's const calls (evaluation, inspection, copyMesh, mesh)
// may run from any number of threads at once. The non-const calls
// (setFaceOptions, tessellate, setCurve, setControlPoints, moving or
// destroying the model) need exclusive access: no other call on the same
// model may run meanwhile. Different models are independent. Batch
// evaluation and tessellation use TBB internally (BatchOptions::threads,
// TessellationOptions::threads).
//
// A C interface over the same calls is in curvenet/curvenet.h. Papers are
// cited by key ([SV14], [OSK11], [HPS09], …) throughout the headers; the
// full references are in docs/references.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "curvenet/curve.hpp"
#include "curvenet/mesh.hpp"
#include "curvenet/network.hpp"
#include "curvenet/shape.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"
#include "curvenet/vec.hpp"

namespace curvenet {
inline namespace v1 {

/// "MAJOR.MINOR.PATCH" of the library this program linked against.
const char *versionString();

/// What went wrong. The numeric values are those of the C interface's
/// cn_status_code and stay fixed within the v1 namespace.
enum class StatusCode : int {
  Ok = 0,
  /// A parameter of the call is wrong: face or curve index out of range,
  /// spans of different sizes, a resolution below 1, an unknown option.
  InvalidArgument = 1,
  /// The network, a curve or a file cannot make a surface: a loop that does
  /// not close, a degenerate tangent, an unreadable file, a scheme that does
  /// not accept the network. `file` and `element` say where.
  InvalidInput = 2,
  /// A domain point outside the face's domain polygon, or not finite.
  OutOfDomain = 3,
  /// A caller-provided buffer is smaller than the size query said.
  BufferTooSmall = 4,
  /// copyMesh or writeMesh before any tessellate, or after an edit cleared it.
  NoMesh = 5,
  /// An engine invariant broke (a bug in curvenet, please report it).
  Internal = 6,
  OutOfMemory = 7,
};

/// "ok", "invalid-argument", "invalid-input", "out-of-domain",
/// "buffer-too-small", "no-mesh", "internal", "out-of-memory".
const char *statusCodeName(StatusCode code);

struct Status {
  StatusCode code = StatusCode::Ok;
  std::string file;    ///< the input file at fault, if any
  std::string element; ///< e.g. "curve 3", "face 0 side 2", "point 17", "line 7"
  std::string message; ///< the reason, for a person to read

  bool ok() const { return code == StatusCode::Ok; }
  /// "file: element: message" (empty parts left out); "ok" on success.
  std::string toString() const;
};

/// A value or, when the call failed, the Status saying why.
template <class T>
class Result {
public:
  Result(T value) : value_(std::move(value)) {}
  /// A failure; `status.code` must not be Ok.
  Result(Status status) : status_(std::move(status)) {}

  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }
  /// Ok when the call succeeded.
  const Status &status() const { return status_; }

  /// The value. Precondition: ok(); otherwise the program aborts (the API
  /// does not throw, and there is no value to give).
  T &value() & { return checked(); }
  const T &value() const & { return const_cast<Result *>(this)->checked(); }
  T &&value() && { return std::move(checked()); }
  T *operator->() { return &checked(); }
  const T *operator->() const { return &const_cast<Result *>(this)->checked(); }
  T &operator*() & { return checked(); }
  const T &operator*() const & { return const_cast<Result *>(this)->checked(); }

private:
  T &checked() {
    if (!value_) std::abort();
    return *value_;
  }
  std::optional<T> value_;
  Status status_;
};

/// A B-spline curve (curve.hpp) from its data, without throwing: degree in
/// [1, 15], knots clamped and non-decreasing with knots = points + degree + 1,
/// finite points, positive weights (empty for a polynomial curve).
Result<BSplineCurve> makeCurve(int degree, std::vector<double> knots, std::vector<Vec3> controlPoints,
                               std::vector<double> weights = {});
/// The Bézier curve of degree points.size() − 1 (at least 2 points) on [0, 1].
Result<BSplineCurve> makeBezier(std::vector<Vec3> controlPoints);
/// A tensor-product B-spline / NURBS surface (bspline_surface.hpp) from its
/// data, without throwing: the control net row by row (point (i, j) at
/// i · countV + j), weights empty or one per point. Put it in
/// NetworkDescription::surfaces and name it from an edge
/// (EdgeDescription::masterSurface) to make it that edge's master.
Result<BSplineSurface> makeSurface(int degreeU, int degreeV, std::vector<double> knotsU, std::vector<double> knotsV,
                                   int countU, int countV, std::vector<Vec3> controlPoints,
                                   std::vector<double> weights = {});

/// How a batch call spreads its work.
struct BatchOptions {
  /// 0 = automatic: serial below `parallelThreshold` points, all cores
  /// above it; 1 = serial on the calling thread; k > 1 = at most k threads.
  int threads = 0;
  /// Batches this large or larger run in parallel when threads = 0. Below
  /// it the cost of waking workers exceeds the gain.
  std::size_t parallelThreshold = 4096;
  /// Second-order step (domain units, [1e-8, 1e-2]) for schemes whose second
  /// derivatives are differenced (all but gregory-g2; see
  /// Surface::evaluateSecondOrder). Ignored for first-order calls.
  double step = 1e-5;
};

/// Sizes of the mesh a tessellate call produced, for sizing caller buffers.
struct MeshSize {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
};

/// A curve network and the surfaces over its faces.
///
/// Faces are numbered as in the description (face f is description face f),
/// curves likewise; vertices and segments as Network::build numbers them.
///
/// Per-face schemes: every face carries its SurfaceOptions (scheme,
/// sweepline, fence normals, edge curvature). Faces with equal options form
/// a group, and the model holds one Surface per group, built over the whole
/// network, so that the vertex tangent planes — computed from all curves at
/// a vertex — agree for every group. Consequences, stated plainly:
///  * each additional group costs one more Surface::build over the whole
///    network (memory and time);
///  * across an edge between two groups the surfaces share the boundary
///    curve (C⁰) and the vertex tangent planes; they share the normal fence,
///    and are G¹ there, only when both groups build the same fences (the G¹
///    schemes gregory-g1 and composite-ribbon with the same FenceNormals).
///    gregory-g2 builds curvature-compatible fences, so a G¹/G² border is
///    C⁰ with tangent planes matching at its vertices only;
///  * bezier-g1 and coons-c0 need every face of the network to be a 4-sided
///    Bézier face, whichever faces use them (InvalidInput otherwise);
///  * options are per face, not per edge: an edge's curvature source is that
///    of the group building it.
class Model {
public:
  /// Face argument meaning every face (tessellate, setFaceOptions).
  static constexpr int allFaces = -1;

  /// Builds the network and one surface for all faces with `options`.
  /// Cost: Network::build plus one Surface::build, linear in the segments.
  static Result<Model> build(NetworkDescription description, const SurfaceOptions &options = {});

  /// One face bounded by `curves` in loop order, each used whole, from its
  /// start to its end: curve k must end where curve k + 1 starts (and the
  /// last where the first starts), within the default tolerance. 2 to 8 curves.
  static Result<Model> fromLoop(std::vector<BSplineCurve> curves, const SurfaceOptions &options = {});

  /// Loads "builtin:NAME" or a network file (.json native, .lop loop file;
  /// see docs/network-format.md) and builds it.
  static Result<Model> load(const std::string &input, const SurfaceOptions &options = {});

  Model(Model &&) noexcept;
  Model &operator=(Model &&) noexcept;
  ~Model();

  // ---- Inspection (const, cheap, thread-safe) ----

  /// The network's faces: where connection curves split a described face
  /// (a concave loop, a hole; network.hpp) its parts are faces of their own.
  /// An edit that changes such a split renumbers the faces (see setCurve).
  int faceCount() const;
  int curveCount() const;
  /// Sides of face `face`'s domain polygon (its loop's side count; 4 for a
  /// 2-sided face); 0 for an index out of range.
  int domainSides(int face) const;
  /// Corner `corner` (taken modulo domainSides) of face `face`'s domain:
  /// (cos 2πk/n, sin 2πk/n) rotated as surface.hpp says.
  Result<Vec2> domainCorner(int face, int corner) const;
  /// True when evaluateSecondOrder is exact for the face (gregory-g2, but not
  /// a master face it keeps as a G¹ patch), false when it differences exact
  /// first derivatives.
  bool hasExactSecondDerivatives(int face) const;

  /// The options face `face` uses (as set: a master face that gregory-g2
  /// keeps as its G¹ patch, MasterFaces::KeptG1, reports the gregory-g2
  /// options it was given); the first face's for an index out of range.
  const SurfaceOptions &faceOptions(int face) const;
  /// Distinct option sets, i.e. Surfaces the model holds (≥ 1).
  int surfaceCount() const;

  /// The network (topology, vertices, segments) and the description it was
  /// built from (after edits: with the edited curves).
  const Network &network() const;
  const NetworkDescription &description() const;
  /// The Surface evaluating face `face` (nullptr for an index out of range),
  /// for the queries this header does not wrap (vertex curvature, fences).
  /// Note: Surface calls throw InputError on bad arguments. The pointer is
  /// valid until the next non-const call on the model.
  const Surface *surface(int face) const;

  /// The shape figures of curvenet/shape.hpp (folded faces, excursion,
  /// fairness, the faces --strict rejects), each face measured on the
  /// surface of its group, the overall figures over all faces. Cost: one
  /// measureShape per Surface (surfaceCount()).
  Result<ShapeReport> shape(const ShapeOptions &options = {}) const;
  /// Every control-point move the vertex repair made (SurfaceOptions::curves),
  /// over all groups, in group order (each group repairs for its scheme).
  std::vector<RepairMove> repairMoves() const;
  /// What the vertex repair left alone (Surface::repairSkipped), over all
  /// groups in group order, each reason once.
  std::vector<std::string> repairSkipped() const;

  // ---- Options ----

  /// Sets the options of face `face` (or of every face, with allFaces) and
  /// rebuilds the surfaces of the groups that changed. Cost: one
  /// Surface::build over the whole network per new option set. Clears the
  /// kept mesh. On failure (e.g. gregory-g2 with the radial sweepline, a
  /// reference source without a reference surface) nothing changes.
  Status setFaceOptions(int face, const SurfaceOptions &options);
  /// Sets every face's options at once (`perFace.size()` == faceCount()),
  /// building each distinct option set once.
  Status setFaceOptions(std::span<const SurfaceOptions> perFace);

  // ---- Evaluation (const, thread-safe, allocation-free per point) ----

  /// Face `face` at domain point uv (inside or on the domain polygon; a
  /// relative tolerance of 1e-9 is allowed outside). Cost: one patch
  /// evaluation, O(n) ribbon evaluations for an n-sided face.
  Result<SurfacePoint> evaluate(int face, const Vec2 &uv) const;

  /// A batch: out[k] = face `face` at uv[k]. `out.size()` must equal
  /// `uv.size()`. Points outside the domain get NaN output and the status
  /// names the first of them (OutOfDomain); the other points are evaluated
  /// all the same. Output is identical for any thread count. The fast path
  /// for many points with derivatives and normals (Surface::evaluate on a
  /// span: batched sweepline roots, ribbon tables and the SIMD derivative
  /// kernels, about 10× the single-point rate; the first call on a face
  /// builds its tables, ~1 ms). From 32 points on it is therefore not bit
  /// for bit the single-point evaluate() but agrees with it to ~1e-13 of
  /// the model's size in the point, ~1e-11 in du, dv (relative) and
  /// ~1e-11 / sin θ in the normal (θ between du and dv); smaller batches
  /// are the single-point evaluation itself.
  Status evaluate(int face, std::span<const Vec2> uv, std::span<SurfacePoint> out,
                  const BatchOptions &batch = {}) const;

  /// Positions alone of a batch (out.size() == uv.size()): the fast path
  /// for many points (Surface::evaluatePositions — batched sweepline roots,
  /// ribbon tables and SIMD kernels for the Gregory schemes; the first call
  /// on a face builds its tables, ~1 ms). Outside points and the status as
  /// for evaluate(); identical output for any thread count.
  Status evaluatePositions(int face, std::span<const Vec2> uv, std::span<Vec3> out,
                           const BatchOptions &batch = {}) const;

  /// With second derivatives (see Surface::evaluateSecondOrder: exact for
  /// gregory-g2, 9 first-order evaluations with step `batch.step` otherwise).
  Result<SurfacePoint2> evaluateSecondOrder(int face, const Vec2 &uv, const BatchOptions &batch = {}) const;
  Status evaluateSecondOrder(int face, std::span<const Vec2> uv, std::span<SurfacePoint2> out,
                             const BatchOptions &batch = {}) const;

  // ---- Tessellation ----

  /// Tessellates the whole network (face = allFaces) or one face and keeps
  /// the mesh in the model, replacing the previous one; returns its size so
  /// that a caller can size buffers for copyMesh. The whole-network mesh is
  /// watertight (tessellate.hpp); a one-face mesh is that face's part of it,
  /// renumbered, so it matches its neighbours' meshes along shared edges.
  /// Cost: one whole-network tessellation per Surface (surfaceCount()) — also
  /// for one face, which is cut from it — plus a copy; the whole-network
  /// result is cached per resolution until an edit or an options change,
  /// so tessellating the faces one by one costs one tessellation in all.
  /// After an edit of a model with one Surface (surfaceCount() == 1) that
  /// kept the topology, the cached result is re-tessellated on the edited
  /// faces only (lastEditedFaces, through the cached plans), so the next
  /// call at that resolution costs a copy; otherwise an edit drops it.
  /// A resolution whose mesh would not fit in the memory available is
  /// refused up front (OutOfMemory, with the estimate); the kept mesh stays.
  /// With options.tolerance (tessellate.hpp: each face and segment its own
  /// resolution, chosen by measurement) the model must have one option set
  /// (surfaceCount() == 1; InvalidArgument otherwise), the result is cached
  /// per tolerance and angle, and an edit drops it instead of updating it.
  Result<MeshSize> tessellate(const TessellationOptions &options = {}, int face = allFaces);

  /// The kept mesh (library-owned; empty before any tessellate and after an
  /// edit). The reference stays valid until the next non-const call.
  const Mesh &mesh() const;

  /// Copies the kept mesh into caller buffers, each at least as large as
  /// the MeshSize tessellate returned (BufferTooSmall otherwise; NoMesh
  /// when there is none). `normals` may be empty to skip them.
  Status copyMesh(std::span<Vec3> positions, std::span<Vec3> normals,
                  std::span<std::array<std::uint32_t, 3>> triangles) const;

  /// Writes the kept mesh as OBJ or PLY by the extension of `path`,
  /// atomically (io.hpp).
  Status writeMesh(const std::string &path) const;

  // ---- Editing ----

  /// Replaces curve `curve` of the description and rebuilds what depends on
  /// it: Network::build (linear in the curves, cheap), then for every group
  /// Surface::rebuildAfterEdit, which recomputes the frames and curvatures
  /// of the vertices at the ends of the curve's segments, the fences (and
  /// gregory-g2 edge curvatures) of every segment at those vertices and the
  /// patches of the faces using those segments — one face ring around the
  /// curve (two rings for gregory-g2 with master–slave or averaging edge
  /// curvature) — and shares everything else with the previous surfaces.
  /// The surfaces evaluate bit for bit as a model built from the edited
  /// description would. Where the edit changes the topology (curve ends or
  /// crossings meeting differently), and for bezier-g1 / coons-c0, the
  /// surfaces are built in full. Cost: proportional to the faces rebuilt
  /// (lastEditedFaces), not to the model, and so is bringing the cached
  /// tessellation up to date (see tessellate). Clears the kept mesh; call
  /// tessellate again. Face and curve numbers stay; vertex and segment
  /// numbers stay unless the edit makes curve ends meet differently. An edit
  /// that changes how connection curves split a face (a concave corner
  /// turned convex) changes the faces: with one option set for every face
  /// the model is then built afresh; with per-face options the edit is
  /// refused (InvalidInput), as they would no longer match the faces. On
  /// failure (a loop no longer closes, …) nothing changes.
  Status setCurve(int curve, BSplineCurve replacement);

  /// The common edit: new control points for curve `curve`, same degree,
  /// knots and weights (points.size() must equal the current count).
  /// Same cost and guarantees as setCurve.
  Status setControlPoints(int curve, std::span<const Vec3> points);

  /// Faces whose patches the last setCurve / setControlPoints rebuilt, over
  /// all groups, ascending (every face after a full rebuild; empty before
  /// any edit).
  const std::vector<int> &lastEditedFaces() const;

private:
  struct Impl;
  explicit Model(std::unique_ptr<Impl> impl);
  /// Each group's Surface once, in group order.
  std::vector<const Surface *> groupSurfaces() const;
  std::unique_ptr<Impl> impl_;
};

} // namespace v1
} // namespace curvenet
