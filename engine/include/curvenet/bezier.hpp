// curvenet/bezier.hpp — what the Bézier schemes (bezier-g1, coons-c0) expose
// beyond Surface: their quintic control nets and their edge continuity.
//
// A Surface built with Scheme::BezierG1 or Scheme::CoonsC0 (curvenet/surface.hpp)
// consists of quintic × quintic Bézier patches: one per 4-sided face, or three
// for a face whose loop runs straight through one of its corners (a T-junction
// at a vertex, split into three rectangles by bezier-g1).
//
// Threads: all functions only read the Surface and may run concurrently.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "curvenet/surface.hpp"

namespace curvenet {
inline namespace v1 {

/// One quintic patch: control point (i, j), i along u and j along v, is
/// points[6 * j + i] (row-major, rows of constant v). Patch side 0 is v = 0
/// (u: 0 → 1), side 1 u = 1, side 2 v = 1 (u: 1 → 0), side 3 u = 0 (v: 1 → 0).
struct QuinticControlNet {
  std::array<Vec3, 36> points;
  /// The patch's (s, t) unit square inside its face's (u, v) square: the face
  /// points of patch corners (0,0), (1,0), (1,1), (0,1). The unit square itself
  /// when the face is one patch (then patch side k is face side k).
  std::array<Vec2, 4> faceCorners;
};

struct FaceControlNets {
  std::string name;
  std::vector<QuinticControlNet> patches;
};

/// Control nets per face of the surface's network. Throws InputError
/// (element "scheme") when the surface does not use a Bézier scheme. O(faces).
std::vector<FaceControlNets> controlNets(const Surface &surface);

/// The nets as a JSON document:
///   {"format": "curvenet-quintic-nets", "version": 1, "scheme": S, "degree": [5, 5],
///    "layout": "row-major: point index 6*j + i, i along u, j along v",
///    "faces": [{"face": f, "name": ..., "side_order": [0, 1, 2, 3],
///               "patches": [{"face_corners": [[u,v] × 4], "points": [[x,y,z] × 36]}]}]}
/// side_order lists the network face side that patch sides 0…3 show (v = 0,
/// u = 1, v = 1, u = 0) for single-patch faces.
std::string controlNetsJson(const Surface &surface);
/// Writes controlNetsJson to `path` (whole file or nothing); InputError when it cannot.
void writeControlNets(const Surface &surface, const std::string &path);

/// Normal continuity across every shared edge of a Bézier-scheme surface:
/// both patches are evaluated at the same points of the edge (samplesPerEdge
/// + 1 equally spaced parameters per edge, ends included) and the angle between
/// their unit normals taken. Edges are the segments with two faces of the
/// construction network — for bezier-g1 this includes the curves the
/// three-rectangle subdivision adds inside a face. Cost O(edges × samples).
struct EdgeContinuity {
  double maxNormalAngleDeg = 0;
  double meanNormalAngleDeg = 0;
  double maxPositionGap = 0; ///< absolute, model units
  int edges = 0;
  int samples = 0;
};
EdgeContinuity bezierEdgeContinuity(const Surface &surface, int samplesPerEdge = 64);

} // namespace v1
} // namespace curvenet
