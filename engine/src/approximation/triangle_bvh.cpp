#include "approximation/triangle_bvh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace curvenet {
inline namespace v1 {

namespace {
constexpr int kLeafSize = 4;

double boxSquaredDistance(const Vec3 &p, const BoundingBox &box) {
  double s = 0;
  for (int i = 0; i < 3; ++i) {
    const double d = std::max({box.min[i] - p[i], 0.0, p[i] - box.max[i]});
    s += d * d;
  }
  return s;
}
} // namespace

Vec3 closestOnTriangle(const Vec3 &p, const Vec3 &a, const Vec3 &b, const Vec3 &c, Vec3 &bary) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return bary = {1, 0, 0}, a;
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return bary = {0, 1, 0}, b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    bary = {1 - v, v, 0};
    return a + ab * v;
  }
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return bary = {0, 0, 1}, c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    bary = {1 - w, 0, w};
    return a + ac * w;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    bary = {0, 1 - w, w};
    return b + (c - b) * w;
  }
  const double denom = 1 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  bary = {1 - v - w, v, w};
  return a + ab * v + ac * w;
}

TriangleBvh::TriangleBvh(std::span<const Vec3> positions, std::span<const std::array<std::uint32_t, 3>> triangles)
    : positions_(positions.begin(), positions.end()), triangles_(triangles.begin(), triangles.end()) {
  if (triangles_.empty()) return;
  std::vector<Vec3> centroids(triangles_.size());
  order_.resize(triangles_.size());
  for (size_t t = 0; t < triangles_.size(); ++t) {
    const auto &tri = triangles_[t];
    centroids[t] = (positions_[tri[0]] + positions_[tri[1]] + positions_[tri[2]]) / 3.0;
    order_[t] = static_cast<int>(t);
  }
  nodes_.reserve(2 * triangles_.size() / kLeafSize + 2);
  nodes_.emplace_back();
  build(0, 0, static_cast<int>(order_.size()), centroids);
}

void TriangleBvh::build(int index, int begin, int end, std::vector<Vec3> &centroids) {
  BoundingBox box, ofCentroids;
  for (int k = begin; k < end; ++k) {
    for (const std::uint32_t v : triangles_[order_[k]]) box.add(positions_[v]);
    ofCentroids.add(centroids[order_[k]]);
  }
  nodes_[index].box = box;
  if (end - begin <= kLeafSize) {
    nodes_[index].first = begin, nodes_[index].count = end - begin;
    return;
  }
  const Vec3 extent = ofCentroids.max - ofCentroids.min;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const int mid = (begin + end) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](int a, int b) { return centroids[a][axis] < centroids[b][axis]; });
  // Children are appended as a pair, so an inner node stores only the first.
  const int child = static_cast<int>(nodes_.size());
  nodes_[index].first = child, nodes_[index].count = 0;
  nodes_.emplace_back();
  nodes_.emplace_back();
  build(child, begin, mid, centroids);
  build(child + 1, mid, end, centroids);
}

TriangleBvh::Hit TriangleBvh::closest(const Vec3 &p) const {
  Hit best;
  best.squaredDistance = std::numeric_limits<double>::infinity();
  if (nodes_.empty()) return best;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node &node = nodes_[stack[--top]];
    // Until a triangle is found nothing is pruned: a point so far out that
    // its squared distances overflow to infinity (or NaN) still gets a
    // triangle, with that distance, instead of none.
    if (best.triangle >= 0 && boxSquaredDistance(p, node.box) >= best.squaredDistance) continue;
    if (node.count > 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        const auto &tri = triangles_[order_[k]];
        Vec3 bary;
        const Vec3 q = closestOnTriangle(p, positions_[tri[0]], positions_[tri[1]], positions_[tri[2]], bary);
        const double d = squaredNorm(q - p);
        if (best.triangle < 0 || d < best.squaredDistance) best = {q, order_[k], bary, d};
      }
      continue;
    }
    // Nearer child last, so it is popped first.
    const int a = node.first, b = node.first + 1;
    const double da = boxSquaredDistance(p, nodes_[a].box);
    const double db = boxSquaredDistance(p, nodes_[b].box);
    if (da < db) stack[top++] = b, stack[top++] = a;
    else stack[top++] = a, stack[top++] = b;
  }
  return best;
}

