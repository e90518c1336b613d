/* The C interface (curvenet/curvenet.h), compiled as C. Builds networks from
 * C arrays, evaluates, tessellates through caller buffers, edits, and checks
 * that every failure comes back as a status code with an element and a
 * message. Exit code 0 = all checks passed. */
#include <curvenet/curvenet.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

static int failures = 0;

#define EXPECT(cond)                                                                                           \
  do {                                                                                                         \
    if (!(cond)) {                                                                                             \
      fprintf(stderr, "%s:%d: expected %s\n", __FILE__, __LINE__, #cond);                                      \
      ++failures;                                                                                              \
    }                                                                                                          \
  } while (0)

static const double pi = 3.14159265358979323846;
static const double bezierKnots[8] = {0, 0, 0, 0, 1, 1, 1, 1};

/* Five cubic Bézier curves around the unit pentagon, inner points raised by `lift`. */
static void pentagon(double points[5][12], curvenet_curve curves[5], double lift) {
  for (int k = 0; k < 5; ++k) {
    const double a[3] = {cos(2 * pi * k / 5), sin(2 * pi * k / 5), 0};
    const double b[3] = {cos(2 * pi * (k + 1) / 5), sin(2 * pi * (k + 1) / 5), 0};
    for (int i = 0; i < 3; ++i) {
      points[k][i] = a[i];
      points[k][3 + i] = a[i] + (b[i] - a[i]) / 3 + (i == 2 ? lift : 0);
      points[k][6 + i] = b[i] + (a[i] - b[i]) / 3 + (i == 2 ? lift : 0);
      points[k][9 + i] = b[i];
    }
    curves[k] = (curvenet_curve){3, bezierKnots, 8, points[k], 4, NULL};
  }
}

static double distance(const double a[3], const double b[3]) {
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

static void loopAndEvaluate(void) {
  double points[5][12];
  curvenet_curve curves[5];
  pentagon(points, curves, 0.3);
  curvenet_surface_options options;
  curvenet_surface_options_init(&options);
  EXPECT(options.scheme == CURVENET_GREGORY_G1);
  options.scheme = CURVENET_GREGORY_G2;
  curvenet_status status;
  curvenet_model *model = NULL;
  EXPECT(curvenet_model_from_loop(curves, 5, &options, &model, &status) == CURVENET_OK);
  if (!model) return;
  EXPECT(status.code == CURVENET_OK && status.message[0] == '\0');
  EXPECT(curvenet_model_face_count(model) == 1 && curvenet_model_curve_count(model) == 5);
  EXPECT(curvenet_model_domain_sides(model, 0) == 5 && curvenet_model_domain_sides(model, 1) == 0);

  /* Domain corner k is network corner k, where curve k starts; the midpoint
   * of domain side k shows the midpoint of curve k: (P0 + 3 P1 + 3 P2 + P3) / 8. */
  double uv[4], corner1[2];
  EXPECT(curvenet_model_domain_corner(model, 0, 0, uv, &status) == CURVENET_OK);
  EXPECT(curvenet_model_domain_corner(model, 0, 1, corner1, &status) == CURVENET_OK);
  uv[2] = (uv[0] + corner1[0]) / 2;
  uv[3] = (uv[1] + corner1[1]) / 2;
  curvenet_point out[2];
  EXPECT(curvenet_model_evaluate(model, 0, uv, 2, out, NULL, &status) == CURVENET_OK);
  EXPECT(distance(out[0].point, points[0]) < 1e-12);
  double mid[3];
  for (int i = 0; i < 3; ++i) mid[i] = (points[0][i] + 3 * points[0][3 + i] + 3 * points[0][6 + i] + points[0][9 + i]) / 8;
  EXPECT(distance(out[1].point, mid) < 1e-12);
  EXPECT(fabs(out[1].normal[0] * out[1].normal[0] + out[1].normal[1] * out[1].normal[1] +
              out[1].normal[2] * out[1].normal[2] - 1) < 1e-12);

  /* Positions alone agree with the full evaluation. */
  double xyz[6];
  EXPECT(curvenet_model_evaluate_positions(model, 0, uv, 2, xyz, NULL, &status) == CURVENET_OK);
  EXPECT(distance(xyz, out[0].point) < 1e-12 && distance(xyz + 3, out[1].point) < 1e-12);

  /* Second order: the centre of a symmetric dome bends the same way in u and v. */
  const double centre[2] = {0, 0};
  curvenet_point2 second;
  EXPECT(curvenet_model_evaluate_second_order(model, 0, centre, 1, &second, NULL, &status) == CURVENET_OK);
  EXPECT(second.duu[2] < 0 && fabs(second.duu[2] - second.dvv[2]) < 1e-6 * fabs(second.duu[2]));

  /* A batch with one point outside: it is NaN, the others evaluated. */
  double batch[6] = {0, 0, 3, 0, 0.1, 0.1};
  curvenet_point three[3];
  curvenet_batch_options parallel;
  curvenet_batch_options_init(&parallel);
  parallel.parallel_threshold = 1;
  EXPECT(curvenet_model_evaluate(model, 0, batch, 3, three, &parallel, &status) == CURVENET_OUT_OF_DOMAIN);
  EXPECT(strcmp(status.element, "point 1") == 0);
  EXPECT(isnan(three[1].point[0]) && !isnan(three[2].point[0]));
  EXPECT(strstr(status.message, "point 1") != NULL);

  /* Tessellation: size query, then caller buffers. */
  size_t vertices = 0, triangles = 0;
  EXPECT(curvenet_model_copy_mesh(model, batch, 0, NULL, 0, (uint32_t *)batch, 0, &status) == CURVENET_NO_MESH);
  EXPECT(curvenet_model_tessellate(model, CURVENET_ALL_FACES, 4, 1, &vertices, &triangles, &status) == CURVENET_OK);
  EXPECT(vertices == 5 * 4 + 1 + 5 * 3 + 5 * 3 * 2 / 2 && triangles == 5 * 16);
  double positions[3 * 66], normals[3 * 66];
  uint32_t indices[3 * 80];
  if (vertices <= 66 && triangles <= 80) {
    EXPECT(curvenet_model_copy_mesh(model, positions, vertices - 1, NULL, 0, indices, triangles, &status) ==
           CURVENET_BUFFER_TOO_SMALL);
    EXPECT(strcmp(status.element, "positions") == 0);
    EXPECT(curvenet_model_copy_mesh(model, positions, vertices, normals, vertices, indices, triangles, &status) ==
           CURVENET_OK);
    /* Network corners come first: vertex 0 is where curve 0 starts. */
    EXPECT(distance(positions, points[0]) < 1e-15);
    uint32_t largest = 0;
    for (size_t t = 0; t < 3 * triangles; ++t) largest = indices[t] > largest ? indices[t] : largest;
    EXPECT(largest == vertices - 1);
  }

  /* To a tolerance: a finer one takes more triangles; no tolerance is refused. */
  size_t coarse = 0, fine = 0;
  EXPECT(curvenet_model_tessellate_to_tolerance(model, CURVENET_ALL_FACES, 1e-2, 0, 1, NULL, &coarse, &status) ==
         CURVENET_OK);
  EXPECT(curvenet_model_tessellate_to_tolerance(model, CURVENET_ALL_FACES, 1e-4, 10, 1, NULL, &fine, &status) ==
         CURVENET_OK);
  EXPECT(coarse > 0 && fine > coarse);
  EXPECT(curvenet_model_tessellate_to_tolerance(model, CURVENET_ALL_FACES, 0, 0, 1, NULL, NULL, &status) ==
         CURVENET_INVALID_ARGUMENT);
  EXPECT(strcmp(status.element, "tolerance") == 0);

  /* Edit: raise curve 0's inner points; the side midpoint follows. */
  points[0][5] += 0.2;
  points[0][8] += 0.2;
  EXPECT(curvenet_model_set_control_points(model, 0, points[0], 4, &status) == CURVENET_OK);
  EXPECT(curvenet_model_copy_mesh(model, positions, 66, NULL, 0, indices, 80, &status) == CURVENET_NO_MESH);
  EXPECT(curvenet_model_evaluate(model, 0, uv, 2, out, NULL, &status) == CURVENET_OK);
  EXPECT(fabs(out[1].point[2] - (mid[2] + 0.75 * 0.2)) < 1e-12);
  /* An edit that opens the loop is refused; the model keeps the last good curves. */
  points[0][2] += 1;
  EXPECT(curvenet_model_set_control_points(model, 0, points[0], 4, &status) == CURVENET_INVALID_INPUT);
  EXPECT(status.message[0] != '\0');
  curvenet_point again[2];
  EXPECT(curvenet_model_evaluate(model, 0, uv, 2, again, NULL, &status) == CURVENET_OK);
  EXPECT(again[1].point[2] == out[1].point[2]);
  EXPECT(curvenet_model_set_control_points(model, 0, points[0], 3, &status) == CURVENET_INVALID_ARGUMENT);

  curvenet_model_destroy(model);
}

static void errors(void) {
  curvenet_status status;
  curvenet_model *model = (curvenet_model *)&status; /* must be reset to NULL on failure */
  EXPECT(curvenet_model_load("builtin:no-such-network", NULL, &model, &status) == CURVENET_INVALID_INPUT);
  EXPECT(model == NULL && status.message[0] != '\0');
  EXPECT(curvenet_model_load(NULL, NULL, &model, &status) == CURVENET_INVALID_ARGUMENT);
  EXPECT(strcmp(status.element, "input") == 0);

  /* A curve with the wrong knot count names the curve. */
  const double knots[3] = {0, 0, 1};
  const double line[6] = {0, 0, 0, 1, 0, 0};
  curvenet_curve bad = {1, knots, 3, line, 2, NULL};
  EXPECT(curvenet_model_from_loop(&bad, 1, NULL, &model, &status) == CURVENET_INVALID_INPUT);
  EXPECT(strcmp(status.element, "curve 0") == 0);

  /* Out-of-range enums are caught before they reach the engine. */
  curvenet_surface_options options;
  curvenet_surface_options_init(&options);
  options.scheme = (curvenet_scheme)42;
  EXPECT(curvenet_model_load("builtin:pentagon", &options, &model, &status) == CURVENET_INVALID_ARGUMENT);

  /* Status may be NULL; the code still says what happened. */
  EXPECT(curvenet_model_load("builtin:pentagon", NULL, &model, NULL) == CURVENET_OK);
  EXPECT(curvenet_model_evaluate(model, 3, line, 1, NULL, NULL, NULL) == CURVENET_INVALID_ARGUMENT);
  options.scheme = CURVENET_GREGORY_G2;
  options.sweepline = CURVENET_SWEEPLINE_RADIAL; /* gregory-g2 refuses the radial sweep */
  EXPECT(curvenet_model_set_face_options(model, 0, &options, &status) == CURVENET_INVALID_INPUT);
  EXPECT(curvenet_model_write_mesh(model, "never.obj", &status) == CURVENET_NO_MESH);
  curvenet_model_destroy(model);
  curvenet_model_destroy(NULL);

  EXPECT(strcmp(curvenet_status_code_name(CURVENET_OUT_OF_DOMAIN), "out-of-domain") == 0);
  EXPECT(strlen(curvenet_version()) >= 5);
}

/* Two faces sharing a curve, given as curve ranges: the shared edge is
 * watertight in the whole-network mesh. */
static void twoFaces(void) {
  /* A square split by the curve x = 0.5; boundary as four straight curves. */
  const double knots[4] = {0, 0, 1, 1};
  const double c[7][6] = {
      {0, 0, 0, 1, 0, 0},     /* 0: bottom */
      {1, 0, 0, 1, 1, 0},     /* 1: right */
      {1, 1, 0, 0, 1, 0},     /* 2: top */
      {0, 1, 0, 0, 0, 0},     /* 3: left */
      {0.5, 0, 0, 0.5, 1, 0}, /* 4: middle */
  };
  curvenet_curve curves[5];
  for (int k = 0; k < 5; ++k) curves[k] = (curvenet_curve){1, knots, 4, c[k], 2, NULL};
  const curvenet_side left[4] = {{0, 0, 0.5}, {4, 0, 1}, {2, 0.5, 1}, {3, 0, 1}};
  const curvenet_side right[4] = {{0, 0.5, 1}, {1, 0, 1}, {2, 0, 0.5}, {4, 1, 0}};
  const curvenet_face faces[2] = {{left, 4}, {right, 4}};
  curvenet_status status;
  curvenet_model *model = NULL;
  EXPECT(curvenet_model_build(curves, 5, faces, 2, NULL, &model, &status) == CURVENET_OK);
  if (!model) {
    fprintf(stderr, "%s\n", status.message);
    return;
  }
  size_t vertices = 0, triangles = 0, rangeCount = 0;
  EXPECT(curvenet_model_face_triangle_ranges(model, NULL, 0, &rangeCount, &status) == CURVENET_NO_MESH);
  EXPECT(curvenet_model_tessellate(model, CURVENET_ALL_FACES, 3, 0, &vertices, &triangles, &status) == CURVENET_OK);
  /* 6 corners, 7 segments × 2 edge samples, 2 × (1 + 4·2 + 4·2·1/2) inside. */
  EXPECT(vertices == 6 + 7 * 2 + 2 * (1 + 8 + 4) && triangles == 2 * 4 * 9);
  /* The planar square is reproduced: every vertex at z = 0. */
  double positions[3 * 46];
  uint32_t indices[3 * 72];
  if (vertices <= 46 && triangles <= 72) {
    EXPECT(curvenet_model_copy_mesh(model, positions, vertices, NULL, 0, indices, triangles, &status) == CURVENET_OK);
    double worst = 0;
    for (size_t v = 0; v < vertices; ++v) worst = fabs(positions[3 * v + 2]) > worst ? fabs(positions[3 * v + 2]) : worst;
    EXPECT(worst < 1e-12);
    /* Per-face triangle ranges: face 0 (left of x = 0.5) first, then face 1. */
    uint32_t starts[3] = {0, 0, 0};
    EXPECT(curvenet_model_face_triangle_ranges(model, NULL, 0, &rangeCount, &status) == CURVENET_OK && rangeCount == 3);
    EXPECT(curvenet_model_face_triangle_ranges(model, starts, 2, NULL, &status) == CURVENET_BUFFER_TOO_SMALL);
    EXPECT(strcmp(status.element, "starts") == 0);
    EXPECT(curvenet_model_face_triangle_ranges(model, starts, 3, NULL, &status) == CURVENET_OK);
    EXPECT(starts[0] == 0 && starts[0] < starts[1] && starts[1] < starts[2] && starts[2] == triangles);
    for (int f = 0; f < 2; ++f)
      for (uint32_t t = starts[f]; t < starts[f + 1] && t < triangles; ++t) {
        double x = 0;
        for (int k = 0; k < 3; ++k) x += positions[3 * indices[3 * t + k]] / 3;
        EXPECT(f == 0 ? x < 0.5 : x > 0.5);
      }
  }
  /* One face: 4 corners + 4 sides × 2 samples + 13 inside. */
  EXPECT(curvenet_model_tessellate(model, 1, 3, 0, &vertices, NULL, &status) == CURVENET_OK);
  EXPECT(vertices == 4 + 8 + 13);
  curvenet_model_destroy(model);
}

/* gregory-g2 keeping the setback fillets (the masters) as their G¹ patches:
 * a fillet evaluates exactly as under gregory-g1, the blend does not. */
static void keptMasters(void) {
  curvenet_surface_options g1, kept;
  curvenet_surface_options_init(&g1);
  curvenet_surface_options_init(&kept);
  EXPECT(kept.master_faces == CURVENET_MASTER_FACES_REBUILT);
  kept.scheme = CURVENET_GREGORY_G2;
  kept.master_faces = (curvenet_master_faces)5;
  curvenet_model *a = NULL, *b = NULL;
  curvenet_status status;
  EXPECT(curvenet_model_load("builtin:setback-vertex-blend", &kept, &b, &status) == CURVENET_INVALID_ARGUMENT);
  kept.master_faces = CURVENET_MASTER_FACES_KEPT_G1;
  EXPECT(curvenet_model_load("builtin:setback-vertex-blend", &g1, &a, &status) == CURVENET_OK);
  EXPECT(curvenet_model_load("builtin:setback-vertex-blend", &kept, &b, &status) == CURVENET_OK);
  if (a && b) {
    const double uv[2] = {0.1, 0.2};
    curvenet_point p, q;
    for (int face = 0; face < 4; ++face) {
      EXPECT(curvenet_model_evaluate(a, face, uv, 1, &p, NULL, &status) == CURVENET_OK);
      EXPECT(curvenet_model_evaluate(b, face, uv, 1, &q, NULL, &status) == CURVENET_OK);
      const int same = memcmp(p.point, q.point, sizeof p.point) == 0;
      EXPECT(same == (face < 3));
    }
  }
  curvenet_model_destroy(a);
  curvenet_model_destroy(b);
}

/* The shape figures and the curve handling: under gregory-g2 the sphere
 * dodecahedron is 12 unfolded sphere caps (fairness 2: κ1² + κ2² = 2/R²
 * against the great circles' 1/R²) and needs no repair; an out-of-range
 * curves value is refused. */
static void shape(void) {
  curvenet_model *model = NULL;
  curvenet_status status;
  curvenet_surface_options options;
  curvenet_surface_options_init(&options);
  EXPECT(options.curves == CURVENET_CURVES_REPAIRED);
  options.scheme = CURVENET_GREGORY_G2;
  EXPECT(curvenet_model_load("builtin:sphere-dodecahedron", &options, &model, &status) == CURVENET_OK);
  curvenet_shape figures;
  EXPECT(curvenet_model_shape(model, &figures, &status) == CURVENET_OK);
  EXPECT(figures.folded_faces == 0 && figures.rejected_faces == 0 && figures.repair_moves == 0);
  EXPECT(figures.max_excursion >= 0 && figures.max_excursion <= figures.excursion_bound);
  EXPECT(fabs(figures.fairness - 2.0) < 0.1);
  int folded = -1;
  double excursion = -1, fairness = -1;
  EXPECT(curvenet_model_face_shape(model, 3, &folded, &excursion, &fairness, &status) == CURVENET_OK);
  EXPECT(folded == 0 && excursion >= 0 && fabs(fairness - 2.0) < 0.1);
  EXPECT(curvenet_model_face_shape(model, 12, NULL, NULL, NULL, &status) == CURVENET_INVALID_ARGUMENT);
  EXPECT(curvenet_model_shape(model, NULL, &status) == CURVENET_INVALID_ARGUMENT);
  curvenet_model_destroy(model);
  options.curves = (curvenet_curves)7;
  EXPECT(curvenet_model_load("builtin:pentagon", &options, &model, &status) == CURVENET_INVALID_ARGUMENT);
}

/* ---- Master surfaces given from outside -------------------------------- */

/* A quarter cylinder (radius 1, axis z; NURBS) is the master of the top arc
 * of a 4-sided face bending in below it (docs/network-format.md's example):
 * the face's normal along the arc is the cylinder's radial normal; a curve
 * that does not lie on its master is refused naming the edge. */
static void externalMasters(void) {
  const double w = 0.70710678118654752440;
  const double arcKnots[6] = {0, 0, 0, 1, 1, 1};
  const double top[9] = {1, 0, 0, 1, 1, 0, 0, 1, 0}, bottom[9] = {0.6, 0, -0.8, 0.6, 0.6, -0.8, 0, 0.6, -0.8};
  const double arcWeights[3] = {1, w, 1};
  const double sideA[12] = {1, 0, 0, 1, 0, -0.25, 1, 0, -0.5, 0.6, 0, -0.8};
  const double sideB[12] = {0, 1, 0, 0, 1, -0.25, 0, 1, -0.5, 0, 0.6, -0.8};
  const curvenet_curve curves[4] = {{2, arcKnots, 6, top, 3, arcWeights},
                                    {3, bezierKnots, 8, sideA, 4, NULL},
                                    {3, bezierKnots, 8, sideB, 4, NULL},
                                    {2, arcKnots, 6, bottom, 3, arcWeights}};
  const curvenet_side sides[4] = {{0, 0, 1}, {2, 0, 1}, {3, 1, 0}, {1, 1, 0}};
  const curvenet_face face = {sides, 4};
  const double linearKnots[4] = {0, 0, 1, 1};
  const double net[18] = {1, 0, 0, 1, 0, 1, 1, 1, 0, 1, 1, 1, 0, 1, 0, 0, 1, 1};
  const double netWeights[6] = {1, 1, w, w, 1, 1};
  const curvenet_master_surface cylinder = {2, 1, arcKnots, 6, linearKnots, 4, net, 3, 2, netWeights};
  curvenet_master_edge edge = {0, 0};
  curvenet_surface_options options;
  curvenet_surface_options_init(&options);
  options.scheme = CURVENET_GREGORY_G2;
  curvenet_status status;
  curvenet_model *model = NULL;
  EXPECT(curvenet_model_build_with_masters(curves, 4, &face, 1, &cylinder, 1, &edge, 1, &options, &model, &status) ==
         CURVENET_OK);
  if (!model) {
    fprintf(stderr, "%s\n", status.message);
    return;
  }
  /* Points of domain side 0 (the arc): normals radial to 1e-8 rad. */
  double c0[2], c1[2], worst = 0;
  EXPECT(curvenet_model_domain_corner(model, 0, 0, c0, &status) == CURVENET_OK);
  EXPECT(curvenet_model_domain_corner(model, 0, 1, c1, &status) == CURVENET_OK);
  for (int k = 1; k < 8; ++k) {
    const double t = k / 8.0, uv[2] = {c0[0] + t * (c1[0] - c0[0]), c0[1] + t * (c1[1] - c0[1])};
    curvenet_point p;
    EXPECT(curvenet_model_evaluate(model, 0, uv, 1, &p, NULL, &status) == CURVENET_OK);
    const double r = sqrt(p.point[0] * p.point[0] + p.point[1] * p.point[1]);
    const double radial[3] = {p.point[0] / r, p.point[1] / r, 0};
    /* |n × radial|: the sine of the angle, accurate for tiny angles. */
    const double cx = p.normal[1] * radial[2] - p.normal[2] * radial[1];
    const double cy = p.normal[2] * radial[0] - p.normal[0] * radial[2];
    const double cz = p.normal[0] * radial[1] - p.normal[1] * radial[0];
    const double angle = sqrt(cx * cx + cy * cy + cz * cz);
    worst = angle > worst ? angle : worst;
  }
  EXPECT(worst < 1e-8);
  curvenet_model_destroy(model);
  /* The bottom arc is not on the cylinder: refused, naming the edge. */
  edge.curve = 3;
  model = NULL;
  EXPECT(curvenet_model_build_with_masters(curves, 4, &face, 1, &cylinder, 1, &edge, 1, &options, &model, &status) ==
         CURVENET_INVALID_INPUT);
  EXPECT(model == NULL && strcmp(status.element, "edges[0]") == 0);
  /* A knot vector one short: the error names the surface. */
  curvenet_master_surface ragged = cylinder;
  ragged.knot_v_count = 3;
  edge.curve = 0;
  EXPECT(curvenet_model_build_with_masters(curves, 4, &face, 1, &ragged, 1, &edge, 1, &options, &model, &status) ==
         CURVENET_INVALID_INPUT);
  EXPECT(strcmp(status.element, "surfaces[0]") == 0);
}

/* ---- end of master surfaces -------------------------------------------- */

/* ---- Network input: holes, reference surface, edge settings ---------- */

/* A square ring around a square hole, the hole filled by a second face, on
 * the paraboloid z = (x² + y²) / 10 given as the reference surface; curve 4
 * (the hole's bottom side) has face `master` as its master. Curves 0–3 run
 * around the outer square, 4–7 around the inner one, both counter-clockwise;
 * each a cubic whose control points lie on the paraboloid. */
static double paraboloid(double x, double y) { return (x * x + y * y) / 10; }

static void ringCurves(double points[8][12], curvenet_curve curves[8]) {
  const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (int k = 0; k < 8; ++k) {
    const double scale = k < 4 ? 2 : 1;
    const double *a = corner[k % 4], *b = corner[(k + 1) % 4];
    for (int i = 0; i < 4; ++i) {
      const double x = scale * (a[0] + (b[0] - a[0]) * i / 3), y = scale * (a[1] + (b[1] - a[1]) * i / 3);
      points[k][3 * i] = x;
      points[k][3 * i + 1] = y;
      points[k][3 * i + 2] = paraboloid(x, y);
    }
    curves[k] = (curvenet_curve){3, bezierKnots, 8, points[k], 4, NULL};
  }
}

static void ringNetwork(curvenet_network *network, curvenet_curve curves[8], curvenet_network_face faces[2],
                        curvenet_loop *hole, curvenet_edge *edge, int master) {
  static const curvenet_side outer[4] = {{0, 0, 1}, {1, 0, 1}, {2, 0, 1}, {3, 0, 1}};
  static const curvenet_side clockwise[4] = {{7, 1, 0}, {6, 1, 0}, {5, 1, 0}, {4, 1, 0}};
  static const curvenet_side inner[4] = {{4, 0, 1}, {5, 0, 1}, {6, 0, 1}, {7, 0, 1}};
  *hole = (curvenet_loop){clockwise, 4};
  faces[0] = (curvenet_network_face){{outer, 4}, hole, 1, "ring"};
  faces[1] = (curvenet_network_face){{inner, 4}, NULL, 0, "cap"};
  *edge = (curvenet_edge){4, master, 0};
  curvenet_network_init(network);
  network->name = "ring";
  network->curves = curves;
  network->curve_count = 8;
  network->faces = faces;
  network->face_count = 2;
  network->edges = edge;
  network->edge_count = 1;
  network->reference = (curvenet_reference){CURVENET_REFERENCE_GRAPH, {0, 0, 0}, {0.1, 0.1, 0}};
}

/* The same network as a native document. */
static int writeRingDocument(const char *path, double points[8][12], int master) {
  FILE *file = fopen(path, "w");
  if (!file) return 0;
  fprintf(file, "{\"format\": \"curvenet-network\", \"version\": 1, \"name\": \"ring\", \"curves\": [");
  for (int k = 0; k < 8; ++k) {
    fprintf(file, "%s{\"degree\": 3, \"knots\": [0, 0, 0, 0, 1, 1, 1, 1], \"points\": [", k ? ", " : "");
    for (int i = 0; i < 4; ++i)
      fprintf(file, "%s[%.17g, %.17g, %.17g]", i ? ", " : "", points[k][3 * i], points[k][3 * i + 1],
              points[k][3 * i + 2]);
    fprintf(file, "]}");
  }
  fprintf(file, "], \"faces\": ["
                "{\"name\": \"ring\", \"sides\": [{\"curve\": 0}, {\"curve\": 1}, {\"curve\": 2}, {\"curve\": 3}],"
                " \"holes\": [[{\"curve\": 7, \"from\": 1, \"to\": 0}, {\"curve\": 6, \"from\": 1, \"to\": 0},"
                " {\"curve\": 5, \"from\": 1, \"to\": 0}, {\"curve\": 4, \"from\": 1, \"to\": 0}]]},"
                " {\"name\": \"cap\", \"sides\": [{\"curve\": 4}, {\"curve\": 5}, {\"curve\": 6}, {\"curve\": 7}]}],"
                " \"edges\": [{\"curve\": 4, \"master\": %d}],"
                " \"reference\": {\"kind\": \"graph\", \"center\": [0, 0, 0], \"size\": [0.1, 0.1, 0]}}\n",
          master);
  return fclose(file) == 0;
}

/* Points of every face of `model` at a few domain points (batched path),
 * into out[face * 40 + k]; returns the face count. */
enum { ringSamples = 40 };
static int sampleFaces(const curvenet_model *model, double *out, int maxFaces) {
  const int faces = curvenet_model_face_count(model);
  double uv[2 * ringSamples];
  for (int k = 0; k < ringSamples; ++k) {
    const double r = 0.8 * (k % 8) / 8, a = 2 * pi * k / ringSamples;
    uv[2 * k] = r * cos(a);
    uv[2 * k + 1] = r * sin(a);
  }
  for (int f = 0; f < faces && f < maxFaces; ++f)
    EXPECT(curvenet_model_evaluate_positions(model, f, uv, ringSamples, out + 3 * ringSamples * f, NULL, NULL) ==
           CURVENET_OK);
  return faces;
}

static void networkWithHoleReferenceAndMaster(void) {
  double points[8][12];
  curvenet_curve curves[8];
  ringCurves(points, curves);
  curvenet_network network;
  curvenet_network_face faces[2];
  curvenet_loop hole;
  curvenet_edge edge;
  curvenet_surface_options options;
  curvenet_surface_options_init(&options);
  options.scheme = CURVENET_GREGORY_G2;
  curvenet_status status;
  enum { maxFaces = 8 };
  static double fromC[maxFaces * 3 * ringSamples], fromFile[maxFaces * 3 * ringSamples];
  const char *path = "capi_test_ring.json";

  for (int master = 0; master < 2; ++master) {
    ringNetwork(&network, curves, faces, &hole, &edge, master);
    curvenet_model *built = NULL, *loaded = NULL;
    EXPECT(curvenet_model_build_network(&network, &options, &built, &status) == CURVENET_OK);
    if (!built) fprintf(stderr, "%s\n", status.message);
    EXPECT(writeRingDocument(path, points, master));
    EXPECT(curvenet_model_load(path, &options, &loaded, &status) == CURVENET_OK);
    if (!loaded) fprintf(stderr, "%s\n", status.message);
    remove(path);
    if (built && loaded) {
      /* The hole splits the ring into four parts; the cap is the fifth face. */
      EXPECT(curvenet_model_face_count(built) == 5 && curvenet_model_face_count(loaded) == 5);
      const int n = sampleFaces(built, fromC, maxFaces);
      EXPECT(sampleFaces(loaded, fromFile, maxFaces) == n);
      EXPECT(memcmp(fromC, fromFile, sizeof(double) * 3 * ringSamples * (size_t)n) == 0);
    }
    curvenet_model_destroy(built);
    curvenet_model_destroy(loaded);
  }

  /* Each setting reaches the surface: without the master edge, or without
   * the reference (onto which the connection curves are projected), the
   * points differ. */
  ringNetwork(&network, curves, faces, &hole, &edge, 1);
  curvenet_model *model = NULL;
  EXPECT(curvenet_model_build_network(&network, &options, &model, &status) == CURVENET_OK);
  if (model) sampleFaces(model, fromC, maxFaces);
  curvenet_model_destroy(model);
  for (int dropped = 0; dropped < 2; ++dropped) {
    ringNetwork(&network, curves, faces, &hole, &edge, 1);
    if (dropped == 0) network.edge_count = 0;
    else network.reference.kind = CURVENET_REFERENCE_NONE;
    model = NULL;
    EXPECT(curvenet_model_build_network(&network, &options, &model, &status) == CURVENET_OK);
    if (model) {
      sampleFaces(model, fromFile, maxFaces);
      EXPECT(memcmp(fromC, fromFile, sizeof(double) * 3 * ringSamples * 5) != 0);
    }
    curvenet_model_destroy(model);
  }

  /* Bad input names its element. */
  ringNetwork(&network, curves, faces, &hole, &edge, 1);
  hole.sides = NULL;
  EXPECT(curvenet_model_build_network(&network, NULL, &model, &status) == CURVENET_INVALID_ARGUMENT);
  EXPECT(model == NULL && strcmp(status.element, "face 0 hole 0") == 0);
  ringNetwork(&network, curves, faces, &hole, &edge, 7);
  EXPECT(curvenet_model_build_network(&network, NULL, &model, &status) == CURVENET_INVALID_INPUT);
  EXPECT(strstr(status.message, "master face 7 does not exist") != NULL);
  ringNetwork(&network, curves, faces, &hole, &edge, 1);
  network.reference = (curvenet_reference){CURVENET_REFERENCE_TORUS, {0, 0, 0}, {1, 2, 0}};
  EXPECT(curvenet_model_build_network(&network, NULL, &model, &status) == CURVENET_INVALID_INPUT);
  EXPECT(strcmp(status.element, "reference") == 0 && strstr(status.message, "tube radius") != NULL);
  network.reference.kind = (curvenet_reference_kind)9;
  EXPECT(curvenet_model_build_network(&network, NULL, &model, &status) == CURVENET_INVALID_ARGUMENT);
  ringNetwork(&network, curves, faces, &hole, &edge, 1);
  network.tolerance = 0;
  EXPECT(curvenet_model_build_network(&network, NULL, &model, &status) == CURVENET_INVALID_INPUT);
  EXPECT(strstr(status.message, "tolerance") != NULL);
  EXPECT(curvenet_model_build_network(NULL, NULL, &model, &status) == CURVENET_INVALID_ARGUMENT);
  EXPECT(strcmp(status.element, "network") == 0);
}

/* ---- End of network input: holes, reference surface, edge settings --- */

int main(void) {
  loopAndEvaluate();
  shape();
  errors();
  twoFaces();
  keptMasters();
  externalMasters();
  networkWithHoleReferenceAndMaster();
  if (failures) fprintf(stderr, "%d check(s) failed\n", failures);
  else printf("all C interface checks passed\n");
  return failures ? 1 : 0;
}
