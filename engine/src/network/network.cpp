// Network::build — from a description (curves + face loops) to topology.
//
// Order of work: validate the description, split every curve at the
// parameters where faces start or end sides on it (segments), merge segment
// end points into vertices, record which faces use each segment, then
// classify vertices. Errors name the face / side / curve at fault.
#include "curvenet/network.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>

#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

const char *toString(VertexKind kind) {
  switch (kind) {
  case VertexKind::Corner: return "corner";
  case VertexKind::Smooth: return "smooth";
  case VertexKind::T: return "T";
  case VertexKind::Y: return "Y";
  case VertexKind::X: return "X";
  case VertexKind::General: return "general";
  }
  return "?";
}

namespace {

std::string sideName(int face, int side) {
  return "face " + std::to_string(face) + " side " + std::to_string(side);
}

std::string formatPoint(const Vec3 &p) {
  std::ostringstream s;
  s.precision(9);
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

// Breakpoints closer than this fraction of a curve's domain are one parameter:
// files written with a few digits fewer than full precision still line up.
constexpr double kParameterTolerance = 1e-10;

// Two segment ends form one curve passing through a vertex when their
// outgoing tangents are opposite within this angle (radians).
constexpr double kContinuationAngle = 1e-4;

struct SegmentKey {
  int curve;
  int interval;
  auto operator<=>(const SegmentKey &) const = default;
};

} // namespace

Vec3 Network::outgoingTangent(int segment, int vertex) const {
  const Segment &seg = segments_.at(segment);
  const bool atStart = seg.start == vertex;
  const double s = atStart ? 0.0 : 1.0;
  Vec3 d = seg.curve.derivatives(s)[1];
  // A curve may start with a repeated control point (zero first derivative):
  // the chord to a nearby point then gives the tangent direction.
  if (squaredNorm(d) < 1e-30) d = seg.curve.point(atStart ? 1e-6 : 1.0 - 1e-6) - seg.curve.point(s);
  else if (!atStart) d = -d;
  return normalized(d);
}

Network Network::build(const NetworkDescription &input, const std::string &file) {
  const NetworkDescription split = insertConnectionCurves(input, file);
  const NetworkDescription &description = split;
  auto fail = [&](const std::string &element, const std::string &reason) {
    return InputError(file, element, reason);
  };

  Network net;
  net.name_ = description.name;
  net.description_ = description;
  net.reference_ = description.reference;

  const auto &curves = description.curves;
  if (description.faces.empty()) throw fail("network", "no faces: a network needs at least one loop of curves");
  for (const BSplineCurve &c : curves)
    for (const Vec3 &p : c.controlPoints()) net.bounds_.add(p);
  const double diagonal = net.bounds_.diagonal();
  if (!(diagonal > 0) || !std::isfinite(diagonal))
    throw fail("network", "degenerate bounding box (all curves in one point, or non-finite coordinates)");
  if (!(description.tolerance > 0 && description.tolerance < 1e-2))
    throw fail("tolerance", "must be in (0, 0.01) relative to the bounding-box diagonal");
  const double tolerance = description.tolerance * diagonal;

  // 1. Validate sides and collect breakpoints per curve.
  std::vector<std::vector<double>> breakpoints(curves.size());
  for (size_t f = 0; f < description.faces.size(); ++f) {
    const FaceDescription &face = description.faces[f];
    const int n = static_cast<int>(face.sides.size());
    if (n < 2 || n > 8)
      throw fail("face " + std::to_string(f), std::to_string(n) + (n == 1 ? " side" : " sides") + "; curvenet supports loops of 2 to 8 sides");
    if (!face.holes.empty())
      throw fail("face " + std::to_string(f), "has a hole, but connection curves are switched off (a face with a hole "
                                              "is built only as the composite of the faces they make)");
    for (int k = 0; k < n; ++k) {
      const SideDescription &side = face.sides[k];
      if (side.curve < 0 || side.curve >= static_cast<int>(curves.size()))
        throw fail(sideName(f, k), "refers to curve " + std::to_string(side.curve) + ", but there are " +
                                       std::to_string(curves.size()) + " curves");
      const BSplineCurve &c = curves[side.curve];
      const double a = c.domainStart(), b = c.domainEnd(), slack = kParameterTolerance * (b - a);
      for (double t : {side.from, side.to})
        if (!std::isfinite(t) || t < a - slack || t > b + slack) {
          std::ostringstream s;
          s << "parameter " << t << " is outside the domain [" << a << ", " << b << "] of curve " << side.curve;
          throw fail(sideName(f, k), s.str());
        }
      if (std::abs(side.to - side.from) <= slack)
        throw fail(sideName(f, k), "empty parameter range on curve " + std::to_string(side.curve));
      breakpoints[side.curve].push_back(std::clamp(side.from, a, b));
      breakpoints[side.curve].push_back(std::clamp(side.to, a, b));
    }
  }
  for (size_t c = 0; c < curves.size(); ++c) {
    auto &bp = breakpoints[c];
    std::sort(bp.begin(), bp.end());
    const double slack = kParameterTolerance * (curves[c].domainEnd() - curves[c].domainStart());
    bp.erase(std::unique(bp.begin(), bp.end(), [&](double x, double y) { return y - x <= slack; }), bp.end());
  }
  auto breakpointIndex = [&](int curve, double t) {
    const auto &bp = breakpoints[curve];
    auto it = std::min_element(bp.begin(), bp.end(),
                               [&](double x, double y) { return std::abs(x - t) < std::abs(y - t); });
    return static_cast<int>(it - bp.begin());
  };

  // 2. Segments: one per (curve, breakpoint interval) that some side covers.
  std::map<SegmentKey, int> segmentOf;
  auto segmentFor = [&](int curve, int interval) {
    auto [it, inserted] = segmentOf.try_emplace({curve, interval}, static_cast<int>(net.segments_.size()));
    if (inserted) {
      Segment seg;
      seg.sourceCurve = curve;
      seg.sourceFrom = breakpoints[curve][interval];
      seg.sourceTo = breakpoints[curve][interval + 1];
      seg.curve = curves[curve].restricted(seg.sourceFrom, seg.sourceTo).reparameterized(0.0, 1.0);
      net.segments_.push_back(std::move(seg));
    }
    return it->second;
  };

  // 3. Vertices: merge segment end points closer than the tolerance.
  auto vertexFor = [&](const Vec3 &p) {
    for (size_t v = 0; v < net.vertices_.size(); ++v)
      if (norm(net.vertices_[v].position - p) <= tolerance) return static_cast<int>(v);
    net.vertices_.push_back(Vertex{p, {}, {}, 0, 0, VertexKind::General, false});
    return static_cast<int>(net.vertices_.size() - 1);
  };

  // 4. Faces: sides as runs of segments; adjacency with orientation checks.
  std::vector<std::array<bool, 2>> forwardUse; // per segment: direction of faces[0], faces[1]
  for (size_t f = 0; f < description.faces.size(); ++f) {
    const FaceDescription &fd = description.faces[f];
    Face face;
    face.name = fd.name.empty() ? "face " + std::to_string(f) : fd.name;
    face.partOf = fd.partOf >= 0 ? fd.partOf : static_cast<int>(f);
    for (size_t k = 0; k < fd.sides.size(); ++k) {
      const SideDescription &sd = fd.sides[k];
      const BSplineCurve &c = curves[sd.curve];
      FaceSide side;
      side.sourceCurve = sd.curve;
      side.sourceFrom = std::clamp(sd.from, c.domainStart(), c.domainEnd());
      side.sourceTo = std::clamp(sd.to, c.domainStart(), c.domainEnd());
      const bool backwards = side.sourceFrom > side.sourceTo;
      const int i0 = breakpointIndex(sd.curve, side.sourceFrom), i1 = breakpointIndex(sd.curve, side.sourceTo);
      const double lo = std::min(side.sourceFrom, side.sourceTo), hi = std::max(side.sourceFrom, side.sourceTo);
      BSplineCurve piece = c.restricted(lo, hi);
      side.curve = (backwards ? piece.reversed() : piece).reparameterized(0.0, 1.0);
      const int first = std::min(i0, i1), last = std::max(i0, i1);
      for (int step = 0; step < last - first; ++step) {
        const int interval = backwards ? last - 1 - step : first + step;
        const int s = segmentFor(sd.curve, interval);
        if (static_cast<int>(forwardUse.size()) <= s) forwardUse.resize(s + 1);
        Segment &seg = net.segments_[s];
        const int slot = seg.faces[0] < 0 ? 0 : (seg.faces[1] < 0 ? 1 : 2);
        if (slot == 2)
          throw fail(sideName(f, k), "segment " + std::to_string(s) + " of curve " + std::to_string(sd.curve) +
                                         " is used by three faces (" + std::to_string(seg.faces[0]) + ", " +
                                         std::to_string(seg.faces[1]) + " and " + std::to_string(f) + ")");
        if (slot == 1 && seg.faces[0] == static_cast<int>(f))
          throw fail(sideName(f, k), "uses segment " + std::to_string(s) + " of curve " + std::to_string(sd.curve) +
                                         " twice");
        if (slot == 1 && forwardUse[s][0] == !backwards)
          throw fail(sideName(f, k), "runs along curve " + std::to_string(sd.curve) + " in the same direction as face " +
                                         std::to_string(seg.faces[0]) +
                                         ": the two faces on a curve must be oriented consistently (opposite directions)");
        seg.faces[slot] = static_cast<int>(f);
        forwardUse[s][slot] = !backwards;
        side.segments.push_back(s);
        side.segmentReversed.push_back(backwards);
        if (step > 0) {
          const double t = breakpoints[sd.curve][backwards ? interval + 1 : interval];
          side.breaks.push_back((t - side.sourceFrom) / (side.sourceTo - side.sourceFrom));
        }
      }
      face.sides.push_back(std::move(side));
    }
    net.faces_.push_back(std::move(face));
  }

  // Segment ends become vertices; reject segments that collapse to a point.
  for (size_t s = 0; s < net.segments_.size(); ++s) {
    Segment &seg = net.segments_[s];
    seg.start = vertexFor(seg.curve.point(0.0));
    seg.end = vertexFor(seg.curve.point(1.0));
    if (seg.curve.arcLength() <= tolerance)
      throw fail("curve " + std::to_string(seg.sourceCurve),
                 "the piece on [" + std::to_string(seg.sourceFrom) + ", " + std::to_string(seg.sourceTo) +
                     "] has (near) zero length");
    // A curve that stops and turns back (a cusp, or a piece running back
    // over itself) has no tangent there to hang a normal fence on.
    {
      constexpr int kSamples = 128;
      const double length = seg.curve.arcLength();
      Vec3 previous = seg.curve.derivatives(0.0)[1];
      for (int k = 1; k <= kSamples; ++k) {
        const double u = double(k) / kSamples;
        const Vec3 tangent = seg.curve.derivatives(u)[1];
        if (norm(tangent) <= 1e-12 * length || dot(tangent, previous) < -0.8 * norm(tangent) * norm(previous)) {
          std::ostringstream where;
          where.precision(3);
          where << "folds back on itself near parameter "
                << seg.sourceFrom + (seg.sourceTo - seg.sourceFrom) * (u - 0.5 / kSamples)
                << " (a cusp or a self-overlap: the tangent reverses), so no surface can follow it";
          throw fail("curve " + std::to_string(seg.sourceCurve), where.str());
        }
        previous = tangent;
      }
    }
    net.vertices_[seg.start].segments.push_back(static_cast<int>(s));
    net.vertices_[seg.end].segments.push_back(static_cast<int>(s));
  }

  // Explicit masters (paper 000 Sec. 5.1).
  std::vector<bool> seen(curves.size(), false);
  for (size_t k = 0; k < description.edges.size(); ++k) {
    const EdgeDescription &edge = description.edges[k];
    const std::string element = "edges[" + std::to_string(k) + "]";
    if (edge.curve < 0 || edge.curve >= static_cast<int>(curves.size()))
      throw fail(element, "curve " + std::to_string(edge.curve) + " does not exist");
    if (seen[edge.curve]) throw fail(element, "curve " + std::to_string(edge.curve) + " has settings twice");
    seen[edge.curve] = true;
    if (edge.connection)
      for (Segment &seg : net.segments_)
        if (seg.sourceCurve == edge.curve) seg.connection = true;
    if (edge.masterFace < 0) continue;
    if (edge.masterFace >= static_cast<int>(description.faces.size()))
      throw fail(element, "master face " + std::to_string(edge.masterFace) + " does not exist");
    for (Segment &seg : net.segments_) {
      if (seg.sourceCurve != edge.curve) continue;
      if (seg.faces[1] < 0 || (seg.faces[0] != edge.masterFace && seg.faces[1] != edge.masterFace))
        throw fail(element, "master face " + std::to_string(edge.masterFace) + " and another face must border every "
                            "piece of curve " + std::to_string(edge.curve));
      seg.masterFace = edge.masterFace;
    }
  }

  // Loops must close: the end vertex of each side is the start of the next.
  for (size_t f = 0; f < net.faces_.size(); ++f) {
    Face &face = net.faces_[f];
    for (FaceSide &side : face.sides) {
      const Segment &head = net.segments_[side.segments.front()];
      const Segment &tail = net.segments_[side.segments.back()];
      side.startVertex = side.segmentReversed.front() ? head.end : head.start;
      side.endVertex = side.segmentReversed.back() ? tail.start : tail.end;
    }
    const int n = face.sideCount();
    for (int k = 0; k < n; ++k) {
      const FaceSide &side = face.sides[k], &next = face.sides[(k + 1) % n];
      if (side.endVertex != next.startVertex) {
        const Vec3 a = side.curve.point(1.0), b = next.curve.point(0.0);
        std::ostringstream s;
        s.precision(3);
        s << "loop does not close: side " << k << " ends at " << formatPoint(a) << " but side " << (k + 1) % n
          << " starts at " << formatPoint(b) << ", " << norm(a - b) << " apart (tolerance " << tolerance << ")";
        throw fail("face " + std::to_string(f), s.str());
      }
    }
  }

  // 5. Vertex classification (paper 000 Fig. 1).
  for (size_t v = 0; v < net.vertices_.size(); ++v) {
    Vertex &vertex = net.vertices_[v];
    // A closed segment is listed twice: its first listing is its start end,
    // the second its end, so the two leave in opposite directions.
    std::vector<int> listed(net.segments_.size(), 0);
    for (int s : vertex.segments) {
      const Segment &seg = net.segments_[s];
      if (seg.isBoundary()) vertex.onBoundary = true;
      const bool useStart = seg.start == static_cast<int>(v) && (seg.end != seg.start || listed[s]++ == 0);
      const Vec3 d = seg.curve.derivatives(useStart ? 0.0 : 1.0)[1];
      vertex.tangents.push_back(normalized(useStart ? d : -d));
    }
    const auto &ends = vertex.tangents;
    vertex.valence = static_cast<int>(ends.size());
    // Greedy pairing of the most opposite tangents: each pair is one curve
    // passing through the vertex.
    std::vector<bool> paired(ends.size(), false);
    int pairs = 0;
    for (;;) {
      double best = std::numbers::pi - kContinuationAngle;
      int bi = -1, bj = -1;
      for (size_t i = 0; i < ends.size(); ++i)
        for (size_t j = i + 1; j < ends.size(); ++j) {
          if (paired[i] || paired[j]) continue;
          const double angle = angleBetween(ends[i], ends[j]);
          if (angle > best) best = angle, bi = static_cast<int>(i), bj = static_cast<int>(j);
        }
      if (bi < 0) break;
      paired[bi] = paired[bj] = true;
      ++pairs;
    }
    vertex.independentCurves = vertex.valence - pairs;
    const int n = vertex.valence, m = vertex.independentCurves;
    vertex.kind = n == 2 ? (m == 2 ? VertexKind::Corner : VertexKind::Smooth)
                : n == 3 ? (m == 3 ? VertexKind::Y : VertexKind::T)
                : (n == 4 && m == 2) ? VertexKind::X
                                     : VertexKind::General;
  }
  return net;
}

} // namespace v1
} // namespace curvenet
