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
#include "curvenet/progress.hpp"
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
  /// Evaluate face interiors through cached evaluation plans (DESIGN.md §4):
  /// the geometry-free part of every sample (sweepline roots, blends) is
  /// computed once per (scheme, sides, resolution, sweepline) and shared by
  /// all faces and calls; the patch then costs its ribbon evaluations plus
  /// SIMD weighted sums. The points equal Surface::evaluate's to ~1e-12
  /// relative. false: evaluate every sample through Surface::evaluate.
  bool usePlans = true;
  /// Optional: the fraction of face-interior samples evaluated so far, on the
  /// calling thread, at most every 50 ms, ending with 1 (curvenet/progress.hpp).
  ProgressCallback progress;
};

/// The process-wide cache of evaluation plans: how many are built and the
/// bytes they hold. Thread-safe.
struct PlanCacheStats {
  std::size_t plans = 0, bytes = 0;
};
PlanCacheStats evaluationPlanCache();
/// Drops every cached plan (tessellations in flight keep theirs alive); the
/// next tessellation builds them again — a cold start. Thread-safe.
void clearEvaluationPlans();

/// Vertices per face interior + boundaries, a quick estimate for memory checks.
std::size_t estimateMeshVertices(const Surface &surface, int resolution);

/// Tessellates every face (see the file comment). Parallel over faces and,
/// for large faces, over tiles of samples (explicit grain sizes); small
/// inputs run serially. Memory: the mesh plus the plans (about 90 bytes per
/// sample of each distinct (sides, resolution)). Thread-safe.
Mesh tessellate(const Surface &surface, const TessellationOptions &options = {});

} // namespace v1
} // namespace curvenet
