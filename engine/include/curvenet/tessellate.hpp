// curvenet/tessellate.hpp — one watertight triangle mesh for a whole network.
//
// Each face is sampled on its domain polygon with an n-fold symmetric
// pattern (n congruent centre–side triangles with `resolution` rows each).
// Every network vertex and every sample on a segment is one mesh vertex,
// shared by the faces on both sides: both sample a segment at the same curve
// parameters (u = j / resolution along the segment), so the mesh is
// watertight by construction. A face side that spans several segments (a
// T-node seen from the straight side) carries all their samples; its first
// row of triangles is zipped onto the regular pattern. Normals come from the
// exact surface derivatives.
//
// Output is deterministic: identical bytes for any thread count.
#pragma once

#include "curvenet/mesh.hpp"
#include "curvenet/surface.hpp"

namespace curvenet {
inline namespace v1 {

struct TessellationOptions {
  /// Intervals per segment and rows per centre–side triangle, ≥ 1. Segments
  /// bounding a 2-sided face use the next even number (their midpoint is a corner).
  int resolution = 16;
  /// Worker threads: 0 = all cores, 1 = serial.
  int threads = 0;
  /// Also fill Mesh::domainPoints (16 bytes more per vertex).
  bool recordDomainPoints = false;
};

/// Vertices per face interior + boundaries, a quick estimate for memory checks.
std::size_t estimateMeshVertices(const Surface &surface, int resolution);

Mesh tessellate(const Surface &surface, const TessellationOptions &options = {});

} // namespace v1
} // namespace curvenet
