// curvenet/analysis.hpp — is a curve network fit for G¹ / G² interpolation at
// its vertices, and the minimal curve change that makes it so.
//
// At every vertex this stage measures what papers [HPS09] (Hermann, Peters,
// Strotman, SPM 2009) and [SV14] (Salvi, Várady, CGF 2014, Sec. 2) ask of the
// curves meeting there:
//
//  * the common tangent plane (least-squares plane of the unit tangents) and
//    how far the tangents leave it;
//  * the curve ends sorted counter-clockwise around the normal, the angles ψ_i
//    between consecutive tangents ([HPS09] eq. 3) and the normal curvature
//    κ_i^n = c''·n / |c'|² of each end (the curve's own second derivative);
//  * the vertex enclosure residual ([HPS09] eq. 6, the condition for C²
//    patches meeting with G¹ around an even number of curves; identically 0
//    for an odd number, Theorem 1), the Euler-constraint residual ([HPS09]
//    eq. 26: the least-squares misfit of Euler's formula to the κ_i^n), and
//    whether the tangents form an X (Lemma 3);
//  * the optimal surface curvature (κ1, κ2, λ) of [SV14] Sec. 2 fitted to the
//    independent curves (a curve passing smoothly through counts once).
//
// Boundary vertices (on a segment with one face) are analysed over the curves
// they have: the patches around them form an open chain, for which the
// enclosure system ([HPS09] eq. 19) is always solvable, so the enclosure
// residual is reported as 0 and not applicable; the Euler residual and the
// curvature fit use the curve ends present. The same holds at interior
// vertices where the ends do not surround the vertex with angles ψ_i < π
// (a T-node's straight angle, a curve merely passing through).
//
// tweakNetwork then changes the curves at the vertices that fail the Euler
// constraint, by moving one control point per curve end along the vertex
// normal ([SV14] Sec. 2 (iii)), so that every normal curvature there equals
// the fitted Euler curvature exactly while positions and tangents stay put.
//
// All functions are pure: they read the Network and return values; calls may
// run concurrently on the same Network.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "curvenet/network.hpp"
#include "curvenet/vertex_math.hpp"

