// curvenet/sketch.hpp — sketches and curve graphs become networks.
//
// People draw curve networks as strokes: polylines sampled densely, meeting
// (or nearly meeting) at the nodes, with no faces given. networkFromCurveGraph
// turns such a curve graph into a NetworkDescription in five steps:
//
//  1. weld: stroke ends closer than the weld distance to another stroke's
//     point are joined to it; an end near the interior of another stroke's
//     polyline splits it there (a T-node); two strokes passing within the
//     weld distance of each other are joined at their closest points (an
//     X-node), unless they are that close only because they run into a
//     point they share (strokes ending at one junction at a small angle).
//     Points that coincide (1e-9 of the diagonal) are one point.
//  2. nodes: every point where other than two polyline pieces meet, and
//     every corner (a stroke turning by more than 75° over 2% of the
//     diagonal on either side: strokes drawn to meet at a corner share a
//     point with only two pieces there); a closed stroke with no node gets
//     one, and a closed edge a second one half way along it. The pieces
//     between nodes are the edges. Edges with a free end, and edges on no
//     cycle (bridges), are dangling: named in the result and left out of
//     the faces.
//  3. curves: at each node the edges that continue each other (the pair
//     closest to a straight line, turning by less than 45°) belong to one
//     curve, so a curve runs straight through X- and T-nodes. Each curve is a
//     cubic B-spline fitted by least squares to its points (chord-length
//     parameters, knots at parameter quantiles of the data, a small fairing
//     term on the third differences of the control points), passing exactly
//     through its nodes; control points are added until the largest distance
//     from a point to the curve point at its parameter (an upper bound on
//     its distance to the curve) is within the fit tolerance, or no more can
//     be placed; then the fairing weight is raised tenfold at a time while
//     that distance stays within a quarter of the tolerance, so that a
//     hand's wobble on a short edge does not become curvature. Where the edges at a node nearly share a plane (no edge
//     leaves their best plane by more than 25°), every curve's tangent there
//     is constrained to that plane: the G¹ vertex condition by construction.
//  4. faces: a rotation system traced into loops. At every node the edges
//     are put in the cyclic order of the shortest closed tour through their
//     directions on the unit sphere (up to 7 edges; more: by angle in their
//     best plane). On a smooth sheet that is the order about the tangent
//     plane, and it stays right at a crease, where a best plane mixes the two
//     sheets and interleaves their edges. The node normal is the tour's fan
//     normal, oriented alike over each connected part by carrying it along
//     the edges (projection on each piece's normal plane, a
//     rotation-minimizing frame in the limit), most confident edge first,
//     then turned to point away from the part's centre. Each loop leaves a
//     node along the edge next clockwise from the one it arrived by, so every
//     edge is run once in each direction and neighbouring faces agree in
//     orientation by construction. A loop whose corner angles sum to more
//     than n·180° (n corners; a flat n-gon has (n − 2)·180°, the outside of
//     one (n + 2)·180°) is the open side of a sheet and is left out; a loop
//     of more than 8 sides is refused by name. Consecutive edges of one
//     curve through a node of three or more edges form one side (a T-node
//     seen from its straight side). A part of the graph that is one cycle of
//     curves beside other parts bounds a region that need not be a disc (a
//     tube between two rims): its loops are named, not built.
//  5. the description: one curve per fitted curve, faces as loops of curve
//     ranges, network tolerance 1e-6 (the curves meet at the nodes exactly).
//  6. creases: the network's crease vertices (tangents more than 5° out of
//     one plane) and the edges where its faces meet at a sharp angle there,
//     as every surface built on it treats them (Surface::isCreaseVertex,
//     isCreaseSegment).
//
// The result also carries the summary a user needs to judge it: nodes by
// valence and kind, each curve's fit error, faces by sides, the dangling
// strokes, the faces refused, and the Euler characteristic of the faced part.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "curvenet/network.hpp"

