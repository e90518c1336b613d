// Tensor-product B-spline / NURBS surfaces (curvenet/bspline_surface.hpp).
#include "curvenet/bspline_surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

constexpr int kOrder = BSplineSurface::maxDegree + 1;

/// Basis functions of one direction at a parameter: the non-zero ones and
/// their first two derivatives (Piegl & Tiller A2.3), starting at index
/// `first` of the control points.
struct BasisDerivatives {
  int first = 0;
  std::array<std::array<double, kOrder>, 3> value{}; ///< [derivative order][k], k = 0..degree
};

/// The knot span [knots[s], knots[s+1]) holding t (clamped to the domain; the
/// domain end belongs to the last non-empty span).
int findSpan(const std::vector<double> &knots, int degree, int count, double t) {
  if (t >= knots[size_t(count)]) {
    int s = count - 1;
    while (s > degree && knots[size_t(s)] == knots[size_t(s + 1)]) --s;
    return s;
  }
  if (t <= knots[size_t(degree)]) {
    int s = degree;
    while (s < count - 1 && knots[size_t(s)] == knots[size_t(s + 1)]) ++s;
    return s;
  }
  const auto it = std::upper_bound(knots.begin() + degree, knots.begin() + count + 1, t);
  return int(it - knots.begin()) - 1;
}

BasisDerivatives basisDerivatives(const std::vector<double> &knots, int degree, int count, double t) {
  const int span = findSpan(knots, degree, count, t);
  t = std::clamp(t, knots[size_t(degree)], knots[size_t(count)]);
  // ndu: basis functions (upper triangle) and knot differences (lower).
  std::array<std::array<double, kOrder>, kOrder> ndu{};
  std::array<double, kOrder> left{}, right{};
  ndu[0][0] = 1;
  for (int j = 1; j <= degree; ++j) {
    left[size_t(j)] = t - knots[size_t(span + 1 - j)];
    right[size_t(j)] = knots[size_t(span + j)] - t;
    double saved = 0;
    for (int r = 0; r < j; ++r) {
      ndu[size_t(j)][size_t(r)] = right[size_t(r + 1)] + left[size_t(j - r)];
      const double temp = ndu[size_t(r)][size_t(j - 1)] / ndu[size_t(j)][size_t(r)];
      ndu[size_t(r)][size_t(j)] = saved + right[size_t(r + 1)] * temp;
      saved = left[size_t(j - r)] * temp;
    }
    ndu[size_t(j)][size_t(j)] = saved;
  }
  BasisDerivatives result;
  result.first = span - degree;
  for (int j = 0; j <= degree; ++j) result.value[0][size_t(j)] = ndu[size_t(j)][size_t(degree)];
  std::array<std::array<double, kOrder>, 2> a{};
  const int orders = std::min(2, degree);
  for (int r = 0; r <= degree; ++r) {
    int s1 = 0, s2 = 1;
    a[0] = {};
    a[1] = {};
    a[0][0] = 1;
    for (int k = 1; k <= orders; ++k) {
      double d = 0;
      const int rk = r - k, pk = degree - k;
      if (r >= k) {
        a[size_t(s2)][0] = a[size_t(s1)][0] / ndu[size_t(pk + 1)][size_t(rk)];
        d = a[size_t(s2)][0] * ndu[size_t(rk)][size_t(pk)];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = r - 1 <= pk ? k - 1 : degree - r;
      for (int j = j1; j <= j2; ++j) {
        a[size_t(s2)][size_t(j)] =
            (a[size_t(s1)][size_t(j)] - a[size_t(s1)][size_t(j - 1)]) / ndu[size_t(pk + 1)][size_t(rk + j)];
        d += a[size_t(s2)][size_t(j)] * ndu[size_t(rk + j)][size_t(pk)];
      }
      if (r <= pk) {
        a[size_t(s2)][size_t(k)] = -a[size_t(s1)][size_t(k - 1)] / ndu[size_t(pk + 1)][size_t(r)];
        d += a[size_t(s2)][size_t(k)] * ndu[size_t(r)][size_t(pk)];
      }
      result.value[size_t(k)][size_t(r)] = d;
      std::swap(s1, s2);
    }
  }
  // Scale by degree! / (degree − k)!.
  double factor = degree;
  for (int k = 1; k <= orders; ++k) {
    for (int j = 0; j <= degree; ++j) result.value[size_t(k)][size_t(j)] *= factor;
    factor *= degree - k;
  }
  return result;
}

void checkKnots(const std::vector<double> &knots, int degree, int count, const char *direction) {
  if (degree < 1 || degree > BSplineSurface::maxDegree)
    throw InputError("", "surface", std::string("degree in ") + direction + " is " + std::to_string(degree) +
                                        ", outside 1.." + std::to_string(BSplineSurface::maxDegree));
  if (count < degree + 1)
    throw InputError("", "surface", std::to_string(count) + " control points in " + direction +
                                        " are too few for degree " + std::to_string(degree));
  if (knots.size() != size_t(count + degree + 1))
    throw InputError("", "surface", std::to_string(knots.size()) + " knots in " + direction + ", expected " +
                                        std::to_string(count + degree + 1) + " (points + degree + 1)");
  for (size_t k = 0; k < knots.size(); ++k) {
    if (!std::isfinite(knots[k])) throw InputError("", "surface", std::string("knot in ") + direction + " is not finite");
    if (k > 0 && knots[k] < knots[k - 1])
      throw InputError("", "surface", std::string("knots in ") + direction + " decrease at index " + std::to_string(k));
  }
  for (int k = 1; k <= degree; ++k)
    if (knots[size_t(k)] != knots[0] || knots[knots.size() - 1 - size_t(k)] != knots.back())
      throw InputError("", "surface", std::string("knots in ") + direction + " are not clamped (the first and last " +
                                          std::to_string(degree + 1) + " must be equal)");
  if (!(knots[size_t(count)] > knots[size_t(degree)]))
    throw InputError("", "surface", std::string("knots in ") + direction + " leave an empty domain");
}

} // namespace

