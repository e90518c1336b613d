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

struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals; ///< unit, same size as positions (may be empty)
  std::vector<std::array<std::uint32_t, 3>> triangles; ///< counter-clockwise seen from the normal side
  /// faceTriangleStart[f] .. faceTriangleStart[f+1]: triangles of network face f
  /// (size faces + 1; empty for meshes not made by the tessellator).
  std::vector<std::uint32_t> faceTriangleStart;

  BoundingBox bounds() const {
    BoundingBox b;
    for (const Vec3 &p : positions) b.add(p);
    return b;
  }
};

} // namespace v1
} // namespace curvenet
