// Mesh approximation (curvenet/approximation.hpp, [SV14] Sec. 5.3).
#include "curvenet/approximation.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "approximation/triangle_bvh.hpp"
#include "curvenet/curvature_jump.hpp"
#include "curvenet/error.hpp"
#include "curvenet/mesh_reference.hpp"
#include "curvenet/tessellate.hpp"
#include "parallel/fork_join.hpp"

namespace curvenet {
inline namespace v1 {

NetworkDescription fitPolylineCurves(const NetworkDescription &description) {
  NetworkDescription out = description;
  for (size_t c = 0; c < out.curves.size(); ++c) {
    const BSplineCurve &curve = out.curves[c];
    if (curve.degree() != 1 || curve.isRational()) continue;
    // A clamped degree-1 curve has knots t0, t0, t1, …, tn, tn: point i sits at knot i + 1.
    const std::vector<Vec3> &points = curve.controlPoints();
    std::vector<double> params(points.size());
    for (size_t i = 0; i < points.size(); ++i) params[i] = curve.knots()[i + 1];
    const int degree = std::min<int>(3, static_cast<int>(points.size()) - 1);
    for (size_t i = 1; i < params.size(); ++i)
      if (!(params[i] > params[i - 1]))
        throw InputError("", "curve " + std::to_string(c), "polyline with repeated knots cannot be interpolated");
    out.curves[c] = BSplineCurve::interpolate(degree, params, points);
  }
  return out;
}

namespace {

bool insideDomain(const Surface &surface, int face, const Vec2 &uv) {
  // Domain polygons are convex and counter-clockwise.
  const int n = surface.domainSides(face);
  for (int i = 0; i < n; ++i) {
    const Vec2 a = surface.domainCorner(face, i), b = surface.domainCorner(face, (i + 1) % n);
    const Vec2 e = b - a, r = uv - a;
    if (e.x * r.y - e.y * r.x < -1e-12) return false;
  }
  return true;
}

} // namespace

DeviationFigures measurePointDeviation(const Surface &surface, const std::vector<Vec3> &points, double diagonal,
                                       int resolution, int threads, const std::vector<Vec3> &normals) {
  if (!normals.empty() && normals.size() != points.size())
    throw InputError("", "normals", "one normal per point expected");
  if (resolution < 2) throw InputError("", "resolution", "must be at least 2");
  TessellationOptions topt;
  topt.resolution = resolution;
  topt.threads = threads;
  topt.recordDomainPoints = true;
  const Mesh mesh = tessellate(surface, topt);
  const TriangleBvh bvh(mesh.positions, mesh.triangles);
  // Edges used by one triangle only: the open boundary of the tessellation,
  // and their end vertices.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edgeUse;
  for (const auto &t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++edgeUse[std::minmax(t[k], t[(k + 1) % 3])];
  std::vector<char> boundaryVertex(mesh.positions.size(), 0);
  for (const auto &[edge, uses] : edgeUse)
    if (uses == 1) boundaryVertex[edge.first] = boundaryVertex[edge.second] = 1;
  auto onBoundary = [&](const TriangleBvh::Hit &hit) {
    const auto &t = mesh.triangles[hit.triangle];
    const double w[3] = {hit.barycentric.x, hit.barycentric.y, hit.barycentric.z};
    // Foot at a corner (the other two weights 0): a boundary vertex, whatever
    // triangle of its fan the search returned; on an edge (the opposite
    // corner's weight 0): a boundary edge.
    for (int k = 0; k < 3; ++k)
      if (w[(k + 1) % 3] <= 1e-12 && w[(k + 2) % 3] <= 1e-12) return boundaryVertex[t[k]] != 0;
    for (int k = 0; k < 3; ++k)
      if (w[k] <= 1e-12 && edgeUse.at(std::minmax(t[(k + 1) % 3], t[(k + 2) % 3])) == 1) return true;
    return false;
  };
  auto faceOf = [&](int triangle) {
    const auto it = std::upper_bound(mesh.faceTriangleStart.begin(), mesh.faceTriangleStart.end(),
                                     static_cast<std::uint32_t>(triangle));
    return static_cast<int>(it - mesh.faceTriangleStart.begin()) - 1;
  };
  std::vector<double> distance(points.size());
  std::vector<char> excluded(points.size(), 0);
  parallel::parallelFor(std::size_t(0), points.size(), [&](std::size_t i) {
    const Vec3 &p = points[i];
    const TriangleBvh::Hit hit = bvh.closest(p);
    if (onBoundary(hit)) {
      excluded[i] = 1;
      return;
    }
    Vec3 foot = hit.point, normal = normalized(cross(mesh.positions[mesh.triangles[hit.triangle][1]] -
                                                         mesh.positions[mesh.triangles[hit.triangle][0]],
                                                     mesh.positions[mesh.triangles[hit.triangle][2]] -
                                                         mesh.positions[mesh.triangles[hit.triangle][0]]));
    // Gauss–Newton on the patch from the barycentric domain point, when all
    // three corners were evaluated on this triangle's face.
    const int face = faceOf(hit.triangle);
    const auto &t = mesh.triangles[hit.triangle];
    bool sameFace = true;
    for (std::uint32_t v : t) sameFace = sameFace && mesh.domainPoints[v].face == face;
    if (sameFace) {
      Vec2 uv = mesh.domainPoints[t[0]].uv * hit.barycentric.x + mesh.domainPoints[t[1]].uv * hit.barycentric.y +
                mesh.domainPoints[t[2]].uv * hit.barycentric.z;
      for (int it = 0; it < 6; ++it) {
        const SurfacePoint s = surface.evaluate(face, uv);
        const Vec3 r = p - s.point;
        const double a = dot(s.du, s.du), b = dot(s.du, s.dv), c = dot(s.dv, s.dv);
        const double gu = dot(s.du, r), gv = dot(s.dv, r), det = a * c - b * b;
        if (!(det > 0)) break;
        const Vec2 next = uv + Vec2{(c * gu - b * gv) / det, (a * gv - b * gu) / det};
        if (!insideDomain(surface, face, next)) break;
        uv = next;
      }
      const SurfacePoint s = surface.evaluate(face, uv);
      if (squaredNorm(p - s.point) <= hit.squaredDistance * (1 + 1e-9) + 1e-30) foot = s.point, normal = s.normal;
    }
    if (!normals.empty() && dot(normals[i], normal) < 0.5) {
      excluded[i] = 1;
      return;
    }
    const Vec3 d = p - foot;
    distance[i] = std::copysign(norm(d), dot(d, normal));
  });
  DeviationFigures fig;
  double sum = 0;
  bool first = true;
  for (size_t i = 0; i < points.size(); ++i) {
    if (excluded[i]) {
      ++fig.excluded;
      continue;
    }
    const double d = distance[i] / diagonal;
    fig.minSigned = first ? d : std::min(fig.minSigned, d);
    fig.maxSigned = first ? d : std::max(fig.maxSigned, d);
    fig.maxAbs = std::max(fig.maxAbs, std::abs(d));
    sum += std::abs(d);
    ++fig.samples;
    first = false;
  }
  if (fig.samples > 0) fig.meanAbs = sum / static_cast<double>(fig.samples);
  return fig;
}

ApproximationResult approximateMesh(const Mesh &mesh, const NetworkDescription &curves,
                                    const ApproximationOptions &options) {
  if (options.resolution < 2) throw InputError("", "resolution", "must be at least 2");
  if (options.fitRadius < 0 || !std::isfinite(options.fitRadius))
    throw InputError("", "fit radius", "must be ≥ 0 (0 = automatic)");
  auto reference = std::make_shared<const MeshReference>(mesh, options.fitRadius);
  NetworkDescription description = fitPolylineCurves(curves);
  description.reference = ReferenceSurface::fromMesh(reference);
  const double diagonal = mesh.bounds().diagonal();

  SurfaceOptions g1Options;
  g1Options.scheme = Scheme::GregoryG1;
  g1Options.fenceNormals = FenceNormals::Reference;
  SurfaceOptions g2Options;
  g2Options.scheme = Scheme::GregoryG2;
  g2Options.fenceNormals = FenceNormals::Reference;
  g2Options.edgeCurvature = EdgeCurvature::Reference;

  Network network = Network::build(description);
  Surface g1 = Surface::build(network, g1Options);
  Surface g2 = Surface::build(network, g2Options);
  ApproximationResult result{network, g1, g2};
  result.diagonal = diagonal;
  const std::vector<Vec3> &normals = reference->mesh().normals;
  result.g1Deviation =
      measurePointDeviation(g1, mesh.positions, diagonal, options.resolution, options.threads, normals);
  result.g2Deviation =
      measurePointDeviation(g2, mesh.positions, diagonal, options.resolution, options.threads, normals);
  for (const Segment &seg : network.segments())
    for (int k = 0; k <= 32; ++k)
      result.curveDistance =
          std::max(result.curveDistance, std::abs(reference->signedDistance(seg.curve.point(k / 32.0))) / diagonal);
  if (options.curvatureSamples > 0) {
    CurvatureJumpOptions jump;
    jump.samplesPerSegment = std::max(2, options.curvatureSamples);
    jump.endExclusion = 0.05;
    result.g1CurvatureJump = measureCurvatureJump(g1, jump).maxJump;
    result.g2CurvatureJump = measureCurvatureJump(g2, jump).maxJump;
  }
  return result;
}

namespace {

/// Subdivided icosahedron on the unit sphere, `levels` times 4-to-1.
Mesh icosphere(int levels) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  Mesh m;
  m.positions = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                 {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (Vec3 &p : m.positions) p = normalized(p);
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      auto [it, fresh] = midpoints.try_emplace(std::minmax(a, b), static_cast<std::uint32_t>(m.positions.size()));
      if (fresh) m.positions.push_back(normalized(m.positions[a] + m.positions[b]));
      return it->second;
    };
    std::vector<std::array<std::uint32_t, 3>> next;
    for (const auto &t : m.triangles) {
      const std::uint32_t a = mid(t[0], t[1]), b = mid(t[1], t[2]), c = mid(t[2], t[0]);
      next.push_back({t[0], a, c});
      next.push_back({t[1], b, a});
      next.push_back({t[2], c, b});
      next.push_back({a, b, c});
    }
    m.triangles = std::move(next);
  }
  return m;
}

/// Periodic or open (u, v) grid triangulated along alternating diagonals.
void gridTriangles(Mesh &m, int nu, int nv, bool periodicU, bool periodicV) {
  const int cu = periodicU ? nu : nu + 1, cv = periodicV ? nv : nv + 1;
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>((i % cu) + cu * (j % cv)); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const std::uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) m.triangles.push_back({a, b, c}), m.triangles.push_back({a, c, d});
      else m.triangles.push_back({a, b, d}), m.triangles.push_back({b, c, d});
    }
}

} // namespace

