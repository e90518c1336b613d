// Network::build — from a description (curves + face loops) to topology.
//
// Order of work (Network::build reads as these steps): check the bounds and
// tolerance; validate every side and collect, per curve, the parameters
// where sides start or end; build the faces, splitting curves at those
// parameters into segments and recording which faces use each; merge
// segment end points into vertices; apply the per-curve edge settings;
// check that every loop closes; classify the vertices. Errors name the
// face / side / curve at fault.
#include "curvenet/network.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
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

/// InputErrors that name the file being built.
struct Failure {
  const std::string &file;
  InputError operator()(const std::string &element, const std::string &reason) const {
    return InputError(file, element, reason);
  }
};

/// Per curve, the sorted distinct parameters where some side starts or ends.
using Breakpoints = std::vector<std::vector<double>>;

/// The bounding box of every control point, after checking that there is a
/// face, that the box has a size and that the tolerance is in range.
BoundingBox checkedBounds(const NetworkDescription &description, const Failure &fail) {
  if (description.faces.empty()) throw fail("network", "no faces: a network needs at least one loop of curves");
  BoundingBox bounds;
  for (const BSplineCurve &c : description.curves)
    for (const Vec3 &p : c.controlPoints()) bounds.add(p);
  const double diagonal = bounds.diagonal();
  if (!(diagonal > 0) || !std::isfinite(diagonal))
    throw fail("network", "degenerate bounding box (all curves in one point, or non-finite coordinates)");
  if (!(description.tolerance > 0 && description.tolerance < 1e-2))
    throw fail("tolerance", "must be in (0, 0.01) relative to the bounding-box diagonal");
  return bounds;
}

/// Step 1: validates every side (side count, curve index, parameter range)
/// and collects the breakpoints of each curve.
Breakpoints collectBreakpoints(const NetworkDescription &description, const Failure &fail) {
  const auto &curves = description.curves;
  Breakpoints breakpoints(curves.size());
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
  return breakpoints;
}

/// The breakpoint of `curve` nearest to parameter t.
int breakpointIndex(const Breakpoints &breakpoints, int curve, double t) {
  const auto &bp = breakpoints[curve];
  auto it = std::min_element(bp.begin(), bp.end(), [&](double x, double y) { return std::abs(x - t) < std::abs(y - t); });
  return static_cast<int>(it - bp.begin());
}

/// Steps 2 and 4: the faces, their sides as runs of segments, and the
/// segments they create (one per curve and breakpoint interval some side
/// covers), with adjacency and orientation checked as each side is added.
class FaceBuilder {
public:
  FaceBuilder(const NetworkDescription &description, const Breakpoints &breakpoints, const Failure &fail)
      : description_(description), breakpoints_(breakpoints), fail_(fail) {}

  std::vector<Face> build(std::vector<Segment> &segments) {
    segments_ = &segments;
    std::vector<Face> faces;
    for (size_t f = 0; f < description_.faces.size(); ++f) {
      const FaceDescription &fd = description_.faces[f];
      Face face;
      face.name = fd.name.empty() ? "face " + std::to_string(f) : fd.name;
      face.partOf = fd.partOf >= 0 ? fd.partOf : static_cast<int>(f);
      for (size_t k = 0; k < fd.sides.size(); ++k) face.sides.push_back(side(static_cast<int>(f), static_cast<int>(k)));
      faces.push_back(std::move(face));
    }
    return faces;
  }

private:
  /// Side k of face f, its segments claimed for the face.
  FaceSide side(int f, int k) {
    const SideDescription &sd = description_.faces[f].sides[k];
    const BSplineCurve &c = description_.curves[sd.curve];
    FaceSide side;
    side.sourceCurve = sd.curve;
    side.sourceFrom = std::clamp(sd.from, c.domainStart(), c.domainEnd());
    side.sourceTo = std::clamp(sd.to, c.domainStart(), c.domainEnd());
    const bool backwards = side.sourceFrom > side.sourceTo;
    const int i0 = breakpointIndex(breakpoints_, sd.curve, side.sourceFrom);
    const int i1 = breakpointIndex(breakpoints_, sd.curve, side.sourceTo);
    const double lo = std::min(side.sourceFrom, side.sourceTo), hi = std::max(side.sourceFrom, side.sourceTo);
    BSplineCurve piece = c.restricted(lo, hi);
    side.curve = (backwards ? piece.reversed() : piece).reparameterized(0.0, 1.0);
    const int first = std::min(i0, i1), last = std::max(i0, i1);
    for (int step = 0; step < last - first; ++step) {
      const int interval = backwards ? last - 1 - step : first + step;
      const int s = segmentFor(sd.curve, interval);
      claim(s, f, k, backwards);
      side.segments.push_back(s);
      side.segmentReversed.push_back(backwards);
      if (step > 0) {
        const double t = breakpoints_[sd.curve][backwards ? interval + 1 : interval];
        side.breaks.push_back((t - side.sourceFrom) / (side.sourceTo - side.sourceFrom));
      }
    }
    return side;
  }

