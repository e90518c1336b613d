// Welding a curve graph (sketch.hpp step 1): coincident points, T-nodes
// where a free end lies on another stroke, X-nodes where strokes cross.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <queue>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "curvenet/error.hpp"

#include "graph/welded_graph.hpp"

namespace curvenet {
inline namespace v1 {
namespace graph {
namespace {

// joinCrossings: two strokes that reach a point they share along paths at
// most this many times their straight distance to it run into that point,
// and the search for such a point goes this many weld distances along the
// strokes (strokes meeting at an angle of 3° or more stay within the weld
// distance of each other only inside that reach).
constexpr double kStraightPath = 1.2;
constexpr double kConvergenceReach = 20;
// joinCrossings: a piece keeps at most this many nearest pieces as crossing
// candidates, and a search along the strokes visits at most this many points
// (the shared-point test needs at most 6 on the public sketches); both bound
// the weld's work on a tangle drawn within the weld distance, which took
// minutes when every pair and every path was followed.
constexpr std::size_t kCandidatesPerPiece = 16;
constexpr std::size_t kAlongBudget = 256;
constexpr std::size_t kPathBudget = 4096; // pathLengthsFrom, nearest first
// crossingCandidates: pairs of pieces it compares before it refuses the
// sketch, a fixed allowance plus this many per piece. The public sketches
// compare at most 4.1 pairs per piece (bathtub.obj: 20 807 for 5 064).
constexpr std::size_t kPairAllowance = 2'000'000;
constexpr std::size_t kPairsPerPiece = 100;

/// Points hashed into cubic cells, for neighbour queries within a radius.
class PointGrid {
public:
  explicit PointGrid(double cell) : cell_(cell) {}
  void add(const Vec3 &p, int id) { cells_[key(cellOf(p))].push_back(id); }
  /// Calls visit(id) for every id whose point was added within one cell of p.
  template <typename Visit> void near(const Vec3 &p, Visit &&visit) const {
    const auto c = cellOf(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          if (auto it = cells_.find(key({c[0] + dx, c[1] + dy, c[2] + dz})); it != cells_.end())
            for (int id : it->second) visit(id);
  }

private:
  std::array<std::int64_t, 3> cellOf(const Vec3 &p) const {
    return {static_cast<std::int64_t>(std::floor(p.x / cell_)), static_cast<std::int64_t>(std::floor(p.y / cell_)),
            static_cast<std::int64_t>(std::floor(p.z / cell_))};
  }
  static std::uint64_t key(const std::array<std::int64_t, 3> &c) {
    return static_cast<std::uint64_t>(c[0]) * 73856093u ^ static_cast<std::uint64_t>(c[1]) * 19349663u ^
           static_cast<std::uint64_t>(c[2]) * 83492791u;
  }
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

/// Closest points of segments [a0, a1] and [b0, b1]: parameters (s, t).
std::pair<double, double> closestParameters(const Vec3 &a0, const Vec3 &a1, const Vec3 &b0, const Vec3 &b1) {
  const Vec3 u = a1 - a0, v = b1 - b0, w = a0 - b0;
  const double a = dot(u, u), b = dot(u, v), c = dot(v, v), d = dot(u, w), e = dot(v, w);
  const double det = a * c - b * b;
  double s = det > 1e-14 * a * c ? std::clamp((b * e - c * d) / det, 0.0, 1.0) : 0.0;
  double t = c > 0 ? std::clamp((b * s + e) / c, 0.0, 1.0) : 0.0;
  s = a > 0 ? std::clamp((b * t - d) / a, 0.0, 1.0) : 0.0;
  return {s, t};
}

class Welder {
public:
  Welder(WeldedGraph &g, double weld) : g_(g), weld_(weld) {}

  void link(int a, int b, int stroke) {
    if (a == b) return;
    for (const auto &l : g_.links[a])
      if (l.point == b) return; // a piece given twice is one piece
    g_.links[a].push_back({b, stroke});
    g_.links[b].push_back({a, stroke});
  }
  void unlink(int a, int b) {
    std::erase_if(g_.links[a], [&](const WeldedGraph::Link &l) { return l.point == b; });
    std::erase_if(g_.links[b], [&](const WeldedGraph::Link &l) { return l.point == a; });
  }
  int strokeOf(int a, int b) const {
    for (const auto &l : g_.links[a])
      if (l.point == b) return l.stroke;
    return -1;
  }
  int addPoint(const Vec3 &p, NodeKind kind) {
    g_.points.push_back(p);
    g_.links.emplace_back();
    g_.madeAs.push_back(kind);
    return static_cast<int>(g_.points.size()) - 1;
  }
  /// Moves every link of `from` onto `to`.
  void merge(int from, int to) {
    const auto old = g_.links[from];
    for (const auto &l : old) {
      unlink(from, l.point);
      link(to, l.point, l.stroke);
    }
  }
  /// Splits piece (a, b) at parameter s; returns the point there (an end
  /// when s is within a tenth of the piece of it).
  int split(int a, int b, double s, NodeKind kind) {
    if (s < 0.1) return a;
    if (s > 0.9) return b;
    const int stroke = strokeOf(a, b);
    const int m = addPoint(pointOnStroke(a, b, s), kind);
    unlink(a, b);
    link(a, m, stroke);
    link(m, b, stroke);
    return m;
  }
  /// The point at parameter s of piece (a, b) on the Catmull–Rom curve
  /// through the piece and its neighbours: on a smooth stroke it lies on the
  /// curve the samples come from, not inside it on the chord (the chord's
  /// sagitta would become a dent at the node that the fit must follow).
  Vec3 pointOnStroke(int a, int b, double s) const {
    const Vec3 p1 = g_.points[a], p2 = g_.points[b];
    const int before = otherNeighbour(a, b), after = otherNeighbour(b, a);
    if (before < 0 || after < 0) return p1 + (p2 - p1) * s;
    const Vec3 p0 = g_.points[before], p3 = g_.points[after];
    const double s2 = s * s, s3 = s2 * s;
    return (p1 * 2.0 + (p2 - p0) * s + (p0 * 2.0 - p1 * 5.0 + p2 * 4.0 - p3) * s2 + (p1 * 3.0 - p0 - p2 * 3.0 + p3) * s3) * 0.5;
  }
  /// The neighbour of `p` other than `not` when p has exactly two, else -1.
  int otherNeighbour(int p, int not_) const {
    if (g_.links[p].size() != 2) return -1;
    return g_.links[p][0].point == not_ ? g_.links[p][1].point : g_.links[p][0].point;
  }

  /// Marks the points reachable from `start` along the polyline within path
  /// length `reach`, and start's neighbours (their piece is its own);
  /// marked(p) tells them until the next search. Stops with true at the
  /// first of `stopA`, `stopB` it reaches, and after kAlongBudget points: a
  /// tangle that dense within the reach is already joined there as far as
  /// the weld can tell, and every search costs at most the budget, whatever
  /// the input.
  bool markAlongStrokes(int start, double reach, int stopA = -1, int stopB = -1) {
    const auto stops = [&](int p) { return p == stopA || p == stopB; };
    if (stops(start)) return true;
    for (const auto &l : g_.links[start])
      if (stops(l.point)) return true;
    if (mark_.size() < g_.points.size()) mark_.resize(g_.points.size(), 0);
    if (++stamp_ == 0) std::fill(mark_.begin(), mark_.end(), 0), stamp_ = 1;
    mark_[start] = stamp_;
    // start's neighbours are marked whichever way the search ends: a free
    // end must never weld onto its own piece.
    const auto markNeighbours = [&] {
      for (const auto &l : g_.links[start]) mark_[l.point] = stamp_;
    };
    queue_.assign(1, {start, 0.0});
    for (std::size_t head = 0; head < queue_.size(); ++head) {
      if (queue_.size() > kAlongBudget) return markNeighbours(), true;
      const auto [p, d] = queue_[head];
      for (const auto &l : g_.links[p]) {
        const double next = d + norm(g_.points[l.point] - g_.points[p]);
        if (next > reach || marked(l.point)) continue;
        if (stops(l.point)) return true;
        mark_[l.point] = stamp_;
        queue_.push_back({l.point, next});
      }
    }
    markNeighbours();
    return false;
  }
  bool marked(int p) const { return p < static_cast<int>(mark_.size()) && mark_[p] == stamp_; }
  /// Path lengths along the strokes from the point at parameter s of piece
  /// (a, b) to every point it reaches within `reach` (shortest paths). The
  /// paths stop at crossings this pass has joined: two strokes crossing at a
  /// shallow angle both run on nearly straight past their X, so beyond it
  /// they would seem to run into a shared point; their other close pieces
  /// are the shared-point test's in joinCrossings.
  std::unordered_map<int, double> pathLengthsFrom(int a, int b, double s, double reach) const {
    const double length = norm(g_.points[b] - g_.points[a]);
    std::unordered_map<int, double> best;
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    queue.push({s * length, a});
    queue.push({(1 - s) * length, b});
    while (!queue.empty()) {
      const auto [d, p] = queue.top();
      queue.pop();
      if (best.count(p)) continue;
      best[p] = d;
      if (best.size() >= kPathBudget) break;
      if (g_.madeAs[p] == NodeKind::X) continue;
      for (const auto &l : g_.links[p]) {
        const double next = d + norm(g_.points[l.point] - g_.points[p]);
        if (next <= reach && !best.count(l.point)) queue.push({next, l.point});
      }
    }
    return best;
  }
  /// True when pieces (a0, a1) and (b0, b1), closest at parameters s and t,
  /// are near each other only because their strokes run into a point they
  /// already share (drawn to meet there): both reach it along nearly
  /// straight paths (no longer than kStraightPath times the straight
  /// distance). Two strokes ending at one junction at an angle θ stay within
  /// the weld distance w of each other for w / (2 sin(θ/2)) from it (2.9 w at
  /// doghead.obj's 20° junction), beyond the 3 w of the shared-point test in
  /// joinCrossings; joined there, they made an X-node one sample short of
  /// the junction and a segment one sample long, into which the curve
  /// through the X bent (normal curvature −19.7 there against −0.19 of the
  /// curve 20° away), and the vertex fit turned that into a principal
  /// curvature of −164 that twisted the gregory-g2 fences of both faces
  /// beside it by more than half a turn. A stroke that comes back to cross
  /// another near a point they share does so along a path that is not
  /// straight (π/2 times its chord for a semicircle).
  bool convergeIntoSharedPoint(int a0, int a1, double s, int b0, int b1, double t) const {
    const Vec3 pa = g_.points[a0] + (g_.points[a1] - g_.points[a0]) * s;
    const Vec3 pb = g_.points[b0] + (g_.points[b1] - g_.points[b0]) * t;
    const double reach = kConvergenceReach * weld_;
    const auto fromA = pathLengthsFrom(a0, a1, s, reach), fromB = pathLengthsFrom(b0, b1, t, reach);
    for (const auto &[q, la] : fromA) {
      const auto other = fromB.find(q);
      if (other == fromB.end() || g_.madeAs[q] == NodeKind::X) continue;
      const Vec3 &at = g_.points[q];
      if (la <= kStraightPath * norm(at - pa) && other->second <= kStraightPath * norm(at - pb)) return true;
    }
    return false;
  }
  std::vector<std::pair<int, int>> pieces() const {
    std::vector<std::pair<int, int>> out;
    for (int a = 0; a < static_cast<int>(g_.links.size()); ++a)
      for (const auto &l : g_.links[a])
        if (a < l.point) out.push_back({a, l.point});
    return out;
  }
  double longestPiece() const {
    double longest = 0;
    for (auto [a, b] : pieces()) longest = std::max(longest, norm(g_.points[a] - g_.points[b]));
    return longest;
  }

  /// A free end (one link) within the weld distance of another stroke's
  /// point is merged into it; else, within it of a piece, the piece is split
  /// there (a T-node).
  void joinFreeEnds() {
    const double cell = std::max(longestPiece(), weld_) + weld_;
    PointGrid grid(cell);
    for (int p = 0; p < static_cast<int>(g_.points.size()); ++p) grid.add(g_.points[p], p);
    const int originalPoints = static_cast<int>(g_.points.size());
    for (int end = 0; end < originalPoints; ++end) {
      if (g_.links[end].size() != 1) continue;
      const Vec3 at = g_.points[end];
      markAlongStrokes(end, 3 * weld_); // marked: the end's own stroke nearby
      int bestPoint = -1;
      double bestPointDistance = weld_;
      int bestA = -1, bestB = -1;
      double bestS = 0, bestPieceDistance = weld_;
      grid.near(at, [&](int q) {
        if (marked(q) || g_.links[q].empty()) return;
        if (const double d = norm(g_.points[q] - at); d <= bestPointDistance) bestPointDistance = d, bestPoint = q;
        for (const auto &l : g_.links[q]) {
          if (marked(l.point)) continue;
          const Vec3 a = g_.points[q], b = g_.points[l.point];
          const double len2 = squaredNorm(b - a);
          const double s = len2 > 0 ? std::clamp(dot(at - a, b - a) / len2, 0.0, 1.0) : 0.0;
          if (const double d = norm(a + (b - a) * s - at); d < bestPieceDistance)
            bestPieceDistance = d, bestA = q, bestB = l.point, bestS = s;
        }
      });
      int target = bestPoint;
      if (target < 0 && bestA >= 0) {
        target = split(bestA, bestB, bestS, NodeKind::T);
        if (target >= originalPoints) grid.add(g_.points[target], target);
      }
      if (target < 0) continue;
      if (g_.madeAs[target] == NodeKind::Junction) g_.madeAs[target] = NodeKind::T;
      merge(end, target);
      ++g_.tNodes;
    }
  }

  struct Candidate {
    double distance;
    int first, second;
    double s, t;
  };
  [[noreturn]] void refuseCrowd(const Vec3 &at, std::size_t compared) const {
    std::ostringstream where, why;
    where << "strokes near (" << at.x << ", " << at.y << ", " << at.z << ")";
    why << "more than " << compared - 1 << " pairs of stroke pieces lie within a few weld distances (" << weld_
        << ") of one another: the strokes are a tangle at this weld distance; give a smaller one (--weld)";
    throw InputError({}, where.str(), why.str());
  }
  /// Pairs of pieces (indices into `all`, first < second) closer than the
  /// weld distance, nearest first, at most kCandidatesPerPiece per piece.
  /// Each piece is hashed into every cell it passes through, cells as large
  /// as the mean piece plus the weld distance: a long piece (a stroke drawn
  /// as one straight segment) then finds only the pieces along it, not every
  /// piece of the sketch.
  std::vector<Candidate> crossingCandidates(const std::vector<std::pair<int, int>> &all) const {
    double total = 0;
    for (auto [a, b] : all) total += norm(g_.points[b] - g_.points[a]);
    const double step = std::max(weld_, all.empty() ? 0.0 : total / static_cast<double>(all.size()));
    PointGrid grid(step + weld_);
    // Samples at most `step` apart: two pieces within the weld distance have
    // samples within step + weld of each other, in neighbouring cells.
    const auto samples = [&](int k, auto &&visit) {
      const Vec3 a = g_.points[all[k].first], b = g_.points[all[k].second];
      const int n = static_cast<int>(std::ceil(norm(b - a) / step)); // at most the piece count
      for (int i = 0; i <= n; ++i) visit(a + (b - a) * (n > 0 ? static_cast<double>(i) / n : 0.0));
    };
    for (int k = 0; k < static_cast<int>(all.size()); ++k)
      samples(k, [&](const Vec3 &p) { grid.add(p, k); });
    std::vector<Candidate> candidates, own;
    std::vector<int> seenBy(all.size(), -1);
    std::size_t compared = 0;
    const std::size_t budget = kPairAllowance + kPairsPerPiece * all.size();
    for (int k = 0; k < static_cast<int>(all.size()); ++k) {
      // Plain names, not a structured binding: the lambda below captures them.
      const int a0 = all[k].first, a1 = all[k].second;
      own.clear();
      samples(k, [&](const Vec3 &p) {
        grid.near(p, [&](int j) {
          if (j <= k || seenBy[j] == k) return;
          seenBy[j] = k;
          if (++compared > budget) refuseCrowd(g_.points[a0], compared);
          const auto [b0, b1] = all[j];
          if (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1) return;
          const auto [s, t] = closestParameters(g_.points[a0], g_.points[a1], g_.points[b0], g_.points[b1]);
          const Vec3 pa = g_.points[a0] + (g_.points[a1] - g_.points[a0]) * s;
          const Vec3 pb = g_.points[b0] + (g_.points[b1] - g_.points[b0]) * t;
          if (const double d = norm(pa - pb); d < weld_) own.push_back({d, k, j, s, t});
        });
      });
      const auto nearer = [](const Candidate &x, const Candidate &y) {
        return x.distance < y.distance || (x.distance == y.distance && x.second < y.second);
      };
      if (own.size() > kCandidatesPerPiece) {
        std::nth_element(own.begin(), own.begin() + kCandidatesPerPiece, own.end(), nearer);
        own.resize(kCandidatesPerPiece);
      }
      candidates.insert(candidates.end(), own.begin(), own.end());
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate &x, const Candidate &y) { return x.distance < y.distance; });
    return candidates;
  }

  /// Pieces of strokes that pass within the weld distance of each other
  /// without sharing a point nearby are joined at their closest points.
  void joinCrossings() {
    const auto all = pieces();
    const auto candidates = crossingCandidates(all);
    std::vector<bool> used(all.size(), false);
    for (const Candidate &c : candidates) {
      if (used[c.first] || used[c.second]) continue;
      const auto [a0, a1] = all[c.first];
      const auto [b0, b1] = all[c.second];
      // Pieces already joined nearby (a shared point within reach) are not a crossing.
      if (markAlongStrokes(a0, 3 * weld_ + norm(g_.points[a1] - g_.points[a0]), b0, b1)) continue;
      used[c.first] = used[c.second] = true;
      if (convergeIntoSharedPoint(a0, a1, c.s, b0, b1, c.t)) continue;
      const int pa = split(a0, a1, c.s, NodeKind::X);
      const int pb = split(b0, b1, c.t, NodeKind::X);
      if (pa == pb) continue;
      const Vec3 middle = (g_.points[pa] + g_.points[pb]) * 0.5;
      g_.points[pa] = middle;
      g_.madeAs[pa] = NodeKind::X;
      merge(pb, pa);
      ++g_.xNodes;
    }
  }

private:
  WeldedGraph &g_;
  double weld_;
  // markAlongStrokes: the marks of its searches (stamp_ is the current one), and its queue.
  std::vector<std::uint32_t> mark_;
  std::uint32_t stamp_ = 0;
  std::vector<std::pair<int, double>> queue_;
};

} // namespace

WeldedGraph weldCurveGraph(const CurveGraph &input, double weld, double diagonal) {
  WeldedGraph g;
  // Coincident points (a curve's end sampled twice, a stroke given per
  // segment with its own copies) are one point.
  const double same = 1e-9 * diagonal;
  std::vector<int> representative(input.points.size(), -1);
  {
    PointGrid grid(std::max(same, 1e-300) * 4);
    for (int p = 0; p < static_cast<int>(input.points.size()); ++p) {
      int found = -1;
      grid.near(input.points[p], [&](int q) {
        if (found < 0 && norm(g.points[q] - input.points[p]) <= same) found = q;
      });
      if (found < 0) {
        found = static_cast<int>(g.points.size());
        g.points.push_back(input.points[p]);
        grid.add(input.points[p], found);
      }
      representative[p] = found;
    }
  }
  g.links.resize(g.points.size());
  g.madeAs.assign(g.points.size(), NodeKind::Junction);
  Welder welder(g, weld);
  for (int s = 0; s < static_cast<int>(input.strokes.size()); ++s) {
    const auto &chain = input.strokes[s];
    for (std::size_t k = 0; k + 1 < chain.size(); ++k)
      welder.link(representative[chain[k]], representative[chain[k + 1]], s);
  }
  if (weld > 0) {
    welder.joinFreeEnds();
    welder.joinCrossings();
  }
  return g;
}

} // namespace graph
} // namespace v1
} // namespace curvenet
