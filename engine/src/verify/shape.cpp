// Shape figures of a built surface (curvenet/shape.hpp).
#include "curvenet/shape.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "approximation/triangle_bvh.hpp"
#include "bezier/bezier_surface.hpp"
#include "curvenet/error.hpp"
#include "curvenet/tessellate.hpp"
#include "patches/corner_grid.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

/// κ1² + κ2² = (κ1 + κ2)² − 2 κ1κ2 from the two fundamental forms, and the
/// area element |du × dv|.
struct PointCurvature {
  double squaredPrincipal = 0;
  double areaElement = 0;
};

PointCurvature pointCurvature(const SurfacePoint2 &p) {
  const double E = dot(p.du, p.du), F = dot(p.du, p.dv), G = dot(p.dv, p.dv);
  const double L = dot(p.duu, p.normal), M = dot(p.duv, p.normal), N = dot(p.dvv, p.normal);
  const double det = E * G - F * F;
  if (!(det > 0)) return {};
  const double mean2 = (E * N - 2 * F * M + G * L) / det; // κ1 + κ2
  const double gauss = (L * N - M * M) / det;             // κ1 κ2
  return {mean2 * mean2 - 2 * gauss, std::sqrt(det)};
}

/// Mean κ² along a curve on [0, 1] by arc length, and its length.
void addCurveCurvature(const BSplineCurve &curve, int samples, double &integral, double &length) {
  for (int j = 0; j < samples; ++j) {
    const double t = curve.domainStart() + (curve.domainEnd() - curve.domainStart()) * (j + 0.5) / samples;
    const auto d = curve.derivatives(t);
    const double speed = norm(d[1]);
    if (!(speed > 0)) continue;
    const double kappa = norm(cross(d[1], d[2])) / (speed * speed * speed);
    const double ds = speed * (curve.domainEnd() - curve.domainStart()) / samples;
    integral += kappa * kappa * ds;
    length += ds;
  }
}

FaceShape measureFace(const Surface &surface, int f, int resolution) {
  const Network &network = surface.network();
  const Face &face = network.faces()[size_t(f)];
  FaceShape out;
  out.face = f;
  BoundingBox boundary;
  double boundaryIntegral = 0, boundaryLength = 0;
  const int curveSamples = 8 * resolution;
  for (const FaceSide &side : face.sides) {
    for (int j = 0; j <= curveSamples; ++j) boundary.add(side.curve.point(double(j) / curveSamples));
    addCurveCurvature(side.curve, curveSamples, boundaryIntegral, boundaryLength);
  }
  BoundingBox withPatch = boundary;
  const int n = surface.domainSides(f);
  Vec2 centre{0, 0};
  for (int k = 0; k < n; ++k) centre += surface.domainCorner(f, k) * (1.0 / n);
  double integral = 0, area = 0;
  const double r = resolution;
  for (int k = 0; k < n; ++k) {
    const Vec2 a = surface.domainCorner(f, k) - centre, b = surface.domainCorner(f, (k + 1) % n) - centre;
    const double triangleArea = 0.5 * std::abs(a.x * b.y - a.y * b.x) / (r * r);
    // Centroids of the resolution² sub-triangles of (centre, corner k, corner k+1).
    for (int i = 0; i < resolution; ++i)
      for (int j = 0; i + j < resolution; ++j)
        for (int flip = 0; flip < (i + j + 1 < resolution ? 2 : 1); ++flip) {
          const double s = flip ? (i + 2.0 / 3) / r : (i + 1.0 / 3) / r;
          const double t = flip ? (j + 2.0 / 3) / r : (j + 1.0 / 3) / r;
          const Vec2 uv = centre + a * s + b * t;
          const SurfacePoint2 p = surface.evaluateSecondOrder(f, uv);
          withPatch.add(p.point);
          const PointCurvature c = pointCurvature(p);
          integral += c.squaredPrincipal * c.areaElement * triangleArea;
          area += c.areaElement * triangleArea;
        }
  }
  out.area = area;
  out.excursion = (withPatch.diagonal() - boundary.diagonal()) / network.diagonal();
  const double floor = 1.0 / (network.diagonal() * network.diagonal());
  const double boundaryMean = boundaryLength > 0 ? boundaryIntegral / boundaryLength : 0.0;
  out.fairness = area > 0 ? (integral / area) / std::max(boundaryMean, floor) : 0.0;
  return out;
}

/// The corners of face f whose neighbourhood folds on the corner grid
/// (patches/corner_grid.hpp), with the extent of the samples turned over
/// against the grid's outer middle one.
std::vector<CornerFold> cornerFolds(const Surface &surface, int f) {
  const int n = surface.domainSides(f);
  std::vector<CornerFold> folds;
  std::vector<Vec2> uv(CornerGrid::kSize + 1);
  std::vector<SurfacePoint> at(uv.size());
  std::vector<Vec3> normals(CornerGrid::kSize);
  for (int k = 0; k < n; ++k) {
    const Vec2 c = surface.domainCorner(f, k);
    const Vec2 previous = surface.domainCorner(f, (k + n - 1) % n), next = surface.domainCorner(f, (k + 1) % n);
    for (int i = 0; i < CornerGrid::kRings; ++i)
      for (int j = 0; j < CornerGrid::kRays; ++j) uv[CornerGrid::index(i, j)] = CornerGrid::point(c, previous, next, i, j);
    uv.back() = c;
    surface.evaluate(f, uv, at);
    for (std::size_t s = 0; s < CornerGrid::kSize; ++s) normals[s] = at[s].normal;
    if (!CornerGrid::folds(normals)) continue;
    const Vec3 outer = normals[CornerGrid::index(CornerGrid::kRings - 1, CornerGrid::kRays / 2)];
    const Vec3 corner = at.back().point;
    double extent = 0;
    for (std::size_t s = 0; s < CornerGrid::kSize; ++s)
      if (dot(normals[s], outer) <= 0) extent = std::max(extent, norm(at[s].point - corner));
    folds.push_back({f, k, extent / surface.network().diagonal()});
  }
  return folds;
}

