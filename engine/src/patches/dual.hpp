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
    // The value by a true division (as plain doubles give it), the partials
    // through one reciprocal: a division costs as much as a dozen products.
    const double q = a.v / b.v, inverse = 1 / b.v;
    return {q, (a.du - q * b.du) * inverse, (a.dv - q * b.dv) * inverse};
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

namespace curvenet {
inline namespace v1 {

/// Second-order forward mode (hyper-dual numbers) over (u, v): value, first
/// and second partial derivatives. Used by gregory-g2 for exact curvatures.
struct Dual2 {
  double v = 0, du = 0, dv = 0, duu = 0, duv = 0, dvv = 0;

  constexpr Dual2() = default;
  constexpr Dual2(double value) : v(value) {}
  constexpr Dual2(double value, double dU, double dV, double dUU, double dUV, double dVV)
      : v(value), du(dU), dv(dV), duu(dUU), duv(dUV), dvv(dVV) {}
  static constexpr Dual2 u(double value) { return {value, 1, 0, 0, 0, 0}; }
  static constexpr Dual2 vCoord(double value) { return {value, 0, 1, 0, 0, 0}; }
  /// f(x) for a scalar function with value f and derivatives df, ddf at x.
  constexpr Dual2 apply(double f, double df, double ddf) const {
    return {f, df * du, df * dv, ddf * du * du + df * duu, ddf * du * dv + df * duv, ddf * dv * dv + df * dvv};
  }

  friend constexpr Dual2 operator+(Dual2 a, Dual2 b) {
    return {a.v + b.v, a.du + b.du, a.dv + b.dv, a.duu + b.duu, a.duv + b.duv, a.dvv + b.dvv};
  }
  friend constexpr Dual2 operator-(Dual2 a, Dual2 b) {
    return {a.v - b.v, a.du - b.du, a.dv - b.dv, a.duu - b.duu, a.duv - b.duv, a.dvv - b.dvv};
  }
  friend constexpr Dual2 operator-(Dual2 a) { return {-a.v, -a.du, -a.dv, -a.duu, -a.duv, -a.dvv}; }
  friend constexpr Dual2 operator*(Dual2 a, Dual2 b) {
    return {a.v * b.v,
            a.du * b.v + a.v * b.du,
            a.dv * b.v + a.v * b.dv,
            a.duu * b.v + 2 * a.du * b.du + a.v * b.duu,
            a.duv * b.v + a.du * b.dv + a.dv * b.du + a.v * b.duv,
            a.dvv * b.v + 2 * a.dv * b.dv + a.v * b.dvv};
  }
  friend constexpr Dual2 operator/(Dual2 a, Dual2 b) {
    const double r = 1 / b.v;
    return a * b.apply(r, -r * r, 2 * r * r * r);
  }
  constexpr Dual2 &operator+=(Dual2 b) { return *this = *this + b; }
  constexpr Dual2 &operator-=(Dual2 b) { return *this = *this - b; }
  constexpr Dual2 &operator*=(Dual2 b) { return *this = *this * b; }
  bool isZero() const { return v == 0 && du == 0 && dv == 0 && duu == 0 && duv == 0 && dvv == 0; }
};

/// A point or vector with first and second partial derivatives over (u, v).
struct Dual2Vec3 {
  Vec3 v, du, dv, duu, duv, dvv;

  static Dual2Vec3 constant(const Vec3 &c) { return {c, {}, {}, {}, {}, {}}; }
  /// C(x) for a curve with value c and derivatives dc, ddc at the parameter x.
  static Dual2Vec3 along(const Vec3 &c, const Vec3 &dc, const Vec3 &ddc, Dual2 x) {
    return {c, dc * x.du, dc * x.dv, ddc * (x.du * x.du) + dc * x.duu, ddc * (x.du * x.dv) + dc * x.duv,
            ddc * (x.dv * x.dv) + dc * x.dvv};
  }
  friend Dual2Vec3 operator+(const Dual2Vec3 &a, const Dual2Vec3 &b) {
    return {a.v + b.v, a.du + b.du, a.dv + b.dv, a.duu + b.duu, a.duv + b.duv, a.dvv + b.dvv};
  }
  friend Dual2Vec3 operator-(const Dual2Vec3 &a, const Dual2Vec3 &b) {
    return {a.v - b.v, a.du - b.du, a.dv - b.dv, a.duu - b.duu, a.duv - b.duv, a.dvv - b.dvv};
  }
  friend Dual2Vec3 operator*(Dual2 s, const Dual2Vec3 &a) {
    return {a.v * s.v,
            a.du * s.v + a.v * s.du,
            a.dv * s.v + a.v * s.dv,
            a.duu * s.v + a.du * (2 * s.du) + a.v * s.duu,
            a.duv * s.v + a.du * s.dv + a.dv * s.du + a.v * s.duv,
            a.dvv * s.v + a.dv * (2 * s.dv) + a.v * s.dvv};
  }
  Dual2Vec3 &operator+=(const Dual2Vec3 &b) { return *this = *this + b; }
  Dual2Vec3 &operator-=(const Dual2Vec3 &b) { return *this = *this - b; }
};

inline Dual2Vec3 operator*(Dual2 s, const Vec3 &c) {
  return {c * s.v, c * s.du, c * s.dv, c * s.duu, c * s.duv, c * s.dvv};
}

} // namespace v1
} // namespace curvenet
