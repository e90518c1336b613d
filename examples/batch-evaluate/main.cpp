// Evaluates random domain points of a G² patch in one batch and prints the
// rate: positions alone (Model::evaluatePositions, the batched path), then
// full surface points with derivatives and normals (Model::evaluate).
// Usage: batch-evaluate [POINTS] [INPUT] (defaults: 1000000, builtin:pentagon)
#include <curvenet/curvenet.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <span>
#include <string>
#include <thread>
#include <vector>

int main(int argc, char **argv) {
  const std::size_t count = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const std::string input = argc > 2 ? argv[2] : "builtin:pentagon";

  curvenet::SurfaceOptions options;
  options.scheme = curvenet::Scheme::GregoryG2;
  auto model = curvenet::Model::load(input, options);
  if (!model) return std::fprintf(stderr, "%s\n", model.status().toString().c_str()), 1;

  // Uniform points of face 0's domain polygon: random points of triangles
  // (centre, corner k, corner k + 1) of its n congruent fan triangles.
  const int n = model->domainSides(0);
  std::vector<curvenet::Vec2> corners;
  for (int k = 0; k <= n; ++k) corners.push_back(*model->domainCorner(0, k));
  std::mt19937_64 random(1);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<curvenet::Vec2> uv(count);
  for (auto &p : uv) {
    const int k = static_cast<int>(unit(random) * n) % n;
    double a = unit(random), b = unit(random);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    p = corners[k] * a + corners[k + 1] * b;
  }
  std::vector<curvenet::Vec3> positions(count);
  std::vector<curvenet::SurfacePoint> points(count);
  // The first call on a face builds its ribbon tables: not part of the rate.
  (void)model->evaluatePositions(0, std::span(uv).first(1), std::span(positions).first(1), {.threads = 1});

  // Serial (one core), then the automatic policy (all cores). Positions:
  // the fastest of three runs, as rates on a shared machine are best
  // measured; full points (seconds per million) once.
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  for (bool full : {false, true})
    for (int threads : {1, 0}) {
      double seconds = 1e300;
      const int runs = full ? 1 : 3;
      for (int run = 0; run < runs; ++run) {
        const auto start = std::chrono::steady_clock::now();
        const auto status = full ? model->evaluate(0, uv, points, {.threads = threads})
                                 : model->evaluatePositions(0, uv, positions, {.threads = threads});
        seconds = std::min(seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        if (!status.ok()) return std::fprintf(stderr, "%s\n", status.toString().c_str()), 1;
      }
      const unsigned used = threads == 1 ? 1 : cores;
      std::printf("%s gregory-g2, face 0 (%d sides), %zu %s, %u thread%s: %.3f s%s, %.3g points/s (%.3g per core)\n",
                  input.c_str(), n, count, full ? "points with derivatives and normals" : "positions", used,
                  used == 1 ? "" : "s", seconds, runs > 1 ? " (fastest of 3)" : "", count / seconds,
                  count / seconds / used);
    }
  return 0;
}
