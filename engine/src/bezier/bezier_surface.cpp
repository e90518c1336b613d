// G¹ quintic Bézier construction (see bezier_surface.hpp for the method).
#include "bezier/bezier_surface.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {
namespace bezier {

namespace {

std::string faceName(int f) { return "face " + std::to_string(f); }

// ---- Boundary curves --------------------------------------------------------

/// Control points of a side curve as a cubic Bézier; throws unless the curve
/// is one polynomial Bézier span of degree ≤ 3.
std::vector<Vec3> cubicPoints(const BSplineCurve &curve, const std::string &element) {
  const int p = curve.degree();
  if (curve.isRational()) throw InputError("", element, "rational curves are not supported by the Bézier schemes");
  if (p > 3) throw InputError("", element, "curve of degree " + std::to_string(p) + "; the Bézier schemes need cubic Bézier curves");
  if (curve.controlPoints().size() != static_cast<size_t>(p + 1))
    throw InputError("", element, "curve has interior knots; the Bézier schemes need one cubic Bézier span per side");
  std::vector<Vec3> q = curve.controlPoints();
  while (q.size() < 4) q = elevate(q);
  return q;
}

std::vector<Vec3> quinticPoints(const std::vector<Vec3> &cubic) { return elevate(elevate(cubic)); }

// ---- Linear algebra on control points ---------------------------------------

struct Term {
  int var;
  double coef;
};
/// An affine expression in the 3D unknowns: constant + Σ coef · X_var.
struct Expr {
  Vec3 constant;
  std::vector<Term> terms;
  bool isConstant() const { return terms.empty(); }
};

Expr combine(const std::vector<double> &weights, const std::vector<Expr> &exprs) {
  Expr out;
  std::map<int, double> acc;
  for (size_t k = 0; k < exprs.size(); ++k) {
    if (weights[k] == 0) continue;
    out.constant += weights[k] * exprs[k].constant;
    for (const Term &t : exprs[k].terms) acc[t.var] += weights[k] * t.coef;
  }
  for (auto [v, c] : acc)
    if (c != 0) out.terms.push_back({v, c});
  return out;
}

/// One vector equation Σ coef X_var + Σ μ_m w_m = rhs.
struct Equation {
  std::vector<Term> vars;
  std::vector<std::pair<int, Vec3>> mus;
  Vec3 rhs;
};

struct Unknowns {
  std::vector<Vec3> value;
  std::vector<char> fixed;
  std::vector<double> mu, muScale;
  std::vector<char> muFixed;
  int addVar(const Vec3 &v) {
    value.push_back(v);
    fixed.push_back(0);
    return static_cast<int>(value.size()) - 1;
  }
  int addMu(double v, double scale, bool isFixed) {
    mu.push_back(v);
    muScale.push_back(scale);
    muFixed.push_back(isFixed);
    return static_cast<int>(mu.size()) - 1;
  }
  Vec3 eval(const Expr &e) const {
    Vec3 p = e.constant;
    for (const Term &t : e.terms) p += t.coef * value[t.var];
    return p;
  }
  Vec3 residual(const Equation &eq) const {
    Vec3 r = -eq.rhs;
    for (const Term &t : eq.vars) r += t.coef * value[t.var];
    for (const auto &[m, w] : eq.mus) r += mu[m] * w;
    return r;
  }
};

/// Solves the equations for their unfixed unknowns with the minimal change
/// (in the least-squares sense when inconsistent), then fixes them. Returns
/// the per-coordinate matrix of the 3D unknowns (for the vertex reports).
Eigen::MatrixXd solveStage(Unknowns &x, const std::vector<Equation> &eqs, std::vector<int> *varColumns = nullptr) {
  std::vector<int> vars, mus;
  std::map<int, int> varCol, muCol;
  for (const Equation &e : eqs) {
    for (const Term &t : e.vars)
      if (!x.fixed[t.var] && !varCol.count(t.var)) varCol[t.var] = static_cast<int>(vars.size()), vars.push_back(t.var);
    for (const auto &[m, w] : e.mus)
      if (!x.muFixed[m] && !muCol.count(m)) muCol[m] = static_cast<int>(mus.size()), mus.push_back(m);
  }
  const int rows = 3 * static_cast<int>(eqs.size()), cols = 3 * static_cast<int>(vars.size()) + static_cast<int>(mus.size());
  Eigen::MatrixXd twist = Eigen::MatrixXd::Zero(static_cast<int>(eqs.size()), static_cast<int>(vars.size()));
  if (varColumns) *varColumns = vars;
  if (cols == 0 || rows == 0) return twist;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, cols);
  Eigen::VectorXd b(rows);
  for (size_t r = 0; r < eqs.size(); ++r) {
    const Vec3 res = x.residual(eqs[r]);
    for (int c = 0; c < 3; ++c) b(3 * r + c) = -res[c];
    for (const Term &t : eqs[r].vars) {
      auto it = varCol.find(t.var);
      if (it == varCol.end()) continue;
      for (int c = 0; c < 3; ++c) A(3 * r + c, 3 * it->second + c) += t.coef;
      twist(static_cast<int>(r), it->second) += t.coef;
    }
    for (const auto &[m, w] : eqs[r].mus) {
      auto it = muCol.find(m);
      if (it == muCol.end()) continue;
      // μ = scale · ν: the minimal change is measured in ν, a length.
      for (int c = 0; c < 3; ++c) A(3 * r + c, 3 * static_cast<int>(vars.size()) + it->second) += w[c] * x.muScale[m];
    }
  }
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(A);
  cod.setThreshold(1e-11);
  const Eigen::VectorXd d = cod.solve(b);
  for (size_t v = 0; v < vars.size(); ++v) {
    x.value[vars[v]] += Vec3{d(3 * v), d(3 * v + 1), d(3 * v + 2)};
    x.fixed[vars[v]] = 1;
  }
  for (size_t m = 0; m < mus.size(); ++m) {
    x.mu[mus[m]] += x.muScale[mus[m]] * d(3 * static_cast<int>(vars.size()) + m);
    x.muFixed[mus[m]] = 1;
  }
  return twist;
}

// ---- The three-rectangle subdivision of a T-junction at a vertex -------------

/// Corner k of a face is straight when the loop runs on without turning.
int straightCorner(const Face &face) {
  for (int k = 0; k < face.sideCount(); ++k) {
    const FaceSide &prev = face.sides[(k + face.sideCount() - 1) % face.sideCount()], &next = face.sides[k];
    const Vec3 a = prev.curve.derivatives(1.0)[1], b = next.curve.derivatives(0.0)[1];
    if (angleBetween(a, b) < 1e-6) return k;
  }
  return -1;
}

QuinticPatch coonsPatch(const std::array<std::vector<Vec3>, 4> &cubicSides) {
  QuinticPatch patch;
  for (int k = 0; k < 4; ++k) {
    const std::vector<Vec3> q = quinticPoints(cubicSides[k]);
    for (int m = 0; m < 6; ++m) patch.at(k, m, 0) = q[m];
  }
  fillCoonsInterior(patch);
  return patch;
}

struct Subdivision {
  NetworkDescription description;
  std::vector<BezierFace> faces;
};

Subdivision subdivideTJunctionsAtVertices(const Network &network) {
  const NetworkDescription &in = network.description();
  Subdivision out;
  out.description = in;
  out.description.faces.clear();
  std::vector<FaceDescription> added;
  const int faces = static_cast<int>(network.faces().size());
  out.faces.resize(faces);
  std::vector<std::pair<int, int>> pendingIndex; // (input face, position in `added`)
  for (int f = 0; f < faces; ++f) {
    const Face &face = network.faces()[f];
    const int k = face.sideCount() == 4 ? straightCorner(face) : -1;
    BezierFace &bf = out.faces[f];
    if (k < 0) {
      bf.constructionFaces = {static_cast<int>(out.description.faces.size())};
      bf.quads = {{Vec2{0, 0}, Vec2{1, 0}, Vec2{1, 1}, Vec2{0, 1}}};
      out.description.faces.push_back(in.faces[f]);
      continue;
    }
    // Rotate so that the straight corner is corner 1 (between sides 0 and 1).
    const int r = (k + 3) % 4;
    bf.rotation = r;
    auto side = [&](int i) { return face.sides[(i + r) % 4]; };
    auto sideDesc = [&](int i) { return in.faces[f].sides[(i + r) % 4]; };
    std::array<std::vector<Vec3>, 4> cubic;
    for (int i = 0; i < 4; ++i) cubic[i] = cubicPoints(side(i).curve, faceName(f) + " side " + std::to_string((i + r) % 4));
    const QuinticPatch coons = coonsPatch(cubic);
    const Vec3 T = side(0).curve.point(1.0);
    const auto centre = coons.evaluate(0.5, 0.5);
    const Vec3 O = centre.point, nO = normalized(cross(centre.du, centre.dv));
    auto inPlane = [&](const Vec3 &d) { return normalized(d - dot(d, nO) * nO); };
    // Leave T opposite to the curve that ends there (an X-node with two
    // collinear pairs); without one, towards O across the straight curve.
    const Vec3 along = normalized(side(0).curve.derivatives(1.0)[1]);
    Vec3 dT;
    const Vertex &vt = network.vertices()[side(0).endVertex];
    for (const Vec3 &t : vt.tangents)
      if (std::abs(dot(t, along)) < 1 - 1e-6) dT = -t;
    if (squaredNorm(dT) == 0) dT = normalized((O - T) - dot(O - T, along) * along);
    const SideDescription s2 = sideDesc(2), s3 = sideDesc(3);
    const double mid2 = 0.5 * (s2.from + s2.to), mid3 = 0.5 * (s3.from + s3.to);
    const Vec3 M2 = in.curves[s2.curve].point(mid2), M1 = in.curves[s3.curve].point(mid3);
    const Vec3 d1 = normalized(coons.evaluate(0.0, 0.5).du), d2 = normalized(-coons.evaluate(0.5, 1.0).dv);
    auto hermite = [&](const Vec3 &P, const Vec3 &dP, const Vec3 &Q) {
      const double L = norm(Q - P);
      return BSplineCurve::bezier({P, P + dP * (L / 3), O - inPlane(Q - P) * (L / 3), Q});
    };
    const int cT = static_cast<int>(out.description.curves.size());
    out.description.curves.push_back(hermite(T, dT, O));
    out.description.curves.push_back(hermite(M1, d1, O));
    out.description.curves.push_back(hermite(M2, d2, O));
    const int c1 = cT + 1, c2 = cT + 2;
    const SideDescription s0 = sideDesc(0), s1 = sideDesc(1);
    const std::string name = face.name;
    added.push_back({{s0, {cT, 0, 1}, {c1, 1, 0}, {s3.curve, mid3, s3.to}}, name + " (1/3)"});
    added.push_back({{s1, {s2.curve, s2.from, mid2}, {c2, 0, 1}, {cT, 1, 0}}, name + " (2/3)"});
    added.push_back({{{c1, 0, 1}, {c2, 1, 0}, {s2.curve, mid2, s2.to}, {s3.curve, s3.from, mid3}}, name + " (3/3)"});
    const Vec2 A{0, 0}, Tq{1, 0}, B{1, 1}, X{0, 1}, Oq{0.5, 0.5}, M1q{0, 0.5}, M2q{0.5, 1};
    bf.quads = {{A, Tq, Oq, M1q}, {Tq, B, M2q, Oq}, {M1q, Oq, M2q, X}};
    for (int j = 0; j < 3; ++j) pendingIndex.push_back({f, static_cast<int>(added.size()) - 3 + j});
  }
  for (auto [f, j] : pendingIndex) {
    out.faces[f].constructionFaces.push_back(static_cast<int>(out.description.faces.size()));
    out.description.faces.push_back(added[j]);
  }
  return out;
}

// ---- Edge units -----------------------------------------------------------------

struct Unit {
  std::string element;
  std::array<Vec3, 4> q;     ///< cubic boundary, in the unit's direction
  std::array<Expr, 6> p, r;  ///< first inner rows of the two sides
  int startVertex = -1, endVertex = -1;
  int rowFace = -1, rowSide = -1; ///< T-junction side: whose row r is (copied once all rows are final)
  bool tStart = false, tEnd = false;
  std::vector<double> lambda;
  std::vector<int> mu;
  std::vector<Equation> eqs; ///< k = 0 … a + 5
  std::vector<Equation> pins; ///< T-junction side: V(c) on the curve ending at the T
  double length = 1;
};

Vec3 rowPoint(const QuinticPatch &patch, int side, int m) { return patch.at(side, m, 1); }

/// The 4-sided check, and the network the patches are built on: the input,
/// or for G¹ with a T-junction at a vertex its three-rectangle subdivision.
BezierSurfaceData constructionFor(const Network &network, bool g1) {
  BezierSurfaceData data;
  for (size_t f = 0; f < network.faces().size(); ++f)
    if (network.faces()[f].sideCount() != 4)
      throw InputError("", faceName(static_cast<int>(f)),
                       std::to_string(network.faces()[f].sideCount()) +
                           " sides; the Bézier schemes need 4-sided faces (a side may span a T-node)");
  bool subdivide = false;
  if (g1)
    for (const Face &face : network.faces()) subdivide = subdivide || straightCorner(face) >= 0;
  if (subdivide) {
    Subdivision s = subdivideTJunctionsAtVertices(network);
    data.construction = Network::build(s.description);
    data.faces = std::move(s.faces);
  } else {
    data.construction = network;
    for (size_t f = 0; f < network.faces().size(); ++f)
      data.faces.push_back({{static_cast<int>(f)}, {{Vec2{0, 0}, Vec2{1, 0}, Vec2{1, 1}, Vec2{0, 1}}}, 0});
  }
  return data;
}

/// k = 0 and k = a + 5 of an edge unit: (R − P) λ + w μ' = Q − P in the
/// tangent plane at `vertex`; {λ, μ'}, or InputError when the tangents there
/// are not coplanar.
std::array<double, 2> endValues(const Vec3 &P, const Vec3 &R, const Vec3 &w, const Vec3 &Q, int vertex, double length) {
  Eigen::Matrix<double, 3, 2> A;
  Eigen::Vector3d rhs;
  for (int c = 0; c < 3; ++c) A(c, 0) = R[c] - P[c], A(c, 1) = w[c], rhs(c) = Q[c] - P[c];
  const Eigen::Vector2d s = A.colPivHouseholderQr().solve(rhs);
  if ((A * s - rhs).norm() > 1e-8 * length || !std::isfinite(s(0)))
    throw InputError("", "vertex " + std::to_string(vertex),
                     "the curve tangents there are not coplanar (or two coincide): no G1 surface with these "
                     "curves unchanged ([OSK11], case 4-a)");
  return {s(0), s(1)};
}

/// The G¹ construction of [OSK11] over one construction network, in the
/// order of its steps (build()): Coons patches whose interior cells are the
/// unknowns; edge units (T-junction sides, then ordinary interior edges) with
/// their λ, μ and G¹ equations; the vertex systems; the edge systems; the
/// residual of every equation and the final control nets.
class BezierConstruction {
public:
  explicit BezierConstruction(BezierSurfaceData &data)
      : data_(data), net_(data.construction), faceCount_(static_cast<int>(net_.faces().size())) {}

