#include "analysis/vertex_frames.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

namespace curvenet {
inline namespace v1 {

std::vector<VertexFrame> computeVertexFrames(const Network &network) {
  std::vector<VertexFrame> frames(network.vertices().size());
  std::vector<int> all(frames.size());
  for (std::size_t v = 0; v < all.size(); ++v) all[v] = static_cast<int>(v);
  updateVertexFrames(network, all, frames);
  return frames;
}

void updateVertexFrames(const Network &network, std::span<const int> listed, std::vector<VertexFrame> &frames) {
  const auto &vertices = network.vertices();
  frames.resize(vertices.size());
  std::vector<char> wanted(vertices.size(), 0);
  for (int v : listed) wanted[v] = 1;

  // Orientation hint per vertex: the sum of the corner normals of the faces,
  // accumulated in face order whichever vertices are listed (same bits).
  std::vector<Vec3> cornerSum(vertices.size());
  for (const Face &face : network.faces()) {
    const int n = face.sideCount();
    for (int k = 0; k < n; ++k) {
      const FaceSide &in = face.sides[(k + n - 1) % n], &out = face.sides[k];
      if (!wanted[out.startVertex]) continue;
      const Vec3 forward = normalized(out.curve.derivatives(0.0)[1]);
      const Vec3 back = normalized(-in.curve.derivatives(1.0)[1]);
      cornerSum[out.startVertex] += cross(forward, back);
    }
  }

  for (int v : listed) {
    const std::vector<Vec3> &tangents = vertices[v].tangents;
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (const Vec3 &t : tangents) {
      const Eigen::Vector3d e(t.x, t.y, t.z);
      scatter += e * e.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
    const Eigen::Vector3d smallest = solver.eigenvectors().col(0);
    Vec3 normal{smallest.x(), smallest.y(), smallest.z()};
    const Vec3 hint = cornerSum[v];
    // Tangents along one line leave the plane free: take the corners' plane.
    const double spread = solver.eigenvalues()(1) / std::max(solver.eigenvalues()(2), 1e-300);
    if (spread < 1e-10 && squaredNorm(hint) > 0) normal = normalized(hint);
    if (dot(normal, hint) < 0) normal = -normal;
    double residual = 0;
    for (const Vec3 &t : tangents) residual = std::max(residual, std::asin(std::min(1.0, std::abs(dot(t, normal)))));
    frames[v] = {normalized(normal), residual};
  }
}

} // namespace v1
} // namespace curvenet
