// G¹ quintic Bézier patches over 4-sided cubic Bézier networks with
// T-junctions ([OSK11], after Cho, Lee and Kim, CAD 38(6) 2006), and the
// C⁰ Coons baseline. Engine-private; Surface and curvenet/bezier.hpp use it.
//
// Construction, in the paper's order:
//  1. Initial patches: the bilinearly blended Coons patch of the four cubic
//     boundaries, which is bicubic, written as a quintic net (exact elevation).
//  2. Per interior edge, the G¹ condition of [OSK11] (4 points in a plane)
//        (1 − λ(t)) p(t) + λ(t) r(t) = (1 − μ(t)) q_b(t) + μ(t) q_t(t),
//     p, r the first inner rows of the two patches (degree 5), q the cubic
//     boundary with q_b, q_t its two degree-2 de Casteljau sub-polygons, λ of
//     degree a (1; 2 where one end is a T-junction, with a flat end there),
//     μ of degree a + 3. Bernstein coefficients k = 0 … a + 5 give one vector
//     equation each. λ and μ at the ends follow from k = 0 and k = a + 5
//     (the curve tangents at the vertex, which must be coplanar).
//  3. Vertex G¹ systems: the k = 1 equations of all interior edges at a vertex
//     couple the patches' twist points (the circulant system of Cho et al.);
//     μ₁ of each edge is a free unknown. Solved in the least-squares sense
//     with minimal change from the Coons twists (complete orthogonal
//     decomposition). At a 4-valent vertex with two pairs of collinear curves
//     the circulant matrix is singular (det = Π λ̄ − Π λ = 0) and the system is
//     solvable only under the condition on μ₁ that [OSK11] states; having μ₁
//     as unknowns in the same solve satisfies it.
//  4. Edge G¹ systems: the remaining equations of each edge in the two edge
//     points of each patch and the free μ coefficients, again least squares.
//  5. T-junction on a boundary (a face side spanning two segments): the two
//     patches on the other side are treated as one virtual patch whose inner
//     row V(t) spans the whole side; their own rows are V subdivided at the
//     T parameter c (the auxiliary cross-derivative curve), and V(c) must hit
//     the first inner control point of the curve ending at the T ([OSK11]'s
//     4 × 4 edge system). The curve ending at the T then uses a quadratic λ
//     with λ₀ = λ₁ (the subdivision fixes λ's value and slope there).
//  6. T-junction at a vertex (a face whose loop runs straight through one of
//     its corners): the face is split into three rectangles by a centre
//     point O and cubic curves O–T (leaving T opposite to the curve that ends
//     there, so T becomes a 4-valent vertex with two collinear pairs), O–M₁,
//     O–M₂ (M the midpoints of the two sides away from T), all drawn on the
//     face's Coons patch; the new vertices are ordinary or T-on-boundary cases.
// The given boundary curves are never changed: boundary control points are
// the exact degree-elevated curves and are never unknowns.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "bezier/quintic.hpp"
#include "curvenet/network.hpp"

namespace curvenet {
inline namespace v1 {
namespace bezier {

/// What one vertex G¹ system looked like and how it was solved.
struct VertexSystemReport {
  enum class Branch {
    Chain,    ///< vertex on the network boundary: open chain of edges, under-determined, minimum-norm
    Regular,  ///< closed circulant system, det ≠ 0 (e.g. valence 3): twists follow from μ₁, least squares in μ₁
    Singular, ///< closed circulant system with det = 0 (4-valent, opposite collinear curves): solvability condition on μ₁
  };
  int vertex = -1;      ///< vertex of the construction network
  int equations = 0;    ///< interior edges at the vertex
  int twists = 0;       ///< unknown twist points
  double determinant = 0; ///< of the per-coordinate twist matrix, relative to Hadamard's bound (square systems)
  Branch branch = Branch::Chain;
  double residual = 0;  ///< max |equation residual| after the solve, relative to the network diagonal
};

struct BezierFace {
  /// One patch, or three for the three-rectangle subdivision.
  std::vector<int> constructionFaces;
  /// Corners of each patch's (s,t) square in the face's own (u,v) square, in
  /// patch corner order (0,0), (1,0), (1,1), (0,1).
  std::vector<std::array<Vec2, 4>> quads;
  /// Quarter turns from the face's (u,v) to the subdivision's frame, where the
  /// straight corner is corner 1.
  int rotation = 0;
};

struct BezierSurfaceData {
  /// The network the patches are built on: the input network, or the one
  /// after the three-rectangle subdivision of T-junctions at vertices.
  Network construction;
  std::vector<QuinticPatch> patches; ///< per construction face
  std::vector<BezierFace> faces;     ///< per input face
  std::vector<VertexSystemReport> vertexSystems;
  /// Largest residual of any G¹ equation after the construction, relative to
  /// the diagonal (0 for the Coons baseline, which solves nothing).
  double maxEquationResidual = 0;
};

/// Builds the patches. g1 = false gives the Coons patches of the input faces.
/// Throws InputError naming the face or vertex when the network is outside
/// what the method handles (non-4-sided face, curve that is no single cubic
/// Bézier span, non-coplanar tangents at a vertex, two T-junctions on one side).
BezierSurfaceData buildBezierSurface(const Network &network, bool g1);

/// Evaluates input face `face` at (u, v) ∈ [0,1]² of its square (side 0 is
/// v = 0, u: 0 → 1, as for QuinticPatch), with exact first derivatives.
QuinticPatch::Point evaluateBezierFace(const BezierSurfaceData &data, int face, double u, double v);

} // namespace bezier

class Surface;
class Patch;
class NormalFence;
/// Engine-internal access to a surface's parts.
struct SurfaceAccess {
  /// The Bézier data of a surface built with bezier-g1 or coons-c0 (nullptr otherwise).
  static const bezier::BezierSurfaceData *bezierData(const Surface &surface);
  /// The transfinite patch of a face (nullptr for the Bézier schemes).
  static const Patch *patch(const Surface &surface, int face);
  /// Where that patch passes through itself (patchSelfCrossing, found when
  /// it was built; world coordinates); nullopt for the Bézier schemes.
  static std::optional<Vec3> selfCrossing(const Surface &surface, int face);
  /// The same patch and a segment's fence, shared (a gregory-g2 surface
  /// keeping its master faces' G¹ patches holds those of its G¹ surface).
  static std::shared_ptr<const Patch> sharedPatch(const Surface &surface, int face);
  static std::shared_ptr<const NormalFence> sharedFence(const Surface &surface, int segment);
};

} // namespace v1
} // namespace curvenet