  void startFromCoonsPatches();
  void build() {
    replaced_.assign(x_.value.size(), 0);
    inLongUnit_.assign(net_.segments().size(), 0);
    for (int f = 0; f < faceCount_; ++f)
      for (int k = 0; k < 4; ++k) addTJunctionUnit(f, k);
    for (Unit &u : units_)
      for (int m = 0; m < 6; ++m) u.r[m] = cell(u.rowFace, u.rowSide, m, 1);
    addInteriorEdgeUnits();
    for (Unit &u : units_) addEquations(u);
    solveVertexSystems();
    solveEdgeSystems();
    finish();
  }

private:
  Expr &cell(int f, int side, int m, int depth) {
    auto [i, j] = QuinticPatch::sideIndex(side, m, depth);
    return grid_[f][i][j];
  }
  int sideOfSegment(int f, int e) const {
    const Face &face = net_.faces()[f];
    for (int k = 0; k < 4; ++k)
      for (int s : face.sides[k].segments)
        if (s == e) return k;
    return -1;
  }

  struct SubFace {
    int face, side; ///< a face across a T-junction side, and its side there
  };
  using Restrictions = std::vector<std::vector<std::vector<double>>>;
  void addTJunctionUnit(int f, int k);
  std::array<Expr, 6> virtualRow(const std::vector<SubFace> &subs, const Restrictions &R);
  void substituteSubRows(Unit &u, const std::vector<SubFace> &subs, const Restrictions &R, const std::array<Expr, 6> &V,
                         const std::string &element);
  void addInteriorEdgeUnits();
  void addEquations(Unit &u);
  void solveVertexSystems();
  void solveEdgeSystems();
  void finish();

