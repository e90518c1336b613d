// insertConnectionCurves — composite faces for concave loops and holes
// (paper 000 Sec. 5.2). Works on the description alone (curves and loops),
// before any topology exists, so Network::build can call it first.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "curvenet/error.hpp"
#include "curvenet/network.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

using Loop = std::vector<SideDescription>;

// A corner turns concave when its interior angle exceeds a straight angle by
// more than this (radians): T-nodes and slightly bent runs stay as they are.
constexpr double kConcaveMargin = 0.2;
// A split is accepted only if each of its four new corner angles keeps this
// distance (radians) from 0 and from a straight angle.
constexpr double kMinSplitAngle = 0.1;
// Parts still concave after a split are split again, to this depth.
constexpr int kMaxSplitDepth = 8;

/// Point and unit tangent (in the loop direction) of a side at s ∈ [0, 1].
struct SidePoint {
  Vec3 point, tangent;
};
SidePoint sidePoint(const std::vector<BSplineCurve> &curves, const SideDescription &side, double s) {
  const BSplineCurve &c = curves[side.curve];
  const auto d = c.derivatives(side.from + s * (side.to - side.from));
  Vec3 t = d[1] * (side.to > side.from ? 1.0 : -1.0);
  // A repeated end control point: the chord to a nearby point.
  if (squaredNorm(t) < 1e-30) {
    const double h = s < 0.5 ? 1e-6 : -1e-6;
    t = (c.point(side.from + (s + h) * (side.to - side.from)) - d[0]) * (h > 0 ? 1.0 : -1.0);
  }
  return {d[0], normalized(t)};
}

/// Newell normal of the loop (sampled), the orientation reference of a face.
Vec3 newellNormal(const std::vector<BSplineCurve> &curves, const Loop &loop) {
  std::vector<Vec3> points;
  for (const SideDescription &side : loop)
    for (int j = 0; j < 8; ++j) points.push_back(sidePoint(curves, side, j / 8.0).point);
  Vec3 n{};
  for (size_t i = 0; i < points.size(); ++i) n += cross(points[i], points[(i + 1) % points.size()]);
  return n;
}

/// Counter-clockwise angle from a to b about n, in [0, 2π).
double angleAbout(const Vec3 &a, const Vec3 &b, const Vec3 &n) {
  const double angle = std::atan2(dot(cross(a, b), n), dot(a, b));
  return angle < 0 ? angle + 2 * std::numbers::pi : angle;
}

Vec3 orthogonalTo(const Vec3 &v, const Vec3 &axis) { return normalized(v - axis * dot(v, axis)); }

/// A point of a loop where a connection curve may end: corner k (the start
/// of side k, s = 0) or the midpoint of side k (s = 0.5). Tangents arriving
/// and leaving in the loop direction; the tangent-plane normal, on the side
/// of the face normal.
struct LoopPoint {
  Vec3 point, in, out, normal;
  bool concave = false;
};

/// The surface normal where the description carries a reference surface
/// (built-ins, mesh approximation), on the side of the face normal.
std::optional<Vec3> referenceNormal(const std::optional<ReferenceSurface> &reference, const Vec3 &point,
                                    const Vec3 &tangent, const Vec3 &faceNormal) {
  if (!reference) return std::nullopt;
  const Vec3 n = orthogonalTo(reference->closest(point).normal, tangent);
  return dot(n, faceNormal) < 0 ? -n : n;
}

LoopPoint cornerPoint(const std::vector<BSplineCurve> &curves, const Loop &loop, int k, const Vec3 &faceNormal,
                      const std::optional<ReferenceSurface> &reference) {
  const int n = static_cast<int>(loop.size());
  const SidePoint prev = sidePoint(curves, loop[(k + n - 1) % n], 1.0), next = sidePoint(curves, loop[k], 0.0);
  LoopPoint p{next.point, prev.tangent, next.tangent, {}};
  const Vec3 c = cross(next.tangent, -prev.tangent);
  if (norm(c) > 1e-3) {
    // The plane of the two curves; it faces away from the face normal
    // exactly when the corner is concave.
    p.normal = normalized(c);
    if (dot(p.normal, faceNormal) < 0) {
      p.normal = -p.normal;
      p.concave = angleBetween(next.tangent, -prev.tangent) < std::numbers::pi - kConcaveMargin;
    }
  } else {
    // A curve passing straight on: its tangent alone fixes no plane. A wrong
    // tilt here would turn the curve's geodesic curvature into normal
    // curvature at the new vertex, so the reference normal is used if any.
    p.normal = referenceNormal(reference, p.point, next.tangent, faceNormal)
                   .value_or(orthogonalTo(faceNormal, next.tangent));
  }
  return p;
}

