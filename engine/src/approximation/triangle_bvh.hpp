// Closest-point and overlap queries on a triangle set (engine-private): a
// binary bounding-volume hierarchy split at the median centroid of the
// longest axis, searched nearest box first with pruning by the best distance
// so far, or traversed against itself for the pairs of triangles whose boxes
// overlap.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "curvenet/vec.hpp"

namespace curvenet {
inline namespace v1 {

class TriangleBvh {
public:
  struct Hit {
    Vec3 point;
    int triangle = -1;
    Vec3 barycentric; ///< weights of the triangle's corners 0, 1, 2
    double squaredDistance = 0;
  };

  TriangleBvh() = default;
  TriangleBvh(std::span<const Vec3> positions, std::span<const std::array<std::uint32_t, 3>> triangles);

  /// The closest point on any triangle (triangle = -1 when there are none).
  Hit closest(const Vec3 &p) const;
  /// visit(a, b), a < b, for every pair of triangles whose bounding boxes
  /// overlap (touching counts), each pair once.
  void forEachOverlappingPair(const std::function<void(int a, int b)> &visit) const;

private:
  BoundingBox triangleBox(int t) const;
  struct Node {
    BoundingBox box;
    int first = 0, count = 0; ///< leaf: range of order_; inner: count = 0, children first, first + 1
  };
  void build(int index, int begin, int end, std::vector<Vec3> &centroids);
  std::vector<Vec3> positions_;
  std::vector<std::array<std::uint32_t, 3>> triangles_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

/// Closest point of triangle (a, b, c) to p with its barycentric weights
/// (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closestOnTriangle(const Vec3 &p, const Vec3 &a, const Vec3 &b, const Vec3 &c, Vec3 &barycentric);

/// Where triangles a and b cross: the first point found where an edge of one
/// passes through the other (Möller–Trumbore, both ends of the edge and the
/// triangle's border excluded); nullopt when no edge does. Two triangles
/// that are not coplanar intersect exactly when one's edge passes through
/// the other, so this decides them; coplanar overlaps are not reported.
std::optional<Vec3> trianglesCross(const std::array<Vec3, 3> &a, const std::array<Vec3, 3> &b);

} // namespace v1
} // namespace curvenet
