// The polar grid around a domain corner on which folds closer to the corner
// than the fold grid's first row are found (docs/surfaces.md, Corner folds).
// The surface build uses it to choose each corner's blend, the shape report
// to name the corners that fold all the same; both with this one grid and
// test, so that what the build avoided is what the report would have named.
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include "curvenet/vec.hpp"

namespace curvenet {
inline namespace v1 {

/// Samples c + ρ ((1 − α) (c₋ − c) + α (c₊ − c)) towards the two
/// neighbouring corners c₋, c₊: ρ from 2e-4 to 0.2 in steps of about √3
/// (rings), α across the corner's wedge (rays); ring-major.
struct CornerGrid {
  static constexpr std::array<double, 13> kRadii = {2e-4, 3.5e-4, 6e-4, 1e-3, 2e-3, 3.5e-3, 6e-3,
                                                    1e-2, 2e-2,   3.5e-2, 6e-2, 0.1,  0.2};
  static constexpr int kRings = static_cast<int>(kRadii.size()), kRays = 9;
  static constexpr std::size_t kSize = static_cast<std::size_t>(kRings * kRays);

  static constexpr std::size_t index(int ring, int ray) { return static_cast<std::size_t>(ring * kRays + ray); }

  /// The sample on `ring` and `ray` of the corner at `corner` whose
  /// neighbouring corners are `previous` and `next`.
  static Vec2 point(const Vec2 &corner, const Vec2 &previous, const Vec2 &next, int ring, int ray) {
    const double alpha = (ray + 0.5) / kRays;
    return corner + ((previous - corner) * (1 - alpha) + (next - corner) * alpha) * kRadii[ring];
  }

  /// True when two neighbouring samples (in ρ or in α) have normals in
  /// opposite half-spaces: the fold grid's test (a smooth surface does not
  /// turn its normal by 90° between samples this close unless it folds).
  /// `normals` in grid order, unit or not.
  static bool folds(std::span<const Vec3> normals) {
    for (int i = 0; i < kRings; ++i)
      for (int j = 0; j < kRays; ++j) {
        const Vec3 &here = normals[index(i, j)];
        if (j + 1 < kRays && dot(here, normals[index(i, j + 1)]) <= 0) return true;
        if (i + 1 < kRings && dot(here, normals[index(i + 1, j)]) <= 0) return true;
      }
    return false;
  }
};

} // namespace v1
} // namespace curvenet
