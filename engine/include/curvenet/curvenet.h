/* curvenet/curvenet.h — the C interface of curvenet.
 *
 * The same engine as curvenet/curvenet.hpp, for C programs and for other
 * languages through their C foreign-function interfaces (Python ctypes/cffi,
 * Rust, C#). Plain C99: opaque handles, status codes, fixed-size error
 * strings, no C++ in this header.
 *
 * Lifecycle. A curvenet_model is a curve network with the surfaces over its
 * faces. Create it with curvenet_model_from_loop, curvenet_model_build,
 * curvenet_model_build_network (faces with holes, a reference surface,
 * master edges) or curvenet_model_load; release it with
 * curvenet_model_destroy.
 *
 * Errors. Every call that can fail returns a curvenet_status_code
 * (CURVENET_OK = 0 on success) and, when `status` is not NULL, fills it with
 * the code, the element at fault ("curve 3", "face 2", "point 17") and a
 * message a person can read. Nothing is thrown or aborted across this
 * interface. After a failed call the model is as it was before the call.
 *
 * Units. Positions are in the units of the input curves. Domain points
 * (u, v) lie in the face's domain polygon: the regular n-gon with corners on
 * the unit circle (curvenet_model_domain_corner gives them; see
 * curvenet/surface.hpp, "Domains"); derivatives are per unit of domain length.
 *
 * Threads. Calls taking `const curvenet_model *` may run concurrently on the
 * same model from any number of threads; calls taking `curvenet_model *`
 * need exclusive access to it. Different models are independent.
 *
 * Linking. The shared library libcurvenet.so carries everything it needs:
 *   cc app.c $(pkg-config --cflags --libs curvenet)
 * (other languages load libcurvenet.so.0 by name). With CMake, link
 * curvenet::shared, or curvenet::engine for the static library, which also
 * brings the C++ runtime. The static library without CMake:
 * libcurvenet.a libcurvenet_kernels.a -ltbb -lhwy -lstdc++ -lm.
 */
#ifndef CURVENET_CURVENET_H
#define CURVENET_CURVENET_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Status ------------------------------------------------------------ */

/* The values equal those of curvenet::StatusCode (curvenet.hpp). */
typedef enum curvenet_status_code {
  CURVENET_OK = 0,
  CURVENET_INVALID_ARGUMENT = 1, /* an argument is wrong: NULL pointer, index out of range, … */
  CURVENET_INVALID_INPUT = 2,    /* the network, a curve or a file cannot make a surface */
  CURVENET_OUT_OF_DOMAIN = 3,    /* a domain point outside the face's polygon (its output is NaN) */
  CURVENET_BUFFER_TOO_SMALL = 4, /* a caller buffer is smaller than the size query said */
  CURVENET_NO_MESH = 5,          /* mesh requested before curvenet_model_tessellate or after an edit */
  CURVENET_INTERNAL = 6,         /* an engine invariant broke (a bug: please report it) */
  CURVENET_OUT_OF_MEMORY = 7
} curvenet_status_code;

typedef struct curvenet_status {
  curvenet_status_code code;
  char element[128]; /* where: "curve 3", "face 0 side 2", "point 17"; may be empty */
  char message[512]; /* "file: element: reason", NUL-terminated, truncated to fit */
} curvenet_status;

/* "ok", "invalid-argument", "invalid-input", "out-of-domain",
 * "buffer-too-small", "no-mesh", "internal", "out-of-memory"; a static string. */
const char *curvenet_status_code_name(curvenet_status_code code);

/* "MAJOR.MINOR.PATCH" of the linked library; a static string. */
const char *curvenet_version(void);

/* ---- Options ----------------------------------------------------------- */

/* Values equal those of the C++ enums in curvenet/surface.hpp, which
 * documents each scheme and option. */
typedef enum curvenet_scheme {
  CURVENET_GREGORY_G1 = 0,
  CURVENET_COMPOSITE_RIBBON = 1,
  CURVENET_GREGORY_G2 = 2,
  CURVENET_BEZIER_G1 = 3, /* 4-sided Bézier networks only */
  CURVENET_COONS_C0 = 4   /* 4-sided Bézier networks only */
} curvenet_scheme;

typedef enum curvenet_sweepline {
  CURVENET_SWEEPLINE_AUTO = 0,
  CURVENET_SWEEPLINE_RADIAL = 1,
  CURVENET_SWEEPLINE_HERMITE = 2,
  CURVENET_SWEEPLINE_QUINTIC_HERMITE = 3
} curvenet_sweepline;

