// Curve fitting shared by the built-ins: interpolation of exact surface curves.
#include "builtins/builtin_support.hpp"

namespace curvenet {
inline namespace v1 {
namespace builtin_detail {

BSplineCurve fitSurfaceCurve(const std::function<Vec3(double)> &exact, double t0, double t1, int intervals,
                             const Vec3 &start, const Vec3 &end) {
  // Uniform samples of a smooth (analytic) parameterization: the degree-5
  // interpolant converges as h⁶ in position and h⁴ in second derivative,
  // which is what the 1e-8 / 1e-5 accuracy targets rest on.
  std::vector<double> params(intervals + 1);
  std::vector<Vec3> points(intervals + 1);
  for (int i = 0; i <= intervals; ++i) {
    params[i] = t0 + (t1 - t0) * i / intervals;
    points[i] = exact(params[i]);
  }
  params.back() = t1;
  points.front() = start;
  points.back() = end;
  return BSplineCurve::interpolate(kFitDegree, params, points);
}

} // namespace builtin_detail
} // namespace v1
} // namespace curvenet
