// Vertex repair (curvenet/analysis.hpp): end tangents turned into the fitted
// tangent plane, then the curvatures tweaked, at the vertices that fail them.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>

#include <Eigen/Eigenvalues>

#include "analysis/editable_curve.hpp"
#include "analysis/vertex_frames.hpp"
#include "curvenet/analysis.hpp"
#include "curvenet/error.hpp"
#include "curvenet/surface.hpp"

namespace curvenet {
inline namespace v1 {

const char *toString(RepairKind kind) {
  switch (kind) {
  case RepairKind::TangentPlane: return "tangent-plane";
  case RepairKind::Curvature: return "curvature";
  }
  return "?";
}

namespace {

/// The smallest rotation taking unit vector `from` to unit vector `to`
/// (Rodrigues), applied to v.
Vec3 rotate(const Vec3 &v, const Vec3 &from, const Vec3 &to) {
  const Vec3 axis = cross(from, to);
  const double s = norm(axis), c = dot(from, to);
  if (s < 1e-300) return v;
  const Vec3 k = axis / s;
  return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

/// The degree a Bézier curve is raised to before its tangents are turned
/// (EditableCurve::raiseBezierDegree).
constexpr int kSmoothTurnDegree = 4;

/// One end tangent to turn: the vertex parameter on its source curve, the
/// side of it the end's segment lies on, and the tangent before and after.
struct EndTurn {
  int vertex = -1;
  double t0 = 0;
  bool right = true;
  Vec3 from, to;
};

/// Index of the control point at parameter t0 (an end of the domain, or an
/// interior knot of multiplicity ≥ p).
int pointAt(const EditableCurve &edit, double t0) {
  if (t0 <= edit.U[edit.p]) return 0;
  if (t0 >= edit.U[edit.U.size() - edit.p - 1]) return edit.count() - 1;
  return int(std::lower_bound(edit.U.begin(), edit.U.end(), t0) - edit.U.begin()) - 1;
}

int turnedPoint(const EditableCurve &edit, const EndTurn &turn) { return pointAt(edit, turn.t0) + (turn.right ? 1 : -1); }

/// Turns the tangents of one curve; appends the moves.
BSplineCurve turnCurve(const Network &network, int curveIndex, std::vector<EndTurn> turns,
                       std::vector<RepairMove> &moves) {
  // Smoothness kept: a turned point of a cubic Bézier side reaches the far
  // vertex's curvature, and a knot inserted to stop it would leave a jump of
  // the third derivative inside the side (which gregory-g2's ribbons carry
  // into the surface's first derivatives). At degree 4 the second point
  // leaves the far end alone to second order with no knot at all.
  EndEdits prepared = startEndEdits(network, curveIndex, kSmoothTurnDegree, turns);
  EditableCurve &edit = prepared.edit;
  const std::vector<double> &pinned = prepared.pinned;
  const double a = network.description().curves[curveIndex].domainStart();
  const double b = network.description().curves[curveIndex].domainEnd();
  // Split the first span beyond each vertex until the turned point leaves the
  // neighbouring vertex alone to second order (position, tangent, curvature).
  separateFromNeighbours(edit, turns, pinned, [&](const EndTurn &turn) { return turnedPoint(edit, turn); }, 100000,
                         "curve " + std::to_string(curveIndex));
  // The rotations, about the vertex point. A curve passing through turns both
  // neighbours with the rotation of its first end listed, which maps the
  // opposite tangent to the opposite of the turned one: it stays C¹.
  std::vector<int> turnedPoints;
  for (const EndTurn &turn : turns) {
    const int j = turnedPoint(edit, turn);
    if (std::find(turnedPoints.begin(), turnedPoints.end(), j) != turnedPoints.end()) continue;
    const int k = pointAt(edit, turn.t0);
    auto turnPoint = [&](int index) {
      const Vec3 centre = edit.wp[k] / edit.w[k], before = edit.wp[index] / edit.w[index];
      const Vec3 after = centre + rotate(before - centre, turn.from, turn.to);
      edit.wp[index] = edit.w[index] * after;
      turnedPoints.push_back(index);
      RepairMove move;
      move.vertex = turn.vertex;
      move.curve = curveIndex;
      move.kind = RepairKind::TangentPlane;
      move.size = norm(after - before);
      move.sizeRelative = move.size / network.diagonal();
      move.angle = angleBetween(turn.from, turn.to);
      moves.push_back(move);
    };
    turnPoint(j);
    const int across = 2 * k - j; // the other neighbour of a vertex inside the curve
    const bool inside = turn.t0 > a && turn.t0 < b;
    if (inside && std::find(turnedPoints.begin(), turnedPoints.end(), across) == turnedPoints.end()) turnPoint(across);
  }
  return edit.curve();
}

/// A vertex whose tangents leave their plane by more than kCreaseResidual.
bool isCrease(const VertexAnalysis &va) { return va.valence >= 3 && va.tangentResidual > kCreaseResidual; }

/// The largest turn (radians) the repair makes at a crease vertex (the
/// public sketches need up to 15.5°, at doghead's vertex 0): a fan
/// whose G¹ curves leave the plane of its crease curves by more, or a crease
/// vertex without crease segments whose tangents leave their plane by more,
/// was drawn that way on purpose and is left alone (RepairResult::skipped).
constexpr double kMaxCreaseTurn = 16 * std::numbers::pi / 180;

/// The turn of `end` into the plane of unit normal n.
EndTurn turnInto(const VertexAnalysis &va, const CurveEnd &end, const Vec3 &n) {
  const Vec3 inPlane = end.tangent - n * dot(end.tangent, n);
  if (squaredNorm(inPlane) == 0)
    throw InputError("", "vertex " + std::to_string(va.vertex),
                     "curve " + std::to_string(end.sourceCurve) +
                         " leaves along the fitted normal; its tangent has no direction in the tangent plane");
  return {va.vertex, end.sourceParameter, end.towardsLargerParameter, end.tangent, normalized(inPlane)};
}

/// The face corners at vertex v, as the two segments each joins there.
std::vector<std::array<int, 2>> cornersAt(const Network &network, int v) {
  std::vector<std::array<int, 2>> corners;
  const auto &segments = network.segments();
  for (const Face &face : network.faces()) {
    std::vector<std::pair<int, bool>> loop;
    for (const FaceSide &side : face.sides)
      for (std::size_t j = 0; j < side.segments.size(); ++j) loop.emplace_back(side.segments[j], side.segmentReversed[j]);
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const auto [s, reversed] = loop[i];
      if ((reversed ? segments[s].start : segments[s].end) == v) corners.push_back({s, loop[(i + 1) % loop.size()].first});
    }
  }
  return corners;
}

/// Why a fan is left alone when its turns would exceed kMaxCreaseTurn.
constexpr const char *kTurnTooLarge = "needs a turn of more than 16°";

/// True when `end`'s curve passes through the vertex (another end of the
/// same curve at the same parameter): turning it turns both halves.
bool passesThrough(const VertexAnalysis &va, const CurveEnd &end) {
  for (const CurveEnd &other : va.ends)
    if (&other != &end && other.sourceCurve == end.sourceCurve && other.sourceParameter == end.sourceParameter)
      return true;
  return false;
}

/// The unit normal of the plane that holds `line` and, among the planes
/// through it, spreads the `others` most (their least-squares plane about
/// that line).
Vec3 planeThroughLine(const Vec3 &line, const std::vector<Vec3> &others) {
  const Vec3 e1 = normalized(cross(line, std::abs(line.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
  const Vec3 e2 = cross(line, e1);
  double xx = 0, xy = 0, yy = 0;
  for (const Vec3 &t : others) {
    const double x = dot(t, e1), y = dot(t, e2);
    xx += x * x, xy += x * y, yy += y * y;
  }
  // The direction (in the e1, e2 plane) of largest spread; the normal is
  // normal to it and the line.
  const double phi = 0.5 * std::atan2(2 * xy, xx - yy);
  return normalized(cross(line, e1 * std::cos(phi) + e2 * std::sin(phi)));
}

/// The unit normal of the least-squares plane through the origin of unit
/// directions: the eigenvector of Σ t tᵀ of the smallest eigenvalue.
Vec3 leastSquaresPlane(const std::vector<Vec3> &directions) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (const Vec3 &t : directions) {
    const Eigen::Vector3d c{t.x, t.y, t.z};
    m += c * c.transpose();
  }
  const Eigen::Vector3d n = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvectors().col(0);
  return normalized(Vec3{n.x(), n.y(), n.z()});
}

/// Turns a fan's G¹ curves (`inner`) into one plane with its two bounding
/// crease curves, a and b: the plane of a and b where that takes at most
/// kMaxCreaseTurn (where they run nearly straight through, the plane holding
/// that line and the inner curves' spread). Where it would take more and a
/// bound may turn (`free`: no other fan's plane holds it), the bounds that
/// may turn join the fit: with both, the least-squares plane of all the
/// fan's curves; with one, the plane through the other bound that fits the
/// rest. The turns go into byCurve; returns why the fan is left alone, or
/// "" when it is not.
std::string turnFan(const VertexAnalysis &va, const CurveEnd &a, const CurveEnd &b,
                    const std::vector<const CurveEnd *> &inner, std::array<bool, 2> free, double tolerance,
                    std::map<int, std::vector<EndTurn>> &byCurve) {
  std::vector<Vec3> innerTangents;
  for (const CurveEnd *end : inner) innerTangents.push_back(end->tangent);
  // The turns into the plane of normal n, or why not.
  std::vector<std::pair<int, EndTurn>> turns;
  auto turnsInto = [&](const Vec3 &n, std::array<bool, 2> turnBounds) -> std::string {
    turns.clear();
    std::vector<const CurveEnd *> ends = inner;
    if (turnBounds[0]) ends.push_back(&a);
    if (turnBounds[1]) ends.push_back(&b);
    for (const CurveEnd *end : ends) {
      if (std::abs(dot(end->tangent, n)) <= std::sin(tolerance)) continue;
      if (passesThrough(va, *end)) return "curve " + std::to_string(end->sourceCurve) + " passes through the vertex";
      turns.emplace_back(end->sourceCurve, turnInto(va, *end, n));
      if (angleBetween(end->tangent, turns.back().second.to) > kMaxCreaseTurn) return kTurnTooLarge;
    }
    return "";
  };
  const Vec3 across = cross(a.tangent, b.tangent);
  const Vec3 exact = norm(across) < std::sin(kMaxCreaseTurn) ? planeThroughLine(normalized(a.tangent - b.tangent), innerTangents)
                                                             : normalized(across);
  std::string refusal = turnsInto(exact, {false, false});
  if (refusal == kTurnTooLarge && (free[0] || free[1])) {
    std::vector<Vec3> all = innerTangents;
    if (free[0]) all.push_back(a.tangent);
    if (free[1]) all.push_back(b.tangent);
    const Vec3 n = free[0] && free[1] ? leastSquaresPlane(all) : planeThroughLine(free[0] ? b.tangent : a.tangent, all);
    refusal = turnsInto(n, free);
  }
  if (!refusal.empty()) return refusal;
  for (const auto &[curve, turn] : turns) byCurve[curve].push_back(turn);
  return "";
}

/// Step 1 at a crease vertex. The faces around it fall into fans: maximal
/// runs of corners joined by G¹ segments, each bounded by two crease (or
/// boundary) segments. A crease curve lies on both sheets it separates, so
/// a fan's one tangent plane is that of its two bounding curves, and the
/// fan's G¹ curves are turned into it: every corner of the fan then has that
/// plane, and the fences of its G¹ segments (the mean of the two corner
/// planes, fenceEndNormal) agree with both patches. A crease vertex with no
/// crease segment is a smooth vertex drawn badly: its tangents are turned
/// into their fitted plane as at any vertex. A fan whose bounds' plane would
/// take a turn above kMaxCreaseTurn turns the bounds that no other fan holds
/// along with its G¹ curves (turnFan); still above it, a fan with other than
/// two bounds, or a G¹ curve passing through the vertex leave the fan alone,
/// named in `skipped`.
void turnCreaseFans(const Network &network, const std::vector<VertexFrame> &frames, const VertexAnalysis &va,
                    double tolerance, std::map<int, std::vector<EndTurn>> &byCurve, std::vector<std::string> &skipped) {
  const int v = va.vertex;
  const std::string where = "vertex " + std::to_string(v) + ": ";
  std::map<int, const CurveEnd *> endOf;
  for (const CurveEnd &end : va.ends) {
    if (endOf.count(end.segment)) return skipped.push_back(where + "a segment with both ends here"), void();
    endOf[end.segment] = &end;
  }
  auto smooth = [&](int s) { return !network.segments()[s].isBoundary() && !isCreaseSegment(network, frames, s); };
  bool anyCrease = false;
  for (const auto &[s, end] : endOf) anyCrease |= !smooth(s);
  if (!anyCrease) {
    // No crease segment: one tangent plane is meant, the fitted one.
    std::vector<std::pair<int, EndTurn>> turns;
    for (const CurveEnd &end : va.ends) {
      if (std::abs(dot(end.tangent, va.normal)) <= std::sin(tolerance)) continue;
      turns.emplace_back(end.sourceCurve, turnInto(va, end, va.normal));
      if (angleBetween(end.tangent, turns.back().second.to) > kMaxCreaseTurn)
        return skipped.push_back(where + "no crease segment, but a tangent leaves the plane by more than 16°"), void();
    }
    for (const auto &[curve, turn] : turns) byCurve[curve].push_back(turn);
    return;
  }
  // Fans: corners joined across their G¹ segments (union-find over corners).
  const std::vector<std::array<int, 2>> corners = cornersAt(network, v);
  std::vector<int> parent(corners.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = int(i);
  auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::map<int, int> firstCorner;
  for (std::size_t i = 0; i < corners.size(); ++i)
    for (int s : corners[i]) {
      if (!smooth(s)) continue;
      if (auto [it, fresh] = firstCorner.emplace(s, int(i)); !fresh) parent[root(int(i))] = root(it->second);
    }
  std::map<int, std::vector<int>> fans; // root → segments (bounds once, G¹ segments twice)
  for (std::size_t i = 0; i < corners.size(); ++i)
    for (int s : corners[i]) fans[root(int(i))].push_back(s);
  struct Fan {
    std::vector<int> bounds, inner;
  };
  std::vector<Fan> split;
  for (auto &[r, segs] : fans) {
    Fan fan;
    for (int s : segs) {
      if (!endOf.count(s)) continue;
      if (!smooth(s)) fan.bounds.push_back(s);
      else if (std::find(fan.inner.begin(), fan.inner.end(), s) == fan.inner.end()) fan.inner.push_back(s);
    }
    split.push_back(std::move(fan));
  }
  // A crease curve may turn with a fan when no other fan's plane holds it:
  // on its other side lies a lone face corner (a fan without G¹ curves), and
  // the curve ends here (turning a curve passing through turns both halves).
  auto mayTurn = [&](int bound, const Fan &own) {
    if (network.segments()[bound].isBoundary() || passesThrough(va, *endOf[bound])) return false;
    for (const Fan &fan : split)
      if (&fan != &own && !fan.inner.empty() &&
          std::find(fan.bounds.begin(), fan.bounds.end(), bound) != fan.bounds.end())
        return false;
    return true;
  };
  for (const Fan &fan : split) {
    if (fan.inner.empty()) continue;
    std::string curves;
    for (int s : fan.inner) curves += (curves.empty() ? "" : ", ") + std::to_string(endOf[s]->sourceCurve);
    const std::string named = where + "fan of curves " + curves + ": ";
    if (fan.bounds.size() != 2) {
      skipped.push_back(named + std::to_string(fan.bounds.size()) + " crease or boundary curves bound it, not 2");
      continue;
    }
    std::vector<const CurveEnd *> inner;
    for (int s : fan.inner) inner.push_back(endOf[s]);
    const std::string refusal = turnFan(va, *endOf[fan.bounds[0]], *endOf[fan.bounds[1]], inner,
                                        {mayTurn(fan.bounds[0], fan), mayTurn(fan.bounds[1], fan)}, tolerance, byCurve);
    if (!refusal.empty()) skipped.push_back(named + refusal);
  }
}

/// Step 1 on every vertex without a tangent plane: turned into the fitted
/// plane, or at a crease per fan (turnCreaseFans).
NetworkDescription turnTangents(const Network &network, const NetworkAnalysis &analysis, double tolerance,
                                std::vector<RepairMove> &moves, std::vector<std::string> &skipped) {
  NetworkDescription out = network.description();
  const std::vector<VertexFrame> frames = computeVertexFrames(network);
  std::map<int, std::vector<EndTurn>> byCurve;
  for (const VertexAnalysis &va : analysis.vertices) {
    if (!(va.tangentResidual > tolerance)) continue;
    if (isCrease(va) && !frames[va.vertex].crease) continue; // normals given along the curves set its plane
    if (frames[va.vertex].crease) {
      turnCreaseFans(network, frames, va, tolerance, byCurve, skipped);
      continue;
    }
    for (const CurveEnd &end : va.ends) byCurve[end.sourceCurve].push_back(turnInto(va, end, va.normal));
  }
  for (auto &[curve, turns] : byCurve) out.curves[curve] = turnCurve(network, curve, std::move(turns), moves);
  return out;
}

} // namespace

RepairResult repairNetwork(const Network &network, const RepairOptions &options) {
  RepairResult result;
  if (!options.tangentPlanes && !options.curvatures) {
    result.network = network.description();
    return result;
  }
  const NetworkAnalysis analysis = analyzeNetwork(network, options.analysis);
  std::optional<Network> turned;
  if (options.tangentPlanes && analysis.maxTangentResidual > options.tangentTolerance) {
    result.network = turnTangents(network, analysis, options.tangentTolerance, result.moves, result.skipped);
    if (!result.moves.empty()) turned = Network::build(result.network, network.name());
  } else {
    result.network = network.description();
  }
  if (options.curvatures) {
    TweakOptions tweakOptions;
    tweakOptions.analysis = options.analysis;
    tweakOptions.skipDegreeOne = true;
    tweakOptions.skipCreases = true;
    const TweakResult tweak = tweakNetwork(turned ? *turned : network, tweakOptions);
    if (!tweak.moves.empty()) {
      result.network = tweak.network;
      for (const ControlPointMove &m : tweak.moves) {
        RepairMove move;
        move.vertex = m.vertex;
        move.curve = m.curve;
        move.kind = RepairKind::Curvature;
        move.size = std::abs(m.distance);
        move.sizeRelative = move.size / network.diagonal();
        result.moves.push_back(move);
      }
    }
  }
  for (const RepairMove &m : result.moves) result.maxMoveRelative = std::max(result.maxMoveRelative, m.sizeRelative);
  return result;
}

std::string curveHandlingName(CurveHandling curves) { return curves == CurveHandling::Kept ? "kept" : "repaired"; }

std::optional<CurveHandling> curveHandlingFromName(const std::string &name) {
  if (name == "kept") return CurveHandling::Kept;
  if (name == "repaired") return CurveHandling::Repaired;
  return std::nullopt;
}

RepairOptions repairOptionsFor(Scheme scheme) {
  RepairOptions options;
  options.tangentPlanes = acceptsAnyLoop(scheme);
  options.curvatures = scheme == Scheme::GregoryG2;
  return options;
}

} // namespace v1
} // namespace curvenet
