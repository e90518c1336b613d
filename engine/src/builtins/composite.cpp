// Built-ins for connection curves ([SV14] Sec. 5.2, Fig. 9): loops that no
// single n-sided patch spans well, on the elliptic bowl z = 0.25 x² + 0.15 y².
//
//  concave-L: one 6-sided L-shaped loop with a concave corner at (0, 0)
//
//      (-1,1)──(0,1)
//        │       │
//        │     (0,0)────(1,0)
//        │                │
//      (-1,-1)─────────(1,-1)
//
//  ring: the square [−1, 1]² with a circular hole of radius 0.45, its four
//  quarter arcs meeting at the diagonals (so each hole corner faces an outer
//  corner); the hole is written clockwise, as holes usually are.
//
//  uneven-loop (Fig. 9): a loop of n sides (built-in: 10) inscribed in the
//  unit circle, n − 2 of its corners crowded on 100° of the turn (n − 3
//  short sides), the other two leaving three long sides of 260°/3; the
//  regular domain stretches its long sides 5.5 times as much as its short
//  ones (3.95 for n = 8).
//
//  many-sided: a loop of n sides (built-in: 12) inscribed in the ellipse
//  with half-axes 1.2 and 1, corners at equal steps of the ellipse's angle
//  parameter.
//
// Curves are lifts (x(t), y(t), z(x, y)) of lines and circle arcs, fitted
// like every built-in; the bowl is the reference surface. Network::build
// inserts the connection curves; no vertex facts are listed because the
// vertices the connection curves end on are the builder's, not the
// construction's.
#include <array>
#include <cmath>
#include <numbers>

#include "builtins/builtin_support.hpp"

namespace curvenet {
inline namespace v1 {
namespace builtin_detail {

namespace {

constexpr double kBowlX = 0.25, kBowlY = 0.15;

Vec3 lift(double x, double y) { return {x, y, kBowlX * x * x + kBowlY * y * y}; }

struct Bowl {
  NetworkDescription &net;
  int line(double x0, double y0, double x1, double y1) {
    auto exact = [=](double t) { return lift(x0 + t * (x1 - x0), y0 + t * (y1 - y0)); };
    net.curves.push_back(fitSurfaceCurve(exact, 0, 1, 16, exact(0), exact(1)));
    return static_cast<int>(net.curves.size()) - 1;
  }
  int arc(double radius, double a0, double a1) {
    auto exact = [=](double t) {
      const double a = a0 + t * (a1 - a0);
      return lift(radius * std::cos(a), radius * std::sin(a));
    };
    const BSplineCurve fit = fitSurfaceCurve(exact, 0, 1, 24, exact(0), exact(1));
    // The four arcs meet smoothly: their end tangents are set to the exact
    // circle tangent (a change of ~1e-8 of the diagonal), so that two arcs
    // meeting at a corner of the hole continue each other exactly instead of
    // to the fit accuracy, which would tilt the vertex plane there.
    auto direction = [&](double a) {
      const double x = radius * std::cos(a), y = radius * std::sin(a);
      return normalized(Vec3{-y, x, 2 * kBowlX * x * -y + 2 * kBowlY * y * x} * (a1 > a0 ? 1.0 : -1.0));
    };
    std::vector<Vec3> control = fit.controlPoints();
    const size_t last = control.size() - 1;
    control[1] = control[0] + direction(a0) * norm(control[1] - control[0]);
    control[last - 1] = control[last] - direction(a1) * norm(control[last] - control[last - 1]);
    net.curves.push_back(BSplineCurve(fit.degree(), fit.knots(), std::move(control)));
    return static_cast<int>(net.curves.size()) - 1;
  }
};

NetworkDescription bowlNetwork(const std::string &name) {
  NetworkDescription net;
  net.name = name;
  net.reference = ReferenceSurface{ReferenceSurface::Kind::Graph, Vec3{}, Vec3{kBowlX, kBowlY, 0}, nullptr};
  return net;
}

} // namespace

namespace {

/// One face bounded by the lifted straight lines between consecutive plan
/// corners (x, y).
BuiltinData planPolygon(const std::string &name, const std::string &faceName,
                        const std::vector<std::array<double, 2>> &corners) {
  BuiltinData data;
  data.network = bowlNetwork(name);
  Bowl bowl{data.network};
  FaceDescription face;
  face.name = faceName;
  const size_t n = corners.size();
  for (size_t k = 0; k < n; ++k) {
    const auto &[x0, y0] = corners[k];
    const auto &[x1, y1] = corners[(k + 1) % n];
    face.sides.push_back({bowl.line(x0, y0, x1, y1), 0.0, 1.0});
  }
  data.network.faces.push_back(face);
  return data;
}

} // namespace

BuiltinData unevenLoop(int sides) {
  std::vector<std::array<double, 2>> corners;
  auto cornerAt = [&](double degrees) {
    const double a = degrees * std::numbers::pi / 180;
    corners.push_back({std::cos(a), std::sin(a)});
  };
  const int crowded = sides - 3; // short sides, over 100°
  for (int k = 0; k <= crowded; ++k) cornerAt(40 + k * 100.0 / crowded);
  for (int k = 1; k <= 2; ++k) cornerAt(140 + k * 260.0 / 3);
  return planPolygon("uneven-loop", "uneven", corners);
}

BuiltinData manySidedLoop(int sides) {
  std::vector<std::array<double, 2>> corners;
  for (int k = 0; k < sides; ++k) {
    const double a = 2 * std::numbers::pi * k / sides;
    corners.push_back({1.2 * std::cos(a), std::sin(a)});
  }
  return planPolygon("many-sided", std::to_string(sides) + "-sided", corners);
}

BuiltinData concaveL() {
  BuiltinData data;
  data.network = bowlNetwork("concave-L");
  Bowl bowl{data.network};
  const double corners[6][2] = {{-1, -1}, {1, -1}, {1, 0}, {0, 0}, {0, 1}, {-1, 1}};
  FaceDescription face;
  face.name = "L";
  for (int k = 0; k < 6; ++k)
    face.sides.push_back({bowl.line(corners[k][0], corners[k][1], corners[(k + 1) % 6][0], corners[(k + 1) % 6][1]),
                          0.0, 1.0});
  data.network.faces.push_back(face);
  return data;
}

BuiltinData ring(int holeSides) {
  BuiltinData data;
  data.network = bowlNetwork("ring");
  Bowl bowl{data.network};
  const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  FaceDescription face;
  face.name = "ring";
  for (int k = 0; k < 4; ++k)
    face.sides.push_back({bowl.line(corners[k][0], corners[k][1], corners[(k + 1) % 4][0], corners[(k + 1) % 4][1]),
                          0.0, 1.0});
  // Clockwise arcs from 225° down to −135° (quarter arcs for the built-in).
  std::vector<SideDescription> hole;
  const double span = 2 * std::numbers::pi / holeSides;
  for (int k = 0; k < holeSides; ++k) {
    const double a0 = 1.25 * std::numbers::pi - k * span;
    hole.push_back({bowl.arc(0.45, a0, a0 - span), 0.0, 1.0});
  }
  face.holes.push_back(hole);
  data.network.faces.push_back(face);
  return data;
}

} // namespace builtin_detail
} // namespace v1
} // namespace curvenet