  BezierSurfaceData &data_;
  const Network &net_;
  const int faceCount_;
  Unknowns x_;
  std::vector<std::array<std::array<Expr, 6>, 6>> grid_; ///< per face, its 6 × 6 control net as expressions
  std::vector<Unit> units_;
  std::set<int> tVertices_;
  std::vector<char> inLongUnit_; ///< per segment: part of a T-junction side's unit
  std::vector<char> replaced_;   ///< per unknown: substituted by a virtual row
  std::vector<std::vector<char>> used_; ///< per unit and equation: already solved in a stage
};

/// Step 1: Coons patches; boundary cells are constants, interior cells unknowns.
void BezierConstruction::startFromCoonsPatches() {
  grid_.resize(faceCount_);
  data_.patches.resize(faceCount_);
  for (int f = 0; f < faceCount_; ++f) {
    const Face &face = net_.faces()[f];
    std::array<std::vector<Vec3>, 4> cubic;
    for (int k = 0; k < 4; ++k) cubic[k] = cubicPoints(face.sides[k].curve, faceName(f) + " side " + std::to_string(k));
    data_.patches[f] = coonsPatch(cubic);
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) {
        Expr &e = grid_[f][i][j];
        if (i == 0 || j == 0 || i == 5 || j == 5) e.constant = data_.patches[f].net[i][j];
        else e.terms = {{x_.addVar(data_.patches[f].net[i][j]), 1.0}};
      }
  }
}

