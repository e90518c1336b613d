// A B-spline under edit by knot insertion and control-point moves: the
// working form of curve tweaking and vertex repair (curvenet/analysis.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "curvenet/curve.hpp"
#include "curvenet/error.hpp"
#include "curvenet/network.hpp"

namespace curvenet {
inline namespace v1 {

/// A curve under edit, in homogeneous form (w·P, w), in which knot insertion
/// is linear also for rational curves.
struct EditableCurve {
  int p = 0;
  std::vector<double> U;
  std::vector<Vec3> wp;
  std::vector<double> w;
  bool rational = false;

  explicit EditableCurve(const BSplineCurve &c) : p(c.degree()), U(c.knots()), rational(c.isRational()) {
    for (size_t i = 0; i < c.controlPoints().size(); ++i) {
      const double wi = rational ? c.weights()[i] : 1.0;
      wp.push_back(wi * c.controlPoints()[i]);
      w.push_back(wi);
    }
  }

  int count() const { return int(w.size()); }

  BSplineCurve curve() const {
    std::vector<Vec3> P(wp.size());
    for (size_t i = 0; i < wp.size(); ++i) P[i] = wp[i] / w[i];
    return BSplineCurve(p, U, std::move(P), rational ? w : std::vector<double>{});
  }

  /// Boehm insertion of knot u (domainStart < u < domainEnd) once
  /// (The NURBS Book, Algorithm A5.1 with r = 1): the curve is unchanged.
  void insertKnot(double u) {
    const int n = count();
    const int k = int(std::upper_bound(U.begin(), U.end(), u) - U.begin()) - 1; // U[k] <= u < U[k+1]
    std::vector<Vec3> qp(n + 1);
    std::vector<double> qw(n + 1);
    for (int i = 0; i <= k - p; ++i) qp[i] = wp[i], qw[i] = w[i];
    for (int i = k; i < n; ++i) qp[i + 1] = wp[i], qw[i + 1] = w[i];
    for (int i = k - p + 1; i <= k; ++i) {
      const double alpha = (u - U[i]) / (U[i + p] - U[i]);
      qp[i] = alpha * wp[i] + (1 - alpha) * wp[i - 1];
      qw[i] = alpha * w[i] + (1 - alpha) * w[i - 1];
    }
    U.insert(U.begin() + k + 1, u);
    wp = std::move(qp);
    w = std::move(qw);
  }

  int multiplicity(double u) const { return int(std::count(U.begin(), U.end(), u)); }

  /// One polynomial (or rational) span: no knots inside the domain.
  bool isBezier() const { return int(U.size()) == 2 * (p + 1); }

  /// A Bézier curve of degree below `degree` raised to it (The NURBS Book
  /// eq. 5.36, once per degree, in homogeneous form so that it holds for
  /// rational curves): the same curve, with more control points. An edit
  /// that moves one of them then needs no knot inside the span, so the curve
  /// stays a single polynomial, smooth to every order. Curves with interior
  /// knots are left as they are.
  void raiseBezierDegree(int degree) {
    if (!isBezier()) return;
    for (; p < degree; ++p) {
      std::vector<Vec3> qp(wp.size() + 1);
      std::vector<double> qw(w.size() + 1);
      qp.front() = wp.front(), qw.front() = w.front();
      qp.back() = wp.back(), qw.back() = w.back();
      for (int i = 1; i <= p; ++i) {
        const double alpha = double(i) / (p + 1);
        qp[i] = alpha * wp[i - 1] + (1 - alpha) * wp[i];
        qw[i] = alpha * w[i - 1] + (1 - alpha) * w[i];
      }
      wp = std::move(qp), w = std::move(qw);
      U.insert(U.begin(), U.front());
      U.push_back(U.back());
    }
  }

  /// The control point whose move changes c''(t0) on the given side and
  /// nothing of lower order: Q_{k+2} right of t0, Q_{k−2} left of it, where
  /// Q_k is the control point at t0 (t0 has multiplicity ≥ p).
  int movedPoint(double t0, bool right) const {
    if (right) {
      const int span = int(std::upper_bound(U.begin(), U.end(), t0) - U.begin()) - 1; // last copy of t0
      return span - p + 2;
    }
    const int first = int(std::lower_bound(U.begin(), U.end(), t0) - U.begin()); // first copy of t0
    return first - 1 - 2;
  }

  /// Whether the basis function of control point j vanishes with its first
  /// and second derivatives at parameter `other` (another vertex on the
  /// curve): true when `other` is outside its support [U[j], U[j+p+1]], or at
  /// a support end that is a knot of multiplicity ≤ p − 2 among its knots
  /// (the basis function is C^{p−m} there).
  bool leavesAlone(int j, double other) const {
    const double lo = U[j], hi = U[j + p + 1];
    if (other < lo || other > hi) return true;
    if (other != lo && other != hi) return false;
    int m = 0;
    for (int i = j; i <= j + p + 1; ++i) m += U[i] == other;
    return m <= p - 2;
  }
};

/// Splits the first span beyond each end in `ends` (a vertex parameter t0
/// with the side `right` its segment lies on, as EndTurn and EndTweak hold
/// them) until the control point `movedPoint(end)` leaves the neighbouring
/// vertex on that side (the next of `pinned`, sorted) alone to second
/// order: moving it then changes nothing there. Returns the knots inserted;
/// more than `limit` is an invariant break on `element`.
template <class End, class MovedPoint>
int separateFromNeighbours(EditableCurve &edit, const std::vector<End> &ends, const std::vector<double> &pinned,
                           const MovedPoint &movedPoint, int limit, const std::string &element) {
  int inserted = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (const End &end : ends) {
      const int j = movedPoint(end);
      CURVENET_CHECK(j >= 0 && j < edit.count(), "moved control point " + std::to_string(j) + " of " +
                                                     std::to_string(edit.count()) + " on " + element);
      const auto next = std::upper_bound(pinned.begin(), pinned.end(), end.t0);
      const auto previous = std::lower_bound(pinned.begin(), pinned.end(), end.t0);
      const bool hasNeighbour = end.right ? next != pinned.end() : previous != pinned.begin();
      if (!hasNeighbour || edit.leavesAlone(j, end.right ? *next : *(previous - 1))) continue;
      const double split =
          end.right ? 0.5 * (end.t0 + *std::upper_bound(edit.U.begin(), edit.U.end(), end.t0))
                    : 0.5 * (*(std::lower_bound(edit.U.begin(), edit.U.end(), end.t0) - 1) + end.t0);
      edit.insertKnot(split);
      changed = true;
      CURVENET_CHECK(++inserted < limit, "knot insertion does not terminate on " + element);
    }
  }
  return inserted;
}

/// t snapped to a knot of `edit` within 1e-13 of the domain [a, b], as
/// BSplineCurve::restricted snaps, so the network builder cuts the edited
/// curve exactly at the knots inserted by an edit.
inline double snappedToKnot(const EditableCurve &edit, double t, double a, double b) {
  const double snap = 1e-13 * (b - a);
  for (double u : edit.U)
    if (std::abs(u - t) <= snap) return u;
  return t;
}

/// Every vertex of `network` on curve `curveIndex` (the ends of its
/// segments), snapped, sorted and unique: the points an edit at one end must
/// leave alone.
inline std::vector<double> pinnedParameters(const Network &network, int curveIndex, const EditableCurve &edit) {
  const BSplineCurve &original = network.description().curves[curveIndex];
  std::vector<double> pinned;
  for (const Segment &seg : network.segments())
    if (seg.sourceCurve == curveIndex) pinned.push_back(seg.sourceFrom), pinned.push_back(seg.sourceTo);
  for (double &t : pinned) t = snappedToKnot(edit, t, original.domainStart(), original.domainEnd());
  std::sort(pinned.begin(), pinned.end());
  pinned.erase(std::unique(pinned.begin(), pinned.end()), pinned.end());
  return pinned;
}

/// A curve of a network under edit at some of its vertices, as
/// startEndEdits leaves it.
struct EndEdits {
  EditableCurve edit;
  std::vector<double> pinned; ///< every vertex on the curve (pinnedParameters)
  int insertedKnots = 0;
};

/// Curve `curveIndex` of `network` made ready for edits at `ends` (each
/// with its vertex parameter t0, snapped here to the curve's knots): raised
/// to `degree` when it is one Bézier span, its vertices pinned, and every
/// end inside the domain made a knot of multiplicity p, so that its point
/// and its two neighbours are control points.
template <class End> EndEdits startEndEdits(const Network &network, int curveIndex, int degree, std::vector<End> &ends) {
  const BSplineCurve &original = network.description().curves[curveIndex];
  EndEdits result{EditableCurve(original), {}, 0};
  EditableCurve &edit = result.edit;
  edit.raiseBezierDegree(degree);
  const double a = original.domainStart(), b = original.domainEnd();
  result.pinned = pinnedParameters(network, curveIndex, edit);
  for (End &end : ends) end.t0 = snappedToKnot(edit, end.t0, a, b);
  for (const End &end : ends)
    if (end.t0 > a && end.t0 < b)
      for (int r = edit.multiplicity(end.t0); r < edit.p; ++r) edit.insertKnot(end.t0), ++result.insertedKnots;
  return result;
}

} // namespace v1
} // namespace curvenet