Mesh triangulateReference(const ReferenceSurface &reference, double edge, const BoundingBox &region) {
  if (!(edge > 0)) throw InputError("", "edge", "must be positive");
  Mesh m;
  switch (reference.kind) {
  case ReferenceSurface::Kind::Ellipsoid: {
    // Icosahedron edge on the unit sphere ≈ 1.05; each level halves it.
    const double scale = std::max({reference.size.x, reference.size.y, reference.size.z});
    int levels = 0;
    while (1.05 * scale / std::pow(2.0, levels) > edge && levels < 9) ++levels;
    m = icosphere(levels);
    for (Vec3 &p : m.positions)
      p = reference.center + Vec3{p.x * reference.size.x, p.y * reference.size.y, p.z * reference.size.z};
    break;
  }
  case ReferenceSurface::Kind::Torus: {
    const double R = reference.size.x, r = reference.size.y;
    const int nu = std::max(8, static_cast<int>(std::ceil(2 * std::numbers::pi * (R + r) / edge)));
    const int nv = std::max(6, static_cast<int>(std::ceil(2 * std::numbers::pi * r / edge)));
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) {
        const double theta = 2 * std::numbers::pi * i / nu, phi = 2 * std::numbers::pi * j / nv;
        const double rho = R + r * std::cos(phi);
        m.positions.push_back(reference.center + Vec3{rho * std::cos(theta), rho * std::sin(theta), r * std::sin(phi)});
      }
    gridTriangles(m, nu, nv, true, true);
    break;
  }
  case ReferenceSurface::Kind::Graph: {
    if (region.empty()) throw InputError("", "region", "a graph needs the xy region to triangulate");
    const int nu = std::max(2, static_cast<int>(std::ceil((region.max.x - region.min.x) / edge)));
    const int nv = std::max(2, static_cast<int>(std::ceil((region.max.y - region.min.y) / edge)));
    for (int j = 0; j <= nv; ++j)
      for (int i = 0; i <= nu; ++i) {
        const double x = region.min.x + (region.max.x - region.min.x) * i / nu;
        const double y = region.min.y + (region.max.y - region.min.y) * j / nv;
        const double lx = x - reference.center.x, ly = y - reference.center.y;
        m.positions.push_back({x, y, reference.center.z + reference.size.x * lx * lx + reference.size.y * ly * ly});
      }
    gridTriangles(m, nu, nv, false, false);
    break;
  }
  case ReferenceSurface::Kind::Mesh: throw InputError("", "reference", "already a mesh");
  }
  return m;
}

NetworkDescription polylineNetwork(const NetworkDescription &description, int intervals) {
  if (intervals < 1) throw InputError("", "intervals", "must be at least 1");
  NetworkDescription out = description;
  out.reference.reset();
  for (BSplineCurve &curve : out.curves) {
    const double t0 = curve.domainStart(), t1 = curve.domainEnd();
    std::vector<double> knots{t0};
    std::vector<Vec3> points;
    for (int k = 0; k <= intervals; ++k) {
      const double t = k == intervals ? t1 : t0 + (t1 - t0) * k / intervals;
      knots.push_back(t);
      points.push_back(curve.point(t));
    }
    knots.push_back(t1);
    curve = BSplineCurve(1, std::move(knots), std::move(points));
  }
  return out;
}

} // namespace v1
} // namespace curvenet