  /// The segment of (curve, interval), made on first use.
  int segmentFor(int curve, int interval) {
    auto [it, inserted] = segmentOf_.try_emplace({curve, interval}, static_cast<int>(segments_->size()));
    if (inserted) {
      Segment seg;
      seg.sourceCurve = curve;
      seg.sourceFrom = breakpoints_[curve][interval];
      seg.sourceTo = breakpoints_[curve][interval + 1];
      seg.curve = description_.curves[curve].restricted(seg.sourceFrom, seg.sourceTo).reparameterized(0.0, 1.0);
      segments_->push_back(std::move(seg));
    }
    return it->second;
  }

  /// Records face f (side k) on segment s: at most two faces, each once, in
  /// opposite directions.
  void claim(int s, int f, int k, bool backwards) {
    const int curve = description_.faces[f].sides[k].curve;
    if (static_cast<int>(forwardUse_.size()) <= s) forwardUse_.resize(s + 1);
    Segment &seg = (*segments_)[s];
    const int slot = seg.faces[0] < 0 ? 0 : (seg.faces[1] < 0 ? 1 : 2);
    if (slot == 2)
      throw fail_(sideName(f, k), "segment " + std::to_string(s) + " of curve " + std::to_string(curve) +
                                      " is used by three faces (" + std::to_string(seg.faces[0]) + ", " +
                                      std::to_string(seg.faces[1]) + " and " + std::to_string(f) + ")");
    if (slot == 1 && seg.faces[0] == f)
      throw fail_(sideName(f, k), "uses segment " + std::to_string(s) + " of curve " + std::to_string(curve) + " twice");
    if (slot == 1 && forwardUse_[s][0] == !backwards)
      throw fail_(sideName(f, k), "runs along curve " + std::to_string(curve) + " in the same direction as face " +
                                      std::to_string(seg.faces[0]) +
                                      ": the two faces on a curve must be oriented consistently (opposite directions)");
    seg.faces[slot] = f;
    forwardUse_[s][slot] = !backwards;
  }

  const NetworkDescription &description_;
  const Breakpoints &breakpoints_;
  const Failure &fail_;
  std::vector<Segment> *segments_ = nullptr;
  std::map<SegmentKey, int> segmentOf_;
  std::vector<std::array<bool, 2>> forwardUse_; ///< per segment: direction of faces[0], faces[1]
};

