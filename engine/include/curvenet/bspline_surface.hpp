// curvenet/bspline_surface.hpp — tensor-product B-spline and NURBS surfaces.
//
// A BSplineSurface is the primary surface a designer keeps beside the curve
// network ([SV14] Sec. 5.1, "master surfaces given from outside"): a fillet,
// a large panel. An edge of the network may name one as its master
// (EdgeDescription::masterSurface); the patches along that edge then take the
// surface's tangent plane and normal curvature across the edge.
//
// Definition: degrees p (in u) and q (in v), clamped knot vectors U (n_u + p + 1
// knots, the first and last p + 1 equal) and V (n_v + q + 1), a control net of
// n_u × n_v points stored row by row — point (i, j) at index i · n_v + j, i
// along u, j along v — and optional positive weights in the same order
// (empty: polynomial). The surface is
//   S(u, v) = Σ N_i,p(u) N_j,q(v) w_ij P_ij / Σ N_i,p(u) N_j,q(v) w_ij
// on [U_p, U_{n_u}] × [V_q, V_{n_v}]; parameters outside clamp to the domain.
//
// Derivatives are exact: the homogeneous derivatives from the basis
// functions' derivatives (de Boor–Cox recursion, Piegl & Tiller A2.3),
// then the quotient rule for the rational case (A4.4). Sign conventions
// follow curvenet/reference.hpp: the unit normal is S_u × S_v normalized,
// and normal curvature is II(t, t) / I(t, t) with II = N · S_xy (positive
// when the surface bends towards the normal).
//
// Values are immutable; every const member may be called from any number of
// threads at once. Cost: evaluation O((p + 1)(q + 1)) per point plus O(p² + q²)
// for the basis; closestPoint a coarse search over the net's spans plus at
// most kProjectionIterations Newton steps.
#pragma once

#include <vector>

#include "curvenet/reference.hpp"
#include "curvenet/vec.hpp"

namespace curvenet {
inline namespace v1 {

/// Position and exact partial derivatives up to second order at (u, v).
struct SurfaceJet {
  Vec3 point, du, dv, duu, duv, dvv;
};

/// First and second fundamental forms at a point: I = E du² + 2F du dv + G dv²,
/// II = L du² + 2M du dv + N dv² (II = normal · second derivatives).
struct FundamentalForms {
  double E = 0, F = 0, G = 0;
  double L = 0, M = 0, N = 0;
};

/// A closest-point projection: the foot's parameters, the foot, and the
/// distance from the projected point.
struct SurfaceProjection {
  double u = 0, v = 0;
  Vec3 point;
  double distance = 0;
};

class BSplineSurface {
public:
  /// Highest degree in either direction.
  static constexpr int maxDegree = 15;
  /// Newton steps a projection takes at most after its coarse start.
  static constexpr int kProjectionIterations = 40;

  BSplineSurface() = default;

  /// Builds a surface; throws InputError (element "surface", with the
  /// reason) for inconsistent data: a degree outside [1, maxDegree], a knot
  /// vector whose size is not points + degree + 1 in its direction, knots that
  /// decrease, are not clamped or leave an empty domain, a net whose size is
  /// not countU × countV, non-finite values, or weights that are not positive
  /// or not one per control point.
  BSplineSurface(int degreeU, int degreeV, std::vector<double> knotsU, std::vector<double> knotsV, int countU,
                 int countV, std::vector<Vec3> controlPoints, std::vector<double> weights = {});

  int degreeU() const { return degreeU_; }
  int degreeV() const { return degreeV_; }
  const std::vector<double> &knotsU() const { return knotsU_; }
  const std::vector<double> &knotsV() const { return knotsV_; }
  int countU() const { return countU_; }
  int countV() const { return countV_; }
  /// Row by row: point (i, j) at i · countV() + j.
  const std::vector<Vec3> &controlPoints() const { return points_; }
  const std::vector<double> &weights() const { return weights_; } ///< empty: polynomial
  bool isRational() const { return !weights_.empty(); }

  double uStart() const { return knotsU_[size_t(degreeU_)]; }
  double uEnd() const { return knotsU_[size_t(countU_)]; }
  double vStart() const { return knotsV_[size_t(degreeV_)]; }
  double vEnd() const { return knotsV_[size_t(countV_)]; }

  Vec3 point(double u, double v) const;
  /// Position with first and second derivatives, exact (rational included).
  SurfaceJet jet(double u, double v) const;
  /// Unit normal S_u × S_v normalized (zero vector where the two are parallel).
  Vec3 normal(double u, double v) const;
  FundamentalForms fundamentalForms(double u, double v) const;
  /// Normal, principal curvatures and direction at (u, v) in the
  /// conventions of SurfaceFrame (κ1 ≥ κ2, κ = II(t, t) for a unit t).
  SurfaceFrame frame(double u, double v) const;

  /// The closest point of the surface to p: the nearest of a grid of
  /// samples over every knot span as the start, then Newton on the
  /// distance's gradient (with the second-order terms, so that it converges
  /// quadratically on curved surfaces), clamped to the domain, at most
  /// kProjectionIterations steps. Feet on the domain boundary are found
  /// too (the step is projected onto the bounds there).
  SurfaceProjection closestPoint(const Vec3 &p) const;
  /// The same starting from (u, v) instead of the grid search: for a
  /// sequence of nearby points (samples along a curve), each started from
  /// the previous foot.
  SurfaceProjection closestPoint(const Vec3 &p, double u, double v) const;

  /// The bounding box diagonal of the control net (contains the surface).
  double netDiagonal() const;

private:
  int degreeU_ = 0, degreeV_ = 0;
  std::vector<double> knotsU_, knotsV_;
  int countU_ = 0, countV_ = 0;
  std::vector<Vec3> points_;
  std::vector<double> weights_;
};

} // namespace v1
} // namespace curvenet
