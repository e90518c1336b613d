// The polyline graph after welding (sketch.hpp step 1), and the stroke-curve
// fit (step 3): the internal pieces of networkFromCurveGraph.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "curvenet/curve.hpp"
#include "curvenet/sketch.hpp"

namespace curvenet {
inline namespace v1 {
namespace graph {

/// Points joined by polyline pieces; every piece remembers its stroke.
struct WeldedGraph {
  struct Link {
    int point = -1;
    int stroke = -1;
  };
  std::vector<Vec3> points;
  std::vector<std::vector<Link>> links; ///< per point, its neighbours
  std::vector<NodeKind> madeAs;         ///< T or X where welding created the node, else Junction
  int tNodes = 0, xNodes = 0;
};

/// Merges coincident points, joins free stroke ends within `weld` (absolute)
/// to a nearby point or polyline piece (T-nodes), and joins pieces of
/// different strokes passing within `weld` of each other (X-nodes) unless
/// they only run into a point they share.
WeldedGraph weldCurveGraph(const CurveGraph &graph, double weld, double diagonal);

/// A constraint of the stroke fit: the curve passes through `position` at
/// `parameter`, and where `planeNormal` is non-zero its tangent there is
/// perpendicular to it.
struct FitNode {
  double parameter = 0;
  Vec3 position;
  Vec3 planeNormal;
};

struct FittedStroke {
  BSplineCurve curve; ///< cubic on [0, 1]
  std::vector<double> parameters; ///< of the stroke points
  double maxError = 0; ///< absolute, point to curve point at its parameter
};

/// Chord-length parameters on [0, 1] of a polyline. (Centripetal ones, the
/// square roots of the chords, would put a jump in the parameter speed
/// wherever a node splits a piece of an evenly sampled stroke in two, which
/// a cubic can only follow with a wiggle.)
std::vector<double> chordLengthParameters(std::span<const Vec3> points);

/// Least-squares cubic through `points` at `parameters` with the fairing
/// weight, meeting every node exactly; control points are added until the
/// error is at most `tolerance` (absolute) or the data cannot carry more;
/// then the fairing weight is raised tenfold at a time while the error
/// stays within a quarter of `tolerance` (or its own, where larger).
/// `closed`: the first and last point are the same node and the curve's
/// tangent is continuous there.
FittedStroke fitStroke(std::span<const Vec3> points, std::span<const double> parameters,
                       std::span<const FitNode> nodes, bool closed, double tolerance, double fairing);

} // namespace graph
} // namespace v1
} // namespace curvenet
