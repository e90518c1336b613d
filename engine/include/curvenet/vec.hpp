// curvenet/vec.hpp — small value types for points and vectors.
//
// Vec3 is the engine's point/vector type in model space; Vec2 is a point of a
// patch's 2D parameter domain. Both are trivially copyable aggregates of
// doubles, laid out as {x, y[, z]}, so arrays of them can be handed to other
// libraries as packed doubles. All functions are pure and thread-safe.
#pragma once

#include <cmath>

namespace curvenet {
inline namespace v1 {

struct Vec3 {
  double x = 0, y = 0, z = 0;

  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3 &operator+=(const Vec3 &o) { x += o.x; y += o.y; z += o.z; return *this; }
  constexpr Vec3 &operator-=(const Vec3 &o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
  constexpr Vec3 &operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
  constexpr Vec3 &operator/=(double s) { x /= s; y /= s; z /= s; return *this; }
  friend constexpr Vec3 operator+(Vec3 a, const Vec3 &b) { return a += b; }
  friend constexpr Vec3 operator-(Vec3 a, const Vec3 &b) { return a -= b; }
  friend constexpr Vec3 operator-(const Vec3 &a) { return {-a.x, -a.y, -a.z}; }
  friend constexpr Vec3 operator*(Vec3 a, double s) { return a *= s; }
  friend constexpr Vec3 operator*(double s, Vec3 a) { return a *= s; }
  friend constexpr Vec3 operator/(Vec3 a, double s) { return a /= s; }
  friend constexpr bool operator==(const Vec3 &, const Vec3 &) = default;
};

constexpr double dot(const Vec3 &a, const Vec3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3 &a, const Vec3 &b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const Vec3 &a) { return std::sqrt(dot(a, a)); }
constexpr double squaredNorm(const Vec3 &a) { return dot(a, a); }
/// Unit vector along a; the zero vector stays zero (never NaN).
inline Vec3 normalized(const Vec3 &a) {
  double n = norm(a);
  return n > 0 ? a / n : Vec3{};
}
inline bool isFinite(const Vec3 &a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
/// Angle in radians between two non-zero vectors, accurate for tiny angles.
inline double angleBetween(const Vec3 &a, const Vec3 &b) { return std::atan2(norm(cross(a, b)), dot(a, b)); }

struct Vec2 {
  double x = 0, y = 0;

  constexpr Vec2 &operator+=(const Vec2 &o) { x += o.x; y += o.y; return *this; }
  constexpr Vec2 &operator-=(const Vec2 &o) { x -= o.x; y -= o.y; return *this; }
  constexpr Vec2 &operator*=(double s) { x *= s; y *= s; return *this; }
  friend constexpr Vec2 operator+(Vec2 a, const Vec2 &b) { return a += b; }
  friend constexpr Vec2 operator-(Vec2 a, const Vec2 &b) { return a -= b; }
  friend constexpr Vec2 operator-(const Vec2 &a) { return {-a.x, -a.y}; }
  friend constexpr Vec2 operator*(Vec2 a, double s) { return a *= s; }
  friend constexpr Vec2 operator*(double s, Vec2 a) { return a *= s; }
  friend constexpr Vec2 operator/(Vec2 a, double s) { return {a.x / s, a.y / s}; }
  friend constexpr bool operator==(const Vec2 &, const Vec2 &) = default;
};

constexpr double dot(const Vec2 &a, const Vec2 &b) { return a.x * b.x + a.y * b.y; }
/// z component of the 3D cross product: twice the signed area of (0, a, b).
constexpr double cross(const Vec2 &a, const Vec2 &b) { return a.x * b.y - a.y * b.x; }
inline double norm(const Vec2 &a) { return std::sqrt(dot(a, a)); }

/// Axis-aligned bounding box; empty until the first point is added.
struct BoundingBox {
  Vec3 min{INFINITY, INFINITY, INFINITY};
  Vec3 max{-INFINITY, -INFINITY, -INFINITY};

  void add(const Vec3 &p) {
    min = {std::fmin(min.x, p.x), std::fmin(min.y, p.y), std::fmin(min.z, p.z)};
    max = {std::fmax(max.x, p.x), std::fmax(max.y, p.y), std::fmax(max.z, p.z)};
  }
  bool empty() const { return !(min.x <= max.x); }
  /// Whether this box and `other` share a point (touching counts; an empty
  /// box meets none).
  bool meets(const BoundingBox &other) const {
    return min.x <= other.max.x && other.min.x <= max.x && min.y <= other.max.y && other.min.y <= max.y &&
           min.z <= other.max.z && other.min.z <= max.z;
  }
  /// The points of both boxes (empty where they do not meet).
  BoundingBox intersection(const BoundingBox &other) const {
    BoundingBox both;
    both.min = {std::fmax(min.x, other.min.x), std::fmax(min.y, other.min.y), std::fmax(min.z, other.min.z)};
    both.max = {std::fmin(max.x, other.max.x), std::fmin(max.y, other.max.y), std::fmin(max.z, other.max.z)};
    return both;
  }
  /// Length of the diagonal: the model scale every relative figure refers to.
  double diagonal() const { return empty() ? 0.0 : norm(max - min); }
  Vec3 center() const { return (min + max) * 0.5; }
};

} // namespace v1
} // namespace curvenet
