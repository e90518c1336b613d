// curvenet/mesh.hpp — triangle meshes produced by tessellation.
//
// One vertex array shared by all faces of the network: a point on a shared
// boundary is stored once and used by the triangles of both faces, so the
// mesh is watertight by construction. Normals are per vertex, computed from
// the exact surface derivatives (not averaged from triangles).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "curvenet/vec.hpp"

namespace curvenet {
inline namespace v1 {

/// Where the tessellator evaluated a mesh vertex: network face `face` at
/// point `uv` of that face's domain polygon (see surface.hpp). A vertex on a
/// boundary shared by several faces records the lowest-numbered face, the one
/// its normal came from; face = -1 for a vertex no face shows (an isolated
/// network vertex).
struct MeshDomainPoint {
  int face = -1;
  Vec2 uv;
};

struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals; ///< unit, same size as positions (may be empty)
  std::vector<std::array<std::uint32_t, 3>> triangles; ///< counter-clockwise seen from the normal side
  /// faceTriangleStart[f] .. faceTriangleStart[f+1]: triangles of network face f
  /// (size faces + 1; empty for meshes not made by the tessellator).
  std::vector<std::uint32_t> faceTriangleStart;
  /// Per vertex, the face and domain point it was evaluated at; filled only
  /// when TessellationOptions::recordDomainPoints is set (empty otherwise).
  /// Lets a caller evaluate further quantities (curvature, deviation) of the
  /// patch itself at exactly the mesh vertices.
  std::vector<MeshDomainPoint> domainPoints;

  BoundingBox bounds() const {
    BoundingBox b;
    for (const Vec3 &p : positions) b.add(p);
    return b;
  }
};

} // namespace v1
} // namespace curvenet
