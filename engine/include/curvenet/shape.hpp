// curvenet/shape.hpp — does a built surface have a usable shape? The figures
// that catch a bad surface which the continuity figures (continuity.hpp)
// cannot: a patch can join its neighbours with G² to 1e-9 and still fold,
// or bulge out to a thousand times its boundary.
//
// Per face, on a fan sampling of its domain (each of the n triangles from
// the centre to a side split into resolution² parts, one point at the
// centroid of each, weighted by its surface area):
//  * folded — Surface::foldedFaces (the normal turns over inside the face);
//  * corner folds — the normal turning over near a corner, closer to it than
//    the fold grid samples (a corner whose two curves leave it in nearly the
//    same direction, where |du × dv| vanishes: ~5e-4 of the diagonal on a
//    few G² faces of the public sketches): each corner's neighbourhood on a
//    polar grid, 2e-4 to 0.2 of the way to the neighbouring corners;
//  * intersections — faces that pass through each other, or a face through
//    itself, without folding in its own parameters (a G² patch curling over
//    its neighbour along a thin tube: doghead.obj, bathtub.obj): the
//    surface's tessellations at 16 and at 32 intervals per segment are
//    searched for triangles of different faces that cross, triangles
//    sharing a mesh vertex left out; a pair of faces counts when both
//    resolutions find it (the chords of a coarse mesh can cross where the
//    surface does not, and those go as the resolution grows). A
//    transfinite face through itself as its build found it on its own
//    lattice (docs/surfaces.md, Intersections), which then sought a variant
//    that does not;
//  * excursion — how far the patch leaves the box of its boundary: the
//    growth of the bounding-box diagonal when the samples are added to the
//    box of the face's boundary curves (sampled at 8·resolution points per
//    side), relative to the model's diagonal. The boundary curves are the
//    ribbons' base: a patch that stays between its ribbons grows that box by
//    little more than its own bulge (the built-ins' faces by ≤ 0.5 % of the
//    diagonal, hemisphere-tjunction under gregory-g1), a patch carrying wrong
//    curvature into its interior by orders of magnitude more (the issue's
//    sketched network: thousands of times its size);
//  * fairness — the area mean of κ1² + κ2² over the face, divided by the arc
//    length mean of κ² along its boundary curves (floored by 1/diagonal²):
//    dimensionless, 2 for a sphere-cap face (κ1 = κ2 = κ of its great
//    circles) under gregory-g2, 3.7 under gregory-g1 (its corner twists);
//    large where the interior is much more curved than the curves that
//    define it.
//
// Thread-safety: reads the surface only; safe concurrently.
#pragma once

#include <vector>

#include "curvenet/surface.hpp"

namespace curvenet {
inline namespace v1 {

/// The excursion above which a face is rejected (check/tessellate/render
/// --strict): 10 % of the model's diagonal, twenty times the largest bulge
/// of a built-in's face over its boundary box (0.48 %).
inline constexpr double kExcursionBound = 0.1;

struct ShapeOptions {
  int resolution = 4; ///< fan subdivision per domain triangle, ≥ 1
};

/// A fold at corner `corner` of face `face`: neighbouring samples of its
/// polar grid whose normals point into opposite half-spaces.
struct CornerFold {
  int face = -1, corner = -1;
  /// How far from the corner's point the samples turned over against the
  /// grid's outer middle reach, relative to the model's diagonal.
  double extent = 0;
};

/// Faces `faceA` ≤ `faceB` whose surfaces pass through each other (the
/// same face: through itself), and a point where they do.
struct FaceIntersection {
  int faceA = -1, faceB = -1;
  Vec3 point;
};

struct FaceShape {
  int face = -1;
  bool folded = false;
  bool foldsAtCorner = false; ///< a CornerFold at one of its corners
  bool intersects = false;    ///< in a FaceIntersection
  double excursion = 0; ///< relative to the model's diagonal, ≥ 0
  double fairness = 0;  ///< dimensionless (see above)
  double area = 0;      ///< surface area of the samples (model units²)
};

struct ShapeReport {
  std::vector<FaceShape> faces; ///< by face index
  std::vector<int> foldedFaces;
  std::vector<CornerFold> cornerFolds; ///< by face, then corner
  std::vector<FaceIntersection> intersections; ///< by faceA, then faceB
  double maxExcursion = 0;
  int worstExcursionFace = -1;
  /// Area-weighted mean of the faces' fairness, and the largest.
  double fairness = 0, maxFairness = 0;
  int worstFairnessFace = -1;
  /// Faces that fold (inside or at a corner), pass through a face, or whose
  /// excursion exceeds kExcursionBound, ascending.
  std::vector<int> rejectedFaces;
  bool acceptable() const { return rejectedFaces.empty(); }
};

/// Cost: n·resolution² second-order evaluations per n-sided face (exact for
/// gregory-g2, 9 first-order evaluations otherwise), plus the boundary
/// samples, the corner grids and a tessellation at 16 intervals per segment
/// (at 32 too where faces cross at 16).
ShapeReport measureShape(const Surface &surface, const ShapeOptions &options = {});

} // namespace v1
} // namespace curvenet
