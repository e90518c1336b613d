// insertConnectionCurves — composite faces for concave, uneven and
// many-sided loops and for holes
// ([SV14] Sec. 5.2). Works on the description alone (curves and loops),
// before any topology exists, so Network::build can call it first.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>

#include "curvenet/error.hpp"
#include "curvenet/network.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

using Loop = std::vector<SideDescription>;

// A corner turns concave when its interior angle exceeds a straight angle by
// more than this (radians): T-nodes and slightly bent runs stay as they are.
constexpr double kConcaveMargin = 0.2;
// A split is accepted only if each of its four new corner angles keeps this
// distance (radians) from 0 and from a straight angle.
constexpr double kMinSplitAngle = 0.1;
// Parts still concave after a split are split again, to this depth.
constexpr int kMaxSplitDepth = 8;
// Sides of a face with a hole and of its hole: the pairing of their corners
// costs O(n⁴) (Splitter::matchCorners).
constexpr int kMaxRingSides = 64;

/// Point and unit tangent (in the loop direction) of a side at s ∈ [0, 1].
struct SidePoint {
  Vec3 point, tangent;
};
SidePoint sidePoint(const std::vector<BSplineCurve> &curves, const SideDescription &side, double s) {
  const BSplineCurve &c = curves[side.curve];
  const auto d = c.derivatives(side.from + s * (side.to - side.from));
  Vec3 t = d[1] * (side.to > side.from ? 1.0 : -1.0);
  // A repeated end control point: the chord to a nearby point.
  if (squaredNorm(t) < 1e-30) {
    const double h = s < 0.5 ? 1e-6 : -1e-6;
    t = (c.point(side.from + (s + h) * (side.to - side.from)) - d[0]) * (h > 0 ? 1.0 : -1.0);
  }
  return {d[0], normalized(t)};
}

/// Newell normal of the loop (sampled), the orientation reference of a face.
Vec3 newellNormal(const std::vector<BSplineCurve> &curves, const Loop &loop) {
  std::vector<Vec3> points;
  for (const SideDescription &side : loop)
    for (int j = 0; j < 8; ++j) points.push_back(sidePoint(curves, side, j / 8.0).point);
  Vec3 n{};
  for (size_t i = 0; i < points.size(); ++i) n += cross(points[i], points[(i + 1) % points.size()]);
  return n;
}

/// Counter-clockwise angle from a to b about n, in [0, 2π).
double angleAbout(const Vec3 &a, const Vec3 &b, const Vec3 &n) {
  const double angle = std::atan2(dot(cross(a, b), n), dot(a, b));
  return angle < 0 ? angle + 2 * std::numbers::pi : angle;
}

Vec3 orthogonalTo(const Vec3 &v, const Vec3 &axis) { return normalized(v - axis * dot(v, axis)); }

/// A point of a loop where a connection curve may end: corner k (the start
/// of side k, s = 0) or the midpoint of side k (s = 0.5). Tangents arriving
/// and leaving in the loop direction; the tangent-plane normal, on the side
/// of the face normal.
struct LoopPoint {
  Vec3 point, in, out, normal;
  bool concave = false;
};

/// The surface normal where the description carries a reference surface
/// (built-ins, mesh approximation), on the side of the face normal.
std::optional<Vec3> referenceNormal(const std::optional<ReferenceSurface> &reference, const Vec3 &point,
                                    const Vec3 &tangent, const Vec3 &faceNormal) {
  if (!reference) return std::nullopt;
  const Vec3 n = orthogonalTo(reference->closest(point).normal, tangent);
  return dot(n, faceNormal) < 0 ? -n : n;
}

LoopPoint cornerPoint(const std::vector<BSplineCurve> &curves, const Loop &loop, int k, const Vec3 &faceNormal,
                      const std::optional<ReferenceSurface> &reference) {
  const int n = static_cast<int>(loop.size());
  const SidePoint prev = sidePoint(curves, loop[(k + n - 1) % n], 1.0), next = sidePoint(curves, loop[k], 0.0);
  LoopPoint p{next.point, prev.tangent, next.tangent, {}};
  const Vec3 c = cross(next.tangent, -prev.tangent);
  if (norm(c) > 1e-3) {
    // The plane of the two curves; it faces away from the face normal
    // exactly when the corner is concave.
    p.normal = normalized(c);
    if (dot(p.normal, faceNormal) < 0) {
      p.normal = -p.normal;
      p.concave = angleBetween(next.tangent, -prev.tangent) < std::numbers::pi - kConcaveMargin;
    }
  } else {
    // A curve passing straight on: its tangent alone fixes no plane. A wrong
    // tilt here would turn the curve's geodesic curvature into normal
    // curvature at the new vertex, so the reference normal is used if any.
    p.normal = referenceNormal(reference, p.point, next.tangent, faceNormal)
                   .value_or(orthogonalTo(faceNormal, next.tangent));
  }
  return p;
}

/// The point at `fraction` along side k (its midpoint by default).
LoopPoint midPoint(const std::vector<BSplineCurve> &curves, const Loop &loop, int k, const Vec3 &faceNormal,
                   const std::optional<ReferenceSurface> &reference, double fraction = 0.5) {
  const int n = static_cast<int>(loop.size());
  const SidePoint m = sidePoint(curves, loop[k], fraction);
  if (auto r = referenceNormal(reference, m.point, m.tangent, faceNormal)) return {m.point, m.tangent, m.tangent, *r};
  // Between the side's two corner planes, weighted by the distance along it.
  const Vec3 start = cornerPoint(curves, loop, k, faceNormal, reference).normal,
             end = cornerPoint(curves, loop, (k + 1) % n, faceNormal, reference).normal;
  const Vec3 average = fraction == 0.5 ? start + end : start * (2 * (1 - fraction)) + end * (2 * fraction);
  return {m.point, m.tangent, m.tangent, orthogonalTo(norm(average) > 1e-9 ? average : faceNormal, m.tangent)};
}