namespace curvenet {
inline namespace v1 {

/// What a vertex allows, from best to worst.
enum class VertexVerdict {
  /// The normal curvatures fit one surface curvature (Euler's formula, [HPS09]
  /// eq. 26) within AnalysisOptions::curvatureTolerance: G² interpolation is
  /// possible without changing the curves. Implies G1Admissible (Theorem 2).
  G2Admissible,
  /// The Euler constraint fails, but patches that are C² at the vertex can
  /// still meet with G¹ there: the enclosure constraint (6) holds, or there is
  /// none (odd number of ends, boundary vertex, an X by Lemma 3). G² needs the
  /// curves tweaked.
  G1Admissible,
  /// Even number of ends around an interior vertex and the enclosure
  /// constraint (6) fails: no C² patches interpolate these curves with G¹
  /// (Theorem 1), let alone G². The curves must be tweaked (tweakNetwork), or
  /// a scheme that is not C² at the vertex used (Gregory-type rational corners).
  NeedsTweaking,
  /// The curve tangents do not share a plane (residual angle above
  /// AnalysisOptions::tangentTolerance): no tangent-continuous surface
  /// interpolates them; the tangents themselves must be edited.
  NoTangentPlane,
};
/// "G2-admissible", "G1-admissible", "needs-tweaking", "no-tangent-plane".
const char *toString(VertexVerdict verdict);

struct AnalysisOptions {
  /// A vertex satisfies a curvature constraint when its residual, divided by
  /// the vertex's curvature scale max(max_i |κ_i^n|, 1/diagonal), is at most
  /// this. The scale is the largest curvature at the vertex, floored by the
  /// curvature of a circle as large as the model, so that the noise of a
  /// nearly flat vertex is not judged relative to itself. Built-ins cut from
  /// analytic surfaces score ≈ 1e-7…1e-6 (their curves are fitted to 1e-5
  /// relative in normal curvature). Dimensionless, > 0.
  double curvatureTolerance = 1e-5;
  /// Largest angle (radians) a unit tangent may make with the fitted tangent
  /// plane. 1e-4 rad ≈ 0.006°: far below what a reflection-line picture shows.
  double tangentTolerance = 1e-4;
  /// Two tangents within this angle (radians) of being opposite are one curve
  /// passing through (the network builder's pairing rule); an angle ψ_i within
  /// it of π is a straight angle, where [HPS09]'s 0 < ψ_i < π fails and the
  /// enclosure constraint is not applied. Also the tolerance of formsX.
  double straightTolerance = 1e-4;
};

/// One segment end at a vertex, in the vertex's tangent-plane frame.
struct CurveEnd {
  int segment = -1;        ///< index into Network::segments()
  bool atSegmentStart = true; ///< the vertex is the segment's start (parameter 0)
  int sourceCurve = -1;    ///< index into the description's curves
  double sourceParameter = 0; ///< parameter of the vertex on the source curve
  /// The source curve continues beyond the vertex with growing parameter
  /// (the segment lies on the side of larger parameters).
  bool towardsLargerParameter = true;
  Vec3 tangent;            ///< unit, leaving the vertex (as Vertex::tangents)
  double omega = 0;        ///< angle of the tangent's projection from the frame's x axis, in [0, 2π)
  double normalCurvature = 0; ///< κ^n = c''·n / |c'|², 1/length; > 0 bending towards the normal
  int independentCurve = -1;  ///< which independent curve this end belongs to
};

struct VertexAnalysis {
  int vertex = -1;
  Vec3 position;
  /// Unit normal of the least-squares tangent plane, oriented to the outside
  /// of the faces (counter-clockwise loops); xAxis is the first end's tangent
  /// projected into the plane, and angles grow towards normal × xAxis.
  Vec3 normal, xAxis;
  double tangentResidual = 0; ///< radians: largest angle of a tangent out of the plane
  int valence = 0;
  int independentCurves = 0;
  bool onBoundary = false;
  /// Ends sorted by omega (counter-clockwise seen from the normal side).
  std::vector<CurveEnd> ends;
  /// psi[i] is the angle from ends[i] to ends[(i+1) % valence] in (0, 2π); they sum to 2π.
  std::vector<double> psi;

  /// max(max_i |κ_i^n|, 1/diagonal): what the relative residuals divide by (1/length).
  double curvatureScale = 0;
  /// [HPS09] eq. (6) is applied: interior vertex, valence ≥ 3, every ψ_i in
  /// (straightTolerance, π − straightTolerance).
  bool enclosureApplies = false;
  double enclosureResidual = 0;         ///< eq. (6) value, 1/length (0 where not applicable or n odd)
  double enclosureResidualRelative = 0; ///< |eq. (6)| / curvatureScale
  double eulerResidual = 0;             ///< rms misfit of eq. (26) over all ends, 1/length
  double eulerResidualRelative = 0;     ///< eulerResidual / curvatureScale
  bool formsX = false;                  ///< [HPS09] Lemma 3 (valence 4, opposite tangents collinear)

  /// [SV14] Sec. 2 fit over the independent curves (one direction and the
  /// mean normal curvature per curve): k1 ≥ k2 in 1/length, lambda in radians
  /// from xAxis. Its branch tells which case of Sec. 2 applied; with fewer
  /// than three independent curves it is a choice ([SV14] eq. 8), not a
  /// measurement of the surface.
  ///
  /// Where the directions leave part of the tensor undetermined (a near-X:
  /// directions in nearly opposite pairs; clustered directions) or the fit
  /// would exceed max|κ_i^n| plus twice the curves' disagreement, those modes come
  /// from the curves' mean curvature instead, so the tensor stays bounded by
  /// what the curves show; regularizedModes says how many (0: the paper's fit).
  CurvatureFit fit;
  int regularizedModes = 0;
  Vec3 principalDirection1; ///< unit 3D direction of k1 (xAxis rotated by lambda)
  VertexVerdict verdict = VertexVerdict::G2Admissible;

  /// The fitted surface's normal curvature in the direction of `end`: the
  /// value tweakNetwork gives that end.
  double targetCurvature(const CurveEnd &end) const { return fit.tensor.normalCurvature(end.omega); }
};

struct NetworkAnalysis {
  std::vector<VertexAnalysis> vertices; ///< by vertex index
  AnalysisOptions options;
  double diagonal = 0;
  /// The worst verdict over all vertices.
  VertexVerdict verdict = VertexVerdict::G2Admissible;
  /// Count of vertices per verdict, indexed by VertexVerdict.
  std::array<int, 4> verdictCounts{};
  double maxEnclosureResidualRelative = 0;
  double maxEulerResidualRelative = 0;
  double maxTangentResidual = 0; ///< radians
  /// Vertex indices ordered worst first: by verdict, then by relative Euler
  /// residual, then enclosure residual, then tangent residual (descending).
  std::vector<int> worstFirst() const;
};

/// Analyses one vertex (0 ≤ vertex < network.vertices().size(), else
/// InputError). Cost: O(size of the network) — the tangent planes are fitted
/// for all vertices at once (their orientation comes from the faces); use
/// analyzeNetwork for many vertices. Throws InputError when a curve has zero
/// speed at the vertex (its normal curvature is undefined there).
VertexAnalysis analyzeVertex(const Network &network, int vertex, const AnalysisOptions &options = {});

/// Analyses every vertex. Cost O(Σ valence² + faces).
NetworkAnalysis analyzeNetwork(const Network &network, const AnalysisOptions &options = {});

// ---------------------------------------------------------------------------
// Curve tweaking ([SV14] Sec. 2 (iii))
// ---------------------------------------------------------------------------
//
// At a vertex that fails the Euler constraint, each curve end gets the normal
// curvature of the fitted surface curvature in its direction, κ(ω_i). The
// change is made where it is smallest and purely second order: on a B-spline
// with the vertex at a knot of multiplicity ≥ p, c(t0) depends on one control
// point Q_k, c'(t0) on Q_k and its neighbour Q_{k±1}, and c''(t0) additionally
// on Q_{k±2} — the second control point from the vertex, counting the vertex's
// own point as the 0th. Moving Q_{k±2} along the vertex normal n changes
// c''(t0)·n linearly (also for rational curves: Q_{k±2}'s basis function and
// its first derivative vanish at t0) and leaves c(t0), c'(t0) and the
// tangential part of c''(t0) unchanged. So the move is solved exactly in one
// step, and a curve passing through a tweaked vertex stays C² there (both
// sides get the same c'').
//
// Before moving, knots are inserted (Boehm; the curve does not change):
// an interior vertex parameter is raised to multiplicity p, and the first span
// beyond the vertex is split until the moved point's basis function vanishes
// to third order at every other vertex on the curve — so tweaking one end
// never disturbs position, tangent or curvature at another vertex, and both
// ends of a short curve are tweaked independently. A Bézier curve (no
// interior knot) is first raised to degree 5 instead (exactly: the same
// curve), where the moved point already leaves the other end alone: a knot
// inside its span would leave the curve only C² there, a jump of the third
// derivative that gregory-g2's ribbons carry into the surface's first
// derivatives. Degree-1 curves have no curvature to tweak: InputError.

struct TweakOptions {
  AnalysisOptions analysis;
  /// Tweak every vertex whose relative Euler residual exceeds this (default:
  /// the analysis tolerance). 0 tweaks every vertex with any misfit.
  double eulerTolerance = -1; ///< < 0: use analysis.curvatureTolerance
  /// Leave vertices with a degree-1 curve end as they are (listed in
  /// TweakResult::skippedVertices) instead of throwing InputError.
  bool skipDegreeOne = false;
  /// Leave crease vertices (three or more curves leaving their plane by more
  /// than 5°, Surface::isCreaseVertex) as they are, listed in
  /// TweakResult::skippedVertices: no surface curvature is meant there.
  bool skipCreases = false;
};

/// One control-point move.
struct ControlPointMove {
  int vertex = -1;      ///< where the curvature was fixed
  int curve = -1;       ///< index into NetworkDescription::curves (after knot insertion)
  int controlPoint = -1; ///< index into that curve's control points after knot insertion
  double parameter = 0; ///< the vertex parameter on the curve
  double distance = 0;  ///< signed length of the move along the vertex normal
  double curvatureBefore = 0, curvatureAfter = 0; ///< normal curvature of the end (target after)
};

struct TweakResult {
  NetworkDescription network; ///< the repaired description (faces and parameters unchanged)
  std::vector<ControlPointMove> moves;
  std::vector<int> tweakedVertices;
  std::vector<int> skippedVertices; ///< TweakOptions::skipDegreeOne: failing vertices left alone
  int insertedKnots = 0;
  double maxMove = 0;         ///< largest |distance| (length)
  double maxMoveRelative = 0; ///< maxMove / the network's diagonal
};

/// Repairs the network's curves at the vertices that fail the Euler
/// constraint (see above). Vertices that pass are untouched, and so is every
/// curve that does not end or pass at a tweaked vertex. Throws InputError
/// naming the curve when one to be tweaked has degree 1. Cost: one analysis
/// plus O(degree²) per moved point and knot.
TweakResult tweakNetwork(const Network &network, const TweakOptions &options = {});

// ---------------------------------------------------------------------------
// Vertex repair ([SV14] Sec. 2: "prior to generating our surface model, we
// need to ensure that the defining network is G² … and in special cases
// slightly adjust some curves")
// ---------------------------------------------------------------------------
//
// Two steps, each only where a vertex fails, and never moving a vertex:
//  1. Tangent plane (G¹): at a vertex whose tangents leave their
//     least-squares plane by more than RepairOptions::tangentTolerance,
//     every end tangent is turned into that plane by the smallest rotation
//     about the vertex: the second control point from the end (the first
//     beyond the vertex's own) is rotated about the vertex point, keeping the
//     tangent's length. A curve passing through the vertex gets both
//     neighbours of its vertex point turned by the same rotation (after knot
//     insertion to multiplicity p), so it stays C¹ there. A Bézier curve is
//     raised to degree 4 first, where the turned point leaves the other end
//     alone without a knot inside the span (the tweak raises it to 5).
//     At a crease vertex (Surface::isCreaseVertex) the faces fall into fans,
//     maximal runs of faces joined by G¹ segments between two crease
//     segments; a crease curve lies on both sheets it separates, so a fan's
//     tangent plane is the plane of its two crease curves, and the fan's G¹
//     curves are turned into it (the crease curves stay): the G¹ segments
//     there become exactly G¹. A crease vertex without crease segments is
//     repaired as any vertex. A fan (or vertex) needing a turn above 16°,
//     bounded other than by two crease or boundary curves, or crossed by a
//     G¹ curve passing through the vertex is left alone and named in
//     RepairResult::skipped.
//  2. Curvature (G²): tweakNetwork on the result, at the vertices that fail
//     the Euler constraint (degree-1 curves are skipped, not refused).
// The moves are reported one per moved control point, with the length of
// the move relative to the network's diagonal.

enum class RepairKind { TangentPlane, Curvature };
/// "tangent-plane", "curvature".
const char *toString(RepairKind kind);

struct RepairOptions {
  AnalysisOptions analysis;
  /// Step 1 turns the tangents at every vertex whose tangents leave their
  /// plane by more than this (radians) — far below the analysis verdict's
  /// tangentTolerance, because the normals of the patches meeting there
  /// disagree by about as much: the analytic built-ins leave their planes by
  /// ≤ 7.6e-9 rad (torus-mixed) and are left alone, a drawn network by
  /// degrees.
  double tangentTolerance = 5e-8;
  bool tangentPlanes = true; ///< step 1
  bool curvatures = true;    ///< step 2
};

struct RepairMove {
  int vertex = -1;
  int curve = -1; ///< index into NetworkDescription::curves
  RepairKind kind = RepairKind::TangentPlane;
  double size = 0;         ///< length of the control point's move
  double sizeRelative = 0; ///< size / the network's diagonal
  double angle = 0;        ///< TangentPlane: radians the tangent turned; Curvature: 0
};

struct RepairResult {
  NetworkDescription network; ///< the repaired description (the input's when nothing moved)
  std::vector<RepairMove> moves;
  double maxMoveRelative = 0;
  /// Crease fans step 1 left alone, each "vertex V: …" with the reason.
  std::vector<std::string> skipped;
  bool changed() const { return !moves.empty(); }
};

/// Repairs tangent planes and (when asked) curvatures at the vertices that
/// fail them; vertices that pass, and curves not ending or passing at a
/// repaired vertex, are untouched. Cost: one analysis per step plus the
/// network builds between them.
RepairResult repairNetwork(const Network &network, const RepairOptions &options = {});

} // namespace v1
} // namespace curvenet