BSplineSurface::BSplineSurface(int degreeU, int degreeV, std::vector<double> knotsU, std::vector<double> knotsV,
                               int countU, int countV, std::vector<Vec3> controlPoints, std::vector<double> weights)
    : degreeU_(degreeU), degreeV_(degreeV), knotsU_(std::move(knotsU)), knotsV_(std::move(knotsV)), countU_(countU),
      countV_(countV), points_(std::move(controlPoints)), weights_(std::move(weights)) {
  checkKnots(knotsU_, degreeU_, countU_, "u");
  checkKnots(knotsV_, degreeV_, countV_, "v");
  const size_t expected = size_t(countU_) * size_t(countV_);
  if (points_.size() != expected)
    throw InputError("", "surface", "control net has " + std::to_string(points_.size()) + " points, expected " +
                                        std::to_string(countU_) + " x " + std::to_string(countV_));
  for (size_t k = 0; k < points_.size(); ++k)
    if (!isFinite(points_[k])) throw InputError("", "surface", "control point " + std::to_string(k) + " is not finite");
  if (!weights_.empty()) {
    if (weights_.size() != expected)
      throw InputError("", "surface", std::to_string(weights_.size()) + " weights for " + std::to_string(expected) +
                                          " control points");
    for (size_t k = 0; k < weights_.size(); ++k)
      if (!(weights_[k] > 0 && std::isfinite(weights_[k])))
        throw InputError("", "surface", "weight " + std::to_string(k) + " is not a positive finite number");
  }
}

