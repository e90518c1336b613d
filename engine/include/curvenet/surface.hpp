// curvenet/surface.hpp — transfinite patches over every face of a network.
//
// Surface::build computes the shared edge data once (vertex tangent planes,
// one normal fence per segment, one ribbon per face side) and a patch per
// face; evaluation then maps a point of the face's regular n-gon domain to
// the surface, with exact first derivatives.
//
// Schemes
//  * gregory-g1 — Gregory corner-based patch ([SV14] eqs. 16–18 with m = 2,
//    linear ribbons): corner interpolants I = R_{i−1} + R_i − Q with the
//    rational-twist correction patch Q of docs/design.md §3; sweeplines radial
//    [CG84] or Hermite (eq. 20).
//  * gregory-g2 — the G² Gregory patch of [SV14] Sec. 4: parabolic ribbons
//    R = P + dT + ½d²C (eq. 15) over curvature-compatible normal fences
//    (eqs. 13–14), corner interpolants (eq. 17), blends with m = 3, the
//    Hermite sweepline (eq. 20, cubic or quintic) and the nine-term rational
//    correction patch (eq. 22, docs/design.md §3). Adjacent patches share the
//    normal fence and the transversal curvature of every edge, so they are
//    curvature continuous along it (Linkage Curve Theorem, App. B).
//  * composite-ribbon — the CR patch of [VSR]: γ(d) = d/(2d+1) ribbons,
//    curved ribbons (Coons patches with three sides given), Wachspress
//    distance parameters, linear-sweep side parameters, S = ½ Σ C_i B_i. Where
//    the two ribbons at a corner disagree (twist or tangent), the corner
//    correction patch uses Gregory's rational terms so that G¹ still holds.
//  * bezier-g1 — G¹ quintic Bézier patches over 4-sided cubic Bézier networks
//    with T-junctions ([OSK11], after Cho, Lee and Kim 2006): Coons-derived
//    initial nets, vertex and edge G¹ systems, virtual rows across T-junction
//    sides, three-rectangle subdivision of T-junctions at vertices. See
//    curvenet/bezier.hpp for the control-net export and edge continuity.
//  * coons-c0 — the bilinearly blended Coons patch of the four boundary
//    curves of each face (a bicubic, written as a quintic net): the C⁰ baseline.
//  For the two Bézier schemes every face must have 4 sides (a side may span a
//  T-node) and every side curve must be one Bézier span of degree ≤ 3 (lower
//  degrees are elevated; B-splines with interior knots are refused — split
//  them into Bézier curves with their own vertices first); else InputError
//  naming the face. Their domain is the square (regular 4-gon): with corners
//  c_0 … c_3, (u, v) = ((x − c_0.x) / (c_1.x − c_0.x), (y − c_0.y) / (c_3.y − c_0.y)),
//  so domain side 0 (v = 0) is face side 0, side 1 (u = 1) face side 1, side 2
//  (v = 1, u decreasing) face side 2, side 3 (u = 0, v decreasing) face side 3.
//
// Domains: face f with n sides uses the regular n-gon with corners on the unit
// circle, counter-clockwise, side i from corner i to corner i+1 mapped onto the
// face's side i. A 2-sided face is evaluated as a 4-sided patch whose sides are
// the two halves of each of its curves (domainSides() == 4); at the two
// midpoints, where the loop runs straight on, the cross-derivative follows the
// normal fence. A T-node seen from the face with the straight angle is one
// side of that face (see network.hpp).
//
// Normals and curvature along the edges: see FenceNormals and EdgeCurvature.
//
// Threads: a built Surface is immutable; evaluate() may be called from any
// number of threads at once. Cost: build is linear in the number of segments
// and faces (the fold check of every patch, then fence construction,
// dominate; gregory-g2 with MasterSlave, Averaging or a named master face
// also builds, keeps and samples the G¹ surface), parallel over segments and
// faces; rebuildAfterEdit rebuilds the faces near an edit only; evaluate is
// O(n) ribbon evaluations (Gregory) or O(3n) (composite ribbon) and
// allocates nothing.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <span>
#include <vector>

