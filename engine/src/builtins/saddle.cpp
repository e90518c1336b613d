// Built-in `saddle-nodes`: an open network on the saddle z = x² − y² over the
// square [−1, 1]², built to exercise the special vertex kinds:
//
//        (-1,1)──────── top ───(0.5,1)──── (1,1)
//          │               │        │         │
//        left     TL       V   TR1  W   TR2  right
//          │               │        │         │
//        (-1,0)─── H ─── (0,0)── H ─(0.5,0)── (1,0)     X-node at (0,0),
//          │   above L1    │                  │         T-node at (0.5,0)
//        P(-1,-.5)═lens═Q(0,-.5)     BR       │
//          │   below L2    │                  │
//        (-1,-1)── bottom ─(0,-1)──────────── (1,-1)
//
// H (y = 0) and V (x = 0) are single curves crossing at the X-node. W ends on
// the interior of H: the T-node, with faces on both sides of H, so BR sees H
// from x = 1 to 0 as one side with a straight angle at (0.5, 0). L1 and L2 are
// two different curves from P to Q bounding the 2-sided lens. Each boundary
// curve also passes straight through the vertices where H, V, W or the lens end.
//
// Curves are lifts (x(t), y(t), x² − y²) of lines and parabolas of the plane:
// polynomials of degree ≤ 4, which the degree-5 fit reproduces exactly.
#include "builtins/builtin_support.hpp"

namespace curvenet {
inline namespace v1 {
namespace builtin_detail {

namespace {

Vec3 lift(double x, double y) { return {x, y, x * x - y * y}; }

} // namespace

BuiltinData saddleNodes() {
  BuiltinData data;
  NetworkDescription &net = data.network;
  net.name = "saddle-nodes";
  net.reference = ReferenceSurface{ReferenceSurface::Kind::Graph, Vec3{}, Vec3{1, -1, 0}, nullptr};

  // Curve parameter = x for curves along x, = y for curves along y, so face
  // sides are written with coordinates.
  auto add = [&](auto xy, double t0, double t1) {
    auto exact = [=](double t) {
      auto [x, y] = xy(t);
      return lift(x, y);
    };
    net.curves.push_back(fitSurfaceCurve(exact, t0, t1, 20, exact(t0), exact(t1)));
    return static_cast<int>(net.curves.size()) - 1;
  };
  struct XY {
    double x, y;
  };
  const int H = add([](double t) { return XY{t, 0}; }, -1, 1);
  const int V = add([](double t) { return XY{0, t}; }, -1, 1);
  const int W = add([](double t) { return XY{0.5, t}; }, 0, 1);
  const int bottom = add([](double t) { return XY{t, -1}; }, -1, 1);
  const int right = add([](double t) { return XY{1, t}; }, -1, 1);
  const int top = add([](double t) { return XY{t, 1}; }, -1, 1);
  const int left = add([](double t) { return XY{-1, t}; }, -1, 1);
  // Lens: y = −0.5 ± 1.2·(−x)(x + 1), bulging to y = −0.2 and y = −0.8.
  const int L1 = add([](double t) { return XY{t, -0.5 + 1.2 * (-t) * (t + 1)}; }, -1, 0);
  const int L2 = add([](double t) { return XY{t, -0.5 - 1.2 * (-t) * (t + 1)}; }, -1, 0);

  // Counter-clockwise seen from +z.
  auto face = [&](std::string name, std::vector<SideDescription> sides) {
    net.faces.push_back({std::move(sides), std::move(name)});
  };
  face("TL", {{H, -1, 0}, {V, 0, 1}, {top, 0, -1}, {left, 1, 0}});
  face("TR1", {{H, 0, 0.5}, {W, 0, 1}, {top, 0.5, 0}, {V, 1, 0}});
  face("TR2", {{H, 0.5, 1}, {right, 0, 1}, {top, 1, 0.5}, {W, 1, 0}});
  face("BR", {{V, 0, -1}, {bottom, 0, 1}, {right, -1, 0}, {H, 1, 0}});
  face("BL-above-lens", {{L1, -1, 0}, {V, -0.5, 0}, {H, 0, -1}, {left, 0, -0.5}});
  face("lens", {{L2, -1, 0}, {L1, 0, -1}});
  face("BL-below-lens", {{left, -0.5, -1}, {bottom, -1, 0}, {V, -1, -0.5}, {L2, 0, -1}});

  // valence = segment ends; independent = valence − curves passing straight through.
  auto fact = [&](double x, double y, int valence, int independent) {
    data.facts.push_back({lift(x, y), valence, independent});
  };
  fact(0, 0, 4, 2);      // X-node: H and V pass through
  fact(0.5, 0, 3, 2);    // T-node: H passes through, W ends
  fact(-1, -0.5, 4, 3);  // P: left passes through, L1 and L2 end
  fact(0, -0.5, 4, 3);   // Q: V passes through, L1 and L2 end
  fact(0.5, 1, 3, 2);    // W ends on top
  fact(0, 1, 3, 2);      // V ends on top
  fact(0, -1, 3, 2);     // V ends on bottom
  fact(-1, 0, 3, 2);     // H ends on left
  fact(1, 0, 3, 2);      // H ends on right
  for (double x : {-1.0, 1.0})
    for (double y : {-1.0, 1.0}) fact(x, y, 2, 2); // square corners
  return data;
}

} // namespace builtin_detail
} // namespace v1
} // namespace curvenet