/// Step 2: a T-junction on a boundary — side k of face f spanning two
/// segments with faces across — becomes one unit: a virtual row V across the
/// side, of which the sub-faces' first inner rows become restrictions.
void BezierConstruction::addTJunctionUnit(int f, int k) {
  const FaceSide &side = net_.faces()[f].sides[k];
  if (side.segments.size() < 2) return;
  const std::string element = faceName(f) + " side " + std::to_string(k);
  int others = 0;
  for (int e : side.segments) others += !net_.segments()[e].isBoundary();
  if (others == 0) return;
  if (others != static_cast<int>(side.segments.size()))
    throw InputError("", element, "a T-node side with faces across only part of it is not supported");
  if (side.segments.size() > 2)
    throw InputError("", element, "more than one T-junction on one side is not supported ([OSK11], future work)");
  Unit u;
  u.element = element + " (T-junction side)";
  const std::vector<Vec3> q = cubicPoints(side.curve, element);
  std::copy(q.begin(), q.end(), u.q.begin());
  u.startVertex = side.startVertex;
  u.endVertex = side.endVertex;
  u.rowFace = f, u.rowSide = k;
  // Sub-face j covers [b_j, b_{j+1}] of the side and runs it backwards.
  std::vector<double> b{0.0};
  for (double t : side.breaks) b.push_back(t);
  b.push_back(1.0);
  std::vector<SubFace> subs;
  for (size_t j = 0; j < side.segments.size(); ++j) {
    const Segment &seg = net_.segments()[side.segments[j]];
    const int g = seg.faces[0] == f ? seg.faces[1] : seg.faces[0];
    const int kk = sideOfSegment(g, side.segments[j]);
    if (net_.faces()[g].sides[kk].segments.size() != 1)
      throw InputError("", element, "T-node sides facing each other are not supported");
    subs.push_back({g, kk});
    inLongUnit_[side.segments[j]] = 1;
  }
  for (size_t j = 0; j + 1 < side.segments.size(); ++j) {
    const Segment &seg = net_.segments()[side.segments[j]];
    tVertices_.insert(side.segmentReversed[j] ? seg.start : seg.end);
  }
  Restrictions R;
  for (size_t j = 0; j < subs.size(); ++j) R.push_back(restrictionMatrix(5, b[j], b[j + 1]));
  const std::array<Expr, 6> V = virtualRow(subs, R);
  substituteSubRows(u, subs, R, V, element);
  // V's cells must not be reused: the arrays above were copied.
  for (int m = 0; m < 6; ++m) u.p[m] = V[m];
  units_.push_back(std::move(u));
}

