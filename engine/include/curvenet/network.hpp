// curvenet/network.hpp — the curve network: vertices, segments and faces.
//
// Input arrives as a NetworkDescription (from a file, a built-in, or code):
// curves, and faces given as closed loops of curve ranges. Network::build
// turns it into topology:
//
//  * every curve is split at each parameter where some face starts or ends a
//    side on it, so a curve passing through a vertex becomes two segments;
//  * segment end points closer than the tolerance are merged into vertices;
//  * each face is an oriented loop of sides; a side is one curve range and
//    may span several segments — this is how a T-node looks from the face
//    that sees a straight angle there: the two segments form one side;
//  * adjacency: each segment knows its one (boundary) or two faces.
//
// Segments and face sides are reparameterized to [0, 1]. A segment runs from
// its `start` vertex to its `end` vertex in the direction of its source curve.
// Networks are immutable after build; const access is thread-safe.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "curvenet/bspline_surface.hpp"
#include "curvenet/curve.hpp"
#include "curvenet/reference.hpp"

namespace curvenet {
inline namespace v1 {

/// One side of a face loop as written in the input: curve `curve` from
/// parameter `from` to parameter `to` (from > to runs the curve backwards).
struct SideDescription {
  int curve = -1;
  double from = 0, to = 0;
};

struct FaceDescription {
  std::vector<SideDescription> sides; ///< in loop order; side k ends where side k+1 starts
  std::string name;                   ///< optional, for reports
  /// Inner loops (holes), each a loop of sides like `sides`, in either
  /// direction. A face with holes is split by connection curves (see
  /// insertConnectionCurves); at most one hole per face.
  std::vector<std::vector<SideDescription>> holes;
  /// Set by insertConnectionCurves on every face of a split description: the
  /// index of the user's face this loop is a part of. -1: the face itself.
  int partOf = -1;
};

/// Per-curve settings (the native format's `edges`).
struct EdgeDescription {
  int curve = -1;
  /// Master face ([SV14] Sec. 5.1): every piece of the curve borders this
  /// face, and gregory-g2 gives the other face of each piece the master's
  /// cross curvature (measured on the master's G¹ patch), whatever the
  /// surface's EdgeCurvature source is elsewhere; the master face itself is
  /// rebuilt as a G² patch or kept as that G¹ patch (MasterFaces). -1: no
  /// master.
  int masterFace = -1;
  /// A connection curve ([SV14] Sec. 5.2): an inner seam of a composite
  /// face, hidden from the user. gregory-g2 averages the two G¹ patches'
  /// cross curvatures on it (EdgeCurvature::Averaging) whatever the surface's
  /// source is elsewhere, so the seam is curvature continuous.
  bool connection = false;
  /// Master surface given from outside ([SV14] Sec. 5.1): an index into
  /// NetworkDescription::surfaces. The curve must lie on that surface
  /// within the description's tolerance; every face along the curve then
  /// takes the surface's tangent plane (the normal fence is the surface
  /// normal, by closest-point projection of the curve samples) and, under
  /// gregory-g2, its normal curvature across the curve (from its second
  /// fundamental form), so gregory-g1 meets the surface G¹ and gregory-g2
  /// G². The curve's end vertices take the surface's curvature tensor too.
  /// The curve may be a boundary of the network (the master is not one of
  /// its faces). At most one of masterFace and masterSurface. -1: none.
  int masterSurface = -1;
};

/// Surface normals sampled along one curve (a curve traced on a mesh
/// carries the mesh's normals): `normals[k]` at the curve's own parameter
/// `parameters[k]` (increasing, inside the domain, at least 2). Between
/// samples they are interpolated (the cubic through the four nearest
/// samples, from 4 samples on, else linearly) and normalized. The fences of the curve's segments take
/// them, made perpendicular to the curve, so the surface meets the surface
/// the curves came from; at a vertex the given normals of its curves set the
/// tangent plane (their mean), into which vertex repair turns the tangents.
struct CurveNormals {
  std::vector<double> parameters;
  std::vector<Vec3> normals;
  bool empty() const { return normals.empty(); }
  /// The unit normal at parameter t (clamped to the sampled range).
  Vec3 at(double t) const;
};

struct NetworkDescription {
  std::string name;
  std::vector<BSplineCurve> curves;
  /// Optional, indexed like `curves` (shorter or an empty entry: no normals
  /// along that curve). See CurveNormals.
  std::vector<CurveNormals> curveNormals;
  std::vector<FaceDescription> faces;
  std::vector<EdgeDescription> edges; ///< optional; at most one per curve
  /// Relative tolerance: points closer than tolerance × bounding-box diagonal
  /// are the same vertex, and loops must close within it.
  double tolerance = 1e-7;
  std::optional<ReferenceSurface> reference;
  /// Surfaces given from outside, which edges may name as their master
  /// (EdgeDescription::masterSurface).
  std::vector<BSplineSurface> surfaces;
  /// Network::build inserts connection curves where a face needs them
  /// (insertConnectionCurves); false builds the loops as given (a face with
  /// holes is then refused).
  bool connectionCurves = true;
};

/// Connection curves ([SV14] Sec. 5.2). A loop with a concave corner
/// cannot be mapped from a regular n-gon without folding, and a face with a
/// hole has no single loop; both are split into convex sub-faces by curves
/// that the user never sees:
///  * a concave corner (its two curves turn by more than a straight angle
///    about the face normal, the Newell normal of the loop) is joined to the
///    loop vertex or side midpoint that splits it best — the one whose four
///    new corner angles stay farthest from 0 and from a straight angle;
///    parts that are still concave are split again;
///  * a pleated corner (at a vertex of valence 2, turning by more than
///    0.2 rad and convex in both faces' loops, which on a smooth sheet one
///    of them could not be: the sheet leaves the corner across the plane of
///    its two curves and folds back) is cut along the fold, the normal of
///    that plane, to the loop vertex or side midpoint whose chord is
///    nearest it (within 60°); the cut arrives along its chord;
///  * a hole is joined to the outer loop by one curve per corner, each
///    outer corner to the hole corner it pairs with, which makes n
///    four-sided faces. When the two loops have different side counts, the
///    one with fewer sides first gets points inside its sides (the curve
///    running straight on through each: T-nodes), so that both have
///    n = max(outer, hole) corners. The pairing (and these points) make the
///    connection curves leave both loops as square as the corners allow:
///    the least sum over the curves of 1 − cos of the angles between each
///    chord and the loops' inward normals (at a corner, its bisector).
/// Each connection curve is a cubic whose end tangents lie in the tangent
/// planes at its ends (the plane of the two loop tangents at a corner; at a
/// side midpoint, the side tangent and the average of the side's corner
/// normals), so the ends are ordinary T- or Y-vertices of the split network;
/// a fold's cut leaves and arrives as said above (leaving the plane of the
/// pleated corner's curves, it makes a crease vertex there).
/// The result lists the sub-faces of each user face consecutively, each with
/// `partOf` = the user face's index, so a composite face's patches — and
/// its triangles in a tessellated mesh (Mesh::faceTriangleStart) — form one
/// contiguous range. Connection curves are appended to `curves` and marked
/// in `edges` (EdgeDescription::connection); a master face named in `edges`
/// that is split is replaced by its part bordering the curve.
/// Returns the description unchanged when no face needs splitting (and
/// when `connectionCurves` is false). Throws InputError naming `file` and
/// the face for a hole that cannot be joined (more than one hole, bad curve
/// references). Cost: a few curve evaluations per side.
NetworkDescription insertConnectionCurves(const NetworkDescription &description, const std::string &file = {});

/// Vertex kinds by [SV14] Fig. 1 (n = independent curves).
enum class VertexKind {
  Corner,  ///< valence 2, two independent curves (a loop corner, e.g. on the boundary)
  Smooth,  ///< valence 2, one curve passing through (no corner in any face)
  T,       ///< valence 3, one curve passing through, one ending
  Y,       ///< valence 3, three independent curves
  X,       ///< valence 4, two curves passing through
  General, ///< any other configuration (valence ≥ 4 with ≥ 3 independent curves, …)
};
const char *toString(VertexKind kind);

struct Vertex {
  Vec3 position;
  std::vector<int> segments; ///< incident segments (a closed segment appears twice)
  std::vector<Vec3> tangents; ///< unit tangent leaving the vertex along each entry of `segments`
  int valence = 0;           ///< number of segment ends at the vertex
  int independentCurves = 0; ///< valence minus the pairs of segments that continue each other
  VertexKind kind = VertexKind::General;
  bool onBoundary = false;   ///< touches a segment with only one face
};

struct Segment {
  BSplineCurve curve; ///< on [0, 1], from start vertex to end vertex
  int start = -1, end = -1;
  int sourceCurve = -1;            ///< index into the description's curves
  double sourceFrom = 0, sourceTo = 0; ///< range of the source curve (sourceFrom < sourceTo)
  std::array<int, 2> faces{-1, -1};    ///< faces[1] == -1 on the boundary
  int masterFace = -1;                 ///< from EdgeDescription: one of `faces`, or -1
  int masterSurface = -1;              ///< from EdgeDescription: index into description().surfaces, or -1
  bool connection = false;             ///< from EdgeDescription: a hidden seam of a composite face
  bool isBoundary() const { return faces[1] < 0; }
};

struct FaceSide {
  BSplineCurve curve;        ///< on [0, 1], in the loop direction
  int startVertex = -1, endVertex = -1;
  std::vector<int> segments; ///< in loop order
  std::vector<bool> segmentReversed; ///< true where the loop runs a segment from end to start
  /// Side parameters where one segment ends and the next begins (T-nodes
  /// seen from the straight side); empty for a one-segment side.
  std::vector<double> breaks;
  int sourceCurve = -1;
  double sourceFrom = 0, sourceTo = 0; ///< as written: from > to when traversed backwards
};

struct Face {
  std::string name;
  /// The user's face this loop is a part of (FaceDescription::partOf), or
  /// the face's own index when connection curves did not split it.
  int partOf = -1;
  std::vector<FaceSide> sides;
  int sideCount() const { return static_cast<int>(sides.size()); }
};

class Network {
public:
  /// Inserts connection curves where the description needs them
  /// (insertConnectionCurves; description() is then the split description),
  /// then builds the topology; throws InputError naming `file` (may be empty) and
  /// the element at fault: unknown curve index, range outside the curve,
  /// loop that does not close, fewer than 2 or more than 8 sides, a segment
  /// used by more than two faces or twice in the same direction; an edge
  /// setting naming an unknown curve, a curve twice, or a master face that
  /// does not border every piece of its curve with a neighbour on the other side;
  /// a master surface that does not exist, an edge naming both a master face
  /// and a master surface, or a curve farther from its master surface than the
  /// tolerance (the message gives the distance found and the curve parameter).
  static Network build(const NetworkDescription &description, const std::string &file = {});

  const std::string &name() const { return name_; }
  const std::vector<Vertex> &vertices() const { return vertices_; }
  const std::vector<Segment> &segments() const { return segments_; }
  const std::vector<Face> &faces() const { return faces_; }
  const std::optional<ReferenceSurface> &reference() const { return reference_; }
  const NetworkDescription &description() const { return description_; }
  /// Bounding box of the curves' control polygons (contains the curves).
  const BoundingBox &bounds() const { return bounds_; }
  double diagonal() const { return bounds_.diagonal(); }

  /// Outgoing unit tangent of segment `segment` at vertex `vertex` (pointing
  /// away from the vertex along the segment).
  Vec3 outgoingTangent(int segment, int vertex) const;

private:
  std::string name_;
  std::vector<Vertex> vertices_;
  std::vector<Segment> segments_;
  std::vector<Face> faces_;
  std::optional<ReferenceSurface> reference_;
  NetworkDescription description_;
  BoundingBox bounds_;
};

} // namespace v1
} // namespace curvenet