/// The cubic from a to b whose end tangents are the chord projected into
/// the tangent planes at its ends (Hermite, speed = chord length).
/// With a reference surface the cubic is projected onto it (samples moved
/// to their closest surface points, interpolated at degree 5, ends kept):
/// a curve on the surface carries the surface's normal curvature into the
/// vertex fits at its ends, as the user's curves do.
BSplineCurve connectionCurve(const LoopPoint &a, const LoopPoint &b, const std::optional<ReferenceSurface> &reference) {
  const Vec3 chord = b.point - a.point;
  const double length = norm(chord);
  const Vec3 d0 = orthogonalTo(chord, a.normal), d1 = orthogonalTo(chord, b.normal);
  BSplineCurve cubic = BSplineCurve::bezier({a.point, a.point + d0 * (length / 3), b.point - d1 * (length / 3), b.point});
  if (!reference) return cubic;
  constexpr int intervals = 16;
  std::vector<double> params(intervals + 1);
  std::vector<Vec3> points(intervals + 1);
  for (int i = 0; i <= intervals; ++i) {
    params[i] = double(i) / intervals;
    points[i] = i == 0 || i == intervals ? cubic.point(params[i]) : reference->closest(cubic.point(params[i])).point;
  }
  const BSplineCurve fitted = BSplineCurve::interpolate(5, params, points);
  // The interpolant's end tangents (along its first and last control legs)
  // leave the tangent planes by the fit error; put them back exactly, or the
  // vertex planes would tilt by it and G¹ with them.
  std::vector<Vec3> control = fitted.controlPoints();
  const size_t last = control.size() - 1;
  const Vec3 leg0 = control[1] - control[0], leg1 = control[last - 1] - control[last];
  control[1] = control[0] + leg0 - a.normal * dot(leg0, a.normal);
  control[last - 1] = control[last] + leg1 - b.normal * dot(leg1, b.normal);
  return BSplineCurve(fitted.degree(), fitted.knots(), std::move(control));
}

SideDescription reversedSide(const SideDescription &side) { return {side.curve, side.to, side.from}; }

/// Smallest of the four corner angles a connection curve from a to b makes
/// with the loop at its ends, each measured from 0 or a straight angle,
/// whichever is nearer (radians).
double newCornerClearance(const LoopPoint &a, const LoopPoint &b) {
  const Vec3 da = orthogonalTo(b.point - a.point, a.normal);
  const Vec3 db = orthogonalTo(a.point - b.point, b.normal);
  const double angles[4] = {angleAbout(a.out, da, a.normal), angleAbout(da, -a.in, a.normal),
                            angleAbout(db, -b.in, b.normal), angleAbout(b.out, db, b.normal)};
  double clearance = INFINITY;
  for (double angle : angles) clearance = std::min(clearance, std::min(angle, std::numbers::pi - angle));
  return clearance;
}

// Pleats. At a vertex of valence 2 the two faces share the corner's two
// curves, and on a smooth sheet their angles there add up to a full turn:
// where the curves turn, one face is convex and the other concave (and the
// concave one is split above). When both are convex, each by its own loop,
// the sheet is pleated: it leaves the corner on both faces across the plane
// of the two curves and folds back from one curve's layer to the other's
// (iron.obj's handle meets the body at a 57° V drawn by one stroke, the
// valley behind it not drawn: both faces beside the V are hexagons that
// rise to a spike where they meet). No n-gon maps onto such a loop without
// turning its normal over; cut along the fold, each part is an ordinary
// face. A corner turning by less than kConcaveMargin is left alone: there
// a face may be convex on both sides within the margin.
// The cut ends on the loop point whose chord from the pleated corner is
// nearest the fold's direction, within this angle (radians; iron's are
// 5–6° off): a chord farther off runs more along the corner's plane than
// across it, and the loop is split as any other. At that
// end the cut takes its chord for tangent: the plane of the loop's curves
// there holds one layer only (iron: the foot of the handle, whose curves'
// plane lies 17° off the chord); turned into that plane, both parts folded
// under every scheme, along the chord none does.
constexpr double kMaxFoldTilt = std::numbers::pi / 3;

/// The normal of the plane of corner k's two curves, turned toward `other`.
Vec3 foldDirection(const std::vector<BSplineCurve> &curves, const Loop &loop, int k, const Vec3 &other) {
  const int n = static_cast<int>(loop.size());
  const SidePoint prev = sidePoint(curves, loop[(k + n - 1) % n], 1.0), next = sidePoint(curves, loop[k], 0.0);
  const Vec3 fold = normalized(cross(next.tangent, -prev.tangent));
  return dot(fold, other - next.point) < 0 ? -fold : fold;
}

/// Angle between the fold at corner k and the chord from there to `other`.
double foldTilt(const std::vector<BSplineCurve> &curves, const Loop &loop, int k, const Vec3 &other) {
  return angleBetween(foldDirection(curves, loop, k, other), other - sidePoint(curves, loop[k], 0).point);
}

/// The end of a cut along the fold at corner k toward `other`: the corner
/// with a tangent-plane normal whose plane holds the fold and the chord,
/// so connectionCurve leaves the corner along the fold.
LoopPoint foldEnd(const std::vector<BSplineCurve> &curves, const Loop &loop, int k, const Vec3 &other) {
  const int n = static_cast<int>(loop.size());
  const SidePoint prev = sidePoint(curves, loop[(k + n - 1) % n], 1.0), next = sidePoint(curves, loop[k], 0.0);
  const Vec3 fold = foldDirection(curves, loop, k, other), chord = other - next.point;
  // A chord along the fold: any plane through the fold will do.
  const bool across = norm(cross(fold, chord)) > 1e-9 * norm(chord);
  const Vec3 normal = orthogonalTo(across ? chord : next.tangent, fold);
  return LoopPoint{next.point, prev.tangent, next.tangent, normal};
}

bool loopIsValid(const std::vector<BSplineCurve> &curves, const Loop &loop);

