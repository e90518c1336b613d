// A 5-sided G² patch from five cubic Bézier curves, written as OBJ.
// Usage: pentagon-cpp [OUT.obj] [RESOLUTION]
#include <curvenet/curvenet.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
using namespace curvenet;

int main(int argc, char **argv) {
  std::vector<BSplineCurve> loop; // around the unit pentagon, inner control points raised
  auto corner = [](int i) {
    const double angle = 2 * std::numbers::pi * i / 5;
    return Vec3{std::cos(angle), std::sin(angle), 0};
  };
  for (int k = 0; k < 5; ++k) {
    const Vec3 a = corner(k), b = corner(k + 1), up{0, 0, 0.3};
    loop.push_back(*makeBezier({a, a + (b - a) / 3 + up, b + (a - b) / 3 + up, b}));
  }
  auto model = Model::fromLoop(loop, {.scheme = Scheme::GregoryG2});
  if (!model) return std::fprintf(stderr, "%s\n", model.status().toString().c_str()), 1;
  auto centre = model->evaluate(0, {0, 0}); // face 0 at the centre of its domain polygon
  auto size = model->tessellate({.resolution = argc > 2 ? std::atoi(argv[2]) : 16});
  if (!size) return std::fprintf(stderr, "%s\n", size.status().toString().c_str()), 1;
  if (Status s = model->writeMesh(argc > 1 ? argv[1] : "pentagon.obj"); !s.ok())
    return std::fprintf(stderr, "%s\n", s.toString().c_str()), 1;
  std::printf("centre (%.6f, %.6f, %.6f); %zu vertices, %zu triangles\n", centre->point.x, centre->point.y,
              centre->point.z, size->vertices, size->triangles);
}