SurfaceJet BSplineSurface::jet(double u, double v) const {
  const BasisDerivatives bu = basisDerivatives(knotsU_, degreeU_, countU_, u);
  const BasisDerivatives bv = basisDerivatives(knotsV_, degreeV_, countV_, v);
  // Homogeneous derivatives A_kl = Σ N_i^(k) N_j^(l) w P and w_kl, k + l ≤ 2.
  std::array<std::array<Vec3, 3>, 3> a{};
  std::array<std::array<double, 3>, 3> w{};
  for (int i = 0; i <= degreeU_; ++i)
    for (int j = 0; j <= degreeV_; ++j) {
      const size_t index = size_t(bu.first + i) * size_t(countV_) + size_t(bv.first + j);
      const double weight = weights_.empty() ? 1.0 : weights_[index];
      const Vec3 wp = points_[index] * weight;
      for (int k = 0; k <= 2; ++k)
        for (int l = 0; k + l <= 2; ++l) {
          const double b = bu.value[size_t(k)][size_t(i)] * bv.value[size_t(l)][size_t(j)];
          a[size_t(k)][size_t(l)] += wp * b;
          w[size_t(k)][size_t(l)] += weight * b;
        }
    }
  // Quotient rule (Piegl & Tiller A4.4) up to second order.
  SurfaceJet s;
  const double w0 = w[0][0];
  s.point = a[0][0] / w0;
  s.du = (a[1][0] - s.point * w[1][0]) / w0;
  s.dv = (a[0][1] - s.point * w[0][1]) / w0;
  s.duu = (a[2][0] - s.du * (2 * w[1][0]) - s.point * w[2][0]) / w0;
  s.duv = (a[1][1] - s.dv * w[1][0] - s.du * w[0][1] - s.point * w[1][1]) / w0;
  s.dvv = (a[0][2] - s.dv * (2 * w[0][1]) - s.point * w[0][2]) / w0;
  return s;
}

Vec3 BSplineSurface::point(double u, double v) const { return jet(u, v).point; }

Vec3 BSplineSurface::normal(double u, double v) const {
  const SurfaceJet s = jet(u, v);
  return normalized(cross(s.du, s.dv));
}

FundamentalForms BSplineSurface::fundamentalForms(double u, double v) const {
  const SurfaceJet s = jet(u, v);
  const Vec3 n = normalized(cross(s.du, s.dv));
  return {dot(s.du, s.du), dot(s.du, s.dv), dot(s.dv, s.dv), dot(n, s.duu), dot(n, s.duv), dot(n, s.dvv)};
}

SurfaceFrame BSplineSurface::frame(double u, double v) const {
  const SurfaceJet s = jet(u, v);
  const FundamentalForms f = fundamentalForms(u, v);
  SurfaceFrame frame;
  frame.point = s.point;
  frame.normal = normalized(cross(s.du, s.dv));
  // Principal curvatures: the eigenvalues of the shape operator I⁻¹ II.
  const double det = f.E * f.G - f.F * f.F;
  const double mean = (f.E * f.N - 2 * f.F * f.M + f.G * f.L) / (2 * det);
  const double gauss = (f.L * f.N - f.M * f.M) / det;
  const double root = std::sqrt(std::max(0.0, mean * mean - gauss));
  frame.k1 = mean + root;
  frame.k2 = mean - root;
  // (II − κ1 I)(a, b) = 0: from the row with the larger coefficients; an
  // umbilic (both rows vanish) takes the u direction.
  const double r0a = f.L - frame.k1 * f.E, r0b = f.M - frame.k1 * f.F;
  const double r1a = f.M - frame.k1 * f.F, r1b = f.N - frame.k1 * f.G;
  const double scale = std::max({std::abs(f.L), std::abs(f.M), std::abs(f.N), 1e-300});
  Vec3 direction = s.du;
  if (std::hypot(r0a, r0b) >= std::hypot(r1a, r1b)) {
    if (std::hypot(r0a, r0b) > 1e-12 * scale) direction = s.du * (-r0b) + s.dv * r0a;
  } else {
    direction = s.du * r1b + s.dv * (-r1a);
  }
  frame.direction1 = normalized(direction - frame.normal * dot(direction, frame.normal));
  return frame;
}