LoopPoint midPoint(const std::vector<BSplineCurve> &curves, const Loop &loop, int k, const Vec3 &faceNormal,
                   const std::optional<ReferenceSurface> &reference) {
  const int n = static_cast<int>(loop.size());
  const SidePoint m = sidePoint(curves, loop[k], 0.5);
  if (auto r = referenceNormal(reference, m.point, m.tangent, faceNormal)) return {m.point, m.tangent, m.tangent, *r};
  // Between the side's two corner planes.
  const Vec3 average = cornerPoint(curves, loop, k, faceNormal, reference).normal +
                       cornerPoint(curves, loop, (k + 1) % n, faceNormal, reference).normal;
  return {m.point, m.tangent, m.tangent, orthogonalTo(norm(average) > 1e-9 ? average : faceNormal, m.tangent)};
}

/// The cubic from a to b whose end tangents are the chord projected into
/// the tangent planes at its ends (Hermite, speed = chord length).
/// With a reference surface the cubic is projected onto it (samples moved
/// to their closest surface points, interpolated at degree 5, ends kept):
/// a curve on the surface carries the surface's normal curvature into the
/// vertex fits at its ends, as the user's curves do.
BSplineCurve connectionCurve(const LoopPoint &a, const LoopPoint &b, const std::optional<ReferenceSurface> &reference) {
  const Vec3 chord = b.point - a.point;
  const double length = norm(chord);
  const Vec3 d0 = orthogonalTo(chord, a.normal), d1 = orthogonalTo(chord, b.normal);
  BSplineCurve cubic = BSplineCurve::bezier({a.point, a.point + d0 * (length / 3), b.point - d1 * (length / 3), b.point});
  if (!reference) return cubic;
  constexpr int intervals = 16;
  std::vector<double> params(intervals + 1);
  std::vector<Vec3> points(intervals + 1);
  for (int i = 0; i <= intervals; ++i) {
    params[i] = double(i) / intervals;
    points[i] = i == 0 || i == intervals ? cubic.point(params[i]) : reference->closest(cubic.point(params[i])).point;
  }
  const BSplineCurve fitted = BSplineCurve::interpolate(5, params, points);
  // The interpolant's end tangents (along its first and last control legs)
  // leave the tangent planes by the fit error; put them back exactly, or the
  // vertex planes would tilt by it and G¹ with them.
  std::vector<Vec3> control = fitted.controlPoints();
  const size_t last = control.size() - 1;
  const Vec3 leg0 = control[1] - control[0], leg1 = control[last - 1] - control[last];
  control[1] = control[0] + leg0 - a.normal * dot(leg0, a.normal);
  control[last - 1] = control[last] + leg1 - b.normal * dot(leg1, b.normal);
  return BSplineCurve(fitted.degree(), fitted.knots(), std::move(control));
}

SideDescription reversedSide(const SideDescription &side) { return {side.curve, side.to, side.from}; }

class Splitter {
public:
  Splitter(std::vector<BSplineCurve> &curves, const std::optional<ReferenceSurface> &reference)
      : curves_(curves), reference_(reference) {}

  /// The loop's convex parts (the loop itself when it has no concave corner
  /// or no acceptable split).
  std::vector<Loop> convexParts(const Loop &loop, int depth = 0) {
    const Vec3 faceNormal = newellNormal(curves_, loop);
    if (!(norm(faceNormal) > 0) || depth >= kMaxSplitDepth) return {loop};
    const int n = static_cast<int>(loop.size());
    for (int c = 0; c < n; ++c) {
      const LoopPoint corner = cornerPoint(curves_, loop, c, faceNormal, reference_);
      if (!corner.concave) continue;
      std::optional<std::pair<Loop, Loop>> parts = split(loop, c, corner, faceNormal);
      if (!parts) continue;
      std::vector<Loop> result = convexParts(parts->first, depth + 1);
      for (Loop &l : convexParts(parts->second, depth + 1)) result.push_back(std::move(l));
      return result;
    }
    return {loop};
  }