/// The virtual row across a T-junction side: its ends fixed by the outer
/// sub-faces' rows, its four inner points new unknowns that start as the
/// least-squares fit of the sub-faces' Coons rows (R[j]: the restriction to
/// sub-face j's part of the side).
std::array<Expr, 6> BezierConstruction::virtualRow(const std::vector<SubFace> &subs, const Restrictions &R) {
  std::array<Expr, 6> V;
  V[0].constant = cell(subs.front().face, subs.front().side, 5, 1).constant;
  V[5].constant = cell(subs.back().face, subs.back().side, 0, 1).constant;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(6 * static_cast<int>(subs.size()), 4);
  Eigen::MatrixXd rhs(6 * static_cast<int>(subs.size()), 3);
  for (size_t j = 0; j < subs.size(); ++j)
    for (int m = 0; m < 6; ++m) {
      const int row = 6 * static_cast<int>(j) + m;
      const Vec3 target = rowPoint(data_.patches[subs[j].face], subs[j].side, 5 - m);
      Vec3 known = R[j][m][0] * V[0].constant + R[j][m][5] * V[5].constant;
      for (int n = 1; n < 5; ++n) M(row, n - 1) = R[j][m][n];
      for (int c = 0; c < 3; ++c) rhs(row, c) = target[c] - known[c];
    }
  const Eigen::MatrixXd fit = M.colPivHouseholderQr().solve(rhs);
  for (int n = 1; n < 5; ++n) V[n].terms = {{x_.addVar({fit(n - 1, 0), fit(n - 1, 1), fit(n - 1, 2)}), 1.0}};
  return V;
}

