// Tangent planes at the vertices of a network (issue: G¹ item 1).
#pragma once

#include <span>
#include <vector>

#include "curvenet/network.hpp"

namespace curvenet {
inline namespace v1 {

struct VertexFrame {
  Vec3 normal;                ///< unit, oriented to the outside of the faces around the vertex
  double residualAngle = 0;   ///< radians: largest angle of a curve tangent out of the plane
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

} // namespace v1
} // namespace curvenet
