// One transfinite patch: a regular domain, a linear ribbon per domain side,
// and the scheme's formula. Internal to the engine; see curvenet/surface.hpp.
#pragma once

#include <vector>

#include "curvenet/surface.hpp"
#include "patches/domain.hpp"
#include "ribbons/ribbons.hpp"

namespace curvenet {
inline namespace v1 {

class Patch {
public:
  Patch(std::vector<LinearRibbon> ribbons, const SurfaceOptions &options);

  const RegularDomain &domain() const { return domain_; }
  const LinearRibbon &ribbon(int side) const { return ribbons_[domain_.wrap(side)]; }

  /// Surface point with exact ∂/∂u, ∂/∂v at domain point (u, v).
  DualVec3 evaluate(double u, double v) const;

private:
  DualVec3 gregory(Dual u, Dual v) const;
  DualVec3 compositeRibbon(Dual u, Dual v) const;

  RegularDomain domain_;
  std::vector<LinearRibbon> ribbons_;
  SurfaceOptions options_;
};

/// Corner data of two ribbons meeting at a corner, in the corner's local
/// coordinates (s along the first side, t across it): a_pq from the ribbon
/// that must be matched across t = 0, b_pq from the one matched across s = 0,
/// p, q ∈ {0, 1}. Used by both schemes' correction patches.
struct CornerData {
  Vec3 a00, a10, a01, a11, b10, b01, b11;
};

/// Gregory's rational correction term (DESIGN.md §3, G¹ case):
/// Q(s,t) = a00 + gs W10 + gt W01 + gs gt W11 with
/// W_pq = (s^{2−p} a_pq + t^{2−q} b_pq) / (s^{2−p} + t^{2−q}), where gs, gt are
/// the (possibly reparameterized) coordinates multiplying the terms. Every
/// term carries s^p t^q, so at the corner itself it is the corner point.
DualVec3 gregoryCorrection(const CornerData &c, Dual s, Dual t, Dual gs, Dual gt);

} // namespace v1
} // namespace curvenet
