// Built-in `torus-mixed`: a closed network on the torus (R = 1, r = 0.45, axis z)
// whose curves are images of straight segments of the (θ, φ) parameter plane.
//
// Construction: a 10 × 6 periodic grid of the parameter torus (φ = 0 is the
// outer equator, φ = π the inner one), edited locally:
//   * a diagonal splits a quad into two triangles (its ends get valence 5);
//   * removing the edge between two neighbouring quads makes a hexagon (the
//     edge's ends drop to valence 3);
//   * a diagonal plus a removed edge makes a pentagon and a triangle.
// Two edits sit in the hyperbolic inner band (cos φ < 0), one in the outer.
// Every vertex is displaced in a checkerboard (±δ, ±δ) so that grid lines
// zigzag: no two edges at a vertex are collinear (no accidental pass-through
// or T-node). The ends of removed edges are pushed further out of the merged
// face (same direction as their checkerboard offset) so its corners there are
// real corners. With these numbers every face corner is ≤ 156° and every pair
// of edges at a vertex deviates ≥ 11° from a straight line (measured in the
// surface metric). Faces: 50 quads, 6 triangles, 2 pentagons, 2 hexagons;
// vertices: 48 of valence 4, 6 of valence 3, 6 of valence 5; V − E + F = 0.
#include <cmath>
#include <map>
#include <numbers>

