// Surface curvature at the vertices of a network ([SV14] Sec. 2, App. A):
// the fit of curvenet/vertex_math.hpp applied to the curves at each vertex.
#pragma once

#include <vector>

#include "analysis/vertex_frames.hpp"
#include "curvenet/network.hpp"
#include "curvenet/vertex_math.hpp"

namespace curvenet {
inline namespace v1 {

/// A curvature tensor placed in a vertex's tangent plane. Normal curvatures
/// are signed with respect to `normal` (positive when bending towards it).
struct VertexCurvature {
  Vec3 normal, xAxis, yAxis; ///< right-handed: yAxis = normal × xAxis
  CurvatureTensor tensor;    ///< λ measured from xAxis towards yAxis
  FitBranch branch = FitBranch::Exact;
  int independentDirections = 0;
  double maxResidual = 0; ///< largest misfit of a curve's normal curvature, 1/length

  /// Normal curvature in tangent direction v (projected into the plane).
  double normalCurvature(const Vec3 &v) const;
  /// Shape operator S(v) (II(v, w) = S(v)·w), for a tangent vector v.
  Vec3 shape(const Vec3 &v) const;
  /// The principal directions as 3D vectors.
  Vec3 direction1() const;
  Vec3 direction2() const { return cross(normal, direction1()); }
};

/// Fits (κ1, κ2, λ) at every vertex to the normal curvatures P''·N/|P'|² of
/// the segment ends there, by fitCurvature (which picks the n = 1, 2, 3, > 3
/// branch). The x axis is the first outgoing tangent projected into the plane.
std::vector<VertexCurvature> fitVertexCurvatures(const Network &network, const std::vector<VertexFrame> &frames);
/// The same fit at vertex v alone (what fitVertexCurvatures gives for it).
VertexCurvature fitVertexCurvature(const Network &network, const std::vector<VertexFrame> &frames, int v);

/// The same tensor read off a reference surface frame, re-signed for `normal`
/// (which may point to the other side than the reference's normal).
VertexCurvature vertexCurvatureFromReference(const SurfaceFrame &frame, const Vec3 &normal, const Vec3 &xHint);

} // namespace v1
} // namespace curvenet