/// Each sub-face's first inner row becomes its restriction of V (those
/// unknowns are dropped); the row's ends, boundary points, become pins of
/// the unit where they depend on V.
void BezierConstruction::substituteSubRows(Unit &u, const std::vector<SubFace> &subs, const Restrictions &R,
                                           const std::array<Expr, 6> &V, const std::string &element) {
  const std::vector<Expr> Vlist(V.begin(), V.end());
  for (size_t j = 0; j < subs.size(); ++j)
    for (int m = 0; m < 6; ++m) {
      const Expr e = combine(R[j][m], Vlist);
      Expr &target = cell(subs[j].face, subs[j].side, 5 - m, 1);
      if (m == 0 || m == 5) {
        // At A and B the ends are V₀, V₅; at the T they pin V(c) to the
        // curve ending there.
        if (!e.isConstant()) {
          Equation pin;
          pin.vars = e.terms;
          pin.rhs = target.constant - e.constant;
          u.pins.push_back(pin);
        }
        continue;
      }
      CURVENET_CHECK(target.terms.size() == 1, element);
      if (replaced_[target.terms[0].var])
        throw InputError("", faceName(subs[j].face), "two adjacent sides on T-junction sides are not supported");
      replaced_[target.terms[0].var] = 1;
      x_.fixed[target.terms[0].var] = 1;
      target = e;
    }
}

/// Step 3: ordinary interior edges, one unit per segment.
void BezierConstruction::addInteriorEdgeUnits() {
  for (size_t e = 0; e < net_.segments().size(); ++e) {
    const Segment &seg = net_.segments()[e];
    if (seg.isBoundary() || inLongUnit_[e]) continue;
    Unit u;
    u.element = "segment " + std::to_string(e) + " (curve " + std::to_string(seg.sourceCurve) + ")";
    const std::vector<Vec3> q = cubicPoints(seg.curve, u.element);
    std::copy(q.begin(), q.end(), u.q.begin());
    u.startVertex = seg.start;
    u.endVertex = seg.end;
    for (int s = 0; s < 2; ++s) {
      const int f = seg.faces[s], k = sideOfSegment(f, static_cast<int>(e));
      const bool reversed = net_.faces()[f].sides[k].segmentReversed[0];
      for (int m = 0; m < 6; ++m) (s == 0 ? u.p : u.r)[m] = cell(f, k, reversed ? 5 - m : m, 1);
    }
    units_.push_back(std::move(u));
  }
}