/// For each face, the corners where its sheet is pleated (see above): a
/// corner at a vertex only it and one other face touch, the two loops
/// running along the same two curve pieces there in opposite directions,
/// turning by more than kConcaveMargin, and convex in both loops. Faces
/// with holes or invalid loops have none.
std::vector<std::vector<int>> pleatedCorners(const std::vector<BSplineCurve> &curves,
                                             const std::vector<FaceDescription> &faces, double tolerance) {
  struct Corner {
    int face, k;
    Vec3 point;
    SideDescription in, out; // the sides arriving at and leaving the corner
    bool pleatable;          // turns by more than the margin and is convex in its loop
  };
  std::vector<Corner> corners;
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
    const Loop &loop = faces[f].sides;
    if (!faces[f].holes.empty() || loop.size() < 3 || !loopIsValid(curves, loop)) continue;
    const Vec3 faceNormal = newellNormal(curves, loop);
    if (!(norm(faceNormal) > 0)) continue;
    const int n = static_cast<int>(loop.size());
    for (int k = 0; k < n; ++k) {
      const SidePoint prev = sidePoint(curves, loop[(k + n - 1) % n], 1.0), next = sidePoint(curves, loop[k], 0.0);
      // A corner with a plane (as cornerPoint takes it) that turns by more than the margin.
      const bool turns = norm(cross(next.tangent, -prev.tangent)) > 1e-3 &&
                         angleBetween(next.tangent, -prev.tangent) < std::numbers::pi - kConcaveMargin;
      const bool convex = !cornerPoint(curves, loop, k, faceNormal, std::nullopt).concave;
      corners.push_back({f, k, next.point, loop[(k + n - 1) % n], loop[k], turns && convex});
    }
  }
  // Corners at one point, found along x (sorted) within the tolerance.
  std::vector<int> order(corners.size());
  for (size_t c = 0; c < order.size(); ++c) order[c] = static_cast<int>(c);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return corners[a].point.x < corners[b].point.x; });
  std::vector<std::vector<int>> pleated(faces.size());
  // The same curve piece run the other way: same curve, the far ends on the same side of the corner.
  auto runsBack = [](const SideDescription &arriving, const SideDescription &leaving) {
    return arriving.curve == leaving.curve && (arriving.from - arriving.to) * (leaving.to - leaving.from) > 0;
  };
  for (size_t a = 0; a < order.size(); ++a) {
    std::vector<int> here;
    for (size_t b = a; b-- > 0 && corners[order[a]].point.x - corners[order[b]].point.x <= tolerance;)
      if (norm(corners[order[a]].point - corners[order[b]].point) <= tolerance) here.push_back(order[b]);
    for (size_t b = a + 1; b < order.size() && corners[order[b]].point.x - corners[order[a]].point.x <= tolerance; ++b)
      if (norm(corners[order[a]].point - corners[order[b]].point) <= tolerance) here.push_back(order[b]);
    if (here.size() != 1) continue;
    const Corner &mine = corners[order[a]], &theirs = corners[here[0]];
    if (mine.face == theirs.face || !mine.pleatable || !theirs.pleatable) continue;
    if (runsBack(mine.in, theirs.out) && runsBack(theirs.in, mine.out)) pleated[mine.face].push_back(mine.k);
  }
  return pleated;
}

// Uneven and many-sided loops. A transfinite patch maps the regular n-gon
// onto its loop, side k of the domain onto side k of the loop, each
// proportionally. When the loop's corners crowd on one part of it and leave
// long sides elsewhere (Fig. 9), that map stretches the long sides several
// times as much as the short ones and the patch bunches its parameter lines
// and its shape there.
//
// When: a loop of five or more sides is uneven when its longest side is more
// than kUnevenSideRatio times as long as its shortest (arc lengths). Measured
// on every face of the built-ins and of the real models the ratio stays at or
// below 2.91 (cagd86.lop's pentagon; torus-mixed's hexagons 2.52, the
// setback blend 2.02, the truncated icosahedron 1.38); the Fig. 9 loops,
// corners crowded on 100° of the turn, measure 3.95 (8 sides) and 5.5 (10).
// Quads are left out: their side ratio is their aspect ratio, which the
// regular domain takes as an affine stretch. Loops of more than
// kMaxPartSides sides are always split.
//
// How: by a hidden connection curve between two of the loop's corners or
// side midpoints. Of all such curves, the one whose worse part has the
// least side ratio (plan lengths, the connection taken straight), among
// those that leave each part kMinPartSides sides or more (a triangle cut off
// a many-sided loop gave gregory-g2 folds), no part more sides than the
// loop, no part whose fan from its centroid folds, no end on the midpoint of
// another connection curve (an X-node of hidden curves: gregory-g2 deviated
// 15% of the diagonal on the 12-gon with them), and the curve's four new
// corner angles kMinEvenSplitAngle (30°) away from 0 and a straight angle
// (with the concave splits' 6° the uneven loops were fanned from one corner
// into wedges, and gregory-g2 deviated 2.9% on the uneven 8-gon against
// 0.74%). A loop of more than kMaxPartSides sides whose sides are even
// takes the split whose larger part has the fewest sides first, so a 12-gon
// halves into two 7-gons (most even parts first instead, gregory-g1
// deviated up to 4.8% on the loops of 9–16 sides against 2.5%); an uneven
// one takes the most even parts first (balanced parts first, gregory-g2
// deviated 4.8% on the Fig. 9 10-gon against 1.2%). Equally even splits
// are common (the worse part's longest and shortest pieces stay the same
// whichever of several corners and midpoints the curve leaves from) and
// take the one whose larger part has the fewest sides: the order among
// them was the sort's, so near-mirror loops were split differently
// (doghead.obj's user face 0 into a quad and a 7-gon, its mirror image 22
// into two hexagons), and the 7-gon folded under composite-ribbon. An
// uneven loop of at most kMaxPartSides sides takes the split only if its
// worse part is more even than the loop. The parts are split again in the same way (a 16-gon
// ends in four parts of 5 and 6 sides). Choosing by the domain map's
// distortion instead (the worst σ₁/σ₂ over the fan triangles, affine part
// taken out) measured worse on balance: over loops of 9–16 sides gregory-g1
// deviated from the bowl by up to 3.7% of the diagonal against 2.5% (the
// 12-gon 1.6% against 0.21%), and accepting splits by distortion too left
// the uneven 8-gon unsplit.
constexpr double kUnevenSideRatio = 3.5;
constexpr int kMaxPartSides = 8;
constexpr int kMinPartSides = 4;
constexpr double kMinEvenSplitAngle = std::numbers::pi / 6;
// Each side sampled at quarters: sample 4k is corner k, 4k + 2 the midpoint
// of side k (the points a connection curve may end on), and every side or
// half side has its midpoint among the samples.
constexpr int kSamplesPerSide = 4;

/// One side (or half side) of a part's outline in the plan: where it starts
/// and its midpoint.
struct PlanPiece {
  Vec2 start, middle;
};

/// The longest piece of the outline over its shortest (plan lengths
/// through the pieces' midpoints).
double sideRatio(const std::vector<PlanPiece> &outline) {
  double longest = 0, shortest = INFINITY;
  for (size_t k = 0; k < outline.size(); ++k) {
    const PlanPiece &piece = outline[k];
    const Vec2 &end = outline[(k + 1) % outline.size()].start;
    const double length = norm(piece.middle - piece.start) + norm(end - piece.middle);
    longest = std::max(longest, length), shortest = std::min(shortest, length);
  }
  return longest / shortest;
}