typedef enum curvenet_fence_normals {
  CURVENET_FENCE_AUTO = 0,
  CURVENET_FENCE_CURVES = 1,
  CURVENET_FENCE_REFERENCE = 2
} curvenet_fence_normals;

typedef enum curvenet_edge_curvature {
  CURVENET_EDGE_CURVATURE_MASTER_SLAVE = 0,
  CURVENET_EDGE_CURVATURE_AVERAGING = 1,
  CURVENET_EDGE_CURVATURE_DIRECT = 2,
  CURVENET_EDGE_CURVATURE_REFERENCE = 3
} curvenet_edge_curvature;

typedef enum curvenet_master_faces {
  CURVENET_MASTER_FACES_REBUILT = 0,
  CURVENET_MASTER_FACES_KEPT_G1 = 1
} curvenet_master_faces;

/* The curves as given, or repaired at the vertices that fail (CurveHandling). */
typedef enum curvenet_curves {
  CURVENET_CURVES_REPAIRED = 0,
  CURVENET_CURVES_KEPT = 1
} curvenet_curves;

typedef struct curvenet_surface_options {
  curvenet_scheme scheme;
  curvenet_sweepline sweepline;
  curvenet_fence_normals fence_normals;
  curvenet_edge_curvature edge_curvature; /* gregory-g2 only */
  curvenet_master_faces master_faces;     /* gregory-g2 only */
  curvenet_curves curves;                 /* every scheme */
} curvenet_surface_options;

/* Fills the defaults: gregory-g1, automatic sweepline and fences, direct
 * edge curvature, master faces rebuilt, curves repaired. */
void curvenet_surface_options_init(curvenet_surface_options *options);

/* How a batch evaluation spreads its work (see BatchOptions in curvenet.hpp). */
typedef struct curvenet_batch_options {
  int threads;               /* 0 = automatic, 1 = serial, k = at most k threads */
  size_t parallel_threshold; /* with threads = 0: batches this large run in parallel */
  double step;               /* second-order difference step, [1e-8, 1e-2] (not gregory-g2) */
} curvenet_batch_options;

/* Fills the defaults: threads 0, threshold 4096, step 1e-5. */
void curvenet_batch_options_init(curvenet_batch_options *options);

/* ---- Network input ----------------------------------------------------- */

/* A clamped B-spline curve: knot_count = point_count + degree + 1, points as
 * x y z triples (3 * point_count doubles), weights NULL for a polynomial
 * curve or point_count positive values. A Bézier curve of degree p has
 * p + 1 points and knots {0 … 0, 1 … 1} (p + 1 of each). The model copies the
 * data; the arrays need live only during the call. */
typedef struct curvenet_curve {
  int degree; /* 1 … 15 */
  const double *knots;
  size_t knot_count;
  const double *points;
  size_t point_count;
  const double *weights;
} curvenet_curve;

/* One side of a face loop: curve `curve` from parameter `from` to `to`
 * (from > to runs the curve backwards). */
typedef struct curvenet_side {
  int curve;
  double from, to;
} curvenet_side;

/* A face: a closed loop of 2 … 8 sides; side k ends where side k + 1 starts. */
typedef struct curvenet_face {
  const curvenet_side *sides;
  size_t side_count;
} curvenet_face;

typedef struct curvenet_model curvenet_model;

/* One face bounded by `curves` in loop order, each used whole from start to
 * end (curve k ends where curve k + 1 starts). `options` NULL = defaults.
 * On success *model receives a new model; on failure NULL. Cost: linear in
 * the curves. */
curvenet_status_code curvenet_model_from_loop(const curvenet_curve *curves, size_t curve_count,
                                              const curvenet_surface_options *options, curvenet_model **model,
                                              curvenet_status *status);

/* A network of curves and faces (curve indices refer to `curves`). The
 * relative vertex tolerance is 1e-7 of the bounding-box diagonal. */
curvenet_status_code curvenet_model_build(const curvenet_curve *curves, size_t curve_count,
                                          const curvenet_face *faces, size_t face_count,
                                          const curvenet_surface_options *options, curvenet_model **model,
                                          curvenet_status *status);

/* ---- Master surfaces given from outside ([SV14] Sec. 5.1) -------------- */

/* A tensor-product B-spline / NURBS surface: degrees 1 … 15, clamped knot
 * vectors of count_u + degree_u + 1 and count_v + degree_v + 1 knots, the
 * control net row by row (point (i, j), i along u, j along v, at
 * points[3 * (i * count_v + j)]), weights NULL (polynomial) or one positive
 * value per point in the same order. */
