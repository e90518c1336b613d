// Curve tweaking ([SV14] Sec. 2 (iii)): give every curve end at a vertex that
// fails the Euler constraint the normal curvature of the fitted surface
// curvature, by one control-point move along the vertex normal per end. The
// reasoning (which control point, why knots are inserted first) is in
// curvenet/analysis.hpp.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "analysis/editable_curve.hpp"
#include "analysis/vertex_frames.hpp"
#include "curvenet/analysis.hpp"
#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

/// The degree a Bézier curve is raised to before its curvatures are tweaked
/// (EditableCurve::raiseBezierDegree).
constexpr int kSmoothTweakDegree = 5;

/// One end to repair: the vertex parameter t0 on a source curve, the side of
/// t0 the end's segment lies on, and the curvature it must get.
struct EndTweak {
  int vertex = -1;
  double t0 = 0;
  bool right = true; ///< the end's segment lies at parameters > t0
  Vec3 normal;
  double target = 0;
};

/// Normal curvature c''·n / |c'|² at t0 from one side, and c' there.
struct EndState {
  double kappa = 0;
  Vec3 velocity;
};
EndState endState(const BSplineCurve &c, double t0, bool right, const Vec3 &n) {
  // derivatives() takes the span to the right of an interior knot; the
  // reversed curve's right side is this curve's left side (c' flips sign,
  // c'' does not).
  const auto d = right ? c.derivatives(t0) : c.reversed().derivatives(c.domainStart() + c.domainEnd() - t0);
  return {dot(d[2], n) / squaredNorm(d[1]), right ? d[1] : -d[1]};
}

} // namespace

TweakResult tweakNetwork(const Network &network, const TweakOptions &options) {
  const NetworkAnalysis analysis = analyzeNetwork(network, options.analysis);
  const double tolerance = options.eulerTolerance < 0 ? options.analysis.curvatureTolerance : options.eulerTolerance;

  TweakResult result;
  result.network = network.description();
  std::map<int, std::vector<EndTweak>> byCurve;
  for (const VertexAnalysis &va : analysis.vertices) {
    if (!(va.eulerResidualRelative > tolerance)) continue;
    if (options.skipCreases && va.valence >= 3 && va.tangentResidual > kCreaseResidual) {
      result.skippedVertices.push_back(va.vertex);
      continue;
    }
    if (options.skipDegreeOne && std::any_of(va.ends.begin(), va.ends.end(), [&](const CurveEnd &end) {
          return result.network.curves[end.sourceCurve].degree() < 2;
        })) {
      result.skippedVertices.push_back(va.vertex);
      continue;
    }
    result.tweakedVertices.push_back(va.vertex);
    for (const CurveEnd &end : va.ends)
      byCurve[end.sourceCurve].push_back(
          {va.vertex, end.sourceParameter, end.towardsLargerParameter, va.normal, va.targetCurvature(end)});
  }

  for (auto &[curveIndex, tweaks] : byCurve) {
    const BSplineCurve &original = result.network.curves[curveIndex];
    const std::string element = "curve " + std::to_string(curveIndex);
    if (original.degree() < 2)
      throw InputError("", element, "degree 1: a polyline has no curvature to tweak; raise its degree");
    // Smoothness kept: on a Bézier curve of degree 5 the moved (third) point
    // leaves the far vertex alone to second order with no knot inside the
    // span, so no third-derivative jump is added where gregory-g2's ribbons
    // would carry it into the surface's first derivatives. Every vertex on
    // the curve is pinned: none of them may feel another end's move.
    // 1. The vertex becomes a knot of multiplicity p (its point a control point).
    EndEdits prepared = startEndEdits(network, curveIndex, kSmoothTweakDegree, tweaks);
    EditableCurve &edit = prepared.edit;
    const std::vector<double> &pinned = prepared.pinned;
    result.insertedKnots += prepared.insertedKnots;

    // 2. Split the first span beyond the vertex until the moved point's basis
    // function vanishes to second order at the neighbouring vertex. At most
    // three splits per end: then the support ends before that vertex.
    result.insertedKnots += separateFromNeighbours(
        edit, tweaks, pinned, [&](const EndTweak &tw) { return edit.movedPoint(tw.t0, tw.right); }, 1000, element);

    // 3. The moves. c''(t0)·n is affine in the move δ of Q_j along n (Q_j's
    // basis function and its derivative vanish at t0, so c and c' do not
    // change, also for rational curves), so the unit move's effect gives δ
    // exactly. The moves are independent by step 2.
    const size_t firstMove = result.moves.size();
    for (const EndTweak &tw : tweaks) {
      const int j = edit.movedPoint(tw.t0, tw.right);
      const EndState s0 = endState(edit.curve(), tw.t0, tw.right, tw.normal);
      EditableCurve probe = edit;
      probe.wp[j] += probe.w[j] * tw.normal;
      const double perUnit = endState(probe.curve(), tw.t0, tw.right, tw.normal).kappa - s0.kappa;
      CURVENET_CHECK(std::abs(perUnit) > 0, "control point " + std::to_string(j) + " does not reach the curvature of " +
                                                element);
      const double delta = (tw.target - s0.kappa) / perUnit;
      edit.wp[j] += (edit.w[j] * delta) * tw.normal;
      ControlPointMove move;
      move.vertex = tw.vertex;
      move.curve = curveIndex;
      move.controlPoint = j;
      move.parameter = tw.t0;
      move.distance = delta;
      move.curvatureBefore = s0.kappa;
      result.moves.push_back(move);
    }
    const BSplineCurve tweaked = edit.curve();
    for (size_t i = 0; i < tweaks.size(); ++i)
      result.moves[firstMove + i].curvatureAfter = endState(tweaked, tweaks[i].t0, tweaks[i].right, tweaks[i].normal).kappa;
    result.network.curves[curveIndex] = tweaked;
  }

  for (const ControlPointMove &move : result.moves) result.maxMove = std::max(result.maxMove, std::abs(move.distance));
  result.maxMoveRelative = result.maxMove / network.diagonal();
  return result;
}

} // namespace v1
} // namespace curvenet
