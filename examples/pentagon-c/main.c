/* A 5-sided patch from five curves, written as OBJ: the C interface.
 * Usage: pentagon-c [OUT.obj] [RESOLUTION]
 * The mesh goes through caller-owned buffers (size query first), and the
 * program writes the OBJ itself, as an embedder feeding its own renderer would. */
#include <curvenet/curvenet.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int failed(const char *what, const curvenet_status *status) {
  fprintf(stderr, "%s: %s (%s)\n", what, status->message, curvenet_status_code_name(status->code));
  return 1;
}

int main(int argc, char **argv) {
  const char *out = argc > 1 ? argv[1] : "pentagon.obj";
  const int resolution = argc > 2 ? atoi(argv[2]) : 16;
  const double pi = 3.14159265358979323846;

  /* Five cubic Bézier curves around a regular pentagon, inner control
   * points raised by 0.3: 4 points (12 doubles) and 8 knots each. */
  static const double knots[8] = {0, 0, 0, 0, 1, 1, 1, 1};
  double points[5][12];
  curvenet_curve curves[5];
  for (int k = 0; k < 5; ++k) {
    const double a[3] = {cos(2 * pi * k / 5), sin(2 * pi * k / 5), 0};
    const double b[3] = {cos(2 * pi * (k + 1) / 5), sin(2 * pi * (k + 1) / 5), 0};
    for (int i = 0; i < 3; ++i) {
      points[k][i] = a[i];
      points[k][3 + i] = a[i] + (b[i] - a[i]) / 3 + (i == 2 ? 0.3 : 0);
      points[k][6 + i] = b[i] + (a[i] - b[i]) / 3 + (i == 2 ? 0.3 : 0);
      points[k][9 + i] = b[i];
    }
    curves[k] = (curvenet_curve){3, knots, 8, points[k], 4, NULL};
  }

  curvenet_surface_options options;
  curvenet_surface_options_init(&options);
  options.scheme = CURVENET_GREGORY_G2;
  curvenet_status status;
  curvenet_model *model = NULL;
  if (curvenet_model_from_loop(curves, 5, &options, &model, &status) != CURVENET_OK)
    return failed("build", &status);

  /* The centre of the domain polygon. */
  const double centre_uv[2] = {0, 0};
  curvenet_point centre;
  if (curvenet_model_evaluate(model, 0, centre_uv, 1, &centre, NULL, &status) != CURVENET_OK)
    return failed("evaluate", &status);

  /* Size query, then the caller's buffers. */
  size_t vertices = 0, triangles = 0;
  if (curvenet_model_tessellate(model, CURVENET_ALL_FACES, resolution, 0, &vertices, &triangles, &status) !=
      CURVENET_OK)
    return failed("tessellate", &status);
  double *positions = malloc(3 * vertices * sizeof(double));
  double *normals = malloc(3 * vertices * sizeof(double));
  uint32_t *indices = malloc(3 * triangles * sizeof(uint32_t));
  if (!positions || !normals || !indices) return fprintf(stderr, "out of memory\n"), 1;
  if (curvenet_model_copy_mesh(model, positions, vertices, normals, vertices, indices, triangles, &status) !=
      CURVENET_OK)
    return failed("copy mesh", &status);

  FILE *file = fopen(out, "w");
  if (!file) return fprintf(stderr, "cannot write %s\n", out), 1;
  for (size_t v = 0; v < vertices; ++v)
    fprintf(file, "v %.17g %.17g %.17g\n", positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
  for (size_t v = 0; v < vertices; ++v)
    fprintf(file, "vn %.17g %.17g %.17g\n", normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
  for (size_t t = 0; t < triangles; ++t) /* OBJ counts from 1 */
    fprintf(file, "f %u//%u %u//%u %u//%u\n", indices[3 * t] + 1, indices[3 * t] + 1, indices[3 * t + 1] + 1,
            indices[3 * t + 1] + 1, indices[3 * t + 2] + 1, indices[3 * t + 2] + 1);
  if (fclose(file) != 0) return fprintf(stderr, "cannot write %s\n", out), 1;

  printf("centre (%.6f, %.6f, %.6f); %zu vertices, %zu triangles\n", centre.point[0], centre.point[1],
         centre.point[2], vertices, triangles);
  free(positions);
  free(normals);
  free(indices);
  curvenet_model_destroy(model);
  return 0;
}
