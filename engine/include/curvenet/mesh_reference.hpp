// curvenet/mesh_reference.hpp — a triangle mesh used as the reference surface.
//
// [SV14] Sec. 5.3 approximates a mesh by transfinite patches over a curve
// network drawn on it: the normal fences (G¹) and also the transversal
// curvatures (G²) along the curves are estimated from the mesh. A
// MeshReference answers the same question an analytic ReferenceSurface does —
// "closest surface point to p, with normal and principal curvatures" — so the
// existing FenceNormals::Reference and EdgeCurvature::Reference paths of
// Surface::build use it unchanged (ReferenceSurface::Kind::Mesh).
//
// Estimation (the "local quadric fit"):
//  1. the closest point c on the triangles (bounding-volume hierarchy, exact);
//  2. the initial normal n0: the area-weighted vertex normals interpolated
//     barycentrically on c's triangle;
//  3. every mesh vertex q within radius r of c whose vertex normal is within
//     60° of n0 (so the far side of a thin part is never used), in the frame
//     (e1, e2, n0) at c: (x, y, z) = coordinates of q − c;
//  4. weighted least squares z = f + d x + e y + a x² + b xy + c y² with
//     weights (1 − |q − c|²/r²)³, which vanish smoothly at the radius so the
//     estimate varies smoothly with the query point (fences and curvatures
//     sampled along a curve are differentiated twice by the G² ribbons);
//  5. the fit is repeated once in the frame of the fitted normal at the
//     fitted point, so the final frame is tangent (d, e ≈ 0) and the
//     curvature is read where the quadric is most accurate;
//  6. point = c + f n, normal = (−d, −e, 1)/w, and the shape operator from the
//     second fundamental form [2a b; b 2c]/w against the first [1+d² de; de 1+e²].
// r is `fitRadius` (mesh units) or, when 0, 3 × the mean edge length; it
// grows by 1.5× (up to 4 times) until at least 12 vertices take part. When no
// fit is possible the frame falls back to the mesh normal with zero curvature.
//
// The curvature error of the fit is O(r · |∇κ|) plus the mesh's own
// discretization; the position error of a vertex-exact mesh is O(r³ · |∇κ|).
//
// Thread-safety: immutable after construction; every query may run from
// any number of threads at once. Cost: construction O(T log T) for T
// triangles; a query O(log T) plus the fit over the vertices within r.
#pragma once

#include <memory>
#include <vector>

#include "curvenet/mesh.hpp"
#include "curvenet/reference.hpp"

namespace curvenet {
inline namespace v1 {

class MeshReference {
public:
  /// `mesh` needs positions and at least one triangle (normals are ignored and
  /// recomputed from the triangles, counter-clockwise = outward); InputError
  /// (element "mesh") when it has none or an index is out of range.
  explicit MeshReference(const Mesh &mesh, double fitRadius = 0);
  ~MeshReference();
  MeshReference(const MeshReference &) = delete;
  MeshReference &operator=(const MeshReference &) = delete;

  /// Closest point on the triangles, its triangle and barycentric coordinates.
  struct Hit {
    Vec3 point;
    int triangle = -1;
    Vec3 barycentric;
    double distance = 0;
  };
  Hit closestOnTriangles(const Vec3 &p) const;

  /// The local quadric frame at the point of the mesh closest to p (see above).
  SurfaceFrame closest(const Vec3 &p) const;

  /// Signed distance from p to the triangles, positive on the side the
  /// interpolated vertex normals point to.
  double signedDistance(const Vec3 &p) const;

  const Mesh &mesh() const;
  /// The radius the fits use (mesh units).
  double fitRadius() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace v1
} // namespace curvenet