#include "builtins/builtin_support.hpp"
#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {
namespace builtin_detail {

namespace {

constexpr int kRing = 10, kTube = 6;        // cells around θ and φ
constexpr double kR = 1.0, kr = 0.45;       // ring and tube radii
constexpr double kZigzag = 0.18, kPush = 0.32; // offsets in cell units

struct GridVertex {
  int i, j; // unwrapped grid indices (a face may step past the seam)
};

int wrap(int k, int n) { return ((k % n) + n) % n; }
int vertexId(const GridVertex &v) { return wrap(v.i, kRing) + kRing * wrap(v.j, kTube); }

// Offset of a canonical vertex in cell units: checkerboard, or the push of an edit.
Vec2 offset(int i, int j) {
  static const std::map<std::pair<int, int>, Vec2> pushed = {
      {{4, 3}, {0, -kPush}}, {{4, 4}, {0, kPush}}, // hexagon (3,3)+(4,3)
      {{0, 5}, {0, -kPush}}, {{0, 0}, {0, kPush}}, // hexagon (9,5)+(0,5)
      {{7, 3}, {0, kPush}},                         // pentagon (6,2)+(7,2)
      {{2, 1}, {-kPush, 0}},                        // pentagon (2,0)+(2,1)
  };
  auto it = pushed.find({i, j});
  if (it != pushed.end()) return it->second;
  double s = ((i + j) % 2 == 0) ? kZigzag : -kZigzag;
  return {s, s};
}

// (θ, φ) of an unwrapped grid vertex: the canonical vertex's offset carried
// along, so both faces of an edge describe the same image curve.
Vec2 parameters(const GridVertex &v) {
  Vec2 o = offset(wrap(v.i, kRing), wrap(v.j, kTube));
  return {(v.i + o.x) * 2 * std::numbers::pi / kRing, (v.j + o.y) * 2 * std::numbers::pi / kTube};
}

Vec3 torusPoint(const Vec2 &p) {
  double rho = kR + kr * std::cos(p.y);
  return {rho * std::cos(p.x), rho * std::sin(p.x), kr * std::sin(p.y)};
}

using Loop = std::vector<GridVertex>;

// Faces counter-clockwise in the (θ, φ) plane; X_θ × X_φ is the outward
// normal, so they are counter-clockwise seen from outside.
std::vector<Loop> torusFaces() {
  std::map<std::pair<int, int>, Loop> quads;
  for (int i = 0; i < kRing; ++i)
    for (int j = 0; j < kTube; ++j) quads[{i, j}] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
  std::vector<Loop> edited;
  auto take = [&](int i, int j) { CURVENET_CHECK(quads.erase({wrap(i, kRing), wrap(j, kTube)}) == 1); };
  // Two triangles: diagonal (i,j)–(i+1,j+1) or (i+1,j)–(i,j+1).
  auto triangles = [&](int i, int j, bool rising) {
    take(i, j);
    if (rising) {
      edited.push_back({{i, j}, {i + 1, j}, {i + 1, j + 1}});
      edited.push_back({{i, j}, {i + 1, j + 1}, {i, j + 1}});
    } else {
      edited.push_back({{i, j}, {i + 1, j}, {i, j + 1}});
      edited.push_back({{i + 1, j}, {i + 1, j + 1}, {i, j + 1}});
    }
  };
  // Hexagon: quads (i,j) and (i+1,j) without their shared edge.
  auto hexagon = [&](int i, int j) {
    take(i, j), take(i + 1, j);
    edited.push_back({{i, j}, {i + 1, j}, {i + 2, j}, {i + 2, j + 1}, {i + 1, j + 1}, {i, j + 1}});
  };
  // Pentagon + triangle: rising diagonal in (i,j), its upper triangle merged with (i−1,j).
  auto pentagonLeft = [&](int i, int j) {
    take(i, j), take(i - 1, j);
    edited.push_back({{i, j}, {i + 1, j}, {i + 1, j + 1}});
    edited.push_back({{i - 1, j}, {i, j}, {i + 1, j + 1}, {i, j + 1}, {i - 1, j + 1}});
  };
  // Pentagon + triangle: falling diagonal in (i,j), its lower triangle merged with (i,j−1).
  auto pentagonBelow = [&](int i, int j) {
    take(i, j), take(i, j - 1);
    edited.push_back({{i + 1, j}, {i + 1, j + 1}, {i, j + 1}});
    edited.push_back({{i, j - 1}, {i + 1, j - 1}, {i + 1, j}, {i, j + 1}, {i, j}});
  };
  triangles(1, 2, true);  // inner band
  triangles(5, 0, false); // outer equator
  hexagon(3, 3);          // inner band
  pentagonLeft(7, 2);     // inner band
  hexagon(9, 5);          // outer, across the θ seam
  pentagonBelow(2, 1);    // outer
  std::vector<Loop> faces;
  for (auto &[key, loop] : quads) faces.push_back(loop);
  faces.insert(faces.end(), edited.begin(), edited.end());
  return faces;
}

} // namespace

BuiltinData torusMixed() {
  BuiltinData data;
  NetworkDescription &net = data.network;
  net.name = "torus-mixed";
  net.reference = ReferenceSurface{ReferenceSurface::Kind::Torus, Vec3{}, Vec3{kR, kr, 0}, nullptr};
  const int count = kRing * kTube;
  std::vector<Vec3> position(count);
  for (int j = 0; j < kTube; ++j)
    for (int i = 0; i < kRing; ++i) position[vertexId({i, j})] = torusPoint(parameters({i, j}));

  std::map<std::pair<int, int>, int> curveOf; // (start id, end id) of the curve's direction
  std::vector<int> valence(count, 0);
  for (const Loop &loop : torusFaces()) {
    FaceDescription face;
    face.name = "face " + std::to_string(net.faces.size()) + " (" + std::to_string(loop.size()) + "-sided)";
    for (size_t k = 0; k < loop.size(); ++k) {
      const GridVertex &a = loop[k], &b = loop[(k + 1) % loop.size()];
      int ia = vertexId(a), ib = vertexId(b);
      if (auto it = curveOf.find({ib, ia}); it != curveOf.end()) {
        face.sides.push_back({it->second, 1.0, 0.0}); // the neighbour made it; run it backwards
        continue;
      }
      CURVENET_CHECK(!curveOf.contains({ia, ib}), "edge used twice in the same direction");
      // Straight segment of the parameter plane, mapped onto the torus.
      const Vec2 pa = parameters(a), pb = parameters(b);
      auto exact = [=](double t) { return torusPoint(pa + t * (pb - pa)); };
      net.curves.push_back(fitSurfaceCurve(exact, 0.0, 1.0, 40, position[ia], position[ib]));
      int curve = static_cast<int>(net.curves.size()) - 1;
      curveOf[{ia, ib}] = curve;
      ++valence[ia], ++valence[ib];
      face.sides.push_back({curve, 0.0, 1.0});
    }
    net.faces.push_back(std::move(face));
  }
  for (int v = 0; v < count; ++v) data.facts.push_back({position[v], valence[v], valence[v]});
  return data;
}

} // namespace builtin_detail
} // namespace v1
} // namespace curvenet
