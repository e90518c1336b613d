// Normals sampled along a curve (curvenet/network.hpp, CurveNormals).
#include <algorithm>

#include "curvenet/network.hpp"

namespace curvenet {
inline namespace v1 {

Vec3 CurveNormals::at(double t) const {
  const int n = static_cast<int>(parameters.size());
  if (n == 0) return {0, 0, 0};
  if (n == 1 || t <= parameters.front()) return normalized(normals.front());
  if (t >= parameters.back()) return normalized(normals.back());
  // The interval [parameters[i], parameters[i + 1]] holding t.
  const int i = static_cast<int>(std::upper_bound(parameters.begin(), parameters.end(), t) - parameters.begin()) - 1;
  if (n < 4) {
    const double x = (t - parameters[i]) / (parameters[i + 1] - parameters[i]);
    return normalized(normals[i] * (1 - x) + normals[i + 1] * x);
  }
  // Lagrange cubic through the four nearest samples (shifted inside at the
  // ends): local, so a sample moves the normal near it only, and exact to
  // O(h⁴) on a smooth field.
  const int first = std::clamp(i - 1, 0, n - 4);
  Vec3 sum{0, 0, 0};
  for (int a = first; a < first + 4; ++a) {
    double weight = 1;
    for (int b = first; b < first + 4; ++b)
      if (b != a) weight *= (t - parameters[b]) / (parameters[a] - parameters[b]);
    sum += normals[a] * weight;
  }
  return normalized(sum);
}

} // namespace v1
} // namespace curvenet