/// True when the triangles from the outline's centroid to each of its
/// corners and side midpoints all turn counter-clockwise: the regular
/// domain's centre and fan then map onto the part without folding.
bool fansOutFromItsCentre(const std::vector<PlanPiece> &outline) {
  std::vector<Vec2> points;
  for (const PlanPiece &piece : outline) {
    points.push_back(piece.start);
    points.push_back(piece.middle);
  }
  const size_t m = points.size();
  double area = 0;
  Vec2 centre{};
  for (size_t i = 0; i < m; ++i) {
    const Vec2 &p = points[i], &q = points[(i + 1) % m];
    area += cross(p, q);
    centre += (p + q) * cross(p, q);
  }
  if (!(area > 0)) return false;
  centre = centre * (1.0 / (3 * area));
  for (size_t i = 0; i < m; ++i)
    if (!(cross(points[i] - centre, points[(i + 1) % m] - centre) > 0)) return false;
  return true;
}

class Splitter {
public:
  Splitter(std::vector<BSplineCurve> &curves, const std::optional<ReferenceSurface> &reference)
      : curves_(curves), reference_(reference) {}

  /// The loop's convex parts (the loop itself when it has no concave corner
  /// or no acceptable split).
  std::vector<Loop> convexParts(const Loop &loop, int depth = 0) {
    const Vec3 faceNormal = newellNormal(curves_, loop);
    if (!(norm(faceNormal) > 0) || depth >= kMaxSplitDepth) return {loop};
    const int n = static_cast<int>(loop.size());
    for (int c = 0; c < n; ++c) {
      const LoopPoint corner = cornerPoint(curves_, loop, c, faceNormal, reference_);
      if (!corner.concave) continue;
      std::optional<std::pair<Loop, Loop>> parts = split(loop, c, corner, faceNormal);
      if (!parts) continue;
      std::vector<Loop> result = convexParts(parts->first, depth + 1);
      for (Loop &l : convexParts(parts->second, depth + 1)) result.push_back(std::move(l));
      return result;
    }
    return {loop};
  }

  /// Splits loop at concave corner c along the best connection curve: to a
  /// corner or side midpoint whose four new corner angles stay farthest
  /// from 0 and π. Part A runs from c along the loop to the target and back
  /// along the connection; part B the rest.
  std::optional<std::pair<Loop, Loop>> split(const Loop &loop, int c, const LoopPoint &corner,
                                             const Vec3 &faceNormal) {
    const int n = static_cast<int>(loop.size());
    double bestScore = kMinSplitAngle;
    int bestSide = -1;
    bool bestMid = false;
    LoopPoint bestTarget;
    for (int k = 0; k < n; ++k)
      for (bool mid : {false, true}) {
        const int ahead = (k - c + n) % n; // sides from c to the target's side
        // Each part needs three sides: a corner target two sides away from c
        // at least, a midpoint target not on either side at c.
        if (mid ? (ahead == 0 || ahead == n - 1) : (ahead < 2 || ahead > n - 2)) continue;
        const LoopPoint target =
            mid ? midPoint(curves_, loop, k, faceNormal, reference_) : cornerPoint(curves_, loop, k, faceNormal, reference_);
        const Vec3 dc = orthogonalTo(target.point - corner.point, corner.normal);
        const Vec3 dt = orthogonalTo(corner.point - target.point, target.normal);
        const double angles[4] = {angleAbout(corner.out, dc, corner.normal), angleAbout(dc, -corner.in, corner.normal),
                                  angleAbout(dt, -target.in, target.normal),
                                  angleAbout(target.out, dt, target.normal)};
        double score = INFINITY;
        for (double a : angles) score = std::min(score, std::min(a, std::numbers::pi - a));
        if (score > bestScore) bestScore = score, bestSide = k, bestMid = mid, bestTarget = target;
      }
    if (bestSide < 0) return std::nullopt;
    const int curve = static_cast<int>(curves_.size());
    curves_.push_back(connectionCurve(corner, bestTarget, reference_));
    connections_.push_back(curve);
    Loop a, b;
    for (int j = c; j != bestSide; j = (j + 1) % n) a.push_back(loop[j]);
    const SideDescription &cut = loop[bestSide];
    if (bestMid) {
      const double m = 0.5 * (cut.from + cut.to);
      a.push_back({cut.curve, cut.from, m});
      b.push_back({cut.curve, m, cut.to});
    } else {
      b.push_back(cut);
    }
    a.push_back({curve, 1.0, 0.0});
    for (int j = (bestSide + 1) % n; j != c; j = (j + 1) % n) b.push_back(loop[j]);
    b.push_back({curve, 0.0, 1.0});
    return std::make_pair(std::move(a), std::move(b));
  }

  /// The four-sided parts of a face with one hole: one connection curve per
  /// corner of the loop with more sides, so max(outer, hole sides) parts.
  std::vector<Loop> ring(Loop outer, Loop hole) {
    const Vec3 faceNormal = newellNormal(curves_, outer);
    // The hole's corners in the outer loop's turning direction.
    if (dot(newellNormal(curves_, hole), faceNormal) < 0) {
      std::reverse(hole.begin(), hole.end());
      for (SideDescription &side : hole) side = reversedSide(side);
    }
    // Corner pairs (see matchCorners); the loop with fewer sides gets points
    // where its curves run straight on (T-nodes of the split network), so
    // that each corner of the other has a partner. Outer corner i pairs
    // with hole corner i + rotation.
    int rotation;
    if (hole.size() <= outer.size())
      rotation = static_cast<int>(outer.size()) - matchCorners(outer, hole, faceNormal, true);
    else
      rotation = matchCorners(hole, outer, faceNormal, false);
    const int n = static_cast<int>(outer.size());
    std::vector<int> joins(n);
    for (int i = 0; i < n; ++i) {
      joins[i] = static_cast<int>(curves_.size());
      curves_.push_back(connectionCurve(cornerPoint(curves_, outer, i, faceNormal, reference_),
                                        cornerPoint(curves_, hole, (i + rotation) % n, faceNormal, reference_),
                                        reference_));
      connections_.push_back(joins[i]);
    }
    std::vector<Loop> parts;
    for (int i = 0; i < n; ++i) {
      const Loop quad = {outer[i], {joins[(i + 1) % n], 0.0, 1.0}, reversedSide(hole[(i + rotation) % n]),
                         {joins[i], 1.0, 0.0}};
      for (Loop &l : convexParts(quad)) parts.push_back(std::move(l));
    }
    return parts;
  }

