// curvenet/reference.hpp — analytic reference surfaces.
//
// A network may carry the surface it was cut from (every built-in does; a
// native file may name one). Quality figures measure against it: deviation of
// the tessellation, and the exact normals and principal curvatures that the
// `reference` fence and curvature sources use. Values are immutable and safe
// to share across threads.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "curvenet/vec.hpp"

namespace curvenet {
inline namespace v1 {

/// Differential geometry of a surface at one point: unit normal (outward for
/// closed surfaces, +z side for graphs), principal curvatures κ1 ≥ κ2 in the
/// sign convention κ = II(t,t) with II = −dN·dP (a sphere of radius r with
/// outward normal has κ1 = κ2 = −1/r), and the unit principal direction e1 of
/// κ1 (e2 = N × e1).
struct SurfaceFrame {
  Vec3 point, normal;
  double k1 = 0, k2 = 0;
  Vec3 direction1;
  /// Normal curvature in the unit tangent direction t (Euler's formula).
  double normalCurvature(const Vec3 &t) const;
};

class MeshReference; // curvenet/mesh_reference.hpp

struct ReferenceSurface {
  enum class Kind {
    Ellipsoid, ///< (x/a)² + (y/b)² + (z/c)² = 1 around `center`, a,b,c = size
    Torus,     ///< ring radius R = size.x, tube radius r = size.y, axis z, around `center`
    Graph,     ///< z = a x² + b y² over the xy-plane, a = size.x, b = size.y, shifted by `center`
    /// A triangle mesh ([SV14] Sec. 5.3): closest points on its triangles,
    /// normals and curvatures by a local quadric fit (curvenet/mesh_reference.hpp).
    /// `mesh` must be set; center and size are unused. Never read from or
    /// written to a network file (the mesh is a separate input).
    Mesh,
  };
  Kind kind = Kind::Ellipsoid;
  Vec3 center;
  Vec3 size{1, 1, 1};
  std::shared_ptr<const MeshReference> mesh; ///< Kind::Mesh only

  /// A mesh-backed reference.
  static ReferenceSurface fromMesh(std::shared_ptr<const MeshReference> mesh);

  /// Short name: "ellipsoid", "torus", "graph", "mesh". kindFromName knows
  /// only the analytic kinds (the ones a network file may name).
  static std::string kindName(Kind kind);
  static std::optional<Kind> kindFromName(const std::string &name);

  /// Implicit function value: zero on the surface, with gradient ≠ 0 there
  /// (Kind::Mesh: the signed distance).
  double implicit(const Vec3 &p) const;
  /// Closest surface point to p with its frame (Newton projection, robust for
  /// points within a fraction of the smallest curvature radius).
  SurfaceFrame closest(const Vec3 &p) const;
  /// Signed distance (positive on the normal side) from p to the surface.
  double signedDistance(const Vec3 &p) const;
};

} // namespace v1
} // namespace curvenet
