// Built-ins cut from ellipsoids: polyhedra projected on the unit sphere, with
// great-arc edges, mapped by diag(a, b, c). A great arc lies in a plane through
// the centre, and a linear map keeps planes, so every edge is an exact planar
// section of the ellipsoid.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "builtins/builtin_support.hpp"
#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {
namespace builtin_detail {

namespace {

constexpr double kGolden = std::numbers::phi;

Vec3 scaled(const Vec3 &radii, const Vec3 &p) { return {radii.x * p.x, radii.y * p.y, radii.z * p.z}; }

// Sorts a face's vertices counter-clockwise seen from outside, i.e. about the
// outward direction of their centroid.
void orderCounterClockwise(const std::vector<Vec3> &points, std::vector<int> &loop) {
  Vec3 c;
  for (int i : loop) c += points[i];
  Vec3 n = normalized(c);
  Vec3 axis = std::abs(n.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  Vec3 u = normalized(axis - dot(axis, n) * n), v = cross(n, u);
  std::sort(loop.begin(), loop.end(), [&](int a, int b) {
    return std::atan2(dot(points[a], v), dot(points[a], u)) < std::atan2(dot(points[b], v), dot(points[b], u));
  });
}

// Faces of a convex polyhedron with vertex set `points`: for each face
// direction, the vertices of maximal support (exactly `size` of them).
std::vector<std::vector<int>> facesBySupport(const std::vector<Vec3> &points, const std::vector<Vec3> &directions,
                                             size_t size) {
  std::vector<std::vector<int>> faces;
  for (const Vec3 &d : directions) {
    double best = -INFINITY;
    for (const Vec3 &p : points) best = std::max(best, dot(p, d));
    std::vector<int> face;
    for (size_t i = 0; i < points.size(); ++i)
      if (dot(points[i], d) > best - 1e-9) face.push_back(static_cast<int>(i));
    CURVENET_CHECK(face.size() == size, "face has " + std::to_string(face.size()) + " vertices");
    faces.push_back(std::move(face));
  }
  return faces;
}

// The 12 icosahedron vertices: cyclic permutations of (0, ±1, ±φ) scaled by s.
std::vector<Vec3> icosahedronVertices(double one, double golden) {
  std::vector<Vec3> v;
  for (double s1 : {1.0, -1.0})
    for (double s2 : {1.0, -1.0}) {
      v.push_back({0, s1 * one, s2 * golden});
      v.push_back({s2 * golden, 0, s1 * one});
      v.push_back({s1 * one, s2 * golden, 0});
    }
  return v;
}

void projectToSphere(SpherePolyhedron &p) {
  for (Vec3 &v : p.vertices) v = normalized(v);
}

} // namespace

SpherePolyhedron dodecahedronOnSphere() {
  SpherePolyhedron p;
  for (double a : {1.0, -1.0})
    for (double b : {1.0, -1.0}) {
      for (double c : {1.0, -1.0}) p.vertices.push_back({a, b, c});
      p.vertices.push_back({0, a / kGolden, b * kGolden});
      p.vertices.push_back({a / kGolden, b * kGolden, 0});
      p.vertices.push_back({a * kGolden, 0, b / kGolden});
    }
  // Face normals of this dodecahedron are the vertices of the dual
  // icosahedron, cyclic permutations of (0, ±φ, ±1).
  p.faces = facesBySupport(p.vertices, icosahedronVertices(kGolden, 1.0), 5);
  projectToSphere(p);
  return p;
}

SpherePolyhedron truncatedIcosahedronOnSphere() {
  // Truncation at one third of every icosahedron edge: vertex (a→b) = a + (b − a)/3.
  const std::vector<Vec3> ico = icosahedronVertices(1.0, kGolden);
  const int n = static_cast<int>(ico.size());
  auto adjacent = [&](int a, int b) { return a != b && std::abs(norm(ico[a] - ico[b]) - 2.0) < 1e-9; };
  SpherePolyhedron p;
  std::map<std::pair<int, int>, int> cut; // directed icosahedron edge → vertex
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      if (adjacent(a, b)) {
        cut[{a, b}] = static_cast<int>(p.vertices.size());
        p.vertices.push_back(ico[a] + (ico[b] - ico[a]) / 3.0);
      }
  // A pentagon around every icosahedron vertex, a hexagon inside every triangle.
  for (int a = 0; a < n; ++a) {
    std::vector<int> face;
    for (int b = 0; b < n; ++b)
      if (adjacent(a, b)) face.push_back(cut[{a, b}]);
    p.faces.push_back(face);
  }
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c)
        if (adjacent(a, b) && adjacent(b, c) && adjacent(a, c))
          p.faces.push_back({cut[{a, b}], cut[{b, a}], cut[{b, c}], cut[{c, b}], cut[{c, a}], cut[{a, c}]});
  projectToSphere(p);
  return p;
}

SpherePolyhedron pentagonCapOnSphere() {
  // Polar angle 35°: well inside the cap bounded by the ellipsoid's umbilics.
  const double polar = 35.0 * std::numbers::pi / 180.0;
  SpherePolyhedron p;
  std::vector<int> loop;
  for (int k = 0; k < 5; ++k) {
    double azimuth = 2 * std::numbers::pi * k / 5 + 0.3;
    p.vertices.push_back({std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar)});
    loop.push_back(k);
  }
  p.faces.push_back(loop);
  return p;
}

