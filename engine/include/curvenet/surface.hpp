// curvenet/surface.hpp — transfinite patches over every face of a network.
//
// Surface::build computes the shared edge data once (vertex tangent planes,
// one normal fence per segment, one ribbon per face side) and a patch per
// face; evaluation then maps a point of the face's regular n-gon domain to
// the surface, with exact first derivatives.
//
// Schemes
//  * gregory-g1 — Gregory corner-based patch (paper 000 eqs. 16–18 with m = 2,
//    linear ribbons): corner interpolants I = R_{i−1} + R_i − Q with the
//    rational-twist correction patch Q of DESIGN.md §3; sweeplines radial
//    [CG84] or Hermite (eq. 20).
//  * composite-ribbon — the CR patch of paper 002: γ(d) = d/(2d+1) ribbons,
//    curved ribbons (Coons patches with three sides given), Wachspress
//    distance parameters, linear-sweep side parameters, S = ½ Σ C_i B_i. Where
//    the two ribbons at a corner disagree (twist or tangent), the corner
//    correction patch uses Gregory's rational terms so that G¹ still holds.
//  * bezier-g1 — G¹ quintic Bézier patches over 4-sided cubic Bézier networks
//    with T-junctions (paper 003, after Cho, Lee and Kim 2006): Coons-derived
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
// Threads: a built Surface is immutable; evaluate() may be called from any
// number of threads at once. Cost: build is linear in the number of segments
// (fence construction dominates); evaluate is O(n) ribbon evaluations
// (Gregory) or O(3n) (composite ribbon) and allocates nothing.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "curvenet/network.hpp"

namespace curvenet {
inline namespace v1 {

enum class Scheme { GregoryG1, CompositeRibbon, BezierG1, CoonsC0 };
enum class Sweepline { Radial, Hermite };

/// "gregory-g1", "composite-ribbon", "bezier-g1", "coons-c0"; and back (std::nullopt for unknown names).
std::string schemeName(Scheme scheme);
std::optional<Scheme> schemeFromName(const std::string &name);
/// Every scheme this build provides, in a fixed order.
std::vector<Scheme> availableSchemes();
/// True for the transfinite schemes, which take loops of 2 to 8 sides of any
/// curves; false for the schemes limited to 4-sided Bézier networks
/// (bezier-g1, coons-c0).
bool acceptsAnyLoop(Scheme scheme);

struct SurfaceOptions {
  Scheme scheme = Scheme::GregoryG1;
  Sweepline sweepline = Sweepline::Hermite; ///< gregory-g1 only
};

/// A surface point with its exact first derivatives in domain coordinates
/// and the unit normal (du × dv normalized; at the rare points where the
/// derivatives are parallel — straight-angle corners — the limit from inside).
struct SurfacePoint {
  Vec3 point, du, dv, normal;
};

class Surface {
public:
  /// Builds fences, ribbons and patches for every face. Throws InputError
  /// naming the face when its data cannot carry a patch (degenerate tangents).
  static Surface build(const Network &network, const SurfaceOptions &options = {});

  const Network &network() const;
  const SurfaceOptions &options() const;
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

  /// Evaluates face `face` at domain point uv (inside or on its polygon).
  SurfacePoint evaluate(int face, const Vec2 &uv) const;

  /// The tangent-plane normal at network vertex v and how far (radians) the
  /// curve tangents there leave that plane.
  Vec3 vertexNormal(int vertex) const;
  double vertexResidualAngle(int vertex) const;

  struct Impl;

private:
  friend struct SurfaceAccess; // engine-internal access for scheme-specific reports

  std::shared_ptr<const Impl> impl_;
};

} // namespace v1
} // namespace curvenet
