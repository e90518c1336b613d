// curvenet/curvature_jump.hpp — curvature continuity across shared edges.
//
// docs/design.md §5 "curvature jump": on every segment shared by two faces, at the
// same curve parameters from both sides, the normal curvatures κ_A, κ_B of
// the two patches in the common transversal direction N × P' (N the first
// face's normal, P' the segment tangent) are compared as
//   |κ_A − κ_B| / max(|κ_A|, |κ_B|, 1 / diagonal).
// By the Linkage Curve Theorem ([SV14] Sec. 3) two patches tangent along
// the edge are curvature continuous iff this vanishes all along it.
//
// Derivative method: Surface::evaluateSecondOrder — exact (hyper-dual
// numbers) for gregory-g2; for the other schemes the exact first derivatives
// differenced with fourth-order stencils of step `step` (one-sided into each
// face's domain across the edge, central along it). Halving the step changes
// the figure by far less than 10% (tests/g2_test.cpp checks this).
//
// Both ends of every segment are excluded (a fraction `endExclusion` of the
// parameter range at each), and so is any point that close to a corner of a
// face's domain (the split points of 2-sided faces): Gregory patches have
// singular twists at corners.
//
// Cost: samplesPerSegment × 2 × 9 patch evaluations per shared segment.
// Thread-safe (reads an immutable Surface).
#pragma once

#include <vector>

#include "curvenet/surface.hpp"

namespace curvenet {
inline namespace v1 {

struct CurvatureJumpOptions {
  int samplesPerSegment = 17; ///< ≥ 2, spread evenly over the non-excluded range
  double endExclusion = 0.01; ///< in [0, 0.5): parameter fraction left out at each end
  double step = 1e-5;         ///< difference step in domain units, [1e-8, 1e-2] (not gregory-g2)
};

/// One compared point.
struct CurvatureJumpSample {
  int segment = -1;
  double u = 0;           ///< segment parameter
  double kappaA = 0;      ///< normal curvature of faces[0], signed along faces[0]'s normal
  double kappaB = 0;      ///< the same for faces[1], signed along faces[0]'s normal too
  double jump = 0;        ///< relative jump as above
};

struct CurvatureJumpReport {
  double maxJump = 0;  ///< 0 when no segment is shared
  double meanJump = 0;
  int worstSegment = -1;
  double worstU = 0;
  std::vector<CurvatureJumpSample> samples; ///< every compared point
};

/// Measures the curvature jump over every segment with two faces. Throws
/// InputError for options out of range.
CurvatureJumpReport measureCurvatureJump(const Surface &surface, const CurvatureJumpOptions &options = {});

/// The curvature jump across one master edge ([SV14] Sec. 5.1): a shared
/// segment whose curve names a master face (Segment::masterFace).
struct MasterEdgeJump {
  int segment = -1;    ///< index into Network::segments()
  int curve = -1;      ///< the description's curve the segment is a piece of
  int masterFace = -1; ///< the face whose cross curvature is kept
  int slaveFace = -1;  ///< the face on the other side, which takes it
  int samples = 0;     ///< compared points on this segment
  double maxJump = 0, meanJump = 0; ///< as CurvatureJumpReport, over this segment's samples
};

/// Per master edge, in segment order, the jump figures of `report` (which
/// must come from measureCurvatureJump on `surface`) restricted to that
/// segment; empty when no segment names a master. Cost: linear in the samples.
std::vector<MasterEdgeJump> masterEdgeJumps(const Surface &surface, const CurvatureJumpReport &report);

} // namespace v1
} // namespace curvenet