  /// The loop's parts after splitting concave corners (convexParts), then
  /// uneven and many-sided parts (evenParts).
  std::vector<Loop> wellShapedParts(const Loop &loop) {
    std::vector<Loop> parts;
    for (const Loop &convex : convexParts(loop))
      for (Loop &even : evenParts(convex)) parts.push_back(std::move(even));
    return parts;
  }

  /// The loop cut along its fold from pleated corner i (see
  /// pleatedCorners), each part then well shaped; the loop well shaped as
  /// it is when no cut fits. The cut leaves the corner across the plane of
  /// its two curves, on the side the face lies: a sheet folding over from
  /// one curve's layer to the other's turns about that direction there, so
  /// each part gets a corner between one layer's curve and the fold, close
  /// to square (iron.obj: 90° on both parts, the loop's own corner 57°).
  /// It ends on the loop corner or side midpoint nearest that direction as
  /// seen from the corner, within kMaxFoldTilt, not on a side at the
  /// corner, arriving along its chord.
  std::vector<Loop> pleatParts(const Loop &loop, int i) {
    const int n = static_cast<int>(loop.size());
    const Vec3 faceNormal = newellNormal(curves_, loop);
    const Vec3 corner = sidePoint(curves_, loop[i], 0).point;
    int best = -1;
    double bestTilt = kMaxFoldTilt;
    for (int sample = 0; sample < n * kSamplesPerSide; sample += kSamplesPerSide / 2) {
      const int ahead = (sample / kSamplesPerSide - i + n) % n;
      const bool mid = sample % kSamplesPerSide != 0;
      if (mid ? (ahead == 0 || ahead == n - 1) : (ahead < 2 || ahead > n - 2)) continue;
      const Vec3 end = loopPointAt(loop, sample, faceNormal).point;
      if (!(norm(end - corner) > 0)) continue;
      const double tilt = foldTilt(curves_, loop, i, end);
      if (tilt < bestTilt) bestTilt = tilt, best = sample;
    }
    if (best < 0) return wellShapedParts(loop);
    // Arriving along the chord (see kMaxFoldTilt): a tangent-plane normal
    // across the chord, as near the target's own as can be.
    LoopPoint target = loopPointAt(loop, best, faceNormal);
    const Vec3 chord = normalized(target.point - corner);
    const Vec3 near = norm(cross(target.normal, chord)) > 1e-6 ? target.normal
                      : norm(cross(target.out, chord)) > norm(cross(target.in, chord)) ? target.out : target.in;
    target.normal = orthogonalTo(near, chord);
    const int curve = static_cast<int>(curves_.size());
    curves_.push_back(connectionCurve(foldEnd(curves_, loop, i, target.point), target, reference_));
    connections_.push_back(curve);
    const int from = i * kSamplesPerSide;
    Loop first = sidesBetween(loop, from, best), second = sidesBetween(loop, best, from);
    first.push_back({curve, 1.0, 0.0});
    second.push_back({curve, 0.0, 1.0});
    std::vector<Loop> parts = wellShapedParts(first);
    for (Loop &l : wellShapedParts(second)) parts.push_back(std::move(l));
    return parts;
  }

  /// The parts of a convex loop that are neither uneven nor have more than
  /// kMaxPartSides sides (see kUnevenSideRatio), or the loop itself when
  /// it needs no split or none is acceptable.
  std::vector<Loop> evenParts(const Loop &loop, int depth = 0) {
    const int n = static_cast<int>(loop.size());
    if (n < 4 || depth >= kMaxEvenSplitDepth) return {loop};
    const Vec3 faceNormal = newellNormal(curves_, loop);
    if (!(norm(faceNormal) > 0)) return {loop};
    const std::vector<Vec2> plan = planSamples(loop, faceNormal);
    const bool manySided = n > kMaxPartSides;
    const bool uneven = n >= 5 && sideLengthRatio(loop) > kUnevenSideRatio;
    if (!manySided && !uneven) return {loop};
    // Connection curves between corners and side midpoints first; where none
    // is acceptable, also from and to the quarter points of the sides. A
    // side that bends concavely (sewing_machine.obj's L-shaped strips: a
    // side turning 88° against the loop, the strip 16 times longer than
    // wide) leaves every part with its bend unable to fan from its centre,
    // and only a cut at the bend's end of the side splits it off.
    for (const int step : {2, 1}) {
      std::optional<std::vector<Loop>> parts = evenSplit(loop, plan, faceNormal, step, depth);
      if (parts) return std::move(*parts);
    }
    return {loop};
  }