double BSplineSurface::netDiagonal() const {
  Vec3 lo = points_.front(), hi = points_.front();
  for (const Vec3 &p : points_) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  return norm(hi - lo);
}

SurfaceProjection BSplineSurface::closestPoint(const Vec3 &p) const {
  // Coarse start: samples across every non-empty knot span in each direction
  // (enough per span that a span's polynomial cannot hide a second minimum
  // between them for nets of moderate curvature).
  auto samples = [](const std::vector<double> &knots, int degree, int count) {
    std::vector<double> t;
    const int perSpan = std::max(4, 2 * degree + 2);
    for (int s = degree; s < count; ++s) {
      if (knots[size_t(s + 1)] <= knots[size_t(s)]) continue;
      for (int k = 0; k < perSpan; ++k)
        t.push_back(knots[size_t(s)] + (knots[size_t(s + 1)] - knots[size_t(s)]) * k / perSpan);
    }
    t.push_back(knots[size_t(count)]);
    return t;
  };
  const std::vector<double> us = samples(knotsU_, degreeU_, countU_), vs = samples(knotsV_, degreeV_, countV_);
  double best = std::numeric_limits<double>::infinity(), bestU = uStart(), bestV = vStart();
  for (double u : us)
    for (double v : vs)
      if (const double d = squaredNorm(point(u, v) - p); d < best) {
        best = d;
        bestU = u;
        bestV = v;
      }
  return closestPoint(p, bestU, bestV);
}

SurfaceProjection BSplineSurface::closestPoint(const Vec3 &p, double u, double v) const {
  u = std::clamp(u, uStart(), uEnd());
  v = std::clamp(v, vStart(), vEnd());
  const double size = std::max(netDiagonal(), 1e-300);
  for (int iteration = 0; iteration < kProjectionIterations; ++iteration) {
    const SurfaceJet s = jet(u, v);
    const Vec3 r = s.point - p;
    // Newton on ½|S − p|²: gradient (r·S_u, r·S_v), Hessian with the r·S_xy
    // terms; where those make it indefinite (far from the surface on the
    // concave side) the Gauss–Newton matrix alone.
    const double gu = dot(r, s.du), gv = dot(r, s.dv);
    double huu = dot(s.du, s.du) + dot(r, s.duu), huv = dot(s.du, s.dv) + dot(r, s.duv),
           hvv = dot(s.dv, s.dv) + dot(r, s.dvv);
    if (!(huu > 0 && huu * hvv - huv * huv > 0)) {
      huu = dot(s.du, s.du);
      huv = dot(s.du, s.dv);
      hvv = dot(s.dv, s.dv);
    }
    const double det = huu * hvv - huv * huv;
    if (!(det > 0)) break;
    double stepU = -(hvv * gu - huv * gv) / det, stepV = -(huu * gv - huv * gu) / det;
    // A foot on a domain edge: the descent leaves the domain in one
    // parameter, so Newton continues in the other alone.
    const bool pinnedU = (u <= uStart() && gu > 0) || (u >= uEnd() && gu < 0);
    const bool pinnedV = (v <= vStart() && gv > 0) || (v >= vEnd() && gv < 0);
    if (pinnedU) {
      stepU = 0;
      stepV = pinnedV ? 0 : -gv / hvv;
    } else if (pinnedV) {
      stepV = 0;
      stepU = -gu / huu;
    }
    const double nextU = std::clamp(u + stepU, uStart(), uEnd()), nextV = std::clamp(v + stepV, vStart(), vEnd());
    stepU = nextU - u;
    stepV = nextV - v;
    u = nextU;
    v = nextV;
    if (norm(s.du * stepU + s.dv * stepV) < 1e-15 * size) break;
  }
  SurfaceProjection result;
  result.u = u;
  result.v = v;
  result.point = point(u, v);
  result.distance = norm(result.point - p);
  return result;
}

} // namespace v1
} // namespace curvenet
