// From a curve graph to a network (sketch.hpp): nodes and edges of the
// welded graph, dangling edges, curves through the nodes, faces from a
// consistently oriented rotation system.
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <queue>
#include <sstream>

#include <Eigen/Dense>

#include "analysis/vertex_frames.hpp"
#include "curvenet/error.hpp"
#include "graph/welded_graph.hpp"

namespace curvenet {
inline namespace v1 {

const char *toString(NodeKind kind) {
  switch (kind) {
  case NodeKind::Junction: return "junction";
  case NodeKind::T: return "T";
  case NodeKind::X: return "X";
  case NodeKind::Loop: return "loop";
  case NodeKind::Corner: return "corner";
  case NodeKind::FreeEnd: return "free end";
  }
  return "?";
}

namespace graph {
namespace {

constexpr double kPi = std::numbers::pi;
/// Edges at a node that turn by less than this continue each other (one curve).
constexpr double kStraightTurn = 45 * kPi / 180;
/// A stroke turning by more than this at a point (over 2% of the diagonal) has a corner there.
constexpr double kCornerTurn = 75 * kPi / 180;
/// Edges leaving a node's best plane by less than this share it exactly after the fit.
constexpr double kPlaneAngle = 25 * kPi / 180;

std::string formatPoint(const Vec3 &p) {
  std::ostringstream s;
  s.precision(4);
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

struct Edge {
  int from = -1, to = -1;   ///< node indices
  std::vector<int> points;  ///< welded-graph points, from the `from` node to the `to` node
  int stroke = -1;
  bool dangling = false;
  int curve = -1;
  double parameterAtFrom = 0, parameterAtTo = 0;
};

/// An edge end at a node: half-edge 2e (leaving `from`) or 2e + 1 (leaving `to`).
int tailNode(const std::vector<Edge> &edges, int half) { return half % 2 ? edges[half / 2].to : edges[half / 2].from; }
int headNode(const std::vector<Edge> &edges, int half) { return half % 2 ? edges[half / 2].from : edges[half / 2].to; }

/// The points of half-edge `half` in its direction.
std::vector<Vec3> halfEdgePoints(const WeldedGraph &g, const Edge &e, bool reversed) {
  std::vector<Vec3> out;
  for (int p : e.points) out.push_back(g.points[p]);
  if (reversed) std::reverse(out.begin(), out.end());
  return out;
}

double polylineLength(const std::vector<Vec3> &q) {
  double length = 0;
  for (std::size_t i = 1; i < q.size(); ++i) length += norm(q[i] - q[i - 1]);
  return length;
}

struct Node {
  int point = -1;
  NodeKind kind = NodeKind::Junction;
  std::vector<int> halves; ///< half-edges leaving, in rotation order once sorted
  Vec3 normal{0, 0, 0};      ///< oriented; the rotation runs counter-clockwise about it
  Vec3 planeNormal{0, 0, 0}; ///< of the edges' best plane (valence ≥ 3)
  bool planeKnown = false;   ///< three or more edges: the tour, its normal and the best plane were measured
  double outOfPlane = kPi;   ///< largest angle of an edge direction out of that plane
  bool faced = false;
};

class Builder {
public:
  Builder(const WeldedGraph &g, const CurveGraph &input, const SketchOptions &options, double diagonal,
          const std::string &file)
      : g_(g), input_(input), options_(options), diagonal_(diagonal), file_(file) {}

  SketchResult run() {
    findNodesAndEdges();
    markDangling();
    splitClosedEdges();
    measureDirections();
    orientNormals();
    traceFaces();
    fitCurves();
    return describe();
  }

private:
  int addNode(int point, NodeKind kind) {
    nodeOfPoint_[point] = static_cast<int>(nodes_.size());
    nodes_.push_back({point, kind});
    return nodeOfPoint_[point];
  }

  /// Walks from node point `start` along its link to `next` until a node.
  void walk(int start, int next, std::vector<std::vector<char>> &usedLink) {
    Edge e;
    e.points = {start};
    int previous = start, at = next;
    auto markUsed = [&](int a, int b) {
      for (std::size_t k = 0; k < g_.links[a].size(); ++k)
        if (g_.links[a][k].point == b) usedLink[a][k] = 1;
      for (std::size_t k = 0; k < g_.links[b].size(); ++k)
        if (g_.links[b][k].point == a) usedLink[b][k] = 1;
    };
    for (const auto &l : g_.links[start])
      if (l.point == next) e.stroke = l.stroke;
    markUsed(start, next);
    while (nodeOfPoint_[at] < 0) {
      e.points.push_back(at);
      const auto &links = g_.links[at];
      const int following = links[0].point == previous ? links[1].point : links[0].point;
      markUsed(at, following);
      previous = at, at = following;
    }
    e.points.push_back(at);
    e.from = nodeOfPoint_[start], e.to = nodeOfPoint_[at];
    edges_.push_back(std::move(e));
  }

  /// The point `reach` along the polyline from `p` through its neighbour
  /// `next` (or the last one before a node or an end).
  Vec3 alongFrom(int p, int next, double reach) const {
    double run = 0;
    int previous = p, at = next;
    for (;;) {
      run += norm(g_.points[at] - g_.points[previous]);
      if (run >= reach || g_.links[at].size() != 2 || at == p) return g_.points[at];
      const auto &links = g_.links[at];
      const int following = links[0].point == previous ? links[1].point : links[0].point;
      previous = at, at = following;
    }
  }

  /// How sharply the polyline turns at a point of two links, seen over
  /// `reach` on each side (0 for a straight run, π for a hairpin).
  double turnAt(int p, double reach) const {
    const Vec3 back = alongFrom(p, g_.links[p][0].point, reach), ahead = alongFrom(p, g_.links[p][1].point, reach);
    return angleBetween(g_.points[p] - back, ahead - g_.points[p]);
  }

  /// Points where a stroke turns by more than kCornerTurn over 2% of the
  /// diagonal on each side, the sharpest within that reach: strokes drawn
  /// to meet at a corner share a point there with only two links, and the
  /// corner is a node all the same.
  std::vector<int> corners() const {
    const double reach = 0.02 * diagonal_;
    std::vector<double> turn(g_.points.size(), 0.0);
    for (int p = 0; p < static_cast<int>(g_.points.size()); ++p)
      if (g_.links[p].size() == 2) turn[p] = turnAt(p, reach);
    std::vector<int> out;
    for (int p = 0; p < static_cast<int>(g_.points.size()); ++p) {
      if (turn[p] < kCornerTurn) continue;
      // The sharpest point within the reach along the polyline (ties: the
      // lowest index), and no node within it: a stroke turning where it
      // meets others has its corner at that node already.
      bool sharpest = true;
      for (const auto &l : g_.links[p]) {
        double run = 0;
        int previous = p, at = l.point;
        while (sharpest && at != p) {
          run += norm(g_.points[at] - g_.points[previous]);
          if (run > reach) break;
          if (g_.links[at].size() != 2 || turn[at] > turn[p] || (turn[at] == turn[p] && at < p)) sharpest = false;
          if (!sharpest) break;
          const auto &links = g_.links[at];
          const int following = links[0].point == previous ? links[1].point : links[0].point;
          previous = at, at = following;
        }
      }
      if (sharpest) out.push_back(p);
    }
    return out;
  }

  void findNodesAndEdges() {
    nodeOfPoint_.assign(g_.points.size(), -1);
    for (int p = 0; p < static_cast<int>(g_.points.size()); ++p) {
      const std::size_t valence = g_.links[p].size();
      if (valence == 0 || valence == 2) continue;
      addNode(p, valence == 1 ? NodeKind::FreeEnd : g_.madeAs[p]);
    }
    for (int p : corners()) addNode(p, NodeKind::Corner);
    std::vector<std::vector<char>> usedLink(g_.points.size());
    for (int p = 0; p < static_cast<int>(g_.points.size()); ++p) usedLink[p].assign(g_.links[p].size(), 0);
    auto walkAllFrom = [&](int point) {
      for (std::size_t k = 0; k < g_.links[point].size(); ++k)
        if (!usedLink[point][k]) walk(point, g_.links[point][k].point, usedLink);
    };
    for (std::size_t n = 0; n < nodes_.size(); ++n) walkAllFrom(nodes_[n].point);
    // What is left are closed strokes with no node: each gets one.
    for (int p = 0; p < static_cast<int>(g_.points.size()); ++p)
      if (g_.links[p].size() == 2 && !usedLink[p][0]) {
        addNode(p, NodeKind::Loop);
        walkAllFrom(p);
      }
  }

  /// Edges with a free end, and edges on no cycle (bridges), repeatedly.
  void markDangling() {
    for (bool changed = true; changed;) {
      changed = false;
      std::vector<int> degree(nodes_.size(), 0);
      for (const Edge &e : edges_)
        if (!e.dangling) ++degree[e.from], ++degree[e.to];
      for (Edge &e : edges_)
        if (!e.dangling && (degree[e.from] == 1 || degree[e.to] == 1)) e.dangling = changed = true;
      if (changed) continue;
      for (int bridge : bridges()) edges_[bridge].dangling = changed = true;
    }
  }

  std::vector<int> bridges() const {
    std::vector<std::vector<std::pair<int, int>>> around(nodes_.size()); // (other node, edge)
    for (int k = 0; k < static_cast<int>(edges_.size()); ++k)
      if (!edges_[k].dangling) {
        around[edges_[k].from].push_back({edges_[k].to, k});
        around[edges_[k].to].push_back({edges_[k].from, k});
      }
    std::vector<int> order(nodes_.size(), -1), low(nodes_.size(), 0), out;
    int counter = 0;
    std::function<void(int, int)> visit = [&](int v, int viaEdge) {
      order[v] = low[v] = counter++;
      for (auto [w, k] : around[v]) {
        if (k == viaEdge) continue;
        if (order[w] < 0) {
          visit(w, k);
          low[v] = std::min(low[v], low[w]);
          if (low[w] > order[v]) out.push_back(k);
        } else {
          low[v] = std::min(low[v], order[w]);
        }
      }
    };
    for (int v = 0; v < static_cast<int>(nodes_.size()); ++v)
      if (order[v] < 0) visit(v, -1);
    return out;
  }

  /// A closed edge (from == to) gets a second node half way along it, so
  /// every face side joins two distinct vertices.
  void splitClosedEdges() {
    const int count = static_cast<int>(edges_.size());
    for (int k = 0; k < count; ++k) {
      if (edges_[k].dangling || edges_[k].from != edges_[k].to) continue;
      const std::vector<int> all = edges_[k].points;
      std::vector<Vec3> q;
      for (int p : all) q.push_back(g_.points[p]);
      const double half = polylineLength(q) / 2;
      double run = 0;
      std::size_t middle = 1;
      for (; middle + 1 < all.size(); ++middle) {
        run += norm(q[middle] - q[middle - 1]);
        if (run >= half) break;
      }
      middle = std::min(middle, all.size() - 2);
      const int node = addNode(all[middle], NodeKind::Loop);
      Edge second = edges_[k];
      second.points.assign(all.begin() + static_cast<long>(middle), all.end());
      second.from = node;
      edges_[k].points.assign(all.begin(), all.begin() + static_cast<long>(middle) + 1);
      edges_[k].to = node;
      edges_.push_back(std::move(second));
    }
    for (int k = 0; k < static_cast<int>(edges_.size()); ++k) {
      if (edges_[k].dangling) continue;
      nodes_[edges_[k].from].halves.push_back(2 * k);
      nodes_[edges_[k].to].halves.push_back(2 * k + 1);
      nodes_[edges_[k].from].faced = nodes_[edges_[k].to].faced = true;
    }
  }

  /// Direction of a half-edge leaving its node: the chord to the point a
  /// quarter of the edge (at most 5% of the diagonal) along it, steadier
  /// than the first polyline piece of a hand-drawn stroke.
  Vec3 leavingDirection(int half) const {
    const auto q = halfEdgePoints(g_, edges_[half / 2], half % 2 == 1);
    const double reach = std::min(0.25 * polylineLength(q), 0.05 * diagonal_);
    double run = 0;
    for (std::size_t i = 1; i < q.size(); ++i) {
      run += norm(q[i] - q[i - 1]);
      if (run >= reach) return normalized(q[i] - q[0]);
    }
    return normalized(q.back() - q[0]);
  }

  void measureDirections() {
    direction_.assign(2 * edges_.size(), {0, 0, 0});
    for (int k = 0; k < static_cast<int>(edges_.size()); ++k)
      if (!edges_[k].dangling) direction_[2 * k] = leavingDirection(2 * k), direction_[2 * k + 1] = leavingDirection(2 * k + 1);
    for (Node &node : nodes_) {
      if (node.halves.size() < 3) continue;
      measureTangentPlane(node);
      orderAroundNode(node);
    }
  }

  /// The best plane of the edge directions (least squares): the tangent
  /// plane the curves are made to share when they nearly do.
  void measureTangentPlane(Node &node) const {
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (int h : node.halves) {
      const Eigen::Vector3d d(direction_[h].x, direction_[h].y, direction_[h].z);
      scatter += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
    const Eigen::Vector3d n = eigen.eigenvectors().col(0);
    node.planeNormal = {n.x(), n.y(), n.z()};
    node.outOfPlane = 0;
    for (int h : node.halves)
      node.outOfPlane = std::max(node.outOfPlane, std::asin(std::min(1.0, std::abs(dot(direction_[h], node.planeNormal)))));
  }

  /// The cyclic order of the edges around a node: the shortest closed tour
  /// through their directions on the unit sphere. On a smooth sheet it is
  /// the order about the tangent plane; it stays right where the plane does
  /// not exist (a crease: a cap meeting a wall, where the best plane mixes
  /// the two and projecting onto it interleaves their edges). The node
  /// normal is the fan normal of that tour, Σ dᵢ × dᵢ₊₁.
  void orderAroundNode(Node &node) const {
    std::vector<int> order = node.halves;
    if (order.size() <= 7) {
      std::vector<int> rest(order.begin() + 1, order.end()), best;
      std::sort(rest.begin(), rest.end());
      double shortest = INFINITY;
      do {
        double length = angleBetween(direction_[order[0]], direction_[rest.front()]) +
                        angleBetween(direction_[rest.back()], direction_[order[0]]);
        for (std::size_t i = 0; i + 1 < rest.size(); ++i) length += angleBetween(direction_[rest[i]], direction_[rest[i + 1]]);
        if (length < shortest - 1e-12) shortest = length, best = rest;
      } while (std::next_permutation(rest.begin(), rest.end()));
      std::copy(best.begin(), best.end(), order.begin() + 1);
    } else {
      // Many edges: by angle in the best plane.
      const Vec3 u = normalized(direction_[order[0]] - node.planeNormal * dot(direction_[order[0]], node.planeNormal));
      const Vec3 w = cross(node.planeNormal, u);
      std::sort(order.begin(), order.end(), [&](int a, int b) {
        return std::atan2(dot(direction_[a], w), dot(direction_[a], u)) < std::atan2(dot(direction_[b], w), dot(direction_[b], u));
      });
    }
    Vec3 fan{0, 0, 0};
    for (std::size_t i = 0; i < order.size(); ++i) fan = fan + cross(direction_[order[i]], direction_[order[(i + 1) % order.size()]]);
    node.halves = order;
    node.normal = norm(fan) > 1e-12 ? normalized(fan) : node.planeNormal;
    node.planeKnown = true;
  }

  /// `normal` carried from the tail to the head of half-edge `half` by
  /// projection onto each piece's normal plane (a rotation-minimizing frame
  /// in the limit of dense samples).
  Vec3 transport(int half, Vec3 normal) const {
    const auto q = halfEdgePoints(g_, edges_[half / 2], half % 2 == 1);
    for (std::size_t i = 1; i < q.size(); ++i) {
      const Vec3 t = normalized(q[i] - q[i - 1]);
      const Vec3 projected = normal - t * dot(normal, t);
      if (norm(projected) > 1e-9) normal = normalized(projected);
    }
    return normal;
  }

  /// Node normals oriented alike over each connected part: a spanning tree
  /// grown along the edges whose transported normals agree best, then each
  /// part turned so that its normals point away from its centre.
  void orientNormals() {
    std::vector<bool> done(nodes_.size(), false);
    struct Step {
      double confidence;
      int half;
      Vec3 carried;
      bool operator<(const Step &o) const { return confidence < o.confidence; }
    };
    std::vector<int> part(nodes_.size(), -1);
    int parts = 0;
    for (;;) {
      int root = -1;
      for (int v = 0; v < static_cast<int>(nodes_.size()); ++v)
        if (nodes_[v].faced && !done[v] && (root < 0 || nodes_[v].halves.size() > nodes_[root].halves.size())) root = v;
      if (root < 0) break;
      Node &r = nodes_[root];
      if (!r.planeKnown) {
        const Vec3 a = direction_[r.halves[0]], b = direction_[r.halves[1]];
        r.normal = norm(cross(a, b)) > 1e-6 ? normalized(cross(a, b)) : normalized(cross(a, std::abs(a.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
      }
      std::priority_queue<Step> queue;
      auto reach = [&](int v) {
        done[v] = true;
        part[v] = parts;
        for (int h : nodes_[v].halves) {
          const int w = headNode(edges_, h);
          if (done[w]) continue;
          const Vec3 carried = transport(h, nodes_[v].normal);
          const double confidence = nodes_[w].planeKnown ? std::abs(dot(carried, nodes_[w].normal)) : 1.0;
          queue.push({confidence, h, carried});
        }
      };
      reach(root);
      while (!queue.empty()) {
        const Step step = queue.top();
        queue.pop();
        const int w = headNode(edges_, step.half);
        if (done[w]) continue;
        Node &node = nodes_[w];
        if (!node.planeKnown) node.normal = step.carried;
        else if (dot(node.normal, step.carried) < 0) node.normal = node.normal * -1.0;
        reach(w);
      }
      ++parts;
    }
    for (int p = 0; p < parts; ++p) {
      Vec3 centre{0, 0, 0};
      int count = 0;
      for (int v = 0; v < static_cast<int>(nodes_.size()); ++v)
        if (part[v] == p) centre = centre + g_.points[nodes_[v].point], ++count;
      centre = centre * (1.0 / count);
      double outward = 0;
      for (int v = 0; v < static_cast<int>(nodes_.size()); ++v)
        if (part[v] == p) outward += dot(nodes_[v].normal, g_.points[nodes_[v].point] - centre);
      if (outward < 0)
        for (int v = 0; v < static_cast<int>(nodes_.size()); ++v)
          if (part[v] == p) nodes_[v].normal = nodes_[v].normal * -1.0;
    }
  }

  double angleAbout(const Node &node, const Vec3 &u, const Vec3 &d) const {
    const Vec3 w = cross(node.normal, u);
    return std::atan2(dot(d, w), dot(d, u));
  }

  /// Faces of the rotation system: arriving at a node, leave along the edge
  /// next clockwise (about the node normal) from the one arrived by, so the
  /// face lies to the left and its loop runs counter-clockwise seen from the
  /// normal side. Every half-edge is in exactly one loop.
  void traceFaces() {
    // The orders run counter-clockwise about the fan normal; where the
    // orientation turned a normal over, the order turns with it.
    for (Node &node : nodes_) {
      if (node.halves.size() < 3) continue;
      Vec3 fan{0, 0, 0};
      const auto &order = node.halves;
      for (std::size_t i = 0; i < order.size(); ++i) fan = fan + cross(direction_[order[i]], direction_[order[(i + 1) % order.size()]]);
      if (dot(fan, node.normal) < 0) std::reverse(node.halves.begin(), node.halves.end());
    }
    std::vector<bool> used(2 * edges_.size(), false);
    for (int start = 0; start < static_cast<int>(2 * edges_.size()); ++start) {
      if (edges_[start / 2].dangling || used[start]) continue;
      Loop loop;
      for (int h = start; !used[h];) {
        used[h] = true;
        loop.halves.push_back(h);
        const int reversedHalf = h ^ 1;
        const Node &at = nodes_[headNode(edges_, h)];
        const auto pos = std::find(at.halves.begin(), at.halves.end(), reversedHalf) - at.halves.begin();
        const int k = static_cast<int>(at.halves.size());
        const int next = at.halves[(pos - 1 + k) % k];
        loop.cornerSum += cornerAngle(at, reversedHalf, next);
        h = next;
      }
      loops_.push_back(std::move(loop));
    }
  }

  /// The face's angle at a node between the edge arrived by and the one
  /// left by: where more than two edges meet, the angle between them (the
  /// tour makes every sector less than a straight angle wide); at a node of
  /// two, turning clockwise about the normal, which tells the inside of a
  /// loop (less than 180°) from the outside.
  double cornerAngle(const Node &at, int arrivedBy, int leftBy) const {
    if (at.halves.size() >= 3) return angleBetween(direction_[arrivedBy], direction_[leftBy]);
    const Vec3 d = direction_[arrivedBy];
    const Vec3 u = normalized(d - at.normal * dot(d, at.normal));
    double corner = -angleAbout(at, u, direction_[leftBy]);
    if (corner <= 0) corner += 2 * kPi;
    return corner;
  }

  /// Pairs the half-edges at each node that continue each other, then
  /// follows the pairs into chains: one curve per chain.
  void fitCurves() {
    std::vector<int> continues(2 * edges_.size(), -1); // half leaving a node -> half arriving continues into
    for (const Node &node : nodes_) {
      struct Pair {
        double turn;
        int a, b;
      };
      std::vector<Pair> pairs;
      for (std::size_t i = 0; i < node.halves.size(); ++i)
        for (std::size_t j = i + 1; j < node.halves.size(); ++j) {
          const int a = node.halves[i], b = node.halves[j];
          const double turn = angleBetween(direction_[a], direction_[b] * -1.0);
          if (node.kind == NodeKind::Loop || turn < kStraightTurn) pairs.push_back({turn, a, b});
        }
      std::sort(pairs.begin(), pairs.end(), [](const Pair &x, const Pair &y) { return x.turn < y.turn; });
      for (const Pair &p : pairs)
        if (continues[p.a] < 0 && continues[p.b] < 0) continues[p.a] = p.b, continues[p.b] = p.a;
    }
    std::vector<bool> taken(edges_.size(), false);
    auto chainFrom = [&](int half) {
      // half: the first half-edge of the chain, leaving its start node.
      std::vector<int> chain;
      for (int h = half;;) {
        chain.push_back(h);
        taken[h / 2] = true;
        const int next = continues[h ^ 1];
        if (next < 0 || taken[next / 2]) break;
        h = next;
      }
      return chain;
    };
    for (int pass = 0; pass < 2; ++pass)
      for (int k = 0; k < static_cast<int>(edges_.size()); ++k) {
        if (edges_[k].dangling || taken[k]) continue;
        for (int h : {2 * k, 2 * k + 1}) {
          if (taken[k]) break;
          // First pass: chains from an end that continues nothing; then cycles.
          if (pass == 0 && continues[h] >= 0) continue;
          fitChain(chainFrom(h));
        }
      }
  }

  void fitChain(const std::vector<int> &chain) {
    std::vector<Vec3> points;
    std::vector<int> nodeAt; // index into points of each chain node
    for (int h : chain) {
      const auto q = halfEdgePoints(g_, edges_[h / 2], h % 2 == 1);
      if (points.empty()) points.push_back(q[0]);
      nodeAt.push_back(static_cast<int>(points.size()) - 1);
      points.insert(points.end(), q.begin() + 1, q.end());
    }
    nodeAt.push_back(static_cast<int>(points.size()) - 1);
    const bool closed = headNode(edges_, chain.back()) == tailNode(edges_, chain.front()) && closesSmoothly(chain);
    const std::vector<double> parameters = chordLengthParameters(points);
    std::vector<FitNode> fitNodes;
    for (std::size_t k = 0; k < nodeAt.size(); ++k) {
      const int node = k < chain.size() ? tailNode(edges_, chain[k]) : headNode(edges_, chain.back());
      FitNode f{parameters[nodeAt[k]], g_.points[nodes_[node].point], {0, 0, 0}};
      if (enforcesPlane(nodes_[node])) f.planeNormal = nodes_[node].planeNormal;
      if (closed && k + 1 == nodeAt.size()) f.planeNormal = {0, 0, 0}; // the closing constraint carries it
      fitNodes.push_back(f);
    }
    const int curve = static_cast<int>(curves_.size());
    FittedStroke fit;
    try {
      fit = fitStroke(points, parameters, fitNodes, closed, options_.fitTolerance * diagonal_, options_.fairing);
    } catch (const InputError &e) {
      // Degenerate data (all points of a chain coinciding): say where.
      throw InputError(file_, "curve " + std::to_string(curve) + " from " + formatPoint(points.front()) + " to " +
                                  formatPoint(points.back()),
                       e.reason());
    }
    curves_.push_back(fit.curve);
    SketchCurve summary;
    summary.pointCount = static_cast<int>(points.size());
    summary.controlPoints = static_cast<int>(fit.curve.controlPoints().size());
    summary.maxError = fit.maxError / diagonal_;
    summary.closed = closed;
    curveSummaries_.push_back(summary);
    for (std::size_t k = 0; k < chain.size(); ++k) {
      Edge &e = edges_[chain[k] / 2];
      e.curve = curve;
      const double a = parameters[nodeAt[k]], b = parameters[nodeAt[k + 1]];
      if (chain[k] % 2 == 0) e.parameterAtFrom = a, e.parameterAtTo = b;
      else e.parameterAtFrom = b, e.parameterAtTo = a;
    }
  }

  /// A chain that came back to its start node closes smoothly when the
  /// node continues its last edge into its first (a cycle of the pairing).
  bool closesSmoothly(const std::vector<int> &chain) const {
    const Node &node = nodes_[tailNode(edges_, chain.front())];
    if (node.kind == NodeKind::Loop) return true;
    return angleBetween(direction_[chain.front()], direction_[chain.back() ^ 1] * -1.0) < kStraightTurn;
  }

  bool enforcesPlane(const Node &node) const { return node.planeKnown && node.outOfPlane < kPlaneAngle; }

  struct Loop {
    std::vector<int> halves;
    double cornerSum = 0;
  };

  SideDescription sideOf(int half) const {
    const Edge &e = edges_[half / 2];
    return half % 2 == 0 ? SideDescription{e.curve, e.parameterAtFrom, e.parameterAtTo}
                         : SideDescription{e.curve, e.parameterAtTo, e.parameterAtFrom};
  }

  /// Sides of a loop: consecutive half-edges along one curve through a node
  /// of valence ≥ 3 where the face goes straight on form one side.
  std::vector<SideDescription> sidesOf(const Loop &loop) const {
    std::vector<SideDescription> sides;
    std::vector<int> endNodes;
    for (int h : loop.halves) {
      const SideDescription s = sideOf(h);
      if (!sides.empty()) {
        SideDescription &last = sides.back();
        const bool sameWay = (last.to > last.from) == (s.to > s.from);
        if (last.curve == s.curve && last.to == s.from && sameWay && nodes_[tailNode(edges_, h)].halves.size() >= 3) {
          last.to = s.to;
          continue;
        }
      }
      sides.push_back(s);
    }
    // The first and last may join too (the loop started inside a side).
    if (sides.size() > 2) {
      SideDescription &last = sides.back(), &first = sides.front();
      const bool sameWay = (last.to > last.from) == (first.to > first.from);
      if (last.curve == first.curve && last.to == first.from && sameWay &&
          nodes_[tailNode(edges_, loop.halves.front())].halves.size() >= 3) {
        first.from = last.from;
        sides.pop_back();
      }
    }
    if (sides.size() < 2) {
      sides.clear();
      for (int h : loop.halves) sides.push_back(sideOf(h));
    }
    return sides;
  }

  /// Per loop: it runs around a connected part that is a single cycle of
  /// edges (as many edges as nodes) while other parts exist. Such a cycle
  /// (a circle drawn alone beside a shape, the two rims of a tube with
  /// nothing along it) bounds a disc on one side only if nothing else meets
  /// its region, which the graph cannot tell: capping it would close a tube
  /// into two lids. With one part only it is the outline of one sheet and
  /// keeps its face.
  std::vector<bool> loneCycleLoops() const {
    std::vector<int> part(nodes_.size(), -1);
    int parts = 0;
    for (int start = 0; start < static_cast<int>(nodes_.size()); ++start) {
      if (part[start] >= 0 || !nodes_[start].faced) continue;
      std::vector<int> stack{start};
      part[start] = parts;
      while (!stack.empty()) {
        const int v = stack.back();
        stack.pop_back();
        for (int h : nodes_[v].halves) {
          const int w = headNode(edges_, h);
          if (part[w] < 0) part[w] = parts, stack.push_back(w);
        }
      }
      ++parts;
    }
    std::vector<int> nodeCount(parts, 0), edgeCount(parts, 0);
    for (int v = 0; v < static_cast<int>(nodes_.size()); ++v)
      if (part[v] >= 0) ++nodeCount[part[v]];
    for (const Edge &e : edges_)
      if (!e.dangling) ++edgeCount[part[e.from]];
    std::vector<bool> lone(loops_.size(), false);
    if (parts < 2) return lone;
    for (std::size_t k = 0; k < loops_.size(); ++k) {
      const int p = part[tailNode(edges_, loops_[k].halves.front())];
      lone[k] = edgeCount[p] == nodeCount[p];
    }
    return lone;
  }

  std::string loopName(const Loop &loop) const {
    std::string name = "loop through nodes";
    for (int h : loop.halves) name += " " + std::to_string(tailNode(edges_, h));
    return name;
  }

  SketchResult describe() {
    SketchResult result;
    result.diagonal = diagonal_;
    result.weldDistance = options_.weld * diagonal_;
    NetworkDescription &d = result.description;
    d.name = input_.name;
    d.curves = curves_;
    d.tolerance = 1e-6;
    result.curves = curveSummaries_;
    for (const Node &node : nodes_) {
      SketchNode s;
      s.position = g_.points[node.point];
      s.kind = node.kind;
      s.planeEnforced = enforcesPlane(node);
      result.nodes.push_back(s);
    }
    for (const Edge &e : edges_) ++result.nodes[e.from].valence, ++result.nodes[e.to].valence;
    for (const SketchNode &n : result.nodes) ++result.nodesByValence[n.valence];
    for (const Edge &e : edges_) {
      if (!e.dangling) {
        ++result.edges;
        continue;
      }
      const std::string stroke = e.stroke >= 0 && e.stroke < static_cast<int>(input_.strokeNames.size())
                                     ? input_.strokeNames[e.stroke]
                                     : "stroke " + std::to_string(e.stroke);
      result.dangling.push_back(stroke + " from " + formatPoint(g_.points[e.points.front()]) + " to " +
                                formatPoint(g_.points[e.points.back()]) +
                                (result.nodes[e.from].kind == NodeKind::FreeEnd || result.nodes[e.to].kind == NodeKind::FreeEnd
                                     ? " (a free end)"
                                     : " (on no cycle)"));
    }
    for (const Node &node : nodes_) result.facedNodes += node.faced ? 1 : 0;
    result.eulerCharacteristic = result.facedNodes - result.edges + static_cast<int>(loops_.size());
    const std::vector<bool> lone = loneCycleLoops();
    for (std::size_t k = 0; k < loops_.size(); ++k) {
      const Loop &loop = loops_[k];
      if (lone[k]) {
        result.notDiscs.push_back(loopName(loop) +
                                  ": a lone cycle of curves joined to no other part; the region it bounds may be "
                                  "a tube or handle with another part, not a disc (a stroke across makes discs)");
        continue;
      }
      const int corners = static_cast<int>(loop.halves.size());
      if (loop.cornerSum > corners * kPi + 1e-9) {
        result.openLoops.push_back(loopName(loop));
        continue;
      }
      FaceDescription face;
      face.sides = sidesOf(loop);
      face.name = "face " + std::to_string(d.faces.size());
      if (face.sides.size() > 8) {
        result.refusedFaces.push_back(loopName(loop) + ": " + std::to_string(face.sides.size()) +
                                      " sides (at most 8 are built)");
        continue;
      }
      ++result.facesBySides[static_cast<int>(face.sides.size())];
      d.faces.push_back(std::move(face));
    }
    return result;
  }

  const WeldedGraph &g_;
  const CurveGraph &input_;
  const SketchOptions &options_;
  double diagonal_;
  const std::string &file_;
  std::vector<int> nodeOfPoint_;
  std::vector<Node> nodes_;
  std::vector<Edge> edges_;
  std::vector<Vec3> direction_;
  std::vector<Loop> loops_;
  std::vector<BSplineCurve> curves_;
  std::vector<SketchCurve> curveSummaries_;
};

/// Step 6: the crease nodes and edges of the network the description builds.
void markCreases(SketchResult &result, const std::string &file) {
  if (result.description.faces.empty()) return;
  const Network network = Network::build(result.description, file);
  const std::vector<VertexFrame> frames = computeVertexFrames(network);
  for (int v = 0; v < static_cast<int>(network.vertices().size()); ++v) {
    if (!frames[v].crease) continue;
    const Vec3 p = network.vertices()[v].position;
    for (SketchNode &node : result.nodes)
      if (norm(node.position - p) <= 1e-9 * network.diagonal()) node.crease = true;
  }
  for (int e = 0; e < static_cast<int>(network.segments().size()); ++e) {
    const Segment &seg = network.segments()[e];
    if (seg.isBoundary()) continue;
    if (!isCreaseSegment(network, frames, e)) {
      ++result.g1Edges;
      continue;
    }
    result.creaseEdges.push_back("curve " + std::to_string(seg.sourceCurve) + " from " +
                                 formatPoint(network.vertices()[seg.start].position) + " to " +
                                 formatPoint(network.vertices()[seg.end].position));
  }
}

} // namespace
} // namespace graph

SketchResult networkFromCurveGraph(const CurveGraph &input, const SketchOptions &options, const std::string &file) {
  if (input.points.empty() || input.strokes.empty()) throw InputError(file, {}, "the curve graph has no strokes");
  BoundingBox box;
  for (std::size_t p = 0; p < input.points.size(); ++p) {
    if (!isFinite(input.points[p])) throw InputError(file, "point " + std::to_string(p + 1), "non-finite coordinates");
    box.add(input.points[p]);
  }
  for (std::size_t s = 0; s < input.strokes.size(); ++s)
    for (int index : input.strokes[s])
      if (index < 0 || index >= static_cast<int>(input.points.size()))
        throw InputError(file, "stroke " + std::to_string(s), "point index out of range");
  const double diagonal = box.diagonal();
  if (!(diagonal > 0)) throw InputError(file, {}, "the curve graph has no extent (all points coincide)");
  if (!(options.weld >= 0 && options.weld < 0.1)) throw InputError(file, {}, "the weld distance must be in [0, 0.1) of the diagonal");
  const graph::WeldedGraph welded = [&] {
    try {
      return graph::weldCurveGraph(input, options.weld * diagonal, diagonal);
    } catch (const InputError &e) {
      throw e.inFile(file);
    }
  }();
  SketchResult result = graph::Builder(welded, input, options, diagonal, file).run();
  graph::markCreases(result, file);
  return result;
}

} // namespace v1
} // namespace curvenet
