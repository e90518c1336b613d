// Whether a patch passes through itself, which it can do without folding in
// its parameters (docs/surfaces.md, Intersections).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "curvenet/vec.hpp"

namespace curvenet {
inline namespace v1 {

class Patch;

/// A point where the patch passes through itself: where two triangles of
/// its fan lattice (each centre–side triangle of the domain split into
/// rows² parts, the spokes' points shared) that share no lattice point
/// cross (trianglesCross), at 24 rows and again at 48 (a coarse lattice's
/// chords can cross where the patch does not: sewing_machine.obj's faces 6
/// and 7 under gregory-g1 at 24 rows, at neither 32, 48 nor 64; its face
/// 11 crosses from 24 rows on, not at 16); nullopt when they do not.
/// The patch's own lattice rather than the surface's tessellation, whose
/// strips stitching a face's rows to its segments' samples can cross near a
/// strongly bent side where the patch does not (sewing_machine.obj's faces
/// 6 and 7 under gregory-g1 at 16 and 32 intervals per segment). About
/// n·300 evaluations for an n-sided patch, n·1176 more where the first
/// lattice crosses.
std::optional<Vec3> patchSelfCrossing(const Patch &patch);

/// A patch's fan lattice at `rows` rows (see patchSelfCrossing) as
/// triangles, each marked when a corner lies on the domain's boundary.
struct PatchLattice {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals; ///< unit, per point
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<char> onBoundary; ///< per triangle
  BoundingBox box; ///< of the positions
  int sides = 0, rows = 0;
};
PatchLattice patchLattice(const Patch &patch, int rows);
/// The lattice at half the rows of `fine` (an even count), from its points.
PatchLattice halved(const PatchLattice &fine);

/// patchSelfCrossing, also giving the 24-row lattice it searched, for the
/// search between patches (forEachLatticeCrossing).
std::optional<Vec3> patchSelfCrossing(const Patch &patch, PatchLattice &coarse);

/// visit(a, b, point), a < b indices into `lattices`, for each pair of
/// lattices with two triangles that cross (trianglesCross), once a pair.
/// Triangles that both touch their domains' boundaries are not counted
/// when touching(a, b): patches that meet along a curve or at a corner
/// sample it apart, and their boundary chords can cross where the
/// patches only meet. Null lattices are skipped; with `within`, so are
/// triangles whose boxes miss it.
void forEachLatticeCrossing(std::span<const PatchLattice *const> lattices,
                            const std::function<bool(int a, int b)> &touching,
                            const std::function<void(int a, int b, const Vec3 &point)> &visit,
                            const BoundingBox *within = nullptr);

} // namespace v1
} // namespace curvenet