typedef struct curvenet_master_surface {
  int degree_u, degree_v;
  const double *knots_u;
  size_t knot_u_count;
  const double *knots_v;
  size_t knot_v_count;
  const double *points;
  size_t count_u, count_v;
  const double *weights;
} curvenet_master_surface;

/* Curve `curve` takes surface `surface` (an index into the surfaces given)
 * as its master: the faces along it meet the surface G1 (gregory-g1,
 * composite-ribbon) or G2 (gregory-g2). The curve must lie on the surface
 * within the vertex tolerance. */
typedef struct curvenet_master_edge {
  int curve;
  int surface;
} curvenet_master_edge;

/* curvenet_model_build with master surfaces: `surfaces` and the edges that
 * name them. Errors name the element ("surfaces[1]: knots in u …",
 * "edges[0]: curve 3 is 0.002 from master surface 1 …"). */
curvenet_status_code curvenet_model_build_with_masters(const curvenet_curve *curves, size_t curve_count,
                                                       const curvenet_face *faces, size_t face_count,
                                                       const curvenet_master_surface *surfaces, size_t surface_count,
                                                       const curvenet_master_edge *edges, size_t edge_count,
                                                       const curvenet_surface_options *options,
                                                       curvenet_model **model, curvenet_status *status);

/* ---- end of master surfaces -------------------------------------------- */

/* ---- Network input: holes, reference surface, edge settings ------------
 *
 * Everything the native format (docs/network-format.md) and the C++
 * NetworkDescription (curvenet/network.hpp) can say about a network, for
 * networks that curvenet_model_build cannot express: faces with a hole,
 * face names, an analytic reference surface, per-curve settings (master
 * faces, connection curves) and the vertex tolerance. A network built this
 * way is the same network as the native file saying the same, and evaluates
 * to the same bits. */

/* A loop of sides in order: side k ends where side k + 1 starts. */
typedef struct curvenet_loop {
  const curvenet_side *sides;
  size_t side_count;
} curvenet_loop;

/* A face: its outer loop, at most one hole (an inner loop, in either
 * direction; Network::build joins it to the outer loop by hidden connection
 * curves) and an optional name for reports (NULL or "" for none). */
typedef struct curvenet_network_face {
  curvenet_loop outer;
  const curvenet_loop *holes;
  size_t hole_count;
  const char *name;
} curvenet_network_face;

/* Per-curve settings (the native format's "edges"), at most one per curve. */
typedef struct curvenet_edge {
  int curve;       /* index into the network's curves */
  int master_face; /* the curve's master face (an index into the faces, as given), or -1 for none */
  int connection;  /* non-zero: a hidden seam inside a composite face */
} curvenet_edge;

/* The analytic reference surfaces of curvenet/reference.hpp. */
typedef enum curvenet_reference_kind {
  CURVENET_REFERENCE_NONE = 0,
  CURVENET_REFERENCE_ELLIPSOID = 1, /* (x/a)² + (y/b)² + (z/c)² = 1 around center; size = a, b, c */
  CURVENET_REFERENCE_TORUS = 2,     /* ring radius size[0] > tube radius size[1] > 0, axis z */
  CURVENET_REFERENCE_GRAPH = 3      /* z = a x² + b y², a = size[0], b = size[1], shifted by center */
} curvenet_reference_kind;

typedef struct curvenet_reference {
  curvenet_reference_kind kind;
  double center[3];
  double size[3];
} curvenet_reference;

typedef struct curvenet_network {
  const char *name; /* shown in messages; NULL for "network" */
  const curvenet_curve *curves;
  size_t curve_count;
  const curvenet_network_face *faces;
  size_t face_count;
  const curvenet_edge *edges;
  size_t edge_count;
  curvenet_reference reference; /* kind CURVENET_REFERENCE_NONE: no reference surface */
  double tolerance;             /* relative vertex tolerance (NetworkDescription::tolerance), > 0 */
  int connection_curves;        /* non-zero: split concave loops and holes by connection curves */
} curvenet_network;

/* Fills the defaults: no name, curves, faces or edges, no reference,
 * tolerance 1e-7, connection curves on. */
void curvenet_network_init(curvenet_network *network);

/* Builds `network` (the arrays need live only during the call). Errors name
 * the element as the native reader does: "curve 2", "face 1 hole 0",
 * "edge 0", "reference"; the rest as curvenet_model_build. */
