/* A C program that knows curvenet only through pkg-config: built with
 * `cc main.c $(pkg-config --cflags --libs curvenet)` and nothing else, it
 * loads a built-in, evaluates it and tessellates it through the shared
 * library, and checks what the C interface promises. Exit status 0 when
 * every check holds. */
#include <curvenet/curvenet.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int fail(const char *what, const curvenet_status *status) {
  fprintf(stderr, "%s: %s\n", what, status ? status->message : "");
  return 1;
}

int main(void) {
  curvenet_status status;
  curvenet_model *model = NULL;
  if (curvenet_model_load("builtin:pentagon", NULL, &model, &status) != CURVENET_OK) return fail("load", &status);
  if (curvenet_model_face_count(model) != 1 || curvenet_model_domain_sides(model, 0) != 5)
    return fail("builtin:pentagon is not one 5-sided face", NULL);

  /* A domain corner evaluates to a network vertex: the point of corner 0
   * and the start of the tessellation agree in being finite and distinct
   * from the centre. */
  double uv[4] = {0, 0, 0, 0};
  if (curvenet_model_domain_corner(model, 0, 0, uv + 2, &status) != CURVENET_OK) return fail("corner", &status);
  double xyz[6];
  if (curvenet_model_evaluate_positions(model, 0, uv, 2, xyz, NULL, &status) != CURVENET_OK)
    return fail("evaluate_positions", &status);
  if (xyz[0] == xyz[3] && xyz[1] == xyz[4] && xyz[2] == xyz[5]) return fail("centre equals corner", NULL);

  /* A point far outside the domain: NaN and OUT_OF_DOMAIN naming it. */
  const double outside[2] = {5, 5};
  if (curvenet_model_evaluate_positions(model, 0, outside, 1, xyz, NULL, &status) != CURVENET_OUT_OF_DOMAIN ||
      xyz[0] == xyz[0] || strstr(status.element, "point 0") == NULL)
    return fail("an outside point is not reported", &status);

  /* The tessellation contract for one 5-sided face at resolution r: 5 r² triangles. */
  const int r = 8;
  size_t vertices = 0, triangles = 0;
  if (curvenet_model_tessellate(model, CURVENET_ALL_FACES, r, 1, &vertices, &triangles, &status) != CURVENET_OK)
    return fail("tessellate", &status);
  if (triangles != (size_t)(5 * r * r)) return fail("unexpected triangle count", NULL);
  double *positions = malloc(3 * vertices * sizeof *positions);
  uint32_t *indices = malloc(3 * triangles * sizeof *indices);
  if (curvenet_model_copy_mesh(model, positions, vertices, NULL, 0, indices, triangles, &status) != CURVENET_OK)
    return fail("copy_mesh", &status);
  for (size_t k = 0; k < 3 * triangles; ++k)
    if (indices[k] >= vertices) return fail("triangle index out of range", NULL);
  free(positions);
  free(indices);
  curvenet_model_destroy(model);
  printf("curvenet %s through pkg-config: %zu vertices, %zu triangles\n", curvenet_version(), vertices, triangles);
  return 0;
}
