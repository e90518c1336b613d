// Built-in `setback-vertex-blend` ([SV14] Sec. 5.1, Fig. 8): the corner of
// a box, x, y, z ≤ 0, whose three edges are rounded by cylindrical fillets of
// different radii; the fillets stop short of the corner (the setbacks) and a
// 6-sided vertex blend fills the gap. The three fillets are the masters, the
// blend is the slave: its three arc edges name the fillet as master face, so
// gregory-g2 gives the blend each fillet's cross curvature.
//
// Fillet a runs along axis a (a, b, c a cyclic permutation of x, y, z) in the
// edge between the planes p_b = 0 and p_c = 0, radius r_a:
//   F_a(t, θ) = t e_a − r_a e_b − r_a e_c + r_a (cos θ e_b + sin θ e_c),
// θ ∈ [0, π/2] (θ = 0 touches plane b, θ = π/2 plane c), t ∈ [−L, −s_a],
// with outward normal cos θ e_b + sin θ e_c. Its end arc at t = −s_a is a
// side of the blend. Between two fillets, in the plane they both touch, a
// setback curve joins the end of one fillet's boundary line to the end of
// the other's, continuing both lines tangentially (a T-node at each end: the
// line passes straight into the setback curve, the arc ends there), so the
// blend's corners are right angles.
//
//   faces 0–2  fillet along x, y, z (4 sides: line, far arc, line, end arc)
//   face  3    the vertex blend (6 sides: end arc, setback curve, … )
//
// Arcs are exact (rational quadratic), lines and setback curves cubic
// Béziers; the setback curves are planar quarter-ellipse-like cubics. There
// is no reference surface: only the fillets are analytic, the blend is what
// the network defines. Every segment of an arc is a master edge; all other
// edges are boundary.
#include <array>
#include <cmath>
#include <numbers>

#include "builtins/builtin_support.hpp"

namespace curvenet {
inline namespace v1 {
namespace builtin_detail {

namespace {

constexpr std::array<double, 3> kRadius = {0.30, 0.22, 0.38}; // r_x, r_y, r_z
constexpr std::array<double, 3> kSetback = {0.72, 0.66, 0.80}; // s_x, s_y, s_z
constexpr double kLength = 1.6;                                  // fillets end at t = −L
// Bézier handle of the setback curves as a fraction of the corner offsets
// (4(√2 − 1)/3 would make a circular quarter).
constexpr double kHandle = 0.5523;

Vec3 axis(int a) {
  Vec3 e;
  (a == 0 ? e.x : a == 1 ? e.y : e.z) = 1;
  return e;
}

/// Cubic Bézier with equally spaced control points: a line at uniform speed.
BSplineCurve line(const Vec3 &p, const Vec3 &q) { return BSplineCurve::bezier({p, p + (q - p) / 3, p + (q - p) * (2.0 / 3), q}); }

Vec3 filletPoint(int a, double t, double theta) {
  const Vec3 ea = axis(a), eb = axis((a + 1) % 3), ec = axis((a + 2) % 3);
  const double r = kRadius[size_t(a)];
  return ea * t - eb * r - ec * r + (eb * std::cos(theta) + ec * std::sin(theta)) * r;
}

} // namespace

BuiltinData setbackVertexBlend() {
  BuiltinData data;
  NetworkDescription &net = data.network;
  net.name = "setback-vertex-blend";
  auto add = [&](BSplineCurve curve) {
    net.curves.push_back(std::move(curve));
    return static_cast<int>(net.curves.size()) - 1;
  };
  // The exact quarter circle θ ∈ [0, π/2] of fillet a at t: rational quadratic.
  auto arc = [&](int a, double t) {
    const Vec3 p0 = filletPoint(a, t, 0), p2 = filletPoint(a, t, std::numbers::pi / 2);
    // Control corner: the intersection of the end tangents, on plane b's
    // normal line through p0 and plane c's through p2: p0 + r e_c.
    const Vec3 middle = p0 + axis((a + 2) % 3) * kRadius[size_t(a)];
    return add(BSplineCurve(2, {0, 0, 0, 1, 1, 1}, {p0, middle, p2}, {1, std::sqrt(0.5), 1}));
  };
  std::array<int, 3> nearArc{}, farArc{}, lineB{}, lineC{};
  for (int a = 0; a < 3; ++a) {
    const double s = kSetback[size_t(a)];
    nearArc[size_t(a)] = arc(a, -s);
    farArc[size_t(a)] = arc(a, -kLength);
    // Boundary lines from the far end towards the corner (direction +e_a).
    lineB[size_t(a)] = add(line(filletPoint(a, -kLength, 0), filletPoint(a, -s, 0)));
    lineC[size_t(a)] = add(line(filletPoint(a, -kLength, std::numbers::pi / 2), filletPoint(a, -s, std::numbers::pi / 2)));
  }
  // Setback curve in plane b (normal e_b) for a cyclic (a, b, c): from the
  // end of fillet c's line there, W = −s_c e_c − r_c e_a, leaving along +e_c,
  // to the end of fillet a's line, V = −s_a e_a − r_a e_c, arriving along
  // −e_a; both lines continue it tangentially.
  std::array<int, 3> setback{}; // by plane
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const Vec3 ea = axis(a), ec = axis(c);
    const Vec3 w = filletPoint(c, -kSetback[size_t(c)], std::numbers::pi / 2);
    const Vec3 v = filletPoint(a, -kSetback[size_t(a)], 0);
    const double along = kSetback[size_t(c)] - kRadius[size_t(a)], across = kSetback[size_t(a)] - kRadius[size_t(c)];
    setback[size_t(b)] = add(BSplineCurve::bezier({w, w + ec * (kHandle * along), v + ea * (kHandle * across), v}));
  }

  const char *axisName[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    // Counter-clockwise seen from outside: down line b, across the far end,
    // up line c, back along the end arc.
    FaceDescription fillet;
    fillet.name = std::string("fillet-") + axisName[a];
    fillet.sides = {{lineB[size_t(a)], 1, 0}, {farArc[size_t(a)], 0, 1}, {lineC[size_t(a)], 0, 1},
                    {nearArc[size_t(a)], 1, 0}};
    net.faces.push_back(fillet);
  }
  FaceDescription blend;
  blend.name = "vertex-blend";
  for (int a = 0; a < 3; ++a) {
    // End arc of fillet a (plane b → plane c), then the setback curve in
    // plane c towards fillet b, which continues with fillet b's arc.
    blend.sides.push_back({nearArc[size_t(a)], 0, 1});
    blend.sides.push_back({setback[size_t((a + 2) % 3)], 0, 1});
    net.edges.push_back({nearArc[size_t(a)], a, false});
  }
  net.faces.push_back(blend);

  // Vertices: the six T-nodes where an end arc meets the line it closes and
  // the setback curve that line runs into; the six corners at the far ends.
  for (int a = 0; a < 3; ++a)
    for (double theta : {0.0, std::numbers::pi / 2}) {
      data.facts.push_back({filletPoint(a, -kSetback[size_t(a)], theta), 3, 2});
      data.facts.push_back({filletPoint(a, -kLength, theta), 2, 2});
    }
  return data;
}

} // namespace builtin_detail
} // namespace v1
} // namespace curvenet
