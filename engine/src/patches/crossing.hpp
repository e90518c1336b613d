// Whether a patch passes through itself, which it can do without folding in
// its parameters (docs/surfaces.md, Intersections).
#pragma once

#include <optional>

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

} // namespace v1
} // namespace curvenet
