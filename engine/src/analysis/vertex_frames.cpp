#include "analysis/vertex_frames.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

namespace curvenet {
inline namespace v1 {

namespace {

/// The mean of the normals given along the curves at vertex v (each turned
/// to agree with the first), unit; zero when no curve there carries any.
Vec3 givenNormal(const Network &network, int v) {
  const auto &given = network.description().curveNormals;
  if (given.empty()) return {0, 0, 0};
  Vec3 sum{0, 0, 0}, first{0, 0, 0};
  for (int s : network.vertices()[v].segments) {
    const Segment &seg = network.segments()[s];
    if (seg.sourceCurve < 0 || seg.sourceCurve >= static_cast<int>(given.size()) || given[seg.sourceCurve].empty()) continue;
    Vec3 n = given[seg.sourceCurve].at(seg.start == v ? seg.sourceFrom : seg.sourceTo);
    if (squaredNorm(first) == 0) first = n;
    if (dot(n, first) < 0) n = -n;
    sum += n;
  }
  return squaredNorm(sum) > 0 ? normalized(sum) : sum;
}

} // namespace

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
    // Normals given along the curves (a traced mesh's) set the plane.
    const Vec3 given = givenNormal(network, v);
    const bool hasGiven = squaredNorm(given) > 0;
    if (hasGiven) normal = given;
    if (dot(normal, hint) < 0) normal = -normal;
    double residual = 0;
    for (const Vec3 &t : tangents) residual = std::max(residual, std::asin(std::min(1.0, std::abs(dot(t, normal)))));
    frames[v] = {normalized(normal), residual, !hasGiven && tangents.size() >= 3 && residual > kCreaseResidual};
  }
}

namespace {

/// Unit tangent of a segment leaving its start (or, `atEnd`, its end) vertex.
Vec3 leavingTangent(const Segment &seg, bool atEnd) {
  return atEnd ? normalized(-seg.curve.derivatives(1.0)[1]) : normalized(seg.curve.derivatives(0.0)[1]);
}

/// The normal of face `f`'s corner at the given end of `segment`: (tangent
/// leaving along the loop) × (tangent back along the loop's incoming
/// segment), the computeVertexFrames orientation. Zero where the face runs
/// straight through the vertex (the two tangents nearly opposite) or does
/// not use the segment.
Vec3 cornerNormal(const Network &network, int f, int segment, bool atEnd) {
  // The face's loop as one list of segment uses.
  struct Use {
    int segment;
    bool reversed;
  };
  std::vector<Use> loop;
  for (const FaceSide &side : network.faces()[f].sides)
    for (std::size_t j = 0; j < side.segments.size(); ++j) loop.push_back({side.segments[j], side.segmentReversed[j]});
  const int n = static_cast<int>(loop.size());
  const auto &segments = network.segments();
  for (int i = 0; i < n; ++i) {
    if (loop[i].segment != segment) continue;
    // The use leaves the vertex when the loop runs the segment away from it.
    const bool leaves = loop[i].reversed == atEnd;
    const Use &other = leaves ? loop[(i + n - 1) % n] : loop[(i + 1) % n];
    // The other use's end at this vertex: where the loop arrives (leaving
    // use) or departs (arriving use).
    const bool otherAtEnd = leaves ? !other.reversed : other.reversed;
    const Vec3 mine = leavingTangent(segments[segment], atEnd);
    const Vec3 theirs = leavingTangent(segments[other.segment], otherAtEnd);
    const Vec3 c = leaves ? cross(mine, theirs) : cross(theirs, mine);
    // Within 6° of straight: no corner (its plane would be noise).
    if (norm(c) < 0.1) return {0, 0, 0};
    return normalized(c);
  }
  return {0, 0, 0};
}

struct EndNormals {
  Vec3 normal[2];
  bool smooth = true;
};

EndNormals endNormals(const Network &network, const std::vector<VertexFrame> &frames, int segment, bool atEnd) {
  const Segment &seg = network.segments()[segment];
  const VertexFrame &frame = frames[atEnd ? seg.end : seg.start];
  EndNormals out;
  out.normal[0] = out.normal[1] = frame.normal;
  if (!frame.crease) return out;
  Vec3 corner[2];
  for (int side = 0; side < 2; ++side)
    corner[side] = seg.faces[side] >= 0 ? cornerNormal(network, seg.faces[side], segment, atEnd) : Vec3{0, 0, 0};
  const bool known[2] = {squaredNorm(corner[0]) > 0, squaredNorm(corner[1]) > 0};
  if (!known[0] && !known[1]) {
    // Straight through on both sides: the vertex plane, turned normal to the segment.
    const Vec3 t = leavingTangent(seg, atEnd);
    const Vec3 n = frame.normal - t * dot(frame.normal, t);
    if (squaredNorm(n) > 0) out.normal[0] = out.normal[1] = normalized(n);
    return out;
  }
  for (int side = 0; side < 2; ++side)
    if (!known[side]) corner[side] = corner[1 - side];
  if (seg.faces[1] < 0) {
    out.normal[0] = out.normal[1] = corner[0];
    return out;
  }
  if (angleBetween(corner[0], corner[1]) < kSmoothCornerAngle) {
    out.normal[0] = out.normal[1] = normalized(corner[0] + corner[1]);
    return out;
  }
  out.normal[0] = corner[0], out.normal[1] = corner[1];
  out.smooth = false;
  return out;
}

} // namespace

Vec3 fenceEndNormal(const Network &network, const std::vector<VertexFrame> &frames, int segment, bool atEnd, int side) {
  return endNormals(network, frames, segment, atEnd).normal[side];
}

bool isCreaseSegment(const Network &network, const std::vector<VertexFrame> &frames, int segment) {
  if (network.segments()[segment].isBoundary()) return false;
  return !endNormals(network, frames, segment, false).smooth || !endNormals(network, frames, segment, true).smooth;
}

} // namespace v1
} // namespace curvenet