curvenet_status_code curvenet_model_build_network(const curvenet_network *network,
                                                  const curvenet_surface_options *options, curvenet_model **model,
                                                  curvenet_status *status);

/* ---- End of network input: holes, reference surface, edge settings ---- */

/* "builtin:NAME" or a network file (.json native format, .lop loop file). */
curvenet_status_code curvenet_model_load(const char *input, const curvenet_surface_options *options,
                                         curvenet_model **model, curvenet_status *status);

/* Releases the model; NULL is allowed. */
void curvenet_model_destroy(curvenet_model *model);

/* ---- Inspection (cheap) ------------------------------------------------ */

/* Faces of the network: connection curves may split a face given to
 * curvenet_model_build into several (see Model::faceCount in curvenet.hpp). */
int curvenet_model_face_count(const curvenet_model *model);
int curvenet_model_curve_count(const curvenet_model *model);
/* Sides of face `face`'s domain polygon (4 for a 2-sided face); 0 for a bad index. */
int curvenet_model_domain_sides(const curvenet_model *model, int face);
/* Corner `corner` (modulo the side count) of the face's domain into uv[0], uv[1]. */
curvenet_status_code curvenet_model_domain_corner(const curvenet_model *model, int face, int corner, double uv[2],
                                                  curvenet_status *status);

/* ---- Options per face -------------------------------------------------- */

#define CURVENET_ALL_FACES (-1)

/* Sets the options of face `face` (or every face with CURVENET_ALL_FACES)
 * and rebuilds the surfaces that changed: one surface build over the whole
 * network per new option set (see Model in curvenet.hpp for what per-face
 * schemes mean at the borders between them). Clears the kept mesh. */
curvenet_status_code curvenet_model_set_face_options(curvenet_model *model, int face,
                                                     const curvenet_surface_options *options,
                                                     curvenet_status *status);

/* ---- Evaluation -------------------------------------------------------- */

/* A surface point with exact first derivatives and the unit normal. */
typedef struct curvenet_point {
  double point[3], du[3], dv[3], normal[3];
} curvenet_point;

/* With second derivatives too. */
typedef struct curvenet_point2 {
  double point[3], du[3], dv[3], normal[3];
  double duu[3], duv[3], dvv[3];
} curvenet_point2;

/* Evaluates face `face` at `count` domain points uv[2k], uv[2k+1] into
 * out[k]. Points outside the domain get NaN and the call returns
 * CURVENET_OUT_OF_DOMAIN naming the first; the rest are evaluated. `batch`
 * NULL = defaults. Batches of 32 points or more take the batched path of
 * Model::evaluate (ribbon tables, batched sweepline roots, SIMD derivative
 * kernels: about 10x the single-point rate, agreeing with it to ~1e-11
 * relative; curvenet.hpp says exactly), spread over threads when large. */
curvenet_status_code curvenet_model_evaluate(const curvenet_model *model, int face, const double *uv, size_t count,
                                             curvenet_point *out, const curvenet_batch_options *batch,
                                             curvenet_status *status);

/* As curvenet_model_evaluate with second derivatives: exact for gregory-g2
 * (except on master faces kept as G¹ patches), 9 first-order evaluations with
 * step batch->step for the other schemes. */
curvenet_status_code curvenet_model_evaluate_second_order(const curvenet_model *model, int face, const double *uv,
                                                          size_t count, curvenet_point2 *out,
                                                          const curvenet_batch_options *batch,
                                                          curvenet_status *status);

/* Positions alone: xyz[3k .. 3k+2] = face `face` at uv[2k], uv[2k+1]. The
 * fast path for many points (batched sweepline roots, ribbon tables, SIMD
 * kernels for the Gregory schemes; the first call on a face builds its
 * tables, about 1 ms). Outside points and status as curvenet_model_evaluate. */
curvenet_status_code curvenet_model_evaluate_positions(const curvenet_model *model, int face, const double *uv,
                                                       size_t count, double *xyz, const curvenet_batch_options *batch,
                                                       curvenet_status *status);

/* ---- Tessellation ------------------------------------------------------ */

/* Tessellates the whole network (face = CURVENET_ALL_FACES; one watertight
 * mesh) or one face, with `resolution` ≥ 1 intervals per segment, on
 * `threads` threads (0 = all cores), and keeps the mesh in the model (a mesh
 * that would not fit in the memory available: CURVENET_OUT_OF_MEMORY up
 * front, the kept mesh unchanged). The
 * sizes go to *vertex_count and *triangle_count (either may be NULL): size
 * the buffers of curvenet_model_copy_mesh with them. Cost: one
 * whole-network tessellation per distinct option set; cached per
 * resolution, so further faces at the same resolution only copy. */