namespace curvenet {
inline namespace v1 {

/// Strokes as index chains into shared points (an OBJ `l` element is one
/// stroke). A stroke whose first and last index agree is closed.
struct CurveGraph {
  std::string name;
  std::vector<Vec3> points;
  std::vector<std::vector<int>> strokes;
  /// Optional, one per stroke: where it came from ("line 12", "curve 3"),
  /// used to name dangling strokes.
  std::vector<std::string> strokeNames;
};

/// True when an OBJ text is a curve graph: it has `l` elements and no `f`.
bool objIsCurveGraph(const std::string &text);

/// Reads `v` and `l` records (an `l` of any length, 1-based or negative
/// indices); `vn`, `vt`, `o`, `g`, `s`, `usemtl`, comments are ignored.
/// InputError naming `file` and the line: a malformed number, an index out
/// of range, an `l` with fewer than two points, an `f` record, no strokes.
CurveGraph parseObjCurveGraph(const std::string &text, const std::string &file = {});

/// The curves of a description as strokes: each curve sampled at `samples`
/// points uniform in its parameter (a degree-1 curve: its control points).
/// Ends that coincide become shared points when the graph is welded.
CurveGraph curveGraphFromCurves(const NetworkDescription &description, int samples = 64);

/// Reads a curve graph file: an OBJ with `l` elements and no `f`
/// (parseObjCurveGraph). The name is the file stem.
CurveGraph readCurveGraphFile(const std::string &path);

struct SketchOptions {
  /// Weld distance relative to the bounding-box diagonal (see step 1). On
  /// the eight public sketches (samples 1.3–4.7 thousandths of the diagonal
  /// apart) every value from 1e-3 to 2e-3 gives the same faces, each closed
  /// (Euler characteristic 2); 5e-4 misses crossings of bathtub and
  /// ellipsetorus, 4e-3 joins strokes of doghead and sewing_machine that
  /// only pass near each other. The default is the middle of that range.
  /// The free stroke ends of iron (2) and bathtub (10) lie 3.6e-5 to 1.2e-4
  /// of the diagonal from another stroke, 10–100× closer than any stroke's
  /// samples: drawn to end on it, so they become T-nodes; below 3.6e-5 they
  /// are named as dangling strokes instead.
  double weld = 1.5e-3;
  /// Largest distance of a stroke point from its fitted curve, relative to
  /// the diagonal, that the fit aims for.
  double fitTolerance = 2e-3;
  /// Starting weight of the fairing term (squared third differences of the
  /// control points) relative to the mean squared data term (step 3 raises
  /// it while the fit stays within a quarter of fitTolerance).
  double fairing = 1e-6;
};

enum class NodeKind {
  Junction, ///< strokes share a point there (valence ≠ 2 in the input)
  T,        ///< a stroke end welded onto another stroke's interior
  X,        ///< two strokes crossing within the weld distance
  Loop,     ///< a vertex placed on a closed stroke (or closed edge)
  Corner,   ///< a stroke turning sharply (more than 75° over 2% of the diagonal)
  FreeEnd,  ///< a stroke end meeting nothing (its edge is dangling)
};
const char *toString(NodeKind kind);

struct SketchNode {
  Vec3 position;
  int valence = 0;
  NodeKind kind = NodeKind::Junction;
  bool planeEnforced = false; ///< the curves' tangents were made to share the node's tangent plane
  /// The curves' tangents leave their plane by more than 5° (Surface::isCreaseVertex):
  /// each face corner there keeps its own plane.
  bool crease = false;
};

struct SketchCurve {
  int pointCount = 0;     ///< stroke points it was fitted to
  int controlPoints = 0;
  double maxError = 0;    ///< largest point-to-curve distance, relative to the diagonal
  bool closed = false;
};

struct SketchResult {
  NetworkDescription description; ///< curves (SketchResult::curves, same order) and faces
  double diagonal = 0;
  double weldDistance = 0;        ///< absolute (options.weld × diagonal)
  std::vector<SketchNode> nodes;
  std::vector<SketchCurve> curves;
  /// Each dangling edge, named by its stroke and end points.
  std::vector<std::string> dangling;
  /// Faces found but not built, each with the reason (more than 8 sides).
  std::vector<std::string> refusedFaces;
  /// Loops left out as the open side of a sheet (holes of the surface).
  std::vector<std::string> openLoops;
  /// Loops left out because the region they bound need not be a disc: a
  /// part of the graph that is a single cycle of curves beside other parts
  /// (a tube's rims with no stroke along it would otherwise be capped).
  std::vector<std::string> notDiscs;
  /// Segments of the network between two faces, by how the surface joins
  /// across them (Surface::isCreaseSegment): G¹, or a crease (a sharp edge,
  /// each named by its curve and end points).
  int g1Edges = 0;
  std::vector<std::string> creaseEdges;
  int edges = 0;                 ///< edges between nodes in the faced part
  int facedNodes = 0;            ///< nodes in the faced part
  /// V − E + F over the faced part (nodes, edges and faces found, including
  /// the open loops and refused faces: the Euler characteristic of the closed
  /// surface the rotation system describes).
  int eulerCharacteristic = 0;
  std::map<int, int> facesBySides;
  std::map<int, int> nodesByValence;
};

/// Steps 1–5 above; `file` names the input in errors. Throws InputError for
/// a graph with no points or strokes, or non-finite coordinates.
SketchResult networkFromCurveGraph(const CurveGraph &graph, const SketchOptions &options = {},
                                   const std::string &file = {});

} // namespace v1
} // namespace curvenet
