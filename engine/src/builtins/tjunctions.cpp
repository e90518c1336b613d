// Built-ins of [OSK11]: cubic Bézier networks of 4-sided faces with
// T-junctions, on the unit sphere (hull-like: on an ellipsoid).
//
// Every curve is a cubic Bézier approximation of a great-circle arc (a planar
// section through the centre): end points on the surface, end tangents the
// exact circle tangents, inner control points at (4/3) tan(θ/4), so all
// tangents at a vertex lie in the surface's tangent plane (a G¹ network).
// A T-junction point is the point C(c) of the curve passing through it (off
// the surface by the approximation error, ~1e-4 of the radius), and the curve
// ending there starts exactly at C(c). Curve deviation from the reference is
// that of the cubic arcs, so reference deviations measure the network, not
// only the patches.
//
// The cube-sphere networks use the box x = 1, |y| ≤ 1, −0.8 ≤ z ≤ 1.2
// projected on the sphere (not symmetric in z, so that no edge system is
// degenerate by symmetry):
//
//   seen from +x:   c ───── b          seen from +y:   b ───── f
//                   │  S3   C (T on C)                 C  S2   │
//                   d ───── a                          T── D ──m   (m on ef)
//                                                      │  S1   │
//                                                      a ───── e
#include <cmath>
#include <optional>

#include "builtins/builtin_support.hpp"