curvenet_status_code curvenet_model_tessellate(curvenet_model *model, int face, int resolution, int threads,
                                               size_t *vertex_count, size_t *triangle_count,
                                               curvenet_status *status);

/* As curvenet_model_tessellate, but to a chordal `tolerance` relative to the
 * network's diagonal, in (0, 1), and, when `angle_deg` > 0, with the normals
 * at the two ends of every mesh edge within angle_deg degrees: each face and
 * segment gets its own resolution, chosen by measuring the mesh against the
 * exact surface; watertight where neighbouring faces differ (TessellationOptions
 * in curvenet/tessellate.hpp). The model must have one option set for every
 * face (CURVENET_INVALID_ARGUMENT otherwise). */
curvenet_status_code curvenet_model_tessellate_to_tolerance(curvenet_model *model, int face, double tolerance,
                                                            double angle_deg, int threads, size_t *vertex_count,
                                                            size_t *triangle_count, curvenet_status *status);

/* Copies the kept mesh: positions and normals as x y z triples (capacities
 * in vertices), triangles as three vertex indices each, counter-clockwise
 * seen from the normal side (capacity in triangles). `normals` NULL (or a
 * capacity of 0) skips the normals. */
curvenet_status_code curvenet_model_copy_mesh(const curvenet_model *model, double *positions,
                                              size_t position_capacity, double *normals, size_t normal_capacity,
                                              uint32_t *triangles, size_t triangle_capacity,
                                              curvenet_status *status);

/* The kept mesh's triangles per network face: starts[f] .. starts[f + 1] - 1
 * are the triangles of face f (a whole-network mesh: face count + 1 entries;
 * a one-face mesh: 2 entries). The number of entries goes to *count (may be
 * NULL); `starts` NULL with capacity 0 asks only for it. A capacity below it:
 * CURVENET_BUFFER_TOO_SMALL; no mesh: CURVENET_NO_MESH. */
curvenet_status_code curvenet_model_face_triangle_ranges(const curvenet_model *model, uint32_t *starts,
                                                         size_t capacity, size_t *count, curvenet_status *status);

/* Writes the kept mesh as OBJ or PLY by the extension of `path`, atomically.
 * OBJ puts each face's triangles in a group `g faceN`; PLY gives every
 * triangle a `face` property, the network face it belongs to. */
curvenet_status_code curvenet_model_write_mesh(const curvenet_model *model, const char *path,
                                               curvenet_status *status);

/* ---- Editing ----------------------------------------------------------- */

/* Replaces curve `curve` and rebuilds network and surfaces (cost: a full
 * rebuild, linear in the segments, whatever moved; figures: SurfaceEdit in bench/README.md).
 * Clears the kept mesh. Face and curve numbers stay. */
curvenet_status_code curvenet_model_set_curve(curvenet_model *model, int curve, const curvenet_curve *replacement,
                                              curvenet_status *status);

/* New control points (x y z triples, the curve's current count) for curve
 * `curve`, keeping degree, knots and weights; rebuilds as above. */
curvenet_status_code curvenet_model_set_control_points(curvenet_model *model, int curve, const double *points,
                                                       size_t point_count, curvenet_status *status);

/* ---- Shape (curvenet/shape.hpp) ---------------------------------------- */

/* The figures that catch a bad surface, over all faces. */
typedef struct curvenet_shape {
  size_t folded_faces;     /* faces whose patch folds */
  size_t rejected_faces;   /* folded, or excursion above the bound */
  double max_excursion;    /* relative to the diagonal */
  int worst_excursion_face;
  double excursion_bound;  /* kExcursionBound */
  double fairness;         /* area-weighted mean over the faces */
  double max_fairness;
  int worst_fairness_face;
  size_t repair_moves;     /* control points moved by the vertex repair */
  double max_repair_move;  /* the largest, relative to the diagonal */
} curvenet_shape;

/* Fills *shape (Model::shape at the default resolution, Model::repairMoves). */
curvenet_status_code curvenet_model_shape(const curvenet_model *model, curvenet_shape *shape,
                                          curvenet_status *status);
/* Face `face`'s figures; any output pointer may be NULL. */
curvenet_status_code curvenet_model_face_shape(const curvenet_model *model, int face, int *folded,
                                               double *excursion, double *fairness, curvenet_status *status);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* CURVENET_CURVENET_H */
