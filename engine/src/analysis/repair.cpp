// Vertex repair (curvenet/analysis.hpp): end tangents turned into the fitted
// tangent plane, then the curvatures tweaked, at the vertices that fail them.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

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

/// A vertex whose tangents leave their plane too far for a turn to be a
/// repair (kCreaseResidual): a crease, where each face corner keeps its own
/// plane.
bool isCrease(const VertexAnalysis &va) { return va.valence >= 3 && va.tangentResidual > kCreaseResidual; }

/// Step 1 on every vertex without a tangent plane that is no crease.
NetworkDescription turnTangents(const Network &network, const NetworkAnalysis &analysis, double tolerance,
                                std::vector<RepairMove> &moves) {
  NetworkDescription out = network.description();
  std::map<int, std::vector<EndTurn>> byCurve;
  for (const VertexAnalysis &va : analysis.vertices) {
    if (!(va.tangentResidual > tolerance) || isCrease(va)) continue;
    for (const CurveEnd &end : va.ends) {
      const Vec3 inPlane = end.tangent - va.normal * dot(end.tangent, va.normal);
      if (squaredNorm(inPlane) == 0)
        throw InputError("", "vertex " + std::to_string(va.vertex),
                         "curve " + std::to_string(end.sourceCurve) +
                             " leaves along the fitted normal; its tangent has no direction in the tangent plane");
      byCurve[end.sourceCurve].push_back(
          {va.vertex, end.sourceParameter, end.towardsLargerParameter, end.tangent, normalized(inPlane)});
    }
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
    result.network = turnTangents(network, analysis, options.tangentTolerance, result.moves);
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