  /// evenParts' split of `loop` along the best acceptable connection
  /// curve, with ends at samples that are multiples of `step` (2: corners
  /// and side midpoints; 1: also quarter points), at least one of them off
  /// the multiples of 2 when step is 1 (those were tried); nullopt if none.
  std::optional<std::vector<Loop>> evenSplit(const Loop &loop, const std::vector<Vec2> &plan, const Vec3 &faceNormal,
                                             int step, int depth) {
    const int n = static_cast<int>(loop.size());
    const int samples = static_cast<int>(plan.size());
    const bool manySided = n > kMaxPartSides;
    const bool uneven = n >= 5 && sideLengthRatio(loop) > kUnevenSideRatio;
    struct Candidate {
      int from, to;
      int sides;    // of the larger part
      double worse; // side ratio of the worse part
    };
    std::vector<Candidate> candidates;
    for (int a = 0; a < samples; a += step)
      for (int b = a + 2; b < samples; b += step) {
        if (step == 1 && a % 2 == 0 && b % 2 == 0) continue;
        const std::vector<PlanPiece> first = outline(plan, a, b), second = outline(plan, b, a);
        const int fewer = static_cast<int>(std::min(first.size(), second.size()));
        const int more = static_cast<int>(std::max(first.size(), second.size()));
        if (fewer < kMinPartSides || more > n) continue;
        if (!fansOutFromItsCentre(first) || !fansOutFromItsCentre(second)) continue;
        if (endsOnConnectionMidpoint(loop, a) || endsOnConnectionMidpoint(loop, b)) continue;
        candidates.push_back({a, b, more, std::max(sideRatio(first), sideRatio(second))});
      }
    // A many-sided loop whose sides are even: the larger part's side count
    // first (balanced parts); an uneven one: the most even parts first, then
    // the fewest sides of the larger part.
    const bool balanced = manySided && !uneven;
    std::sort(candidates.begin(), candidates.end(), [balanced](const Candidate &x, const Candidate &y) {
      if (balanced && x.sides != y.sides) return x.sides < y.sides;
      if (x.worse != y.worse) return x.worse < y.worse;
      return x.sides < y.sides;
    });
    // A many-sided loop takes the best split, an uneven one only a more even one.
    const double own = manySided ? INFINITY : sideRatio(outline(plan, 0, 0));
    for (const Candidate &c : candidates) {
      if (!(c.worse < own)) break;
      const LoopPoint from = loopPointAt(loop, c.from, faceNormal), to = loopPointAt(loop, c.to, faceNormal);
      if (!(newCornerClearance(from, to) > kMinEvenSplitAngle)) continue;
      const int curve = static_cast<int>(curves_.size());
      curves_.push_back(connectionCurve(from, to, reference_));
      connections_.push_back(curve);
      Loop first = sidesBetween(loop, c.from, c.to), second = sidesBetween(loop, c.to, c.from);
      first.push_back({curve, 1.0, 0.0});
      second.push_back({curve, 0.0, 1.0});
      std::vector<Loop> parts = evenParts(first, depth + 1);
      for (Loop &l : evenParts(second, depth + 1)) parts.push_back(std::move(l));
      return parts;
    }
    return std::nullopt;
  }

  const std::vector<int> &connections() const { return connections_; }

  /// Pairs the corners of `more` with those of `fewer` (fewer sides), in
  /// loop order, and cuts `fewer`'s sides so that every corner of `more` has
  /// a partner: each corner of `fewer` pairs with one of `more`, and the
  /// corners of `more` in between pair with new points on the side between.
  /// A connection curve is best when it leaves both loops square, into the
  /// face: its chord along the loop's inward normal there (at a corner, that
  /// of the mean of the two tangents, so along the corner's bisector). The
  /// pairing, and each new point (among 64 along its side), minimize the sum
  /// over the chords of 1 − cos of those angles at both ends, distance
  /// breaking ties. Both loops run counter-clockwise about `faceNormal`, the
  /// face to the left of the outer loop and to the right of the hole.
  /// Returns `first`: point q of the cut `fewer` pairs with corner first + q
  /// (mod n) of `more`.
  int matchCorners(const Loop &more, Loop &fewer, const Vec3 &faceNormal, bool moreIsOuter) const {
    const int n = static_cast<int>(more.size()), m = static_cast<int>(fewer.size());
    constexpr int kSamples = 64;
    struct Point {
      Vec3 point, inward;
    };
    const double moreSide = moreIsOuter ? 1.0 : -1.0;
    auto inward = [&](const Vec3 &tangent, double side) { return normalized(cross(faceNormal, tangent)) * side; };
    auto cornerOf = [&](const Loop &loop, int k, double side) {
      const int size = static_cast<int>(loop.size());
      const SidePoint in = sidePoint(curves_, loop[(k + size - 1) % size], 1), out = sidePoint(curves_, loop[k], 0);
      const Vec3 mean = in.tangent + out.tangent;
      return Point{out.point, inward(norm(mean) > 1e-9 ? normalized(mean) : out.tangent, side)};
    };
    std::vector<Point> corner(n), fewerCorner(m);
    for (int i = 0; i < n; ++i) corner[i] = cornerOf(more, i, moreSide);
    for (int j = 0; j < m; ++j) fewerCorner[j] = cornerOf(fewer, j, -moreSide);
    // Side j of `fewer` sampled inside (its ends are corners).
    std::vector<std::array<Point, kSamples>> samples(m);
    double size = 0;
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < kSamples; ++k) {
        const SidePoint p = sidePoint(curves_, fewer[j], (k + 1.0) / (kSamples + 1));
        samples[j][k] = {p.point, inward(p.tangent, -moreSide)};
        size = std::max(size, norm(p.point - corner[0].point));
      }
    auto cost = [&](const Point &a, const Point &b) -> double {
      const Vec3 chord = b.point - a.point;
      const double length = norm(chord);
      if (!(length > 0)) return INFINITY;
      const Vec3 u = chord / length;
      return (1 - dot(u, a.inward)) + (1 + dot(u, b.inward)) + 1e-3 * length / size;
    };
    auto best = [&](int j, const Point &a, double &c) {
      int at = 0;
      c = INFINITY;
      for (int k = 0; k < kSamples; ++k)
        if (const double d = cost(a, samples[j][k]); d < c) c = d, at = k;
      return (at + 1.0) / (kSamples + 1);
    };
    // pair[j][i]: corner j of `fewer` with corner i of `more`; cutCost[j][i]:
    // corner i of `more` with its best point on side j, at cutAt[j][i].
    std::vector<std::vector<double>> pair(m, std::vector<double>(n)), cutCost = pair, cutAt = pair;
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < n; ++i) pair[j][i] = cost(corner[i], fewerCorner[j]), cutAt[j][i] = best(j, corner[i], cutCost[j][i]);
    // Corner j of `fewer` pairs with corner first + offset[j] of `more`,
    // 0 = offset[0] < offset[1] < … < offset[m − 1] < n; the corners of
    // `more` in between are cut onto side j. For each first, by dynamic
    // programming over j: total[j][o], the least cost of sides 0 … j − 1
    // with offset[j] = o. O(m n³) in all (n ≤ kMaxRingSides).
    std::vector<int> bestOffset(m);
    for (int j = 0; j < m; ++j) bestOffset[j] = j; // if no pairing has a finite cost
    int bestFirst = 0;
    double bestCost = INFINITY;
    std::vector<std::vector<double>> total(m, std::vector<double>(n + 1));
    std::vector<std::vector<int>> previous(m, std::vector<int>(n + 1)); // offset[j − 1] on the best path
    std::vector<std::vector<double>> prefix(m, std::vector<double>(n + 1));
    for (int first = 0; first < n; ++first) {
      for (int j = 0; j < m; ++j)
        for (int i = 1; i <= n; ++i) prefix[j][i] = prefix[j][i - 1] + cutCost[j][(first + i - 1) % n];
      auto corners = [&](int j, int o, int next) { // side j from offset o to next: its pair, then the cuts
        return pair[j][(first + o) % n] + prefix[j][next] - prefix[j][o + 1];
      };
      for (auto &row : total) std::fill(row.begin(), row.end(), INFINITY);
      total[0][0] = 0;
      for (int j = 0; j + 1 < m; ++j)
        for (int o = j; o < n; ++o) {
          if (!(total[j][o] < INFINITY)) continue;
          for (int next = o + 1; next <= n - (m - j - 1); ++next)
            if (const double t = total[j][o] + corners(j, o, next); t < total[j + 1][next])
              total[j + 1][next] = t, previous[j + 1][next] = o;
        }
      for (int o = m - 1; o < n; ++o) {
        if (!(total[m - 1][o] < INFINITY)) continue;
        const double t = total[m - 1][o] + corners(m - 1, o, n);
        if (!(t < bestCost)) continue;
        bestCost = t, bestFirst = first;
        for (int j = m - 1, at = o; j >= 0; at = previous[j][at], --j) bestOffset[j] = at;
      }
    }
    // The cuts: on side j, one per corner of `more` between its partners, in
    // order (if the best points are not, evenly spaced instead).
    Loop cut;
    for (int j = 0; j < m; ++j) {
      const int from = bestOffset[j], to = j + 1 < m ? bestOffset[j + 1] : n;
      const SideDescription &side = fewer[j];
      std::vector<double> at;
      for (int i = from + 1; i < to; ++i) at.push_back(cutAt[j][(bestFirst + i) % n]);
      if (std::adjacent_find(at.begin(), at.end(), std::greater_equal<>()) != at.end())
        for (std::size_t k = 0; k < at.size(); ++k) at[k] = (k + 1.0) / (at.size() + 1);
      double last = 0;
      for (double t : at) {
        cut.push_back({side.curve, side.from + last * (side.to - side.from), side.from + t * (side.to - side.from)});
        last = t;
      }
      cut.push_back({side.curve, side.from + last * (side.to - side.from), side.to});
    }
    fewer = std::move(cut);
    return bestFirst;
  }

