// Tangent planes at the vertices of a network (issue: G¹ item 1), and the
// face corners' own planes at crease vertices.
#pragma once

#include <numbers>
#include <span>
#include <vector>

#include "curvenet/network.hpp"

namespace curvenet {
inline namespace v1 {

/// A vertex of three or more curve ends whose tangents leave their best plane
/// by more than this (radians) is a crease: no tangent plane is meant there
/// (a lid meeting a wall, a cube's corner), and each face corner keeps the
/// plane of its own two curves. Measured on the eight public sketches: every
/// vertex either shares its plane to rounding (the fit enforces it where the
/// strokes nearly do) or leaves it by 7° or more; the analytic built-ins
/// leave theirs by at most 7.6e-9 rad. 5° sits inside that gap and above
/// what vertex repair is for: tangents a little out of one plane (the
/// robustness corpus turns them by up to 3°), which it turns into it.
inline constexpr double kCreaseResidual = 5 * std::numbers::pi / 180;

/// At a crease vertex, the two faces across a segment are smooth (G¹) there
/// when their corner planes meet at less than this angle (radians): their
/// fences then share the mean normal. Measured on the eight public
/// sketches: the corner planes across a segment at a crease vertex meet at
/// 10°–18° where the drawing goes on as one sheet (doghead, box) and at 26°
/// or more where it folds (iron's shallowest, then 28°, 39°, ...).
inline constexpr double kSmoothCornerAngle = 20 * std::numbers::pi / 180;

struct VertexFrame {
  Vec3 normal;                ///< unit, oriented to the outside of the faces around the vertex
  double residualAngle = 0;   ///< radians: largest angle of a curve tangent out of the plane
  bool crease = false;        ///< see kCreaseResidual: `normal` is then only a mean
};

/// The common tangent plane of the curves at every vertex: the least-squares
/// plane of the unit tangents (smallest eigenvector of Σ t tᵀ). Where the
/// tangents span only a line (a curve merely passing through), the plane of
/// the face corners around it is used instead. Oriented by the face loops:
/// at a corner, (outgoing tangent) × (tangent back along the incoming side)
/// points outside for counter-clockwise loops.
std::vector<VertexFrame> computeVertexFrames(const Network &network);

/// Recomputes frames[v] for the listed vertices only (after their curves
/// changed), bit for bit what computeVertexFrames gives for them. Cost: one
/// pass over the face corners plus one 3×3 eigenproblem per listed vertex.
void updateVertexFrames(const Network &network, std::span<const int> vertices, std::vector<VertexFrame> &frames);

/// The normal the fence of `segment` takes at one end (`atEnd`: its end
/// vertex, else its start) for the face on `side` (0 or 1, Segment::faces).
/// At a vertex that is no crease: the vertex normal, for both faces. At a
/// crease: the unit normal of that face's corner there (the plane of the
/// segment and the face's next curve at the vertex, oriented like the
/// loop); where the two faces' corner planes meet within
/// kSmoothCornerAngle, both take their mean, so the surface stays G¹
/// across the segment. A face running straight through the vertex (a
/// T-node seen from its straight side) has no corner there and takes the
/// other face's.
Vec3 fenceEndNormal(const Network &network, const std::vector<VertexFrame> &frames, int segment, bool atEnd, int side);

/// True when the two faces of `segment` get different fence normals at one
/// of its ends (fenceEndNormal): the segment is a crease, the surface is
/// only C⁰ across it. False for boundary segments.
bool isCreaseSegment(const Network &network, const std::vector<VertexFrame> &frames, int segment);

} // namespace v1
} // namespace curvenet