/// Step 4: λ and μ of a unit, and its equations k = 0 … a + 5.
void BezierConstruction::addEquations(Unit &u) {
  u.tStart = tVertices_.count(u.startVertex) > 0;
  u.tEnd = tVertices_.count(u.endVertex) > 0;
  u.length = norm(u.q[1] - u.q[0]) + norm(u.q[2] - u.q[1]) + norm(u.q[3] - u.q[2]);
  const auto [l0, m0] = endValues(u.p[0].constant, u.r[0].constant, -(u.q[1] - u.q[0]), u.q[0], u.startVertex, u.length);
  const auto [l1, nu1] = endValues(u.p[5].constant, u.r[5].constant, u.q[3] - u.q[2], u.q[3], u.endVertex, u.length);
  const double m1 = 1 - nu1;
  u.lambda = {l0};
  if (u.tStart) u.lambda.push_back(l0); // flat λ at a T-junction: λ₀ = λ₁
  if (u.tEnd) u.lambda.push_back(l1);
  u.lambda.push_back(l1);
  const int a = static_cast<int>(u.lambda.size()) - 1, bdeg = a + 3, n = a + 5;
  for (int i = 0; i <= bdeg; ++i) u.mu.push_back(x_.addMu(m0 + (m1 - m0) * i / bdeg, 1.0 / u.length, i == 0 || i == bdeg));
  for (int k = 0; k <= n; ++k) {
    std::vector<double> wp;
    std::vector<Expr> ex;
    for (int i = std::max(0, k - 5); i <= std::min(a, k); ++i) {
      const double w = binomial(a, i) * binomial(5, k - i) / binomial(n, k);
      ex.push_back(u.p[k - i]);
      wp.push_back(w * (1 - u.lambda[i]));
      ex.push_back(u.r[k - i]);
      wp.push_back(w * u.lambda[i]);
    }
    const Expr lhs = combine(wp, ex);
    Equation eq;
    eq.vars = lhs.terms;
    eq.rhs = -lhs.constant;
    for (int i = std::max(0, k - 2); i <= std::min(bdeg, k); ++i) {
      const int l = k - i;
      const double v = binomial(bdeg, i) * binomial(2, l) / binomial(n, k);
      eq.rhs += v * u.q[l];
      eq.mus.push_back({u.mu[i], -v * (u.q[l + 1] - u.q[l])});
    }
    u.eqs.push_back(eq);
  }
}

/// Step 5: the vertex systems (each unit's equation next to the vertex),
/// except at T-junctions, which the subdivision settles; one report each.
void BezierConstruction::solveVertexSystems() {
  used_.resize(units_.size());
  for (size_t i = 0; i < units_.size(); ++i) used_[i].assign(units_[i].eqs.size(), 0);
  const double diagonal = net_.diagonal();
  for (size_t v = 0; v < net_.vertices().size(); ++v) {
    if (tVertices_.count(static_cast<int>(v))) continue;
    std::vector<Equation> eqs;
    for (size_t i = 0; i < units_.size(); ++i) {
      Unit &u = units_[i];
      const int last = static_cast<int>(u.eqs.size()) - 1;
      if (u.startVertex == static_cast<int>(v)) eqs.push_back(u.eqs[1]), used_[i][1] = 1;
      if (u.endVertex == static_cast<int>(v)) eqs.push_back(u.eqs[last - 1]), used_[i][last - 1] = 1;
    }
    if (eqs.empty()) continue;
    VertexSystemReport report;
    report.vertex = static_cast<int>(v);
    report.equations = static_cast<int>(eqs.size());
    std::vector<int> columns;
    const Eigen::MatrixXd M = solveStage(x_, eqs, &columns);
    report.twists = static_cast<int>(columns.size());
    const bool closed = !net_.vertices()[v].onBoundary;
    if (closed && M.rows() == M.cols() && M.rows() > 0) {
      double hadamard = 1;
      for (int r = 0; r < M.rows(); ++r) hadamard *= M.row(r).norm();
      report.determinant = M.determinant() / hadamard;
      report.branch = std::abs(report.determinant) < 1e-9 ? VertexSystemReport::Branch::Singular
                                                          : VertexSystemReport::Branch::Regular;
    }
    for (const Equation &e : eqs) report.residual = std::max(report.residual, norm(x_.residual(e)) / diagonal);
    data_.vertexSystems.push_back(report);
  }
}

/// Step 6: the edge systems — T-junction sides first (they settle the
/// sub-faces' rows and the twists at the T), then every other edge.
void BezierConstruction::solveEdgeSystems() {
  auto edgeStage = [&](size_t i, const std::vector<Equation> &extra) {
    std::vector<Equation> eqs = extra;
    for (size_t k = 1; k + 1 < units_[i].eqs.size(); ++k)
      if (!used_[i][k]) eqs.push_back(units_[i].eqs[k]), used_[i][k] = 1;
    solveStage(x_, eqs);
  };
  for (size_t i = 0; i < units_.size(); ++i)
    if (!units_[i].pins.empty()) edgeStage(i, units_[i].pins);
  for (size_t i = 0; i < units_.size(); ++i)
    if (units_[i].pins.empty()) edgeStage(i, {});
}