private:
  // Halving a loop each time, 2^8 parts: loops of far more sides than anyone
  // draws.
  static constexpr int kMaxEvenSplitDepth = 8;

  /// The longest side over the shortest, by arc length.
  double sideLengthRatio(const Loop &loop) const {
    constexpr int kChords = 16;
    double longest = 0, shortest = INFINITY;
    for (const SideDescription &side : loop) {
      double length = 0;
      for (int j = 0; j < kChords; ++j)
        length += norm(sidePoint(curves_, side, (j + 1.0) / kChords).point -
                       sidePoint(curves_, side, double(j) / kChords).point);
      longest = std::max(longest, length), shortest = std::min(shortest, length);
    }
    return longest / shortest;
  }

  /// The loop's samples (kSamplesPerSide per side) in the plane normal to
  /// faceNormal, turning counter-clockwise.
  std::vector<Vec2> planSamples(const Loop &loop, const Vec3 &faceNormal) const {
    const Vec3 normal = normalized(faceNormal);
    const Vec3 u = orthogonalTo(std::abs(normal.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}, normal);
    const Vec3 v = cross(normal, u);
    std::vector<Vec2> plan;
    for (const SideDescription &side : loop)
      for (int j = 0; j < kSamplesPerSide; ++j) {
        const Vec3 p = sidePoint(curves_, side, double(j) / kSamplesPerSide).point;
        plan.push_back({dot(p, u), dot(p, v)});
      }
    return plan;
  }

  /// Calls piece(sample index, its end's index) for each side or half side
  /// from sample `from` to sample `to` along the loop (both corners or side
  /// midpoints; from == to: the whole loop).
  template <class Piece>
  static void forEachPiece(int samples, int from, int to, Piece &&piece) {
    int at = from;
    do {
      int end = at - at % kSamplesPerSide + kSamplesPerSide; // the next corner
      const int ahead = (to - at + samples) % samples;
      if (ahead > 0 && ahead < end - at) end = at + ahead;
      piece(at, end);
      at = end % samples;
    } while (at != to);
  }

  /// The outline of the part from sample `from` along the loop to sample
  /// `to`, closed by a straight connection back to `from` (from == to: the
  /// whole loop).
  static std::vector<PlanPiece> outline(const std::vector<Vec2> &plan, int from, int to) {
    const int samples = static_cast<int>(plan.size());
    std::vector<PlanPiece> pieces;
    forEachPiece(samples, from, to, [&](int at, int end) {
      // A piece of an odd number of quarters (a quarter point at one end)
      // has no sample in its middle: the mean of the two nearest.
      const int half = (end - at) / 2;
      const Vec2 middle = (end - at) % 2 == 0 ? plan[(at + half) % samples]
                                              : (plan[(at + half) % samples] + plan[(at + half + 1) % samples]) * 0.5;
      pieces.push_back({plan[at], middle});
    });
    if (from != to) pieces.push_back({plan[to], (plan[to] + plan[from]) * 0.5});
    return pieces;
  }

  /// The sides of the loop from sample `from` to sample `to`, cut at side
  /// midpoints where those are the ends.
  static Loop sidesBetween(const Loop &loop, int from, int to) {
    const int samples = static_cast<int>(loop.size()) * kSamplesPerSide;
    Loop sides;
    forEachPiece(samples, from, to, [&](int at, int end) {
      const SideDescription &side = loop[at / kSamplesPerSide];
      // Samples along this side where the piece starts and ends.
      const int start = at % kSamplesPerSide, stop = start + (end - at);
      auto parameter = [&](int sample) {
        return sample == 0                 ? side.from
               : sample == kSamplesPerSide ? side.to
                                           : side.from + double(sample) / kSamplesPerSide * (side.to - side.from);
      };
      sides.push_back({side.curve, parameter(start), parameter(stop)});
    });
    return sides;
  }

  /// True when sample `sample` is the midpoint of a connection curve: a
  /// second connection curve ending there would make an X-node of hidden
  /// curves inside the user's face.
  bool endsOnConnectionMidpoint(const Loop &loop, int sample) const {
    if (sample % kSamplesPerSide == 0) return false;
    const int curve = loop[sample / kSamplesPerSide].curve;
    return std::find(connections_.begin(), connections_.end(), curve) != connections_.end();
  }

  LoopPoint loopPointAt(const Loop &loop, int sample, const Vec3 &faceNormal) const {
    const int side = sample / kSamplesPerSide;
    return sample % kSamplesPerSide == 0
               ? cornerPoint(curves_, loop, side, faceNormal, reference_)
               : midPoint(curves_, loop, side, faceNormal, reference_, double(sample % kSamplesPerSide) / kSamplesPerSide);
  }

  std::vector<BSplineCurve> &curves_;
  const std::optional<ReferenceSurface> &reference_;
  std::vector<int> connections_;
};

