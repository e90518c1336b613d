// Tensor-product Bézier patches of degree 5 × 5 ([OSK11]) and the Bernstein
// helpers the G¹ construction needs (products, degree elevation, subdivision).
#pragma once

#include <array>
#include <vector>

#include "curvenet/vec.hpp"

namespace curvenet {
inline namespace v1 {
namespace bezier {

/// Binomial coefficient C(n, k) for the small degrees used here (n ≤ 12).
double binomial(int n, int k);

/// Bernstein polynomials B_i^n(t), i = 0..n, and their derivatives.
void bernstein(int n, double t, double *values, double *derivatives = nullptr);

/// A quintic × quintic patch; net[i][j] with i along u, j along v. Side 0 is
/// v = 0 (u: 0 → 1), side 1 is u = 1 (v: 0 → 1), side 2 is v = 1 (u: 1 → 0),
/// side 3 is u = 0 (v: 1 → 0): the loop order of a 4-sided face.
struct QuinticPatch {
  std::array<std::array<Vec3, 6>, 6> net{};

  struct Point {
    Vec3 point, du, dv;
  };
  /// Point and exact first derivatives at (u, v) ∈ [0, 1]².
  Point evaluate(double u, double v) const;

  /// Grid index (i, j) of the control point at position `along` (0..5, in the
  /// side's loop direction) and `depth` (0 = on the side, 1 = first inner row)
  /// for side k.
  static std::array<int, 2> sideIndex(int side, int along, int depth);
  Vec3 &at(int side, int along, int depth) {
    auto [i, j] = sideIndex(side, along, depth);
    return net[i][j];
  }
  const Vec3 &at(int side, int along, int depth) const {
    auto [i, j] = sideIndex(side, along, depth);
    return net[i][j];
  }
};

/// Degree elevation of a Bézier control polygon by one.
std::vector<Vec3> elevate(const std::vector<Vec3> &points);

/// Matrix R (n+1)×(n+1) with row m the weights of control point m of the
/// piece on [a, b] of a degree-n Bézier curve: piece_m = Σ_k R[m][k] P_k.
std::vector<std::vector<double>> restrictionMatrix(int n, double a, double b);

/// The bilinearly blended Coons patch of four quintic boundaries given as a
/// net whose boundary rows are set: fills the interior (exact for degree ≤ 5).
void fillCoonsInterior(QuinticPatch &patch);

} // namespace bezier
} // namespace v1
} // namespace curvenet