/// Step 7: every equation, k = 0 … a + 5, and the pins: how exactly G¹
/// holds; then the solved interior cells into the control nets.
void BezierConstruction::finish() {
  const double diagonal = net_.diagonal();
  for (const Unit &u : units_) {
    for (const Equation &e : u.eqs)
      data_.maxEquationResidual = std::max(data_.maxEquationResidual, norm(x_.residual(e)) / diagonal);
    for (const Equation &e : u.pins)
      data_.maxEquationResidual = std::max(data_.maxEquationResidual, norm(x_.residual(e)) / diagonal);
  }
  for (int f = 0; f < faceCount_; ++f)
    for (int i = 1; i < 5; ++i)
      for (int j = 1; j < 5; ++j) data_.patches[f].net[i][j] = x_.eval(grid_[f][i][j]);
}

} // namespace

BezierSurfaceData buildBezierSurface(const Network &network, bool g1) {
  BezierSurfaceData data = constructionFor(network, g1);
  BezierConstruction construction(data);
  construction.startFromCoonsPatches();
  if (g1) construction.build();
  return data;
}

QuinticPatch::Point evaluateBezierFace(const BezierSurfaceData &data, int face, double u, double v) {
  const BezierFace &bf = data.faces.at(face);
  if (bf.constructionFaces.size() == 1) return data.patches[bf.constructionFaces[0]].evaluate(u, v);
  // Into the subdivision frame: one quarter turn back per rotation step,
  // (u, v) → (v, 1 − u), carrying the Jacobian d(u',v')/d(u,v).
  double U = u, W = v;
  Eigen::Matrix2d J = Eigen::Matrix2d::Identity();
  Eigen::Matrix2d step;
  step << 0, 1, -1, 0;
  for (int i = 0; i < bf.rotation; ++i) {
    const double nu = W, nw = 1 - U;
    U = nu, W = nw;
    J = step * J;
  }
  // Find the quad and invert its bilinear map by Newton.
  int best = 0;
  double bestOut = INFINITY, bs = 0, bt = 0;
  for (size_t q = 0; q < bf.quads.size(); ++q) {
    const auto &c = bf.quads[q];
    double s = 0.5, t = 0.5;
    for (int it = 0; it < 30; ++it) {
      const Vec2 P = (1 - s) * (1 - t) * c[0] + s * (1 - t) * c[1] + s * t * c[2] + (1 - s) * t * c[3];
      const Vec2 Ps = (1 - t) * (c[1] - c[0]) + t * (c[2] - c[3]);
      const Vec2 Pt = (1 - s) * (c[3] - c[0]) + s * (c[2] - c[1]);
      const Vec2 r = Vec2{U, W} - P;
      const double det = cross(Ps, Pt);
      const double ds = cross(r, Pt) / det, dt = cross(Ps, r) / det;
      s += ds, t += dt;
      if (std::abs(ds) + std::abs(dt) < 1e-15) break;
    }
    const double out = std::max({-s, s - 1, -t, t - 1, 0.0});
    if (out < bestOut) bestOut = out, best = static_cast<int>(q), bs = s, bt = t;
  }
  const auto &c = bf.quads[best];
  bs = std::clamp(bs, 0.0, 1.0), bt = std::clamp(bt, 0.0, 1.0);
  const Vec2 Ps = (1 - bt) * (c[1] - c[0]) + bt * (c[2] - c[3]);
  const Vec2 Pt = (1 - bs) * (c[3] - c[0]) + bs * (c[2] - c[1]);
  Eigen::Matrix2d D;
  D << Ps.x, Pt.x, Ps.y, Pt.y; // d(U,W)/d(s,t)
  const Eigen::Matrix2d G = D.inverse() * J; // d(s,t)/d(u,v)
  const QuinticPatch::Point p = data.patches[bf.constructionFaces[best]].evaluate(bs, bt);
  return {p.point, G(0, 0) * p.du + G(1, 0) * p.dv, G(0, 1) * p.du + G(1, 1) * p.dv};
}

} // namespace bezier
} // namespace v1
} // namespace curvenet
