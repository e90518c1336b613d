// The regular n-gon domain of a patch and the maps from it to the ribbons'
// local parameters (side parameter s_i, distance parameter d_i).
//
// Corners p_0 … p_{n-1} lie counter-clockwise on the unit circle; side i runs
// from p_i to p_{i+1} and is mapped onto boundary curve P_i. All maps return
// Duals so that patches get exact derivatives.
#pragma once

#include "curvenet/kernels/kernels.hpp"

#include <array>
#include <span>
#include <vector>

#include "patches/dual.hpp"

namespace curvenet {
inline namespace v1 {

class RegularDomain {
public:
  explicit RegularDomain(int sides);

  int sides() const { return n_; }
  const Vec2 &corner(int i) const { return corners_[wrap(i)]; }
  int wrap(int i) const {
    // Callers mostly step one side around (i ± 1, i + 2): no division then.
    if (i >= 0 && i < n_) return i;
    if (i >= n_ && i < 2 * n_) return i - n_;
    if (i < 0 && i >= -n_) return i + n_;
    return ((i % n_) + n_) % n_;
  }
  /// Point at fraction s ∈ [0, 1] along side i.
  Vec2 pointOnSide(int i, double s) const;
  /// The corner that (u, v) is exactly (bit for bit), or −1. There the
  /// Hermite sweeps of its two sides are their ends exactly, s_j = 0 and
  /// s_{j−1} = 1, in every path (hermiteSweepSides; the batched paths set
  /// the same values after their roots): a root or a quotient of distances
  /// leaves them a rounding error off (1e-32 … 1e-16), and the G² corner's
  /// limits (the two-ribbon blend's ½, the correction's (a + b) / 2) are
  /// taken at s = t = 0 alone, so that two paths an ulp apart would take
  /// different ones.
  int cornerAt(double u, double v) const {
    if (u * u + v * v < 1 - 1e-9) return -1; // the corners lie on the unit circle
    for (int i = 0; i < n_; ++i)
      if (u == corners_[i].x && v == corners_[i].y) return i;
    return -1;
  }

  /// Perpendicular distance to the line of side i, in units of the side
  /// length (0 on the side, positive inside): the Δ_i of the Gregory blends.
  Dual perpendicularDistance(int i, Dual u, Dual v) const {
    Dual x, y;
    sideFrame(i, u, v, x, y);
    return y;
  }

  /// Radial sweep [CG84]: s_i along the line through the intersection of the
  /// extended sides i−1 and i+1 (a parallel sweep when they do not meet).
  Dual radialSideParameter(int i, Dual u, Dual v) const;
  /// The same from side i's frame coordinates (x, y) (as perpendicularDistance
  /// and sideFrame define them) and its sweepFrame(i): one division, for
  /// batches that compute the frame once per side.
  template <class T> static T radialSideParameter(const kernels::SweepFrame &frame, T x, T y) {
    if (frame.parallel) return x - y * (frame.ax / frame.ay); // sweep lines parallel to sides i ± 1
    // The sweep line through the apex and (x, y) meets the base line y = 0 at s.
    return T(frame.apexX) - T(frame.apexY) * (x - frame.apexX) / (y - frame.apexY);
  }

  /// Hermite sweepline ([SV14] eq. 20): (u,v) = (s,0) + d [a H(s) + b H(1−s)]
  /// in side i's frame. Returns s_i and d_i with derivatives (implicit
  /// differentiation of the quartic's root). `quintic` uses the fifth-degree
  /// Hermite polynomial of the footnote of Sec. 4.3.
  struct SweepParameters {
    Dual s, d;
  };
  /// The cubic sweep's root comes from kernels::hermiteSweepRoots (certified
  /// Newton, the robust solver where the certificate fails); the quintic
  /// sweep's from hermiteSweepByGrid. A triangle's cubic sweep is
  /// triangleSideParameter instead (d: the distance from side i in units of
  /// the height), its quintic one eq. 20 by the grid solver.
  SweepParameters hermiteSweep(int i, Dual u, Dual v, bool quintic = false) const;
  /// hermiteSweep's s_i for every side at once (s holds sides() entries):
  /// the cubic sweeps' roots in one batch of the kernel solver, which fills
  /// its vector lanes with the sides instead of solving them one by one.
  /// At a corner (cornerAt) its two sides' parameters are their exact ends.
  void hermiteSweepSides(Dual u, Dual v, bool quintic, std::span<Dual> s) const;
  /// The same by the engine's own scalar solver, independent of the kernels:
  /// sign changes of the quartic on a 64-cell grid refined by bisection, with
  /// the kernels' selection rule (about ten times the kernel's cost).
  SweepParameters hermiteSweepByGrid(int i, Dual u, Dual v, bool quintic = false) const;
  /// Side i's sweep constants for the batched kernels (kernels::SweepFrame):
  /// the neighbouring sides' directions in its frame and the radial apex.
  /// The same for every side of a regular domain.
  const kernels::SweepFrame &sweepFrame(int) const { return frame_; }
  /// hermiteSweep's result for a root found elsewhere (the batched solver of
  /// curvenet::kernels): s_i = root with its derivatives, and d_i.
  SweepParameters hermiteSweepFromRoot(int i, Dual u, Dual v, double root, bool quintic = false) const;
  /// s_i of the Hermite sweepline with exact second derivatives: the root of
  /// hermiteSweep refined by two Newton steps in hyper-dual arithmetic (the
  /// first fixes the first derivatives, the second the second derivatives).
  Dual2 hermiteSweepSide2(int i, Dual2 u, Dual2 v, bool quintic = false) const;
  /// Side parameter of a triangle (n = 3) in closed form: the sweep that
  /// replaces eq. 20 there (see Sweepline in curvenet/surface.hpp). With
  /// t = a / (a + b) the radial parameter (a, b the distances to sides i − 1
  /// and i + 1) and c the distance to side i, all in units of the height
  /// (a + b + c = 1),
  ///   s_i = (1 − c) t + c (3t² − 2t³),
  /// the radial sweep eased by the smoothstep in proportion to the distance
  /// from the side. Properties:
  ///  - s_i = 0 on side i − 1, 1 on side i + 1, the fraction t on side i;
  ///  - ∂s_i/∂a = 1 on side i − 1 and ∂s_i/∂b = −1 on side i + 1, all along
  ///    them: across side i the parameters s_{i+1} and 1 − s_{i−1} that the
  ///    two corner interpolants give ribbon i's distance agree to first
  ///    order (what eq. 19 asks for G², with the rate of eq. 20);
  ///  - s_i increases strictly along every line parallel to side i
  ///    (∂s/∂t ≥ 1 − c > 0), so its isolines never cross: the map
  ///    (s_i, c) ↦ (u, v) is one-to-one with a positive Jacobian inside.
  /// The radial parameter is undefined at the opposite corner (a = b = 0),
  /// where every blend of this side vanishes; 1/2 is returned there.
  /// Arguments: perpendicular distances as perpendicularDistance gives them.
  template <class T> T triangleSideParameter(T previous, T next, T own) const {
    const T a = previous * inverseHeight_, b = next * inverseHeight_, c = own * inverseHeight_;
    const T sum = a + b;
    if (valueOf(sum) <= 0) return T(0.5);
    const T t = a / sum;
    return t + c * t * (T(1.0) - t) * (t * 2.0 - 1.0);
  }
  /// triangleSideParameter of side i at a domain point, first or second
  /// derivatives included.
  Dual triangleSweep(int i, Dual u, Dual v) const;
  Dual2 triangleSweep2(int i, Dual2 u, Dual2 v) const;

  /// perpendicularDistance with second derivatives (it is affine).
  Dual2 perpendicularDistance2(int i, Dual2 u, Dual2 v) const;

  /// Linear sweep ([VSR] Sec. 2.3): the isoline of s_i is the straight
  /// line from the point at fraction s on side i to the point at fraction s
  /// on the chord p_{i−1} p_{i+2}; s = 0 is side i−1 and s = 1 side i+1.
  Dual linearSweepSideParameter(int i, Dual u, Dual v) const;

  /// Wachspress distance parameter of [VSR] Sec. 2.3: d_i = 1 − λ_i − λ_{i+1}
  /// (λ at the two ends of side i), for all sides at once.
  /// `distances` holds at least sides() entries.
  void wachspressDistances(Dual u, Dual v, std::span<Dual> distances) const;

  /// The corner products of the blends in product form ([SV14] eq. 18,
  /// [VSR]): products[i] = D_{i,i−1} = ∏_{j ∉ {i−1, i}} powered[j], where
  /// powered[j] is side j's distance to the blend exponent. Returns their sum.
  /// Finite on the sides, where the reciprocal form divides by zero.
  template <typename T, std::size_t N>
  T cornerProducts(const std::array<T, N> &powered, std::array<T, N> &products) const {
    T total = 0.0;
    for (int i = 0; i < n_; ++i) {
      T product = 1.0;
      for (int j = 0; j < n_; ++j)
        if (j != i && j != wrap(i - 1)) product *= powered[j];
      products[i] = product;
      total += product;
    }
    return total;
  }

  /// Side i's frame: maps a domain point to (x, y) where side i is (0,0)→(1,0)
  /// and the domain lies at y > 0.
  void sideFrame(int i, Dual u, Dual v, Dual &x, Dual &y) const {
    const SideAxes &f = sideAxes_[static_cast<std::size_t>(wrap(i))];
    const Dual qx = u - f.origin.x, qy = v - f.origin.y;
    x = qx * f.axis.x + qy * f.axis.y;
    y = qy * f.axis.x - qx * f.axis.y;
  }

private:
  /// hermiteSweepSides without the exact ends at corners.
  void solveHermiteSweepSides(Dual u, Dual v, bool quintic, std::span<Dual> s) const;
  /// A side-frame point (x, y) whose cubic sweep root is an end of [0, 1]:
  /// the solver kernel cannot certify it, hermiteSweepByGrid takes it.
  bool rootAtSweepEnd(double x, double y) const;

  static double valueOf(double x) { return x; }
  static double valueOf(const Dual &x) { return x.v; }
  static double valueOf(const Dual2 &x) { return x.v; }

  int n_;
  /// 1 / the height of the triangle over a side, in units of the side length (n = 3).
  double inverseHeight_ = 0;
  std::vector<Vec2> corners_;
  /// Side i's frame (sideFrame): its start corner and e / |e|², e = p_{i+1} − p_i.
  struct SideAxes {
    Vec2 origin, axis;
  };
  std::vector<SideAxes> sideAxes_;
  /// The neighbouring sides' directions in a side's frame (sweepFrame's a, b).
  Vec2 a_, b_;
  kernels::SweepFrame frame_;
};

} // namespace v1
} // namespace curvenet
