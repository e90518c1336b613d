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

// ---- setback-external-masters ----------------------------------------------
//
// Built-in `setback-external-masters` ([SV14] Sec. 5.1, Fig. 8 with the
// primary surfaces given from outside): the same box corner, but the network
// is the 6-sided vertex blend alone, and the three fillets are external
// master surfaces — exact NURBS cylinders — that the blend's arc edges name
// (EdgeDescription::masterSurface). Each fillet is trimmed obliquely: its
// end curve runs from the setback s_a0 on plane b (θ = 0) to another
// setback s_a1 on plane c (θ = π/2), so the edge is not a cross-section
// circle and the master's curvature across it is not zero: with the master
// data ignored, the blend's tangent planes and curvature along those edges
// come from the two curves at each corner alone and miss the cylinders.
//
// Fillet a as a NURBS surface: u ∈ [0, 1] along the quarter circle (rational,
// degree 3: the exact quadratic arc elevated), v ∈ [0, 1] straight along the
// axis from the far end t = −L (v = 0) to the oblique trim (v = 1), where
// t = −s_a0 (1 − u) − s_a1 u. The trim is the same rational cubic, the
// blend's side.

namespace {

constexpr std::array<std::array<double, 2>, 3> kObliqueSetback = {{{0.72, 0.60}, {0.66, 0.78}, {0.80, 0.68}}};

/// The quarter circle of fillet a at axis position 0 as a homogeneous
/// quadratic (control points times weights, and the weights).
struct HomogeneousArc {
  std::array<Vec3, 3> points;
  std::array<double, 3> weights;
};

HomogeneousArc quarterCircle(int a) {
  const Vec3 p0 = filletPoint(a, 0, 0), p2 = filletPoint(a, 0, std::numbers::pi / 2);
  const Vec3 middle = p0 + axis((a + 2) % 3) * kRadius[size_t(a)];
  const double w = std::sqrt(0.5);
  return {{p0, middle * w, p2}, {1, w, 1}};
}

/// Fillet a's rational cubic section where the axis position is linear in
/// u from t0 (u = 0) to t1 (u = 1): the homogeneous arc elevated to degree 3
/// plus the axis term t(u) w(u) e_a (a linear times a quadratic Bernstein
/// product). The weights do not depend on t0, t1, so all sections of one
/// fillet share them and a ruled surface between two is the cylinder.
BSplineCurve filletSection(int a, double t0, double t1) {
  const HomogeneousArc arc = quarterCircle(a);
  const auto &h = arc.points;
  const auto &w = arc.weights;
  const std::array<Vec3, 4> elevated = {h[0], (h[0] + h[1] * 2) / 3, (h[1] * 2 + h[2]) / 3, h[2]};
  const std::array<double, 4> weights = {w[0], (w[0] + 2 * w[1]) / 3, (2 * w[1] + w[2]) / 3, w[2]};
  const std::array<double, 4> axial = {t0 * w[0], (t1 * w[0] + 2 * t0 * w[1]) / 3, (2 * t1 * w[1] + t0 * w[2]) / 3,
                                       t1 * w[2]};
  std::vector<Vec3> points(4);
  for (size_t k = 0; k < 4; ++k) points[k] = (elevated[k] + axis(a) * axial[k]) / weights[k];
  return BSplineCurve(3, {0, 0, 0, 0, 1, 1, 1, 1}, std::move(points),
                      std::vector<double>(weights.begin(), weights.end()));
}

/// Fillet a between its far end and the oblique trim: ruled, degree 3 × 1.
BSplineSurface filletSurface(int a) {
  const auto &s = kObliqueSetback[size_t(a)];
  const BSplineCurve far = filletSection(a, -kLength, -kLength), trim = filletSection(a, -s[0], -s[1]);
  std::vector<Vec3> net;
  std::vector<double> weights;
  for (size_t i = 0; i < 4; ++i) {
    net.push_back(far.controlPoints()[i]);
    net.push_back(trim.controlPoints()[i]);
    weights.push_back(far.weights()[i]);
    weights.push_back(trim.weights()[i]);
  }
  return BSplineSurface(3, 1, {0, 0, 0, 0, 1, 1, 1, 1}, {0, 0, 1, 1}, 4, 2, std::move(net), std::move(weights));
}

} // namespace

BuiltinData setbackExternalMasters() {
  BuiltinData data;
  NetworkDescription &net = data.network;
  net.name = "setback-external-masters";
  std::array<int, 3> trim{}, setback{};
  for (int a = 0; a < 3; ++a) {
    const auto &s = kObliqueSetback[size_t(a)];
    net.surfaces.push_back(filletSurface(a));
    trim[size_t(a)] = int(net.curves.size());
    net.curves.push_back(filletSection(a, -s[0], -s[1]));
    net.edges.push_back({trim[size_t(a)], -1, false, a});
  }
  // Setback curve in plane b between fillet c's trim end on it (θ = π/2)
  // and fillet a's (θ = 0), leaving and arriving along the fillets' axes so
  // that the blend's corners are tangent to the cylinders (as setback.cpp).
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const Vec3 ea = axis(a), ec = axis(c);
    const double sc = kObliqueSetback[size_t(c)][1], sa = kObliqueSetback[size_t(a)][0];
    const Vec3 w = filletPoint(c, -sc, std::numbers::pi / 2), v = filletPoint(a, -sa, 0);
    const double along = sc - kRadius[size_t(a)], across = sa - kRadius[size_t(c)];
    setback[size_t(b)] = int(net.curves.size());
    net.curves.push_back(BSplineCurve::bezier({w, w + ec * (kHandle * along), v + ea * (kHandle * across), v}));
  }
  FaceDescription blend;
  blend.name = "vertex-blend";
  for (int a = 0; a < 3; ++a) {
    blend.sides.push_back({trim[size_t(a)], 0, 1});
    blend.sides.push_back({setback[size_t((a + 2) % 3)], 0, 1});
  }
  net.faces.push_back(blend);
  // Six corners: each trim end, where one setback curve ends.
  for (int a = 0; a < 3; ++a)
    for (int end = 0; end < 2; ++end)
      data.facts.push_back(
          {filletPoint(a, -kObliqueSetback[size_t(a)][size_t(end)], end * std::numbers::pi / 2), 2, 2});
  return data;
}

// ---- end of setback-external-masters ----------------------------------------

} // namespace builtin_detail
} // namespace v1
} // namespace curvenet