/// InputError when consecutive sides of `loop` (valid, see loopIsValid) do
/// not meet within `tolerance`: checked before a hole is joined, whose parts
/// would otherwise carry the gap into loops the user never wrote.
void requireClosed(const std::vector<BSplineCurve> &curves, const Loop &loop, double tolerance, const std::string &file,
                   const std::string &element) {
  const int n = static_cast<int>(loop.size());
  for (int k = 0; k < n; ++k) {
    const Vec3 a = sidePoint(curves, loop[k], 1).point, b = sidePoint(curves, loop[(k + 1) % n], 0).point;
    if (norm(a - b) > tolerance)
      throw InputError(file, element,
                       "does not close: side " + std::to_string(k) + " ends " + std::to_string(norm(a - b)) +
                           " away from where side " + std::to_string((k + 1) % n) + " starts");
  }
}

/// True when every side refers to an existing curve inside its domain (else
/// the loop is left to Network::build, which names the fault).
bool loopIsValid(const std::vector<BSplineCurve> &curves, const Loop &loop) {
  for (const SideDescription &side : loop) {
    if (side.curve < 0 || side.curve >= static_cast<int>(curves.size())) return false;
    const BSplineCurve &c = curves[side.curve];
    const double slack = 1e-10 * (c.domainEnd() - c.domainStart());
    for (double t : {side.from, side.to})
      if (!std::isfinite(t) || t < c.domainStart() - slack || t > c.domainEnd() + slack) return false;
    if (side.from == side.to) return false;
  }
  return loop.size() >= 2;
}

} // namespace

NetworkDescription insertConnectionCurves(const NetworkDescription &description, const std::string &file) {
  if (!description.connectionCurves) return description;
  NetworkDescription out = description;
  out.faces.clear();
  Splitter splitter(out.curves, description.reference);
  // Network::build's vertex tolerance (it checks the description's value).
  BoundingBox bounds;
  for (const BSplineCurve &c : description.curves)
    for (const Vec3 &p : c.controlPoints()) bounds.add(p);
  const double tolerance = description.tolerance * bounds.diagonal();
  // Before any split: in a split description read back the cuts end at the
  // pleated corners, which are then of valence 3 or more, no pleat.
  const std::vector<std::vector<int>> pleated = pleatedCorners(description.curves, description.faces, tolerance);
  std::vector<std::vector<int>> partsOf(description.faces.size());
  bool changed = false;
  for (size_t f = 0; f < description.faces.size(); ++f) {
    const FaceDescription &face = description.faces[f];
    const std::string element = "face " + std::to_string(f);
    std::vector<Loop> parts;
    if (!face.holes.empty()) {
      if (face.holes.size() > 1)
        throw InputError(file, element, std::to_string(face.holes.size()) + " holes; a face may have one");
      if (!loopIsValid(description.curves, face.holes[0]))
        throw InputError(file, element + " hole", "a side refers to a missing curve or a range outside it");
      if (!loopIsValid(description.curves, face.sides))
        throw InputError(file, element, "a side refers to a missing curve or a range outside it");
      for (const Loop *loop : {&face.sides, &face.holes[0]})
        if (loop->size() > static_cast<std::size_t>(kMaxRingSides))
          throw InputError(file, loop == &face.sides ? element : element + " hole",
                           std::to_string(loop->size()) + " sides; a face with a hole and its hole may have up to " +
                               std::to_string(kMaxRingSides) + " each");
      if (std::isfinite(tolerance) && tolerance > 0) {
        requireClosed(description.curves, face.sides, tolerance, file, element);
        requireClosed(description.curves, face.holes[0], tolerance, file, element + " hole");
      }
      parts = splitter.ring(face.sides, face.holes[0]);
    } else if (loopIsValid(description.curves, face.sides) && face.sides.size() >= 3) {
      // A loop of more than kMaxPartSides sides is always split: a gap in it
      // would be reported on parts the user never wrote.
      if (face.sides.size() > static_cast<std::size_t>(kMaxPartSides) && std::isfinite(tolerance) && tolerance > 0)
        requireClosed(description.curves, face.sides, tolerance, file, element);
      // A part of a split face (a split description read back) stays as it
      // was split; only a concave corner would still be split.
      if (face.partOf >= 0)
        parts = splitter.convexParts(face.sides);
      else if (!pleated[f].empty())
        parts = splitter.pleatParts(face.sides, pleated[f][0]);
      else
        parts = splitter.wellShapedParts(face.sides);
    } else {
      parts = {face.sides};
    }
    if (parts.size() > 1) changed = true;
    for (size_t k = 0; k < parts.size(); ++k) {
      FaceDescription part;
      part.sides = std::move(parts[k]);
      part.partOf = face.partOf >= 0 ? face.partOf : static_cast<int>(f);
      part.name = parts.size() == 1 ? face.name
                                    : (face.name.empty() ? element : face.name) + " part " + std::to_string(k);
      partsOf[f].push_back(static_cast<int>(out.faces.size()));
      out.faces.push_back(std::move(part));
    }
  }
  if (!changed) return description;
  // A named master that was split: its part that borders the curve.
  for (EdgeDescription &edge : out.edges) {
    if (edge.masterFace < 0 || edge.masterFace >= static_cast<int>(partsOf.size())) continue;
    const std::vector<int> &parts = partsOf[edge.masterFace];
    auto borders = [&](int p) {
      return std::any_of(out.faces[p].sides.begin(), out.faces[p].sides.end(),
                         [&](const SideDescription &side) { return side.curve == edge.curve; });
    };
    const auto it = std::find_if(parts.begin(), parts.end(), borders);
    edge.masterFace = it == parts.end() ? parts.front() : *it;
  }
  for (int curve : splitter.connections()) out.edges.push_back({curve, -1, true});
  return out;
}

} // namespace v1
} // namespace curvenet
