// curvenet/tessellate.hpp — one watertight triangle mesh for a whole network.
//
// Each face is sampled on its domain polygon with an n-fold symmetric
// pattern (n congruent centre–side triangles with `resolution` rows each).
// Every network vertex and every sample on a segment is one mesh vertex,
// shared by the faces on both sides: both sample a segment at the same curve
// parameters (u = j / resolution along the segment), so the mesh is
// watertight by construction. Tessellating to a tolerance
// (TessellationOptions::tolerance) gives each segment its own interval count
// and each face its own rows, the sharing unchanged. A face side that spans several segments (a
// T-node seen from the straight side) carries all their samples; its first
// row of triangles is zipped onto the regular pattern. Normals come from the
// exact surface derivatives.
//
// Output is deterministic: identical bytes for any thread count.
#pragma once

#include <span>
#include <string>

#include <vector>

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
  /// Evaluate face interiors through cached evaluation plans (docs/design.md §4):
  /// the geometry-free part of every sample (sweepline roots, blends) is
  /// computed once per (scheme, sides, resolution, sweepline) and shared by
  /// all faces and calls; the patch then costs its ribbon evaluations (from
  /// per-patch quintic Hermite tables of the ribbons from resolution 32 on,
  /// built on first use) plus one SIMD kernel pass. The points equal
  /// Surface::evaluate's to ~1e-12 relative. false: evaluate every sample
  /// through Surface::evaluate.
  bool usePlans = true;
  /// Optional: the fraction of face-interior samples evaluated so far, on the
  /// calling thread, at most every 50 ms, ending with 1 (curvenet/progress.hpp;
  /// not called when tessellating to a tolerance).
  ProgressCallback progress;
  /// > 0: tessellate to this chordal tolerance, relative to the network's
  /// bounding-box diagonal, instead of one `resolution` everywhere: each
  /// face gets its own resolution (rows per centre–side triangle) and each
  /// segment its own intervals — the largest resolution of the faces along
  /// it, so both faces share its samples and the mesh stays watertight where
  /// neighbouring faces differ (the first row of each face is zipped onto
  /// its sides' samples). Chosen by measurement: every face starts at
  /// resolution 8; each pass measures every triangle of the mesh (the exact
  /// surface at the domain midpoints of its edges and at its centroid
  /// against the mesh) and re-resolves the faces that miss, the deviation
  /// taken to fall as 1/r² (at most 8 passes, each at most 4 times finer,
  /// within the memory available; TessellationReport says what was
  /// reached and what stopped it). In (0, 1); `resolution` is then ignored.
  double tolerance = 0;
  /// With `tolerance`: also keep the angle between the face's normals at
  /// the two ends of every mesh edge within this many degrees, [0, 90); 0 =
  /// no angle limit. (The face's own normals: a vertex shared with a face
  /// across a crease carries one of the two.)
  double angle = 0;
};

