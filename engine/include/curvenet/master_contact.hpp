// curvenet/master_contact.hpp — how the patches meet their master surfaces.
//
// An edge that names a master surface given from outside
// (EdgeDescription::masterSurface, [SV14] Sec. 5.1) should leave every face
// along it tangent to that surface (gregory-g1, composite-ribbon) and, under
// gregory-g2, curvature continuous with it. This measures both against the
// surface itself, not between faces: at each compared point of the edge
// the face's point is projected onto the master (BSplineSurface::closestPoint)
// and compared there with
//  * the distance to the master (relative to the network's diagonal),
//  * the angle between the face's normal and the master's (either side),
//  * the curvature jump as in curvenet/curvature_jump.hpp: the normal
//    curvatures κ_F of the face and κ_M of the master in the direction
//    N × P' (N the master's normal, P' the segment tangent), as
//    |κ_F − κ_M| / max(|κ_F|, |κ_M|, 1 / diagonal).
// Sampling: normals and distances at u = j / n, j = 0 … n (n =
// samplesPerSegment − 1), ends included; curvatures at the samples of
// measureCurvatureJump (ends left out by endExclusion, where the Gregory
// corners have singular twists), with the same derivative methods (exact for
// gregory-g2, differenced otherwise).
//
// Cost: per master edge and face, samplesPerSegment × (1 + 9) patch
// evaluations and 2 × samplesPerSegment projections. Thread-safe (reads an
// immutable Surface).
#pragma once

#include <vector>

#include "curvenet/curvature_jump.hpp"
#include "curvenet/surface.hpp"

namespace curvenet {
inline namespace v1 {

/// One face along one master-surface edge.
struct MasterSurfaceContact {
  int segment = -1;       ///< index into Network::segments()
  int curve = -1;         ///< the description's curve the segment is a piece of
  int masterSurface = -1; ///< index into the description's surfaces
  int face = -1;          ///< the face measured (one entry per face along the segment)
  int samples = 0;        ///< compared points for the curvature (normals: samplesPerSegment)
  double maxDistance = 0;       ///< relative to the diagonal
  double maxNormalAngleDeg = 0; ///< degrees
  double maxCurvatureJump = 0, meanCurvatureJump = 0;
};

/// Every face along every master-surface edge, in segment order (faces[0]
/// before faces[1]); empty when no edge names a master surface. Throws
/// InputError for options out of range (as measureCurvatureJump).
std::vector<MasterSurfaceContact> measureMasterSurfaceContact(const Surface &surface,
                                                              const CurvatureJumpOptions &options = {});

} // namespace v1
} // namespace curvenet
