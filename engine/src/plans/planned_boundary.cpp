// Patch::evaluatePlannedBoundary: the tessellator's boundary samples from a
// plan's side-0 boundary data (see curvenet/tessellate.hpp, plans/plan.hpp).
#include "curvenet/error.hpp"
#include "patches/patch.hpp"
#include "plans/plan.hpp"

namespace curvenet {
inline namespace v1 {

void Patch::evaluatePlannedBoundary(const EvaluationPlan &plan, int i, const std::uint32_t *j, std::size_t count,
                                    const JetBlockSink &out) const {
  checkPlan(plan);
  CURVENET_CHECK(plan.hasBoundary() && options_.scheme != Scheme::CompositeRibbon,
                 "planned boundary samples need a Gregory plan with boundary data");
  gregoryJetsFrom(
      count,
      [&](int k, std::size_t block, std::size_t m, double *const s[3], double *const b[3]) {
        plan.boundarySidesAndBlends(i, k, j + block, m, s, b);
        return SideBlendArrays{{s[0], s[1], s[2]}, {b[0], b[1], b[2]}};
      },
      plan.key().resolution >= kTableResolution, out);
}

} // namespace v1
} // namespace curvenet
