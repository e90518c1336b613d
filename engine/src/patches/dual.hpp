// Forward-mode derivatives over the 2D domain: a Dual carries a value and
// its partial derivatives with respect to the domain coordinates (u, v).
// Patch formulas are written once over Dual, so every evaluation returns the
// exact first derivatives S_u, S_v alongside the point (no differencing).
#pragma once

#include <cmath>

#include "curvenet/vec.hpp"

namespace curvenet {
inline namespace v1 {

struct Dual {
  double v = 0, du = 0, dv = 0;

  constexpr Dual() = default;
  constexpr Dual(double value) : v(value) {}
  constexpr Dual(double value, double dU, double dV) : v(value), du(dU), dv(dV) {}
  /// The coordinate functions u and v themselves.
  static constexpr Dual u(double value) { return {value, 1, 0}; }
  static constexpr Dual vCoord(double value) { return {value, 0, 1}; }
  /// f(x) for a scalar function with value f and derivative df at x.
  constexpr Dual apply(double f, double df) const { return {f, df * du, df * dv}; }

  friend constexpr Dual operator+(Dual a, Dual b) { return {a.v + b.v, a.du + b.du, a.dv + b.dv}; }
  friend constexpr Dual operator-(Dual a, Dual b) { return {a.v - b.v, a.du - b.du, a.dv - b.dv}; }
  friend constexpr Dual operator-(Dual a) { return {-a.v, -a.du, -a.dv}; }
  friend constexpr Dual operator*(Dual a, Dual b) { return {a.v * b.v, a.du * b.v + a.v * b.du, a.dv * b.v + a.v * b.dv}; }
  friend constexpr Dual operator/(Dual a, Dual b) {
    const double q = a.v / b.v;
    return {q, (a.du - q * b.du) / b.v, (a.dv - q * b.dv) / b.v};
  }
  constexpr Dual &operator+=(Dual b) { return *this = *this + b; }
  constexpr Dual &operator-=(Dual b) { return *this = *this - b; }
  constexpr Dual &operator*=(Dual b) { return *this = *this * b; }
  bool isZero() const { return v == 0 && du == 0 && dv == 0; }
};

inline Dual pow(Dual a, int m) {
  Dual r = 1.0;
  for (int k = 0; k < m; ++k) r *= a;
  return r;
}

/// A point or vector with its derivatives: value, ∂/∂u, ∂/∂v.
struct DualVec3 {
  Vec3 v, du, dv;

  static DualVec3 constant(const Vec3 &c) { return {c, {}, {}}; }
  /// C(x) for a curve with value c and derivative dc at the Dual parameter x.
  static DualVec3 along(const Vec3 &c, const Vec3 &dc, Dual x) { return {c, dc * x.du, dc * x.dv}; }

  friend DualVec3 operator+(const DualVec3 &a, const DualVec3 &b) { return {a.v + b.v, a.du + b.du, a.dv + b.dv}; }
  friend DualVec3 operator-(const DualVec3 &a, const DualVec3 &b) { return {a.v - b.v, a.du - b.du, a.dv - b.dv}; }
  friend DualVec3 operator*(Dual s, const DualVec3 &a) {
    return {a.v * s.v, a.du * s.v + a.v * s.du, a.dv * s.v + a.v * s.dv};
  }
  friend DualVec3 operator*(const DualVec3 &a, Dual s) { return s * a; }
  DualVec3 &operator+=(const DualVec3 &b) { return *this = *this + b; }
  DualVec3 &operator-=(const DualVec3 &b) { return *this = *this - b; }
};

inline DualVec3 operator*(Dual s, const Vec3 &c) { return {c * s.v, c * s.du, c * s.dv}; }

} // namespace v1
} // namespace curvenet
