// Normal fences and linear ribbons (paper 000 Sec. 3.2, DESIGN.md §3).
//
// A fence belongs to a segment and is shared by the faces on both sides, so
// both patches see the same normal N(u) and their cross-derivatives lie in
// the same plane span(P', N × P'): G¹ by construction.
#pragma once

#include <memory>
#include <vector>

#include "curvenet/network.hpp"

namespace curvenet {
inline namespace v1 {

/// Unit normal along a segment (u ∈ [0, 1]) perpendicular to its tangent,
/// equal to the given vertex normals at both ends: the rotation-minimizing
/// frame by double reflection [WJZL08] from the start normal, with the angle
/// left to the end normal distributed along the arc length.
class NormalFence {
public:
  NormalFence(const BSplineCurve &segment, const Vec3 &startNormal, const Vec3 &endNormal);

  Vec3 normal(double u) const;
  /// Normal and its derivative d N / d u.
  void normalAndDerivative(double u, Vec3 &n, Vec3 &dn) const;

private:
  BSplineCurve curve_;
  BSplineCurve smoothNormal_; ///< cubic interpolant of the corrected RMF normals (before projection)
};

/// Side data of a ribbon at one side parameter: P, P', T and T' (d/ds).
struct RibbonJet {
  Vec3 P, dP, T, dT;
};

/// Linear ribbon R(s, d) = P(s) + d T(s) of one face side, with
/// T = α D + β P', D = N × P' (eqs. 9, 11, 12) and α, β linear in s, fixed
/// by the end conditions T(0) = −P_prev'(1), T(1) = P_next'(0). At a corner
/// where the loop runs straight on (a T-node seen from the straight side,
/// or the midpoints of a 2-sided face) the neighbour's tangent gives no
/// cross direction; there T = D, the fence direction itself.
class LinearRibbon {
public:
  struct Piece {
    const NormalFence *fence;
    double sFrom, sTo; ///< range of side parameters on this segment
    bool reversed;     ///< the side runs the segment from end to start
  };
  LinearRibbon(BSplineCurve curve, std::vector<Piece> pieces);

  /// Sets α, β from the cross-derivative targets at both ends.
  void setEndConditions(const Vec3 &startTarget, const Vec3 &endTarget);

  const BSplineCurve &curve() const { return curve_; }
  RibbonJet at(double s) const;
  /// D = N × P' at the ends (for straight-angle corners).
  Vec3 fenceDirection(double s) const;

private:
  void fence(double s, Vec3 &n, Vec3 &dn) const;
  BSplineCurve curve_;
  std::vector<Piece> pieces_;
  double alpha0_ = 0, alpha1_ = 0, beta0_ = 0, beta1_ = 0;
};

} // namespace v1
} // namespace curvenet