BuiltinData ellipsoidNetworkFromSphere(const std::string &name, const SpherePolyhedron &polyhedron,
                                       const Vec3 &radii) {
  BuiltinData data;
  NetworkDescription &net = data.network;
  net.name = name;
  net.reference = ReferenceSurface{ReferenceSurface::Kind::Ellipsoid, Vec3{}, radii, nullptr};
  const std::vector<Vec3> &unit = polyhedron.vertices;
  std::vector<Vec3> position(unit.size());
  for (size_t i = 0; i < unit.size(); ++i) position[i] = scaled(radii, unit[i]);

  std::map<std::pair<int, int>, int> curveOf; // undirected edge (low, high) → curve, which runs low → high
  std::vector<int> valence(unit.size(), 0);
  auto edgeCurve = [&](int a, int b) {
    auto key = std::minmax(a, b);
    auto it = curveOf.find(key);
    if (it != curveOf.end()) return it->second;
    const Vec3 u = unit[key.first], w = unit[key.second];
    const double angle = angleBetween(u, w), s = std::sin(angle);
    // Great arc by slerp, parameter proportional to the angle.
    auto exact = [=](double t) {
      return scaled(radii, (std::sin((1 - t) * angle) / s) * u + (std::sin(t * angle) / s) * w);
    };
    int intervals = std::max(16, static_cast<int>(std::ceil(angle / 0.025)));
    net.curves.push_back(fitSurfaceCurve(exact, 0.0, 1.0, intervals, position[key.first], position[key.second]));
    ++valence[key.first];
    ++valence[key.second];
    return curveOf[key] = static_cast<int>(net.curves.size()) - 1;
  };

  for (std::vector<int> loop : polyhedron.faces) {
    orderCounterClockwise(unit, loop);
    FaceDescription face;
    face.name = "face " + std::to_string(net.faces.size()) + " (" + std::to_string(loop.size()) + "-sided)";
    for (size_t k = 0; k < loop.size(); ++k) {
      int a = loop[k], b = loop[(k + 1) % loop.size()];
      int curve = edgeCurve(a, b);
      bool forward = a < b;
      face.sides.push_back({curve, forward ? 0.0 : 1.0, forward ? 1.0 : 0.0});
    }
    net.faces.push_back(std::move(face));
  }
  for (size_t i = 0; i < unit.size(); ++i) data.facts.push_back({position[i], valence[i], valence[i]});
  return data;
}

} // namespace builtin_detail
} // namespace v1
} // namespace curvenet