/// Pairs of faces (a ≤ b) whose tessellation at `resolution` intervals per
/// segment has crossing triangles that share no vertex, with a point where
/// they cross. A face with a transfinite patch is not paired with itself:
/// its own lattice decides that (faceIntersections).
std::map<std::pair<int, int>, Vec3> crossingFaces(const Surface &surface, int resolution) {
  TessellationOptions options;
  options.resolution = resolution;
  const Mesh mesh = tessellate(surface, options);
  std::vector<int> faceOf(mesh.triangles.size());
  for (std::size_t f = 0; f + 1 < mesh.faceTriangleStart.size(); ++f)
    std::fill(faceOf.begin() + mesh.faceTriangleStart[f], faceOf.begin() + mesh.faceTriangleStart[f + 1],
              static_cast<int>(f));
  std::map<std::pair<int, int>, Vec3> crossings;
  const TriangleBvh bvh(mesh.positions, mesh.triangles);
  bvh.forEachOverlappingPair([&](int s, int t) {
    const auto &a = mesh.triangles[static_cast<std::size_t>(s)], &b = mesh.triangles[static_cast<std::size_t>(t)];
    for (const std::uint32_t v : a)
      if (v == b[0] || v == b[1] || v == b[2]) return;
    const std::pair faces = std::minmax(faceOf[static_cast<std::size_t>(s)], faceOf[static_cast<std::size_t>(t)]);
    if (crossings.count(faces) || (faces.first == faces.second && SurfaceAccess::patch(surface, faces.first))) return;
    auto corners = [&](const std::array<std::uint32_t, 3> &tri) {
      return std::array<Vec3, 3>{mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]};
    };
    if (const std::optional<Vec3> x = trianglesCross(corners(a), corners(b))) crossings.emplace(faces, *x);
  });
  return crossings;
}

/// Faces passing through each other or themselves (shape.hpp,
/// intersections): pairs found at 16 intervals per segment and again at 32;
/// a transfinite patch through itself on its own lattice, as the build found
/// it (patchSelfCrossing).
std::vector<FaceIntersection> faceIntersections(const Surface &surface) {
  std::map<std::pair<int, int>, Vec3> found;
  for (int f = 0; f < surface.faceCount(); ++f)
    if (const std::optional<Vec3> x = SurfaceAccess::selfCrossing(surface, f)) found.emplace(std::pair(f, f), *x);
  if (const std::map<std::pair<int, int>, Vec3> coarse = crossingFaces(surface, 16); !coarse.empty())
    for (const auto &[faces, point] : crossingFaces(surface, 32))
      if (coarse.count(faces)) found.emplace(faces, point);
  std::vector<FaceIntersection> list;
  for (const auto &[faces, point] : found) list.push_back({faces.first, faces.second, point});
  return list;
}

} // namespace

ShapeReport measureShape(const Surface &surface, const ShapeOptions &options) {
  if (options.resolution < 1) throw InputError("", "shape resolution", "must be at least 1");
  ShapeReport report;
  report.foldedFaces = surface.foldedFaces();
  report.intersections = faceIntersections(surface);
  std::vector<char> intersects(static_cast<std::size_t>(surface.faceCount()), 0);
  for (const FaceIntersection &x : report.intersections)
    intersects[static_cast<std::size_t>(x.faceA)] = intersects[static_cast<std::size_t>(x.faceB)] = 1;
  double weighted = 0, totalArea = 0;
  for (int f = 0; f < surface.faceCount(); ++f) {
    FaceShape face = measureFace(surface, f, options.resolution);
    face.folded = std::find(report.foldedFaces.begin(), report.foldedFaces.end(), f) != report.foldedFaces.end();
    const std::vector<CornerFold> corners = cornerFolds(surface, f);
    face.foldsAtCorner = !corners.empty();
    face.intersects = intersects[static_cast<std::size_t>(f)];
    report.cornerFolds.insert(report.cornerFolds.end(), corners.begin(), corners.end());
    if (face.excursion > report.maxExcursion || report.worstExcursionFace < 0)
      report.maxExcursion = face.excursion, report.worstExcursionFace = f;
    if (face.fairness > report.maxFairness || report.worstFairnessFace < 0)
      report.maxFairness = face.fairness, report.worstFairnessFace = f;
    weighted += face.fairness * face.area;
    totalArea += face.area;
    if (face.folded || face.foldsAtCorner || face.intersects || !(face.excursion <= kExcursionBound))
      report.rejectedFaces.push_back(f);
    report.faces.push_back(face);
  }
  report.fairness = totalArea > 0 ? weighted / totalArea : 0.0;
  return report;
}

} // namespace v1
} // namespace curvenet
