// MeshReference: closest point and local quadric frame on a triangle mesh
// (curvenet/mesh_reference.hpp).
#include "curvenet/mesh_reference.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "approximation/triangle_bvh.hpp"
#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

namespace {
constexpr double kDefaultRadiusEdges = 3.0; // fit radius in mean edge lengths
constexpr int kMinimumFitVertices = 12;
constexpr double kNormalCone = 0.5; // cos 60°: vertices facing further away are another sheet

Vec3 anyPerpendicular(const Vec3 &n) {
  const Vec3 axis = std::abs(n.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  return normalized(axis - n * dot(axis, n));
}

/// Principal curvatures and direction of the symmetric form [a b; b c] in the
/// orthonormal tangent basis (u, v).
void principal(double a, double b, double c, const Vec3 &u, const Vec3 &v, SurfaceFrame &f) {
  const double mean = 0.5 * (a + c), half = std::hypot(0.5 * (a - c), b);
  f.k1 = mean + half, f.k2 = mean - half;
  Vec3 e1 = u;
  if (half > 1e-14 * (std::abs(mean) + 1e-300)) {
    const double x1 = b, y1 = f.k1 - a, x2 = f.k1 - c, y2 = b;
    e1 = x1 * x1 + y1 * y1 >= x2 * x2 + y2 * y2 ? u * x1 + v * y1 : u * x2 + v * y2;
    e1 = normalized(e1);
  }
  f.direction1 = e1;
}
} // namespace

struct MeshReference::Impl {
  Mesh mesh;
  std::vector<Vec3> vertexNormals;
  TriangleBvh bvh;
  double radius = 0;
  // Uniform grid of the vertices, cell size = radius.
  double cell = 1;
  std::unordered_map<std::uint64_t, std::vector<int>> grid;

  std::uint64_t key(long long i, long long j, long long k) const {
    // 21 bits per axis (offset so negatives stay distinct).
    constexpr long long bias = 1 << 20;
    return (std::uint64_t(i + bias) << 42) | (std::uint64_t(j + bias) << 21) | std::uint64_t(k + bias);
  }
  /// The grid index of coordinate x, clamped to ±2⁴⁰ cells: a vertex far
  /// from the rest (a mesh may hold unreferenced vertices anywhere; the
  /// radius comes from its triangles) would otherwise convert a quotient
  /// beyond long long's range, which is undefined. Clamped cells share keys
  /// with others (key() keeps 21 bits an axis anyway); visits compare
  /// distances, so sharing costs time, never a wrong neighbour.
  long long cellOf(double x) const {
    constexpr double kLimit = 0x1p40;
    const double q = std::floor(x / cell);
    return static_cast<long long>(q > -kLimit ? (q < kLimit ? q : kLimit) : -kLimit); // NaN: −kLimit
  }

  template <class F> void forEachWithin(const Vec3 &p, double r, F &&visit) const {
    const double r2 = r * r;
    for (long long i = cellOf(p.x - r); i <= cellOf(p.x + r); ++i)
      for (long long j = cellOf(p.y - r); j <= cellOf(p.y + r); ++j)
        for (long long k = cellOf(p.z - r); k <= cellOf(p.z + r); ++k) {
          auto it = grid.find(key(i, j, k));
          if (it == grid.end()) continue;
          for (int v : it->second)
            if (squaredNorm(mesh.positions[v] - p) <= r2) visit(v);
        }
  }

  /// Weighted quadric fit in the frame (u, v, n) at origin o; false when the
  /// neighbourhood is too small or degenerate. Coefficients f, d, e, a, b, c
  /// of z = f + d x + e y + a x² + b xy + c y².
  bool fit(const Vec3 &o, const Vec3 &n, Eigen::Matrix<double, 6, 1> &coef) const {
    const Vec3 u = anyPerpendicular(n), v = cross(n, u);
    double r = radius;
    for (int attempt = 0; attempt < 5; ++attempt, r *= 1.5) {
      Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
      Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
      int count = 0;
      forEachWithin(o, r, [&](int k) {
        if (dot(vertexNormals[k], n) < kNormalCone) return;
        const Vec3 q = mesh.positions[k] - o;
        const double x = dot(q, u) / r, y = dot(q, v) / r, z = dot(q, n);
        // Scaled coordinates keep the normal equations well conditioned. The
        // weight falls to zero with two vanishing derivatives at the radius,
        // so a vertex entering or leaving the neighbourhood changes the fit
        // smoothly: fences and curvatures sampled along a curve stay smooth
        // enough to be differentiated twice (parabolic ribbons need N'').
        const double t = 1 - squaredNorm(q) / (r * r);
        const double w = t * t * t;
        Eigen::Matrix<double, 6, 1> row;
        row << 1, x, y, x * x, x * y, y * y;
        A += w * row * row.transpose();
        rhs += w * z * row;
        ++count;
      });
      if (count < kMinimumFitVertices) continue;
      const auto ldlt = A.ldlt();
      if (ldlt.info() != Eigen::Success) continue;
      coef = ldlt.solve(rhs);
      if (!coef.allFinite()) continue;
      coef(1) /= r, coef(2) /= r;
      coef(3) /= r * r, coef(4) /= r * r, coef(5) /= r * r;
      return true;
    }
    return false;
  }

