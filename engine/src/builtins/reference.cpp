// Analytic reference surfaces (curvenet/reference.hpp).
//
// Every kind is written as an implicit F(p) = 0 that is positive on the normal
// side. The frame at a surface point follows from ∇F and the Hessian H:
// N = ∇F/|∇F| and, for a unit tangent t, II(t,t) = −dN(t)·t = −tᵀHt/|∇F|
// (the tangential part of dN is P·H/|∇F|), which gives the sign convention of
// the header (sphere with outward normal: κ = −1/r). Closest points use the
// structure of each kind: a 1D secular equation for the ellipsoid, the exact
// tube construction for the torus, Newton on the parameterization for graphs.
#include <algorithm>
#include <array>
#include <cmath>

#include "curvenet/reference.hpp"

#include "curvenet/mesh_reference.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

using Mat3 = std::array<std::array<double, 3>, 3>;

Vec3 applyMatrix(const Mat3 &H, const Vec3 &v) {
  return {H[0][0] * v.x + H[0][1] * v.y + H[0][2] * v.z, H[1][0] * v.x + H[1][1] * v.y + H[1][2] * v.z,
          H[2][0] * v.x + H[2][1] * v.y + H[2][2] * v.z};
}

// Frame at surface point q from the implicit gradient g and Hessian H.
SurfaceFrame frameFromImplicit(const Vec3 &q, const Vec3 &g, const Mat3 &H) {
  SurfaceFrame f;
  f.point = q;
  const double gn = norm(g);
  f.normal = g / gn;
  // Any orthonormal tangent basis (u, v) with u × v = N.
  const Vec3 &n = f.normal;
  Vec3 axis = std::abs(n.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  Vec3 u = normalized(axis - dot(axis, n) * n);
  Vec3 v = cross(n, u);
  // Shape matrix in (u, v): symmetric 2×2 [a b; b c], eigen-decomposed in closed form.
  double a = -dot(u, applyMatrix(H, u)) / gn, b = -dot(u, applyMatrix(H, v)) / gn, c = -dot(v, applyMatrix(H, v)) / gn;
  double mean = 0.5 * (a + c), half = std::hypot(0.5 * (a - c), b);
  f.k1 = mean + half;
  f.k2 = mean - half;
  Vec3 e1 = u;
  if (half > 1e-14 * (std::abs(mean) + 1e-300)) {
    // Eigenvector of k1: rows of (M − k1 I) are orthogonal to it; take the better-conditioned one.
    double x1 = b, y1 = f.k1 - a;    // from row 1: (a − k1) x + b y = 0
    double x2 = f.k1 - c, y2 = b;    // from row 2: b x + (c − k1) y = 0
    if (x1 * x1 + y1 * y1 >= x2 * x2 + y2 * y2) e1 = x1 * u + y1 * v;
    else e1 = x2 * u + y2 * v;
    e1 = normalized(e1);
  }
  f.direction1 = e1;
  return f;
}

SurfaceFrame ellipsoidFrame(const Vec3 &center, const Vec3 &r, const Vec3 &q) {
  Vec3 l = q - center;
  Vec3 g{2 * l.x / (r.x * r.x), 2 * l.y / (r.y * r.y), 2 * l.z / (r.z * r.z)};
  Mat3 H{};
  H[0][0] = 2 / (r.x * r.x), H[1][1] = 2 / (r.y * r.y), H[2][2] = 2 / (r.z * r.z);
  return frameFromImplicit(q, g, H);
}

// Closest point on (x/a)² + (y/b)² + (z/c)² = 1: x_i = a_i² p_i / (a_i² + t) with
// t the largest root of f(t) = Σ (a_i p_i / (a_i² + t))² − 1, which is convex
// and decreasing on (−min a_i², ∞); bracketed Newton.
Vec3 ellipsoidClosest(const Vec3 &r, const Vec3 &p) {
  const std::array<double, 3> a{r.x, r.y, r.z}, x{p.x, p.y, p.z};
  auto f = [&](double t, double &fp) {
    double s = -1;
    fp = 0;
    for (int i = 0; i < 3; ++i) {
      double d = a[i] * a[i] + t, q = a[i] * x[i] / d;
      s += q * q;
      fp -= 2 * q * q / d;
    }
    return s;
  };
  const double amin = std::min({a[0], a[1], a[2]}), amax = std::max({a[0], a[1], a[2]});
  double lo = -amin * amin, hi = amax * norm(p) + amax * amax;
  double t = 0;
  for (int it = 0; it < 200; ++it) {
    double fp, ft = f(t, fp);
    if (ft > 0) lo = t;
    else hi = t;
    if (ft == 0) break;
    double tn = t - ft / fp;
    if (!(tn > lo && tn < hi)) tn = 0.5 * (lo + hi);
    if (std::abs(tn - t) <= 1e-16 * (amax * amax + std::abs(t))) {
      t = tn;
      break;
    }
    t = tn;
  }
  Vec3 q;
  q.x = a[0] * a[0] * x[0] / (a[0] * a[0] + t);
  q.y = a[1] * a[1] * x[1] / (a[1] * a[1] + t);
  q.z = a[2] * a[2] * x[2] / (a[2] * a[2] + t);
  return q;
}

// Torus F = (ρ − R)² + z² − r², ρ = √(x² + y²).
SurfaceFrame torusFrame(const Vec3 &center, double R, const Vec3 &q) {
  Vec3 l = q - center;
  double rho = std::hypot(l.x, l.y), s = rho - R;
  Vec3 g{2 * s * l.x / rho, 2 * s * l.y / rho, 2 * l.z};
  double rho2 = rho * rho, rho3 = rho2 * rho;
  Mat3 H{};
  H[0][0] = 2 * (l.x * l.x / rho2 + s * l.y * l.y / rho3);
  H[1][1] = 2 * (l.y * l.y / rho2 + s * l.x * l.x / rho3);
  H[0][1] = H[1][0] = 2 * (l.x * l.y / rho2 - s * l.x * l.y / rho3);
  H[2][2] = 2;
  return frameFromImplicit(q, g, H);
}

Vec3 torusClosest(double R, double r, const Vec3 &p) {
  double rho = std::hypot(p.x, p.y);
  Vec3 radial = rho > 0 ? Vec3{p.x / rho, p.y / rho, 0} : Vec3{1, 0, 0};
  Vec3 c = R * radial, d = p - c;
  // On the core circle every tube point is equally close; choose the outward one.
  Vec3 dir = norm(d) > 0 ? d / norm(d) : radial;
  return c + r * dir;
}

// Graph F = z − a x² − b y² (positive above, normal on the +z side).
SurfaceFrame graphFrame(const Vec3 &center, double a, double b, const Vec3 &q) {
  Vec3 l = q - center;
  Vec3 g{-2 * a * l.x, -2 * b * l.y, 1};
  Mat3 H{};
  H[0][0] = -2 * a, H[1][1] = -2 * b;
  return frameFromImplicit(q, g, H);
}

// Newton on the stationarity of |X(u,v) − p|², X = (u, v, a u² + b v²), with a
// Gauss–Newton fallback where the Hessian is not positive definite and step
// halving so the distance never increases.
Vec3 graphClosest(double a, double b, const Vec3 &p) {
  auto X = [&](double u, double v) { return Vec3{u, v, a * u * u + b * v * v}; };
  double u = p.x, v = p.y, d = squaredNorm(X(u, v) - p);
  for (int it = 0; it < 100; ++it) {
    Vec3 r = X(u, v) - p, Xu{1, 0, 2 * a * u}, Xv{0, 1, 2 * b * v};
    double gu = dot(r, Xu), gv = dot(r, Xv);
    double huu = dot(Xu, Xu) + 2 * a * r.z, huv = dot(Xu, Xv), hvv = dot(Xv, Xv) + 2 * b * r.z;
    double det = huu * hvv - huv * huv;
    if (!(huu > 0 && det > 0)) {
      huu = dot(Xu, Xu), hvv = dot(Xv, Xv);
      det = huu * hvv - huv * huv;
    }
    double du = -(hvv * gu - huv * gv) / det, dv = -(huu * gv - huv * gu) / det;
    // Near the solution the distance is stationary and rounding hides the
    // decrease; allow that much slack so Newton can finish.
    const double slack = d * 1e-12;
    double un = u + du, vn = v + dv, dn = squaredNorm(X(un, vn) - p);
    for (int h = 0; h < 40 && dn > d + slack; ++h) {
      du *= 0.5, dv *= 0.5;
      un = u + du, vn = v + dv;
      dn = squaredNorm(X(un, vn) - p);
    }
    if (dn > d + slack) break;
    bool done = std::abs(du) + std::abs(dv) <= 1e-16 * (1 + std::abs(u) + std::abs(v));
    u = un, v = vn, d = dn;
    if (done) break;
  }
  return X(u, v);
}

} // namespace