  /// Splits loop at concave corner c along the best connection curve: to a
  /// corner or side midpoint whose four new corner angles stay farthest
  /// from 0 and π. Part A runs from c along the loop to the target and back
  /// along the connection; part B the rest.
  std::optional<std::pair<Loop, Loop>> split(const Loop &loop, int c, const LoopPoint &corner,
                                             const Vec3 &faceNormal) {
    const int n = static_cast<int>(loop.size());
    double bestScore = kMinSplitAngle;
    int bestSide = -1;
    bool bestMid = false;
    LoopPoint bestTarget;
    for (int k = 0; k < n; ++k)
      for (bool mid : {false, true}) {
        const int ahead = (k - c + n) % n; // sides from c to the target's side
        // Each part needs three sides: a corner target two sides away from c
        // at least, a midpoint target not on either side at c.
        if (mid ? (ahead == 0 || ahead == n - 1) : (ahead < 2 || ahead > n - 2)) continue;
        const LoopPoint target =
            mid ? midPoint(curves_, loop, k, faceNormal, reference_) : cornerPoint(curves_, loop, k, faceNormal, reference_);
        const Vec3 dc = orthogonalTo(target.point - corner.point, corner.normal);
        const Vec3 dt = orthogonalTo(corner.point - target.point, target.normal);
        const double angles[4] = {angleAbout(corner.out, dc, corner.normal), angleAbout(dc, -corner.in, corner.normal),
                                  angleAbout(dt, -target.in, target.normal),
                                  angleAbout(target.out, dt, target.normal)};
        double score = INFINITY;
        for (double a : angles) score = std::min(score, std::min(a, std::numbers::pi - a));
        if (score > bestScore) bestScore = score, bestSide = k, bestMid = mid, bestTarget = target;
      }
    if (bestSide < 0) return std::nullopt;
    const int curve = static_cast<int>(curves_.size());
    curves_.push_back(connectionCurve(corner, bestTarget, reference_));
    connections_.push_back(curve);
    Loop a, b;
    for (int j = c; j != bestSide; j = (j + 1) % n) a.push_back(loop[j]);
    const SideDescription &cut = loop[bestSide];
    if (bestMid) {
      const double m = 0.5 * (cut.from + cut.to);
      a.push_back({cut.curve, cut.from, m});
      b.push_back({cut.curve, m, cut.to});
    } else {
      b.push_back(cut);
    }
    a.push_back({curve, 1.0, 0.0});
    for (int j = (bestSide + 1) % n; j != c; j = (j + 1) % n) b.push_back(loop[j]);
    b.push_back({curve, 0.0, 1.0});
    return std::make_pair(std::move(a), std::move(b));
  }

  /// n four-sided parts of a face with one hole of n sides.
  std::vector<Loop> ring(const Loop &outer, Loop hole, const std::string &file, const std::string &element) {
    const int n = static_cast<int>(outer.size());
    if (static_cast<int>(hole.size()) != n)
      throw InputError(file, element,
                       "the hole has " + std::to_string(hole.size()) + " sides and the outer loop " +
                           std::to_string(n) + ": connection curves join corner to corner, so the counts must agree");
    const Vec3 faceNormal = newellNormal(curves_, outer);
    // The hole's corners in the outer loop's turning direction.
    if (dot(newellNormal(curves_, hole), faceNormal) < 0) {
      std::reverse(hole.begin(), hole.end());
      for (SideDescription &side : hole) side = reversedSide(side);
    }
    int rotation = 0;
    double best = INFINITY;
    for (int r = 0; r < n; ++r) {
      double total = 0;
      for (int i = 0; i < n; ++i)
        total += norm(sidePoint(curves_, outer[i], 0).point - sidePoint(curves_, hole[(i + r) % n], 0).point);
      if (total < best) best = total, rotation = r;
    }
    std::vector<int> joins(n);
    for (int i = 0; i < n; ++i) {
      joins[i] = static_cast<int>(curves_.size());
      curves_.push_back(connectionCurve(cornerPoint(curves_, outer, i, faceNormal, reference_),
                                        cornerPoint(curves_, hole, (i + rotation) % n, faceNormal, reference_),
                                        reference_));
      connections_.push_back(joins[i]);
    }
    std::vector<Loop> parts;
    for (int i = 0; i < n; ++i) {
      const Loop quad = {outer[i], {joins[(i + 1) % n], 0.0, 1.0}, reversedSide(hole[(i + rotation) % n]),
                         {joins[i], 1.0, 0.0}};
      for (Loop &l : convexParts(quad)) parts.push_back(std::move(l));
    }
    return parts;
  }

