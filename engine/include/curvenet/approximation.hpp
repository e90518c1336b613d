// curvenet/approximation.hpp — transfinite surfaces fitted to a triangle mesh
// ([SV14] Sec. 5.3, Fig. 10).
//
// Input: a triangle mesh and a curve network drawn on it. Curves given as
// polylines — degree-1 B-splines in the native format, one point per knot —
// are fitted by cubic B-splines interpolating the polyline points at the
// polyline's own parameters (its knots), so face sides keep their parameter
// ranges; curves of higher degree are used as they are. The mesh becomes the
// network's reference surface (ReferenceSurface::Kind::Mesh, a local quadric
// fit, curvenet/mesh_reference.hpp), and two surfaces are built:
//  * G¹: gregory-g1 whose normal fences sample the mesh normals
//    (FenceNormals::Reference) — "normals only";
//  * G²: gregory-g2 with the same fences from the mesh and the transversal
//    curvature of every edge from the mesh's quadric fit
//    (EdgeCurvature::Reference; vertex tensors too) — "normals + curvatures".
// The figure of merit is the signed distance of every mesh vertex from each
// surface, relative to the mesh's bounding-box diagonal (Fig. 10 form:
// min, max, mean of |d|).
//
// Deviation method: each surface is tessellated at `resolution`, the closest
// point on its triangles is found (bounding-volume hierarchy), then refined by
// Gauss–Newton on the patch of that triangle's face (exact first
// derivatives) while it stays inside the face's domain; the sign is that of
// the patch normal. Mesh vertices whose closest point lies on the open
// boundary of the tessellation (beyond the network), or whose vertex normal
// is more than 60° from the surface normal there (another sheet of the mesh),
// are left out and counted.
//
// Thread-safety: functions are reentrant; cost is dominated by the reference
// queries of Surface::build (one quadric fit per fence and curvature sample)
// and by one closest-point query per mesh vertex per surface.
#pragma once

#include <cstddef>

#include "curvenet/mesh.hpp"
#include "curvenet/network.hpp"
#include "curvenet/surface.hpp"

namespace curvenet {
inline namespace v1 {

/// Replaces every degree-1 curve (a polyline) by the cubic B-spline that
/// interpolates its points at its knots (needs ≥ 2 points; 2 or 3 points
/// give a curve of degree 1 or 2). Other curves and everything else are kept.
NetworkDescription fitPolylineCurves(const NetworkDescription &description);

/// Signed deviation figures, relative to a diagonal.
struct DeviationFigures {
  double minSigned = 0, maxSigned = 0; ///< most negative and most positive d / diagonal
  double maxAbs = 0, meanAbs = 0;      ///< max and mean |d| / diagonal
  std::size_t samples = 0;             ///< points measured
  std::size_t excluded = 0;            ///< points beyond the surface's open boundary
};

struct ApproximationOptions {
  int resolution = 24;    ///< tessellation rows per face for the deviation, ≥ 2
  double fitRadius = 0;   ///< quadric-fit radius (mesh units); 0 = 3 mean edge lengths
  int curvatureSamples = 9; ///< per shared segment, for the curvature-jump figures (0 = skip)
  int threads = 0;        ///< 0 = all cores
};

struct ApproximationResult {
  Network network;       ///< fitted curves with the mesh as reference
  Surface g1, g2;        ///< gregory-g1 / gregory-g2 as described above
  double diagonal = 0;   ///< of the mesh bounding box
  DeviationFigures g1Deviation, g2Deviation; ///< mesh vertices → surface
  double curveDistance = 0; ///< max distance of the fitted curves from the mesh / diagonal
  double g1CurvatureJump = 0, g2CurvatureJump = 0; ///< max, curvenet/curvature_jump.hpp (0 when skipped)
};

/// Fits the polylines, attaches the mesh, builds both surfaces and measures
/// them. InputError for a bad mesh or network (naming the element), or for
/// options out of range.
ApproximationResult approximateMesh(const Mesh &mesh, const NetworkDescription &curves,
                                    const ApproximationOptions &options = {});

/// Signed distance of `points` from `surface` as described above, relative
/// to `diagonal`. With `normals` (one unit normal per point, e.g. the mesh's
/// vertex normals) a point whose normal is more than 60° from the surface
/// normal at its closest point is also left out: it belongs to another part
/// of the mesh (the far side of a closed mesh under an open network).
DeviationFigures measurePointDeviation(const Surface &surface, const std::vector<Vec3> &points, double diagonal,
                                       int resolution, int threads = 0, const std::vector<Vec3> &normals = {});

// Test data: meshes and polylines from the analytic built-ins.

/// Triangulates an analytic reference surface with edges of about `edge`
/// (mesh units): ellipsoid — a subdivided icosahedron mapped onto it; torus —
/// a (θ, φ) grid; graph — a grid over `region`'s xy extent. Every vertex lies
/// on the surface; triangles are counter-clockwise seen from the normal side.
/// InputError for Kind::Mesh or edge ≤ 0.
Mesh triangulateReference(const ReferenceSurface &reference, double edge, const BoundingBox &region = {});

/// The description with every curve replaced by the polyline through
/// `intervals` + 1 of its points, uniform in its parameter (so sides keep
/// their ranges), and no reference surface: the analytic form is forgotten.
NetworkDescription polylineNetwork(const NetworkDescription &description, int intervals);

} // namespace v1
} // namespace curvenet