namespace curvenet {
inline namespace v1 {
namespace builtin_detail {

namespace {

/// Cubic Bézier of the great arc from direction a to direction b (unit
/// sphere), with the end points optionally replaced (T-junction points).
BSplineCurve greatArc(const Vec3 &a0, const Vec3 &b0, std::optional<Vec3> from = {}, std::optional<Vec3> to = {}) {
  const Vec3 a = normalized(a0), b = normalized(b0);
  const double theta = angleBetween(a, b);
  const Vec3 t0 = normalized(b - dot(a, b) * a);
  const Vec3 t1 = -std::sin(theta) * a + std::cos(theta) * t0;
  const double k = 4.0 / 3.0 * std::tan(theta / 4);
  const Vec3 p0 = from ? *from : a, p3 = to ? *to : b;
  return BSplineCurve::bezier({p0, p0 + k * t0, p3 - k * t1, p3});
}

Vec3 n(double x, double y, double z) { return normalized(Vec3{x, y, z}); }

struct Builder {
  NetworkDescription net;
  int add(BSplineCurve c) {
    net.curves.push_back(std::move(c));
    return static_cast<int>(net.curves.size()) - 1;
  }
  void face(std::string name, std::vector<SideDescription> sides) { net.faces.push_back({std::move(sides), std::move(name)}); }
  BuiltinData done(const std::string &name, const Vec3 &radii) {
    for (BSplineCurve &c : net.curves) {
      std::vector<Vec3> p = c.controlPoints();
      for (Vec3 &q : p) q = {q.x * radii.x, q.y * radii.y, q.z * radii.z};
      c = BSplineCurve::bezier(p);
    }
    net.name = name;
    net.reference = ReferenceSurface{ReferenceSurface::Kind::Ellipsoid, Vec3{}, radii, nullptr};
    return {net, {}};
  }
};

constexpr double kTParameter = 0.45; // where D meets C

enum class CubeVariant { ThreeFaces, Surrounded, TAtVertex };

BuiltinData cubeSphere(const std::string &name, CubeVariant variant) {
  Builder b;
  const Vec3 A = n(1, 1, -0.8), B = n(1, 1, 1.2), C_ = n(1, -1, 1.2), D_ = n(1, -1, -0.8);
  const Vec3 E = n(0, 1, -0.8), F = n(0, 1, 1.2), G = n(0, -1, 1.2), H = n(0, -1, -0.8);
  const int C = b.add(greatArc(A, B));
  const Vec3 T = b.net.curves[C].point(kTParameter);
  const int ae = b.add(greatArc(A, E)), ef = b.add(greatArc(E, F)), fb = b.add(greatArc(F, B));
  const Vec3 M = b.net.curves[ef].point(0.5);
  const int D = b.add(greatArc(T, M, T, M));
  const double c = kTParameter;
  b.face("S1", {{ae, 0, 1}, {ef, 0, 0.5}, {D, 1, 0}, {C, c, 0}});
  b.face("S2", {{D, 0, 1}, {ef, 0.5, 1}, {fb, 0, 1}, {C, 1, c}});
  if (variant == CubeVariant::TAtVertex) {
    // F's loop runs straight through T: a T-junction at a vertex.
    const Vec3 X = n(1, -0.7, 0.15);
    const int bx = b.add(greatArc(B, X)), xa = b.add(greatArc(X, A));
    b.face("F", {{C, 0, c}, {C, c, 1}, {bx, 0, 1}, {xa, 0, 1}});
    return b.done(name, {1, 1, 1});
  }
  const int bc = b.add(greatArc(B, C_)), cd = b.add(greatArc(C_, D_)), da = b.add(greatArc(D_, A));
  b.face("S3", {{da, 0, 1}, {C, 0, 1}, {bc, 0, 1}, {cd, 0, 1}});
  if (variant == CubeVariant::Surrounded) {
    const int fg = b.add(greatArc(F, G)), gc = b.add(greatArc(G, C_)), gh = b.add(greatArc(G, H));
    const int hd = b.add(greatArc(H, D_)), he = b.add(greatArc(H, E));
    b.face("top", {{bc, 1, 0}, {fb, 1, 0}, {fg, 0, 1}, {gc, 0, 1}});
    b.face("y-", {{cd, 1, 0}, {gc, 1, 0}, {gh, 0, 1}, {hd, 0, 1}});
    b.face("bottom", {{da, 1, 0}, {hd, 1, 0}, {he, 0, 1}, {ae, 1, 0}});
  }
  return b.done(name, {1, 1, 1});
}

} // namespace

BuiltinData hemisphereTJunction() { return cubeSphere("hemisphere-tjunction", CubeVariant::ThreeFaces); }
BuiltinData tjunctionSurrounded() { return cubeSphere("tjunction-surrounded", CubeVariant::Surrounded); }
BuiltinData tjunctionVertex() { return cubeSphere("tjunction-vertex", CubeVariant::TAtVertex); }

// hull-like: three rows of patches on the side y > 0 of the ellipsoid
// (3, 1, 0.8), between "stations" x_i and "waterlines" z_j of the unit sphere
// (nodes normalize(x_i, 1, z_j): each waterline and each station is one great
// circle). Rows A and C have a station curve at every x_i; row B only at
// x_0, x_2, x_4, so its two patches see the waterline curves z_1 and z_2 as
// long sides with a T-junction each: four T-junctions in all.
BuiltinData hullLike() {
  Builder b;
  const double xs[5] = {-1.6, -0.75, 0.1, 0.85, 1.5};
  const double zs[4] = {0.35, -0.45, -1.25, -2.1};
  auto P = [&](int i, int j) { return n(xs[i], 1, zs[j]); };
  int H0[4], H3[4];
  for (int i = 0; i < 4; ++i) H0[i] = b.add(greatArc(P(i, 0), P(i + 1, 0))), H3[i] = b.add(greatArc(P(i, 3), P(i + 1, 3)));
  // Long waterline curves x_0 → x_2 and x_2 → x_4 at z_1 and z_2, T at c.
  const double c = 0.5;
  int H1[2], H2[2];
  Vec3 T1[2], T2[2];
  for (int k = 0; k < 2; ++k) {
    H1[k] = b.add(greatArc(P(2 * k, 1), P(2 * k + 2, 1)));
    H2[k] = b.add(greatArc(P(2 * k, 2), P(2 * k + 2, 2)));
    T1[k] = b.net.curves[H1[k]].point(c);
    T2[k] = b.net.curves[H2[k]].point(c);
  }
  // Node on waterline 1 / 2 at station i: a vertex P or a T point.
  auto node1 = [&](int i) { return i % 2 ? T1[i / 2] : P(i, 1); };
  auto node2 = [&](int i) { return i % 2 ? T2[i / 2] : P(i, 2); };
  int VA[5], VB[5] = {-1, -1, -1, -1, -1}, VC[5];
  for (int i = 0; i < 5; ++i) {
    VA[i] = b.add(greatArc(P(i, 0), node1(i), std::nullopt, node1(i)));
    VC[i] = b.add(greatArc(node2(i), P(i, 3), node2(i), std::nullopt));
    if (i % 2 == 0) VB[i] = b.add(greatArc(P(i, 1), P(i, 2)));
  }
  // Waterline ranges between stations i and i+1 (curve, from, to), increasing x.
  auto w1 = [&](int i) { return SideDescription{H1[i / 2], i % 2 ? c : 0.0, i % 2 ? 1.0 : c}; };
  auto w2 = [&](int i) { return SideDescription{H2[i / 2], i % 2 ? c : 0.0, i % 2 ? 1.0 : c}; };
  auto rev = [](SideDescription s) { return SideDescription{s.curve, s.to, s.from}; };
  // Counter-clockwise seen from +y (x grows to the left): bottom (x decreasing),
  // up station x_i, top (x increasing), down station x_{i+1}.
  for (int i = 0; i < 4; ++i)
    b.face("A" + std::to_string(i), {rev(w1(i)), {VA[i], 1, 0}, {H0[i], 0, 1}, {VA[i + 1], 0, 1}});
  for (int k = 0; k < 2; ++k)
    b.face("B" + std::to_string(k), {{H2[k], 1, 0}, {VB[2 * k], 1, 0}, {H1[k], 0, 1}, {VB[2 * k + 2], 0, 1}});
  for (int i = 0; i < 4; ++i)
    b.face("C" + std::to_string(i), {{H3[i], 1, 0}, {VC[i], 1, 0}, w2(i), {VC[i + 1], 0, 1}});
  return b.done("hull-like", {3, 1, 0.8});
}

} // namespace builtin_detail
} // namespace v1
} // namespace curvenet