  const std::vector<int> &connections() const { return connections_; }

private:
  std::vector<BSplineCurve> &curves_;
  const std::optional<ReferenceSurface> &reference_;
  std::vector<int> connections_;
};

/// True when every side refers to an existing curve inside its domain (else
/// the loop is left to Network::build, which names the fault).
bool loopIsValid(const std::vector<BSplineCurve> &curves, const Loop &loop) {
  for (const SideDescription &side : loop) {
    if (side.curve < 0 || side.curve >= static_cast<int>(curves.size())) return false;
    const BSplineCurve &c = curves[side.curve];
    const double slack = 1e-10 * (c.domainEnd() - c.domainStart());
    for (double t : {side.from, side.to})
      if (!std::isfinite(t) || t < c.domainStart() - slack || t > c.domainEnd() + slack) return false;
    if (side.from == side.to) return false;
  }
  return loop.size() >= 2;
}

} // namespace

NetworkDescription insertConnectionCurves(const NetworkDescription &description, const std::string &file) {
  if (!description.connectionCurves) return description;
  NetworkDescription out = description;
  out.faces.clear();
  Splitter splitter(out.curves, description.reference);
  std::vector<std::vector<int>> partsOf(description.faces.size());
  bool changed = false;
  for (size_t f = 0; f < description.faces.size(); ++f) {
    const FaceDescription &face = description.faces[f];
    const std::string element = "face " + std::to_string(f);
    std::vector<Loop> parts;
    if (!face.holes.empty()) {
      if (face.holes.size() > 1)
        throw InputError(file, element, std::to_string(face.holes.size()) + " holes; a face may have one");
      if (!loopIsValid(description.curves, face.holes[0]))
        throw InputError(file, element + " hole", "a side refers to a missing curve or a range outside it");
      if (!loopIsValid(description.curves, face.sides))
        throw InputError(file, element, "a side refers to a missing curve or a range outside it");
      parts = splitter.ring(face.sides, face.holes[0], file, element);
    } else if (loopIsValid(description.curves, face.sides) && face.sides.size() >= 3) {
      parts = splitter.convexParts(face.sides);
    } else {
      parts = {face.sides};
    }
    if (parts.size() > 1) changed = true;
    for (size_t k = 0; k < parts.size(); ++k) {
      FaceDescription part;
      part.sides = std::move(parts[k]);
      part.partOf = face.partOf >= 0 ? face.partOf : static_cast<int>(f);
      part.name = parts.size() == 1 ? face.name
                                    : (face.name.empty() ? element : face.name) + " part " + std::to_string(k);
      partsOf[f].push_back(static_cast<int>(out.faces.size()));
      out.faces.push_back(std::move(part));
    }
  }
  if (!changed) return description;
  // A named master that was split: its part that borders the curve.
  for (EdgeDescription &edge : out.edges) {
    if (edge.masterFace < 0 || edge.masterFace >= static_cast<int>(partsOf.size())) continue;
    const std::vector<int> &parts = partsOf[edge.masterFace];
    auto borders = [&](int p) {
      return std::any_of(out.faces[p].sides.begin(), out.faces[p].sides.end(),
                         [&](const SideDescription &side) { return side.curve == edge.curve; });
    };
    const auto it = std::find_if(parts.begin(), parts.end(), borders);
    edge.masterFace = it == parts.end() ? parts.front() : *it;
  }
  for (int curve : splitter.connections()) out.edges.push_back({curve, -1, true});
  return out;
}

} // namespace v1
} // namespace curvenet