#include "curvenet/analysis.hpp"
#include "curvenet/network.hpp"
#include "curvenet/vertex_math.hpp"

namespace curvenet {
inline namespace v1 {

enum class Scheme { GregoryG1, CompositeRibbon, GregoryG2, BezierG1, CoonsC0 };

/// Side parameterization of the Gregory schemes. Radial [CG84] suits G¹
/// only; Hermite is eq. 20 with H(s) = 2s³ − 3s² + 1 (G²: the two
/// parameterizations of a ribbon agree to first order on its side);
/// QuinticHermite uses 1 − 10s³ + 15s⁴ − 6s⁵ (footnote of Sec. 4.3: also to
/// second order, C² reproduction of the ribbons). Auto is Radial for
/// gregory-g1 and Hermite for gregory-g2.
///
/// On a 3-sided face straight Hermite sweeplines cannot all reach the
/// opposite corner: with the constant parametric speed along the two other
/// sides that eq. 19 demands, they cross beyond 2/3 of the way there (on the
/// bisector), and patches folded along it. There Hermite is instead the
/// radial parameter t eased towards the smoothstep 3t² − 2t³ in proportion
/// to the distance c from the side (in units of the height):
/// s = (1 − c) t + c (3t² − 2t³). It meets eq. 19 to first order with the
/// cubic sweep's rate, and its isolines never cross. QuinticHermite keeps
/// eq. 20 on triangles, crossings included. gregory-g1 defaults to the
/// radial sweep, which covers every n-gon one-to-one.
enum class Sweepline { Auto, Radial, Hermite, QuinticHermite };

/// Where the normal fences (the shared normals along every edge) come from.
enum class FenceNormals {
  /// Reference when the network carries a reference surface, Curves otherwise.
  Auto,
  /// From the curves alone: rotation-minimizing between the vertex tangent
  /// planes (G¹ schemes) or curvature-compatible at both ends (gregory-g2).
  Curves,
  /// From the network's reference surface ([SV14] Sec. 5.3, mesh
  /// approximation): normals sampled along each segment, vertex normals too.
  /// InputError when the network has no reference.
  Reference,
};

/// How gregory-g2 chooses the transversal curvature κ_D(s) of each edge (the
/// normal curvature in the common direction N × P', [SV14] Sec. 3.3).
/// Every source uses the vertex tensors at the segment ends and keeps κ in
/// the curve's own direction equal to the curve's normal curvature
/// (constraint κ(ω0) = k0) when it fits (Direct: within a bound, below). A segment whose curve names a master face
/// (EdgeDescription::masterFace, [SV14] Sec. 5.1) always takes the master's
/// G¹ patch curvature as MasterSlave does, whichever source is chosen here;
/// a connection curve (Segment::connection, [SV14] Sec. 5.2) always
/// averages its two G¹ patches as Averaging does.
enum class EdgeCurvature {
  /// The G¹ patch of the edge's first face (Segment::faces[0]) is the master:
  /// its curvature tensor along the edge, measured in five directions and
  /// fitted with the constraint, is imposed on the other face.
  MasterSlave,
  /// Sec. 3.3 (ii): both adjacent G¹ patches are measured in five directions,
  /// the measurements averaged and fitted with the constraint.
  Averaging,
  /// The two end-vertex tensors, expressed in the fence frame (t, N × t) at
  /// each end and blended linearly in arc length; κ_D moves with the
  /// curve's own curvature as the constrained fit moves it (a third of the
  /// curve's disagreement with the blend) while that disagreement is of the
  /// size of the ends' κ_D, and not where it is a spike of the curve
  /// (docs/surfaces.md, Folds). Needs no G¹ patches: the cheapest, and the
  /// default.
  Direct,
  /// The reference surface's normal curvature (built-ins: analytic); vertex
  /// tensors from it too. InputError when the network has no reference.
  Reference,
};

/// What gregory-g2 builds over a master face: a face that an edge names as
/// its master (EdgeDescription::masterFace, [SV14] Sec. 5.1).
enum class MasterFaces {
  /// Rebuilt from parabolic ribbons like every other face: the whole surface
  /// is G² patches (a G² patch cannot reproduce a circular cross-section, so
  /// a cylindrical fillet master leaves its cylinder by ~1.5% of the radius).
  Rebuilt,
  /// Kept as the G¹ patch the slaves' curvature is measured on (gregory-g1,
  /// radial sweep, the G¹ fences): exactly the face a gregory-g1 build gives
  /// (faceOptions tells which faces these are), so a cylindrical fillet
  /// stays its cylinder. Every edge of a kept face keeps the G¹ fence (the
  /// surface stays G¹ everywhere), and the G² face across it takes the kept
  /// patch's cross curvature, as across a named master edge, whether or not
  /// the edge names it. At the edge's ends the G² face keeps the vertex
  /// tensors, so the two meet curvature continuously along the whole edge
  /// when the kept patch has those tensors' curvature at its corners (the
  /// fillets of a setback vertex blend: jumps ~1e-10), and otherwise only
  /// away from the vertices, the jump growing towards them (a G¹ patch's
  /// corner curvature is generally not the tensor fitted to all the curves
  /// there). Two kept faces meet G¹. Surface::rebuildAfterEdit makes a full
  /// build.
  KeptG1,
};

/// Whether the surface is built on the curves as given or on the curves
/// repaired at the vertices that fail (repairNetwork, curvenet/analysis.hpp;
/// [SV14] Sec. 2).
enum class CurveHandling {
  /// The default. For every transfinite scheme the end tangents at a vertex
  /// whose tangents leave their plane are turned into it (without a common
  /// tangent plane no scheme can be G¹ there); for gregory-g2 the normal
  /// curvatures at vertices failing the Euler constraint are also tweaked to
  /// the fitted tensor (G² needs one curvature per vertex). Vertices never
  /// move. Surface::network() is then the repaired network, and
  /// Surface::repairMoves() lists every control-point move. bezier-g1 and
  /// coons-c0 build on the curves as given (a repair may split their Bézier
  /// spans).
  Repaired,
  /// The curves as given.
  Kept,
};

/// "gregory-g1", "composite-ribbon", "gregory-g2", "bezier-g1", "coons-c0"; and back
/// (std::nullopt for unknown names).
std::string schemeName(Scheme scheme);
std::optional<Scheme> schemeFromName(const std::string &name);
/// Every scheme this build provides, in a fixed order.
std::vector<Scheme> availableSchemes();
/// True for the transfinite schemes, which take loops of 2 to 8 sides of any
/// curves; false for the schemes limited to 4-sided Bézier networks
/// (bezier-g1, coons-c0).
bool acceptsAnyLoop(Scheme scheme);
/// "master-slave", "averaging", "direct", "reference"; and back.
std::string edgeCurvatureName(EdgeCurvature source);
std::optional<EdgeCurvature> edgeCurvatureFromName(const std::string &name);
/// "rebuilt", "kept-g1"; and back.
std::string masterFacesName(MasterFaces masters);
std::optional<MasterFaces> masterFacesFromName(const std::string &name);
/// "repaired", "kept"; and back.
std::string curveHandlingName(CurveHandling curves);
std::optional<CurveHandling> curveHandlingFromName(const std::string &name);
/// What CurveHandling::Repaired repairs for `scheme`.
RepairOptions repairOptionsFor(Scheme scheme);

struct SurfaceOptions {
  Scheme scheme = Scheme::GregoryG1;
  Sweepline sweepline = Sweepline::Auto;              ///< Gregory schemes; gregory-g2 refuses Radial
  FenceNormals fenceNormals = FenceNormals::Auto;     ///< every scheme
  EdgeCurvature edgeCurvature = EdgeCurvature::Direct; ///< gregory-g2 only
  MasterFaces masterFaces = MasterFaces::Rebuilt;      ///< gregory-g2 only
  CurveHandling curves = CurveHandling::Repaired;      ///< every scheme (see CurveHandling)
};

/// A surface point with its exact first derivatives in domain coordinates
/// and the unit normal (du × dv normalized; at the rare points where the
/// derivatives are parallel — straight-angle corners — the limit from inside).
struct SurfacePoint {
  Vec3 point, du, dv, normal;
};

/// A surface point with second derivatives in domain coordinates too.
struct SurfacePoint2 : SurfacePoint {
  Vec3 duu, duv, dvv;
  /// Normal curvature (sign: positive when bending towards `normal`) in the
  /// tangent direction closest to `direction` (any 3D vector not along the
  /// normal): II(X, X) / |X|² for X = a du + b dv the least-squares fit.
  double normalCurvature(const Vec3 &direction) const;
};

/// Which vertex curvature the surface uses and how it was fitted.
struct VertexCurvatureInfo {
  /// (κ1, κ2, λ) with λ from `xAxis` towards normal × xAxis; signed with
  /// respect to Surface::vertexNormal.
  CurvatureTensor tensor;
  Vec3 xAxis; ///< the first curve's outgoing tangent projected into the tangent plane
  FitBranch branch = FitBranch::Exact;
  int independentDirections = 0;
  double maxResidual = 0; ///< 1/length: largest misfit of a curve's normal curvature
};

struct SurfaceEdit;

class Surface {
public:
  /// Builds fences, ribbons and patches for every face. Throws InputError
  /// naming the face when its data cannot carry a patch (degenerate tangents).
  /// Threads: fences, edge curvatures and patches are each built in
  /// parallel over TBB (one segment or face per task, inside the caller's
  /// task arena or global_control limit); the result is bit for bit the same
  /// for any thread count, and so is the error reported (the lowest face's).
  static Surface build(const Network &network, const SurfaceOptions &options = {});

  /// The surface over `edited`, a network built from this surface's
  /// network's description with some curves changed in shape (moved control
  /// points, other knots or degree) but the same loops, edge settings and
  /// reference surface, rebuilding only what the changed curves reach:
  ///  * the frames and curvatures of the vertices at the ends of every
  ///    segment whose curve changed (all curves at a vertex enter its
  ///    tangent plane and curvature fit);
  ///  * the fences and (gregory-g2) transversal curvatures of every segment
  ///    at those vertices — with master–slave, averaging, named masters or
  ///    connection curves also of the segments of the faces whose G¹ patch
  ///    (kept from the build) changed;
  ///  * the patches of the faces using any of those segments.
  /// Everything else is shared with this surface. The result evaluates bit
  /// for bit like Surface::build(edited, options()). A full build is made
  /// instead (partial = false, every face listed) for the Bézier schemes,
  /// for a network built away from the origin (origin() ≠ 0) or that would
  /// be, for gregory-g2 keeping master faces as G¹ patches
  /// (MasterFaces::KeptG1, when some face is), and when the topology differs
  /// (curve ends meeting differently, another face or vertex count). Cost: proportional to the faces rebuilt,
  /// one face ring around the edited curves (two rings for G¹-measured edge
  /// curvature). Thread-safety: const; this surface stays valid and
  /// unchanged.
  SurfaceEdit rebuildAfterEdit(const Network &edited) const;

  /// The network the patches interpolate: the one given to build, or its
  /// repair (SurfaceOptions::curves).
  const Network &network() const;
  /// The control-point moves of the vertex repair (empty with
  /// CurveHandling::Kept or when every vertex passed).
  const std::vector<RepairMove> &repairMoves() const;
  /// What the vertex repair left alone, each "vertex V: …" with the reason
  /// (RepairResult::skipped: a crease fan needing a turn above 16°, a curve
  /// passing through the vertex, …); empty as repairMoves() is.
  const std::vector<std::string> &repairSkipped() const;
  /// The origin of the patches' internal frame in world coordinates: zero,
  /// except for a network whose bounding-box centre lies more than 4
  /// diagonals from the origin (e.g. a part placed at 1e6 in a large
  /// assembly). Such a network is built translated to that centre, vertex
  /// repair included (network() is the repaired one, back in place), so the
  /// patches' arithmetic keeps the model's own precision (normals and
  /// continuity figures as good as at the origin); every point returned is
  /// translated back. Only the rounding of the final addition remains.
  Vec3 origin() const;
  /// Faces whose patch folds over itself: the surface normal turns over
  /// inside the face (a loop too far from convex for its regular n-gon
  /// domain, or ribbons extrapolated far beyond what the boundary supports).
  /// Found at build time by sampling each face on an 8-row fan grid; empty
  /// for well-formed patches. The command-line tools warn about every such
  /// face and `check` lists them; the surface is still built and evaluated.
  const std::vector<int> &foldedFaces() const;
  const SurfaceOptions &options() const;
  /// The options face f is built with: options(), except for the master
  /// faces a gregory-g2 surface keeps as G¹ patches (MasterFaces::KeptG1):
  /// gregory-g1 with the radial sweep there.
  SurfaceOptions faceOptions(int face) const;
  int faceCount() const;

  /// Sides of face f's domain polygon (the face's side count; 4 for 2-sided faces).
  int domainSides(int face) const;
  Vec2 domainCorner(int face, int corner) const;
  /// Which part of the face's loop domain side i shows: loop side `faceSide`
  /// on side parameters [sFrom, sTo] ([0, 1] except for 2-sided faces, whose
  /// sides are split at a segment break nearest the middle, or the middle).
  struct DomainSideRange {
    int faceSide;
    double sFrom, sTo;
  };
  DomainSideRange domainSideRange(int face, int domainSide) const;

  /// The domain point where face `face` shows its own loop side `side` at
  /// side parameter s ∈ [0, 1].
  Vec2 domainPointOnFaceSide(int face, int side, double s) const;

  /// The domain point where face `face` shows segment `segment` at segment
  /// parameter u ∈ [0, 1]. InputError when the face does not use the segment.
  Vec2 domainPointOnSegment(int face, int segment, double u) const;

  /// Evaluates face `face` at domain point uv (inside or on its polygon).
  SurfacePoint evaluate(int face, const Vec2 &uv) const;

  /// Positions alone of face `face` at many domain points: out[k] is
  /// evaluate(face, uv[k]).point to ~1e-12 relative (out.size() ≥
  /// uv.size()). The Gregory schemes with the radial or cubic Hermite sweep
  /// run batched: sweepline roots by the SIMD solver, corner blends, the
  /// face's ribbon tables (built on first use, ~1 ms) and one kernel pass —
  /// about 30× the pointwise rate. composite-ribbon batches of 512 points or
  /// more take the same tables and the CR kernel (about 8× the pointwise
  /// rate); smaller ones, and the other schemes, evaluate point by point.
  /// Serial; thread-safe (call it from several threads on disjoint outputs).
  void evaluatePositions(int face, std::span<const Vec2> uv, std::span<Vec3> out) const;

  /// evaluate() at many domain points of face `face` (out.size() ≥
  /// uv.size()), the fast path for an embedding program's batches. The
  /// transfinite schemes run batched as evaluatePositions does, with exact
  /// first derivatives through the derivative kernels: about 10× the
  /// pointwise rate (the face's ribbon tables are built on first use,
  /// ~1 ms). Not bit for bit evaluate(): the ribbons come from the tables
  /// (1e-13 of their size in value, 1e-10 in slope) and the sweepline roots
  /// from the batched solver, so out[k] agrees with evaluate(face, uv[k])
  /// to ~1e-13 of the model's size in the point, ~1e-11 of their size in
  /// du and dv (≤ 3e-12 measured on the built-ins) and ~1e-11 / sin θ in
  /// the normal (θ between du and dv). Batches under 32 points, the Bézier
  /// schemes and any point whose derivatives are parallel (a straight-angle
  /// corner: the normal's limit from inside) are evaluate() itself. From 32
  /// points on, a point's result does not depend on the batch it comes in
  /// (its size, the point's place). Serial; thread-safe (call it from
  /// several threads on disjoint outputs).
  void evaluate(int face, std::span<const Vec2> uv, std::span<SurfacePoint> out) const;

  /// Evaluates with second derivatives. gregory-g2 faces (faceOptions): exact, by hyper-dual
  /// numbers through the whole formula (sweepline roots by implicit
  /// differentiation; only the ribbons' C'' is a fourth-order difference of the
  /// exact C', which matters away from the boundary only); `step` is ignored.
  /// A point within rounding of a domain side (a sweep parameter within
  /// 1e-15 of 0 or 1) is evaluated on the side itself: near a corner the
  /// second derivatives change within the cube of the distance to it, and
  /// the side's value is the limit the surface's G² holds for.
  /// Other schemes: the exact first derivatives are differenced along two
  /// orthogonal domain directions with fourth-order stencils of step `step`
  /// (domain units; circumradius 1): central (±h, ±2h) where the stencil stays
  /// in the domain, one-sided (0, h, …, 4h) into it otherwise — near a side,
  /// along it and along its inward normal. Truncation O(step⁴), rounding
  /// O(ε/step); Gregory corners make the second derivatives vary on a scale
  /// ~t² (t the distance to the corner), so keep step well below that.
  /// Costs 9 evaluations. step ∈ [1e-8, 1e-2].
  SurfacePoint2 evaluateSecondOrder(int face, const Vec2 &uv, double step = 1e-5) const;

  /// The tangent-plane normal at network vertex v and how far (radians) the
  /// curve tangents there leave that plane.
  Vec3 vertexNormal(int vertex) const;
  double vertexResidualAngle(int vertex) const;

  /// A crease vertex: three or more curves whose tangents leave their plane
  /// by more than 5° (a lid meeting a wall, a cube's corner). No tangent
  /// plane is meant there: vertex repair leaves it alone, each face corner
  /// keeps the plane of its own two curves, and vertexNormal is only their
  /// mean.
  bool isCreaseVertex(int vertex) const;
  /// A crease segment: at a crease vertex its two faces' corner planes meet
  /// at 20° or more, so each face takes its own corner's normal there and
  /// the surface is only C⁰ across it (a sharp edge). Every other segment
  /// shared by two faces is G¹ (its faces share one fence). False on the
  /// boundary.
  bool isCreaseSegment(int segment) const;

  /// The curvature fitted at vertex v from its curves ([SV14] Sec. 2,
  /// App. A; computed for every scheme), or for gregory-g2 with the
  /// reference edge curvature the reference surface's tensor.
  VertexCurvatureInfo vertexCurvature(int vertex) const;

  /// gregory-g2: the transversal curvature κ_D of segment `segment` at u ∈
  /// [0, 1] (normal curvature in direction N × P'); NaN for other schemes.
  double transversalCurvature(int segment, double u) const;
  /// The shared fence normal of segment `segment` at u ∈ [0, 1].
  Vec3 fenceNormal(int segment, double u) const;

  struct Impl;

private:
  friend struct SurfaceAccess; // engine-internal access for scheme-specific reports

  std::shared_ptr<const Impl> impl_;
};

/// What Surface::rebuildAfterEdit made.
struct SurfaceEdit {
  Surface surface;
  /// Faces whose patch was rebuilt, ascending; every other face's patch is
  /// the old surface's own object (shared, not copied).
  std::vector<int> changedFaces;
  /// False when the edit needed a full build (see rebuildAfterEdit).
  bool partial = false;
};

} // namespace v1
} // namespace curvenet