BoundingBox TriangleBvh::triangleBox(int t) const {
  const auto &tri = triangles_[static_cast<std::size_t>(t)];
  BoundingBox box;
  for (const std::uint32_t v : tri) box.add(positions_[v]);
  return box;
}

void TriangleBvh::forEachOverlappingPair(const std::function<void(int a, int b)> &visit) const {
  if (nodes_.empty()) return;
  std::vector<BoundingBox> boxes(triangles_.size());
  for (std::size_t t = 0; t < triangles_.size(); ++t) boxes[t] = triangleBox(static_cast<int>(t));
  auto visitIfBoxesOverlap = [&](int a, int b) {
    if (boxes[static_cast<std::size_t>(a)].meets(boxes[static_cast<std::size_t>(b)])) visit(std::min(a, b), std::max(a, b));
  };
  auto volume = [](const Node &n) {
    const Vec3 extent = n.box.max - n.box.min;
    return extent.x * extent.y * extent.z;
  };
  // Pairs of nodes whose triangles may overlap; (k, k) stands for the pairs
  // within node k.
  std::vector<std::pair<int, int>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    const Node &na = nodes_[a], &nb = nodes_[b];
    if (a == b) {
      if (na.count > 0) {
        for (int i = na.first; i < na.first + na.count; ++i)
          for (int j = i + 1; j < na.first + na.count; ++j) visitIfBoxesOverlap(order_[i], order_[j]);
      } else {
        stack.push_back({na.first, na.first}), stack.push_back({na.first + 1, na.first + 1});
        stack.push_back({na.first, na.first + 1});
      }
      continue;
    }
    if (!na.box.meets(nb.box)) continue;
    if (na.count > 0 && nb.count > 0) {
      for (int i = na.first; i < na.first + na.count; ++i)
        for (int j = nb.first; j < nb.first + nb.count; ++j) visitIfBoxesOverlap(order_[i], order_[j]);
    } else if (nb.count > 0 || (na.count == 0 && volume(na) >= volume(nb))) {
      stack.push_back({na.first, b}), stack.push_back({na.first + 1, b});
    } else {
      stack.push_back({a, nb.first}), stack.push_back({a, nb.first + 1});
    }
  }
}

namespace {
/// Where segment p → q passes through the interior of triangle t (both ends
/// of the segment excluded), by Möller–Trumbore.
std::optional<Vec3> segmentThroughTriangle(const Vec3 &p, const Vec3 &q, const std::array<Vec3, 3> &t) {
  const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0], d = q - p;
  const Vec3 h = cross(d, e2);
  const double det = dot(e1, h);
  if (!(std::abs(det) > 0)) return std::nullopt; // parallel to the plane (or not finite)
  const double inv = 1 / det;
  const Vec3 s = p - t[0];
  const double u = inv * dot(s, h);
  if (!(u > 0 && u < 1)) return std::nullopt;
  const Vec3 r = cross(s, e1);
  const double v = inv * dot(d, r);
  if (!(v > 0 && u + v < 1)) return std::nullopt;
  const double along = inv * dot(e2, r);
  if (!(along > 0 && along < 1)) return std::nullopt;
  return p + d * along;
}
} // namespace

std::optional<Vec3> trianglesCross(const std::array<Vec3, 3> &a, const std::array<Vec3, 3> &b) {
  for (int k = 0; k < 3; ++k) {
    if (auto x = segmentThroughTriangle(a[k], a[(k + 1) % 3], b)) return x;
    if (auto x = segmentThroughTriangle(b[k], b[(k + 1) % 3], a)) return x;
  }
  return std::nullopt;
}

} // namespace v1
} // namespace curvenet