/// A segment must have a length and a tangent everywhere: a curve that stops
/// and turns back (a cusp, or a piece running back over itself) has no
/// tangent there to hang a normal fence on.
void checkSegmentShape(const Segment &seg, double tolerance, const Failure &fail) {
  if (seg.curve.arcLength() <= tolerance)
    throw fail("curve " + std::to_string(seg.sourceCurve),
               "the piece on [" + std::to_string(seg.sourceFrom) + ", " + std::to_string(seg.sourceTo) +
                   "] has (near) zero length");
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

/// Step 3: segment ends closer than the tolerance become one vertex; every
/// segment's shape is checked on the way.
std::vector<Vertex> mergeVertices(std::vector<Segment> &segments, double tolerance, const Failure &fail) {
  std::vector<Vertex> vertices;
  auto vertexFor = [&](const Vec3 &p) {
    for (size_t v = 0; v < vertices.size(); ++v)
      if (norm(vertices[v].position - p) <= tolerance) return static_cast<int>(v);
    vertices.push_back(Vertex{p, {}, {}, 0, 0, VertexKind::General, false});
    return static_cast<int>(vertices.size() - 1);
  };
  for (size_t s = 0; s < segments.size(); ++s) {
    Segment &seg = segments[s];
    seg.start = vertexFor(seg.curve.point(0.0));
    seg.end = vertexFor(seg.curve.point(1.0));
    checkSegmentShape(seg, tolerance, fail);
    vertices[seg.start].segments.push_back(static_cast<int>(s));
    vertices[seg.end].segments.push_back(static_cast<int>(s));
  }
  return vertices;
}

// ---- Master surfaces given from outside ([SV14] Sec. 5.1) ----------------

/// Curve samples per segment at which a curve is projected onto its master
/// surface: enough that a curve leaving the surface between its control
/// points is caught (its deviation is a polynomial of the curve's degree
/// over each span, sampled several times per span at this count).
constexpr int kMasterCheckSamples = 64;

/// The largest distance from curve `curve`'s pieces to `master`, and where
/// (a source-curve parameter).
struct MasterDistance {
  double distance = 0, parameter = 0;
};

std::string formatDistance(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

MasterDistance distanceToMaster(const std::vector<Segment> &segments, int curve, const BSplineSurface &master,
                                double tolerance) {
  MasterDistance worst;
  for (const Segment &seg : segments) {
    if (seg.sourceCurve != curve) continue;
    SurfaceProjection foot = master.closestPoint(seg.curve.point(0.0));
    for (int j = 0; j <= kMasterCheckSamples; ++j) {
      const double u = double(j) / kMasterCheckSamples;
      const Vec3 p = seg.curve.point(u);
      // From the previous foot (the samples are close); a warm start that
      // lands off the surface may have stalled in a local minimum, so it is
      // confirmed by the global search before it counts.
      foot = master.closestPoint(p, foot.u, foot.v);
      if (foot.distance > tolerance) {
        const SurfaceProjection global = master.closestPoint(p);
        if (global.distance < foot.distance) foot = global;
      }
      if (foot.distance > worst.distance)
        worst = {foot.distance, seg.sourceFrom + (seg.sourceTo - seg.sourceFrom) * u};
    }
  }
  return worst;
}

/// Edge `k` names a master surface: it must exist, not come with a master
/// face, and the curve must lie on it within the tolerance.
void applyMasterSurface(const NetworkDescription &description, size_t k, std::vector<Segment> &segments,
                        double tolerance, const Failure &fail) {
  const EdgeDescription &edge = description.edges[k];
  const std::string element = "edges[" + std::to_string(k) + "]";
  const std::string name = "master surface " + std::to_string(edge.masterSurface);
  if (edge.masterSurface >= static_cast<int>(description.surfaces.size()))
    throw fail(element, name + " does not exist (the document has " + std::to_string(description.surfaces.size()) +
                            " surfaces)");
  if (edge.masterFace >= 0) throw fail(element, "names both a master face and a master surface");
  const MasterDistance d = distanceToMaster(segments, edge.curve, description.surfaces[size_t(edge.masterSurface)],
                                            tolerance);
  if (d.distance > tolerance)
    throw fail(element, "curve " + std::to_string(edge.curve) + " is " + formatDistance(d.distance) + " from " + name +
                            " at curve parameter " + formatDistance(d.parameter) + " (tolerance " +
                            formatDistance(tolerance) + ", " + formatDistance(description.tolerance) +
                            " of the diagonal)");
  for (Segment &seg : segments)
    if (seg.sourceCurve == edge.curve) seg.masterSurface = edge.masterSurface;
}

// ---- end of master surfaces --------------------------------------------------

/// The per-curve settings of `edges`: connection curves, and explicit
/// masters ([SV14] Sec. 5.1): a face bordering every piece of its curve, or
/// a surface given from outside that the curve lies on.
void applyEdgeSettings(const NetworkDescription &description, std::vector<Segment> &segments, double tolerance,
                       const Failure &fail) {
  const auto &curves = description.curves;
  std::vector<bool> seen(curves.size(), false);
  for (size_t k = 0; k < description.edges.size(); ++k) {
    const EdgeDescription &edge = description.edges[k];
    const std::string element = "edges[" + std::to_string(k) + "]";
    if (edge.curve < 0 || edge.curve >= static_cast<int>(curves.size()))
      throw fail(element, "curve " + std::to_string(edge.curve) + " does not exist");
    if (seen[edge.curve]) throw fail(element, "curve " + std::to_string(edge.curve) + " has settings twice");
    seen[edge.curve] = true;
    if (edge.connection)
      for (Segment &seg : segments)
        if (seg.sourceCurve == edge.curve) seg.connection = true;
    if (edge.masterSurface >= 0) applyMasterSurface(description, k, segments, tolerance, fail);
    if (edge.masterFace < 0) continue;
    if (edge.masterFace >= static_cast<int>(description.faces.size()))
      throw fail(element, "master face " + std::to_string(edge.masterFace) + " does not exist");
    for (Segment &seg : segments) {
      if (seg.sourceCurve != edge.curve) continue;
      if (seg.faces[1] < 0 || (seg.faces[0] != edge.masterFace && seg.faces[1] != edge.masterFace))
        throw fail(element, "master face " + std::to_string(edge.masterFace) + " and another face must border every "
                            "piece of curve " + std::to_string(edge.curve));
      seg.masterFace = edge.masterFace;
    }
  }
}

/// Each side's end vertices; loops must close: the end vertex of each side
/// is the start of the next.
void closeLoops(std::vector<Face> &faces, const std::vector<Segment> &segments, double tolerance, const Failure &fail) {
  for (size_t f = 0; f < faces.size(); ++f) {
    Face &face = faces[f];
    for (FaceSide &side : face.sides) {
      const Segment &head = segments[side.segments.front()];
      const Segment &tail = segments[side.segments.back()];
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
}

/// How many pairs of opposite tangents (within kContinuationAngle) the
/// vertex's curve ends form, paired greedily, most opposite first: each pair
/// is one curve passing through the vertex.
int continuingPairs(const std::vector<Vec3> &ends) {
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
    if (bi < 0) return pairs;
    paired[bi] = paired[bj] = true;
    ++pairs;
  }
}

/// Step 5: tangents, valence, independent curves and kind of every vertex
/// ([SV14] Fig. 1).
void classifyVertices(std::vector<Vertex> &vertices, const std::vector<Segment> &segments) {
  for (size_t v = 0; v < vertices.size(); ++v) {
    Vertex &vertex = vertices[v];
    // A closed segment is listed twice: its first listing is its start end,
    // the second its end, so the two leave in opposite directions.
    std::vector<int> listed(segments.size(), 0);
    for (int s : vertex.segments) {
      const Segment &seg = segments[s];
      if (seg.isBoundary()) vertex.onBoundary = true;
      const bool useStart = seg.start == static_cast<int>(v) && (seg.end != seg.start || listed[s]++ == 0);
      const Vec3 d = seg.curve.derivatives(useStart ? 0.0 : 1.0)[1];
      vertex.tangents.push_back(normalized(useStart ? d : -d));
    }
    vertex.valence = static_cast<int>(vertex.tangents.size());
    vertex.independentCurves = vertex.valence - continuingPairs(vertex.tangents);
    const int n = vertex.valence, m = vertex.independentCurves;
    vertex.kind = n == 2 ? (m == 2 ? VertexKind::Corner : VertexKind::Smooth)
                : n == 3 ? (m == 3 ? VertexKind::Y : VertexKind::T)
                : (n == 4 && m == 2) ? VertexKind::X
                                     : VertexKind::General;
  }
}

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
  const NetworkDescription description = insertConnectionCurves(input, file);
  const Failure fail{file};
  Network net;
  net.name_ = description.name;
  net.description_ = description;
  net.reference_ = description.reference;
  net.bounds_ = checkedBounds(description, fail);
  const double tolerance = description.tolerance * net.bounds_.diagonal();
  const Breakpoints breakpoints = collectBreakpoints(description, fail);
  net.faces_ = FaceBuilder(description, breakpoints, fail).build(net.segments_);
  net.vertices_ = mergeVertices(net.segments_, tolerance, fail);
  applyEdgeSettings(description, net.segments_, tolerance, fail);
  closeLoops(net.faces_, net.segments_, tolerance, fail);
  classifyVertices(net.vertices_, net.segments_);
  return net;
}

} // namespace v1
} // namespace curvenet