/// What a tessellation reached (tessellate with a report).
struct TessellationReport {
  double diagonal = 0;  ///< the network's bounding-box diagonal, which `deviation` is relative to
  /// The largest chordal deviation measured, relative to the diagonal: the
  /// exact surface at every triangle's edge midpoints and centroid (in its
  /// face's domain) against the mesh's linear interpolation there.
  double deviation = 0;
  double angle = 0;     ///< the largest angle between the normals at an edge's two ends, degrees
  std::size_t triangles = 0;
  int minResolution = 0, maxResolution = 0; ///< of the faces
  int passes = 0;       ///< tessellations made to choose the resolutions
  /// The smallest uniform resolution whose mesh, measured the same way,
  /// meets the same tolerance and angle, and its triangle count (with a
  /// fixed resolution: that resolution and this mesh's count); 0 and 0 when
  /// none with at most 32 times this mesh's vertices or 2²³ vertices,
  /// whichever is more (and within the memory available), does.
  int uniformResolution = 0;
  std::size_t uniformTriangles = 0;
  /// With a tolerance: whether every face met it, and the angle where asked
  /// of the face (not of angleUnreachableFaces).
  bool met = true;
  /// Faces whose largest angle between neighbouring normals did not fall as
  /// their resolution grew — normals that turn over within a sample spacing
  /// of a point whatever the spacing (a fold there, or a corner whose two
  /// curves leave it in nearly the same direction): refined for the
  /// tolerance alone.
  std::vector<int> angleUnreachableFaces;
  /// The memory available (80 % of it, memoryShortfall) stopped the
  /// refinement: the last pass was scaled back to fit.
  bool memoryLimited = false;
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

/// Vertices per face interior + boundaries, a quick estimate for memory
/// checks (saturates instead of overflowing for huge resolutions).
std::size_t estimateMeshVertices(const Surface &surface, int resolution);

/// The one check behind every refusal of work too large for the machine:
/// when `bytes` exceed 80% of the memory available now (Linux MemAvailable,
/// else the physical memory), "needs about X GiB of memory but only Y GiB is
/// available"; empty when they fit or the available memory is unknown.
std::string memoryShortfall(double bytes);

/// Tessellates every face (see the file comment). Parallel over faces and,
/// for large faces, over tiles of samples (explicit grain sizes); small
/// inputs run serially. Memory: the mesh plus the plans (about 90 bytes per
/// sample of each distinct (sides, resolution)). Thread-safe.
Mesh tessellate(const Surface &surface, const TessellationOptions &options = {});
/// tessellate() into `mesh`, reusing its storage: for repeated tessellation
/// (a viewer re-meshing after every edit, a benchmark) without allocating,
/// zeroing and faulting in a fresh mesh each time, which costs about as much
/// as the normals. The result equals tessellate(surface, options) byte for
/// byte, whatever `mesh` held before. Thread-safe for distinct meshes.
void tessellate(const Surface &surface, const TessellationOptions &options, Mesh &mesh);
/// The same with what it reached measured into `report`. Cost: with a
/// tolerance, the uniform comparison tessellates and measures the uniform
/// meshes of a bisection up to the largest face resolution (about log₂ of it
/// tessellations); without one, the mesh measured once.
Mesh tessellate(const Surface &surface, const TessellationOptions &options, TessellationReport &report);

/// Positions alone of every face's interior samples at options.resolution:
/// the points tessellate() places inside the faces, in its vertex order
/// (face by face, after the boundary samples), without normals, boundary
/// samples or triangles. The Gregory schemes go through the plans, each
/// patch's ribbon tables (built on first use: about 1 ms per face) and one
/// SIMD kernel pass per tile — the fastest way to many surface points, and
/// what `curvenet bench` reports as evaluation speed. Other schemes take
/// the planned or pointwise path of tessellate(). Threads as
/// options.threads; output independent of the thread count. Thread-safe.
std::vector<Vec3> evaluateFaceInteriors(const Surface &surface, const TessellationOptions &options = {});

/// Number of points evaluateFaceInteriors gives at `resolution` (≥ 1).
std::size_t faceInteriorPoints(const Surface &surface, int resolution);

/// evaluateFaceInteriors into a caller's buffer of at least
/// faceInteriorPoints(surface, options.resolution) points (InputError if
/// shorter): for repeated evaluation without allocating and clearing the
/// output each time, and with every point written by the thread that
/// evaluates it. Returns the number of points written. Thread-safe for
/// distinct buffers.
std::size_t evaluateFaceInteriors(const Surface &surface, std::span<Vec3> out, const TessellationOptions &options = {});

/// After an edit (Surface::rebuildAfterEdit, same topology): updates `mesh`,
/// which holds tessellate(before, options) of the surface before the edit,
/// to equal tessellate(surface, options) bit for bit, re-evaluating only
/// `faces` (the edit's changedFaces): their interior samples through the
/// cached plans, the samples of their segments, the boundary normals they
/// own, and their triangles. Vertex and triangle numbering stay. Cost:
/// proportional to the listed faces' samples plus a topology walk over the
/// boundaries. InputError for a face index out of range; an engine check
/// fails when the mesh does not have this surface's layout at
/// options.resolution. Thread-safe for distinct meshes.
void retessellateFaces(const Surface &surface, std::span<const int> faces, Mesh &mesh,
                       const TessellationOptions &options = {});

} // namespace v1
} // namespace curvenet