  SurfaceFrame frameAt(const Vec3 &o, const Vec3 &n0, Vec3 &originOut, Vec3 &normalOut, bool &ok) const {
    Eigen::Matrix<double, 6, 1> c;
    SurfaceFrame f;
    f.point = o, f.normal = n0, f.direction1 = anyPerpendicular(n0);
    ok = fit(o, n0, c);
    if (!ok) return f;
    const Vec3 u = anyPerpendicular(n0), v = cross(n0, u);
    const double d = c(1), e = c(2), w = std::sqrt(1 + d * d + e * e);
    const Vec3 normal = normalized(n0 - u * d - v * e);
    f.point = o + n0 * c(0);
    f.normal = normal;
    // Tangent basis of the fitted normal; a tangent t has frame coordinates
    // (t·u, t·v) as a combination of X_x, X_y, so II(t, t) = [tx ty] H [tx ty]ᵀ / w.
    const Vec3 tu = anyPerpendicular(normal), tv = cross(normal, tu);
    auto form = [&](const Vec3 &s, const Vec3 &t) {
      const double sx = dot(s, u), sy = dot(s, v), tx = dot(t, u), ty = dot(t, v);
      return (2 * c(3) * sx * tx + c(4) * (sx * ty + sy * tx) + 2 * c(5) * sy * ty) / w;
    };
    principal(form(tu, tu), form(tu, tv), form(tv, tv), tu, tv, f);
    originOut = f.point, normalOut = normal;
    return f;
  }
};

MeshReference::MeshReference(const Mesh &mesh, double fitRadius) : impl_(std::make_unique<Impl>()) {
  Impl &m = *impl_;
  if (mesh.positions.empty() || mesh.triangles.empty())
    throw InputError("", "mesh", "needs vertices and at least one triangle");
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (std::uint32_t i : mesh.triangles[t])
      if (i >= mesh.positions.size())
        throw InputError("", "mesh triangle " + std::to_string(t), "vertex index out of range");
  m.mesh.positions = mesh.positions;
  m.mesh.triangles = mesh.triangles;
  // Area-weighted vertex normals (the cross product's length is twice the area).
  m.vertexNormals.assign(mesh.positions.size(), Vec3{});
  double edgeSum = 0;
  for (const auto &tri : mesh.triangles) {
    const Vec3 &a = mesh.positions[tri[0]], &b = mesh.positions[tri[1]], &c = mesh.positions[tri[2]];
    const Vec3 n = cross(b - a, c - a);
    for (std::uint32_t i : tri) m.vertexNormals[i] += n;
    edgeSum += norm(b - a) + norm(c - b) + norm(a - c);
  }
  for (Vec3 &n : m.vertexNormals)
    if (squaredNorm(n) > 0) n = normalized(n);
  m.mesh.normals = m.vertexNormals;
  const double meanEdge = edgeSum / (3.0 * static_cast<double>(mesh.triangles.size()));
  m.radius = fitRadius > 0 ? fitRadius : kDefaultRadiusEdges * meanEdge;
  if (!(m.radius > 0) || !std::isfinite(m.radius)) throw InputError("", "mesh", "degenerate triangles (zero edge length)");
  m.cell = m.radius;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3 &p = mesh.positions[v];
    m.grid[m.key(m.cellOf(p.x), m.cellOf(p.y), m.cellOf(p.z))].push_back(static_cast<int>(v));
  }
  m.bvh = TriangleBvh(m.mesh.positions, m.mesh.triangles);
}

MeshReference::~MeshReference() = default;

const Mesh &MeshReference::mesh() const { return impl_->mesh; }
double MeshReference::fitRadius() const { return impl_->radius; }

MeshReference::Hit MeshReference::closestOnTriangles(const Vec3 &p) const {
  const TriangleBvh::Hit h = impl_->bvh.closest(p);
  return {h.point, h.triangle, h.barycentric, std::sqrt(h.squaredDistance)};
}

namespace {
Vec3 interpolatedNormal(const Mesh &mesh, const std::vector<Vec3> &normals, int triangle, const Vec3 &bary) {
  const auto &tri = mesh.triangles[triangle];
  const Vec3 n = normals[tri[0]] * bary.x + normals[tri[1]] * bary.y + normals[tri[2]] * bary.z;
  if (squaredNorm(n) > 0) return normalized(n);
  const Vec3 &a = mesh.positions[tri[0]], &b = mesh.positions[tri[1]], &c = mesh.positions[tri[2]];
  return normalized(cross(b - a, c - a));
}
} // namespace

SurfaceFrame MeshReference::closest(const Vec3 &p) const {
  const Impl &m = *impl_;
  const TriangleBvh::Hit hit = m.bvh.closest(p);
  const Vec3 n0 = interpolatedNormal(m.mesh, m.vertexNormals, hit.triangle, hit.barycentric);
  Vec3 origin, normal;
  bool ok = false;
  SurfaceFrame first = m.frameAt(hit.point, n0, origin, normal, ok);
  if (!ok) return first;
  // Second pass in the tangent frame of the first fit, at the foot of p on it.
  const Vec3 foot = origin + (p - origin) - normal * dot(p - origin, normal);
  Vec3 origin2, normal2;
  bool ok2 = false;
  SurfaceFrame second = m.frameAt(foot, normal, origin2, normal2, ok2);
  return ok2 ? second : first;
}

double MeshReference::signedDistance(const Vec3 &p) const {
  const Impl &m = *impl_;
  const TriangleBvh::Hit hit = m.bvh.closest(p);
  const Vec3 n = interpolatedNormal(m.mesh, m.vertexNormals, hit.triangle, hit.barycentric);
  const Vec3 d = p - hit.point;
  return std::copysign(std::sqrt(hit.squaredDistance), dot(d, n));
}

} // namespace v1
} // namespace curvenet
