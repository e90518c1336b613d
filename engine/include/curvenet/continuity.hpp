// curvenet/continuity.hpp — the quality figures of docs/design.md §5 for a built
// Surface: how well neighbouring patches join, how exactly each patch keeps
// its boundary curves, and how far the surface lies from a known reference.
//
// All lengths are relative to the bounding-box diagonal of the network's
// curves (Network::diagonal()), so figures compare across model sizes.
// Every function here only reads the surface; all are safe to call from
// several threads on the same Surface.
#pragma once

#include <cstddef>
#include <optional>

#include "curvenet/surface.hpp"

namespace curvenet {
inline namespace v1 {

struct ContinuityOptions {
  /// Points per segment (≥ 1 interval): u = j / samplesPerSegment, j = 0..samplesPerSegment,
  /// the same curve parameters seen from both faces on the segment.
  int samplesPerSegment = 64;
};

/// Figures over every segment shared by two faces (boundary segments have
/// one face and only enter `maxBoundaryDeviation`). The normal angles are
/// measured on the G¹ segments only: crease segments (Surface::isCreaseSegment)
/// are sharp edges by design and enter the position gap alone.
struct ContinuityReport {
  int sharedSegments = 0;
  int creaseSegments = 0; ///< of the shared ones, left out of the normal angles
  std::size_t samples = 0; ///< points whose normals were compared (G¹ segments)
  int samplesPerSegment = 0;
  /// max |S_A − S_B| at the same curve parameter, relative to the diagonal.
  double maxPositionGap = 0;
  /// max / mean angle in degrees between the unit normals of the two faces
  /// (oriented consistently: faces that run the segment in the same
  /// direction have one normal flipped), over the G¹ segments. Computed as
  /// atan2(|a×b|, a·b) so that angles far below 1e-6° are resolved.
  double maxNormalAngleDeg = 0, meanNormalAngleDeg = 0;
  int worstNormalSegment = -1; ///< segment with the largest normal angle (−1: none shared)
  /// max distance between a patch evaluated on its domain side and the
  /// boundary curve it must reproduce, over every face side, relative to the diagonal.
  double maxBoundaryDeviation = 0;
};

/// Cost: (samplesPerSegment + 1) × (2 per shared segment + 1 per face side) surface evaluations.
ContinuityReport measureContinuity(const Surface &surface, const ContinuityOptions &options = {});

/// Distance of the tessellated surface to the network's reference surface.
struct ReferenceDeviation {
  int resolution = 0;       ///< tessellation resolution whose vertices were measured
  std::size_t samples = 0;  ///< number of mesh vertices measured
  /// max |d| and mean |d| over the samples, and the signed extremes (positive
  /// outside / above the reference), all relative to the diagonal.
  double maxDeviation = 0, meanDeviation = 0, minSigned = 0, maxSigned = 0;
};

/// std::nullopt when the network carries no reference surface. Cost: one
/// tessellation at `resolution` (see curvenet/tessellate.hpp) plus one
/// closest-point query per mesh vertex.
std::optional<ReferenceDeviation> measureReferenceDeviation(const Surface &surface, int resolution = 32,
                                                            int threads = 0);

} // namespace v1
} // namespace curvenet