double SurfaceFrame::normalCurvature(const Vec3 &t) const {
  // Euler: κ(t) = κ1 cos²α + κ2 sin²α, α the angle from e1 in the tangent plane.
  Vec3 tangent = normalized(t - dot(t, normal) * normal);
  Vec3 e2 = cross(normal, direction1);
  double c = dot(tangent, direction1), s = dot(tangent, e2);
  return k1 * c * c + k2 * s * s;
}

std::string ReferenceSurface::kindName(Kind kind) {
  switch (kind) {
  case Kind::Ellipsoid: return "ellipsoid";
  case Kind::Torus: return "torus";
  case Kind::Graph: return "graph";
  case Kind::Mesh: return "mesh";
  }
  return "unknown";
}

ReferenceSurface ReferenceSurface::fromMesh(std::shared_ptr<const MeshReference> mesh) {
  ReferenceSurface r;
  r.kind = Kind::Mesh;
  r.mesh = std::move(mesh);
  return r;
}

std::optional<ReferenceSurface::Kind> ReferenceSurface::kindFromName(const std::string &name) {
  for (Kind k : {Kind::Ellipsoid, Kind::Torus, Kind::Graph})
    if (kindName(k) == name) return k;
  return std::nullopt;
}

double ReferenceSurface::implicit(const Vec3 &p) const {
  Vec3 l = p - center;
  switch (kind) {
  case Kind::Ellipsoid: {
    double x = l.x / size.x, y = l.y / size.y, z = l.z / size.z;
    return x * x + y * y + z * z - 1;
  }
  case Kind::Torus: {
    double s = std::hypot(l.x, l.y) - size.x;
    return s * s + l.z * l.z - size.y * size.y;
  }
  case Kind::Graph: return l.z - size.x * l.x * l.x - size.y * l.y * l.y;
  case Kind::Mesh: return mesh->signedDistance(p);
  }
  return 0;
}

SurfaceFrame ReferenceSurface::closest(const Vec3 &p) const {
  Vec3 l = p - center;
  switch (kind) {
  case Kind::Ellipsoid: return ellipsoidFrame(center, size, center + ellipsoidClosest(size, l));
  case Kind::Torus: return torusFrame(center, size.x, center + torusClosest(size.x, size.y, l));
  case Kind::Graph: return graphFrame(center, size.x, size.y, center + graphClosest(size.x, size.y, l));
  case Kind::Mesh: return mesh->closest(p);
  }
  return {};
}

double ReferenceSurface::signedDistance(const Vec3 &p) const {
  if (kind == Kind::Mesh) return mesh->signedDistance(p);
  SurfaceFrame f = closest(p);
  Vec3 d = p - f.point;
  return std::copysign(norm(d), dot(d, f.normal));
}

} // namespace v1
} // namespace curvenet
