// Whether a patch passes through itself (patches/crossing.hpp).
#include "patches/crossing.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "approximation/triangle_bvh.hpp"
#include "patches/patch.hpp"

namespace curvenet {
inline namespace v1 {

namespace {
/// The fan lattice at `rows` rows: lattice point (k, i, j) = i/rows corner
/// k + j/rows corner k+1 (the domain's centre is the origin); (k, 0, j) is
/// (k + 1, j, 0) and the centre is one point.
struct FanLattice {
  std::vector<DualVec3> points; ///< with their derivatives
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<char> boundary; ///< per point: on the domain's boundary (i + j = rows)
  int sides = 0, rows = 0;
};

/// The index of lattice point (k, i, j) of an n-sided domain's fan lattice.
std::uint32_t latticeId(int n, int rows, int k, int i, int j) {
  if (i == 0 && j == 0) return 0;
  if (i == 0) k = (k + 1) % n, i = j, j = 0;
  // Rows i = 1 … rows hold rows − i + 1 points each.
  const int before = (i - 1) * (rows + 1) - (i - 1) * i / 2;
  return static_cast<std::uint32_t>(1 + k * (rows * (rows + 1) / 2) + before + j);
}

std::size_t latticeSize(int n, int rows) { return static_cast<std::size_t>(1 + n * (rows * (rows + 1) / 2)); }

/// The fan lattice's triangles, and per point whether it lies on the
/// domain's boundary (i + j = rows).
void fanTriangles(int n, int rows, std::vector<std::array<std::uint32_t, 3>> &triangles, std::vector<char> &boundary) {
  auto id = [&](int k, int i, int j) { return latticeId(n, rows, k, i, j); };
  boundary.assign(latticeSize(n, rows), 0);
  for (int k = 0; k < n; ++k)
    for (int i = 1; i <= rows; ++i) boundary[id(k, i, rows - i)] = 1;
  triangles.clear();
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < rows; ++i)
      for (int j = 0; i + j < rows; ++j) {
        triangles.push_back({id(k, i, j), id(k, i + 1, j), id(k, i, j + 1)});
        if (i + j + 1 < rows) triangles.push_back({id(k, i + 1, j), id(k, i + 1, j + 1), id(k, i, j + 1)});
      }
}

FanLattice fanLattice(const Patch &patch, int rows) {
  const RegularDomain &domain = patch.domain();
  const int n = domain.sides();
  auto id = [&](int k, int i, int j) { return latticeId(n, rows, k, i, j); };
  std::vector<double> us(latticeSize(n, rows)), vs(us.size());
  for (int k = 0; k < n; ++k)
    for (int i = 1; i <= rows; ++i)
      for (int j = 0; i + j <= rows; ++j) {
        const Vec2 uv = domain.corner(k) * (double(i) / rows) + domain.corner(k + 1) * (double(j) / rows);
        us[id(k, i, j)] = uv.x, vs[id(k, i, j)] = uv.y;
      }
  FanLattice lattice;
  lattice.sides = n, lattice.rows = rows;
  fanTriangles(n, rows, lattice.triangles, lattice.boundary);
  lattice.points.resize(us.size());
  patch.evaluateBatch(us.size(), us.data(), vs.data(), lattice.points.data());
  return lattice;
}

/// True when every normal du × dv of the lattice points into the half-space
/// of their sum (false where one is not finite). The patch's projection onto
/// the plane normal to that sum is then a local diffeomorphism: it could
/// pass through itself only by winding its boundary loop around that axis,
/// as no face of the public models does, so the search is skipped — most
/// faces, which keeps the build's cost down.
bool normalsInOneHalfSpace(const FanLattice &lattice) {
  Vec3 sum{0, 0, 0};
  for (const DualVec3 &p : lattice.points) sum += normalized(cross(p.du, p.dv));
  return std::all_of(lattice.points.begin(), lattice.points.end(),
                     [&](const DualVec3 &p) { return dot(cross(p.du, p.dv), sum) > 0; });
}

/// Where two triangles of the lattice that share no lattice point cross
/// (trianglesCross); nullopt when none do. A patch can pass through itself
/// without folding in its parameters — its normal turning gradually over a
/// third of the face, so no two neighbouring samples of the fold grid
/// disagree by 90° (sewing_machine.obj's nearly flat face 36 under
/// gregory-g1 crossed itself in the middle of one centre–side triangle).
std::optional<Vec3> latticeCrossing(const FanLattice &lattice) {
  std::vector<Vec3> positions(lattice.points.size());
  for (std::size_t p = 0; p < positions.size(); ++p) positions[p] = lattice.points[p].v;
  const auto &triangles = lattice.triangles;
  std::optional<Vec3> crossing;
  TriangleBvh(positions, triangles).forEachOverlappingPair([&](int s, int t) {
    if (crossing) return;
    const auto &a = triangles[static_cast<std::size_t>(s)], &b = triangles[static_cast<std::size_t>(t)];
    for (const std::uint32_t v : a)
      if (v == b[0] || v == b[1] || v == b[2]) return;
    crossing = trianglesCross({positions[a[0]], positions[a[1]], positions[a[2]]},
                              {positions[b[0]], positions[b[1]], positions[b[2]]});
  });
  return crossing;
}

/// The box of the triangle (a, b, c).
BoundingBox triangleBox(const Vec3 &a, const Vec3 &b, const Vec3 &c) {
  BoundingBox box;
  box.add(a), box.add(b), box.add(c);
  return box;
}

/// Which triangles touch the boundary, and the box of the positions.
void finish(PatchLattice &lattice, const std::vector<char> &boundary) {
  lattice.onBoundary.resize(lattice.triangles.size());
  for (std::size_t t = 0; t < lattice.triangles.size(); ++t)
    lattice.onBoundary[t] = std::any_of(lattice.triangles[t].begin(), lattice.triangles[t].end(),
                                        [&](std::uint32_t v) { return boundary[v] != 0; });
  lattice.box = {};
  for (const Vec3 &p : lattice.positions) lattice.box.add(p);
}

PatchLattice asTriangles(const FanLattice &fan) {
  PatchLattice lattice;
  lattice.sides = fan.sides, lattice.rows = fan.rows;
  lattice.positions.resize(fan.points.size());
  lattice.normals.resize(fan.points.size());
  for (std::size_t p = 0; p < fan.points.size(); ++p)
    lattice.positions[p] = fan.points[p].v, lattice.normals[p] = normalized(cross(fan.points[p].du, fan.points[p].dv));
  lattice.triangles = fan.triangles;
  finish(lattice, fan.boundary);
  return lattice;
}
} // namespace

std::optional<Vec3> patchSelfCrossing(const Patch &patch, PatchLattice &coarseLattice) {
  const FanLattice coarse = fanLattice(patch, 24);
  coarseLattice = asTriangles(coarse);
  if (normalsInOneHalfSpace(coarse) || !latticeCrossing(coarse)) return std::nullopt;
  return latticeCrossing(fanLattice(patch, 48));
}

std::optional<Vec3> patchSelfCrossing(const Patch &patch) {
  PatchLattice coarse;
  return patchSelfCrossing(patch, coarse);
}

PatchLattice patchLattice(const Patch &patch, int rows) { return asTriangles(fanLattice(patch, rows)); }

PatchLattice halved(const PatchLattice &fine) {
  const int n = fine.sides, rows = fine.rows / 2;
  PatchLattice lattice;
  lattice.sides = n, lattice.rows = rows;
  lattice.positions.resize(latticeSize(n, rows)), lattice.normals.resize(lattice.positions.size());
  for (int k = 0; k < n; ++k)
    for (int i = 0; i <= rows; ++i)
      for (int j = 0; i + j <= rows; ++j) {
        const std::uint32_t to = latticeId(n, rows, k, i, j), from = latticeId(n, fine.rows, k, 2 * i, 2 * j);
        lattice.positions[to] = fine.positions[from], lattice.normals[to] = fine.normals[from];
      }
  std::vector<char> boundary;
  fanTriangles(n, rows, lattice.triangles, boundary);
  finish(lattice, boundary);
  return lattice;
}

void forEachLatticeCrossing(std::span<const PatchLattice *const> lattices,
                            const std::function<bool(int a, int b)> &touching,
                            const std::function<void(int a, int b, const Vec3 &point)> &visit,
                            const BoundingBox *within) {
  // Every lattice's triangles in one set, each remembering its lattice; the
  // set searched against itself.
  std::vector<Vec3> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<int> latticeOf;
  std::vector<char> onBoundary;
  for (std::size_t l = 0; l < lattices.size(); ++l) {
    if (!lattices[l]) continue;
    const PatchLattice &lattice = *lattices[l];
    const auto first = static_cast<std::uint32_t>(positions.size());
    positions.insert(positions.end(), lattice.positions.begin(), lattice.positions.end());
    for (std::size_t t = 0; t < lattice.triangles.size(); ++t) {
      const auto &tri = lattice.triangles[t];
      if (within && !within->meets(triangleBox(lattice.positions[tri[0]], lattice.positions[tri[1]], lattice.positions[tri[2]])))
        continue;
      triangles.push_back({first + tri[0], first + tri[1], first + tri[2]});
      latticeOf.push_back(static_cast<int>(l));
      onBoundary.push_back(lattice.onBoundary[t]);
    }
  }
  std::map<std::pair<int, int>, Vec3> found;
  std::map<std::pair<int, int>, bool> touchingPairs;
  TriangleBvh(positions, triangles).forEachOverlappingPair([&](int s, int t) {
    const auto S = static_cast<std::size_t>(s), T = static_cast<std::size_t>(t);
    if (latticeOf[S] == latticeOf[T]) return;
    const std::pair pair = std::minmax(latticeOf[S], latticeOf[T]);
    if (found.count(pair)) return;
    if (onBoundary[S] && onBoundary[T]) {
      auto [at, fresh] = touchingPairs.try_emplace(pair, false);
      if (fresh) at->second = touching(pair.first, pair.second);
      if (at->second) return;
    }
    const auto &a = triangles[S], &b = triangles[T];
    if (const std::optional<Vec3> x = trianglesCross({positions[a[0]], positions[a[1]], positions[a[2]]},
                                                     {positions[b[0]], positions[b[1]], positions[b[2]]}))
      found.emplace(pair, *x);
  });
  for (const auto &[pair, point] : found) visit(pair.first, pair.second, point);
}

} // namespace v1
} // namespace curvenet
