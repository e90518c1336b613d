// Per-vertex network analysis (curvenet/analysis.hpp): [HPS09] eqs. (3), (6),
// (26), Lemma 3 and the [SV14] Sec. 2 curvature fit, on the curve ends of a
// built Network.
#include "curvenet/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>

#include "analysis/vertex_curvature.hpp"
#include "analysis/vertex_frames.hpp"
#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

const char *toString(VertexVerdict verdict) {
  switch (verdict) {
  case VertexVerdict::G2Admissible: return "G2-admissible";
  case VertexVerdict::G1Admissible: return "G1-admissible";
  case VertexVerdict::NeedsTweaking: return "needs-tweaking";
  case VertexVerdict::NoTangentPlane: return "no-tangent-plane";
  }
  return "?";
}

namespace {

constexpr double pi = std::numbers::pi;

void requireOptions(const AnalysisOptions &o) {
  if (!(o.curvatureTolerance > 0) || !std::isfinite(o.curvatureTolerance))
    throw InputError("", "curvature tolerance", "must be a positive number");
  if (!(o.tangentTolerance > 0) || !std::isfinite(o.tangentTolerance))
    throw InputError("", "tangent tolerance", "must be a positive number");
  if (!(o.straightTolerance > 0 && o.straightTolerance < 0.5))
    throw InputError("", "straight tolerance", "must be in (0, 0.5) radians");
}

/// The local frame's x axis at a vertex with normal n: the first end's
/// tangent t0 projected into the plane.
Vec3 tangentPlaneAxis(const Vec3 &n, const Vec3 &t0) {
  Vec3 x = normalized(t0 - dot(t0, n) * n);
  if (squaredNorm(x) == 0) { // a tangent along the normal: any perpendicular will do
    x = normalized(cross(n, std::abs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
  }
  return x;
}

/// The curve ends at vertex v in the order of Vertex::segments, with their
/// angles ω about the normal n from the x axis (x, y = n × x) and their
/// normal curvatures. A closed segment is listed twice, first for its start
/// (the network builder's convention).
std::vector<CurveEnd> curveEndsAt(const Network &network, int v, const Vec3 &n, const Vec3 &x, const Vec3 &y) {
  const Vertex &vertex = network.vertices()[v];
  std::vector<CurveEnd> ends;
  std::vector<int> seenClosed;
  for (size_t i = 0; i < vertex.segments.size(); ++i) {
    const int s = vertex.segments[i];
    const Segment &seg = network.segments()[s];
    bool atStart = seg.start == v;
    if (seg.start == seg.end) {
      atStart = std::find(seenClosed.begin(), seenClosed.end(), s) == seenClosed.end();
      if (atStart) seenClosed.push_back(s);
    }
    const auto d = seg.curve.derivatives(atStart ? 0.0 : 1.0);
    const double speed2 = squaredNorm(d[1]);
    if (!(speed2 > 1e-24 * network.diagonal() * network.diagonal()))
      throw InputError("", "vertex " + std::to_string(v),
                       "curve " + std::to_string(seg.sourceCurve) +
                           " has zero speed there, so its normal curvature is undefined; reparameterize it");
    CurveEnd end;
    end.segment = s;
    end.atSegmentStart = atStart;
    end.sourceCurve = seg.sourceCurve;
    end.sourceParameter = atStart ? seg.sourceFrom : seg.sourceTo;
    end.towardsLargerParameter = atStart;
    end.tangent = vertex.tangents[i];
    // The first end defines the x axis: exactly 0, so that rounding never
    // wraps it to 2π and reorders the ends.
    const double omega = i == 0 ? 0.0 : std::atan2(dot(end.tangent, y), dot(end.tangent, x));
    end.omega = omega < 0 ? omega + 2 * pi : omega;
    // κ^n = c''·n / |c'|²: invariant to the segment's affine reparameterization
    // and to its direction, so the segment on [0, 1] serves.
    end.normalCurvature = finiteNormalCurvature(dot(d[2], n) / speed2, v, seg.sourceCurve);
    ends.push_back(end);
  }
  return ends;
}

/// Independent curves: pairs the most opposite tangents greedily, exactly
/// as Network::build counts them ([SV14] Fig. 1: an X is two curves), and
/// numbers each end's curve (CurveEnd::independentCurve). Returns how many.
int numberIndependentCurves(std::vector<CurveEnd> &ends, double straightTolerance) {
  const int m = int(ends.size());
  std::vector<int> partner(m, -1);
  for (;;) {
    double best = pi - straightTolerance;
    int bi = -1, bj = -1;
    for (int i = 0; i < m; ++i)
      for (int j = i + 1; j < m; ++j) {
        if (partner[i] >= 0 || partner[j] >= 0) continue;
        const double angle = angleBetween(ends[i].tangent, ends[j].tangent);
        if (angle > best) best = angle, bi = i, bj = j;
      }
    if (bi < 0) break;
    partner[bi] = bj, partner[bj] = bi;
  }
  int curves = 0;
  for (int i = 0; i < m; ++i)
    if (partner[i] < 0 || partner[i] > i) {
      ends[i].independentCurve = curves;
      if (partner[i] >= 0) ends[partner[i]].independentCurve = curves;
      ++curves;
    }
  return curves;
}

/// [SV14] Sec. 2 counts a curve passing through once: one direction and the
/// mean normal curvature (its least-squares value) per independent curve,
/// then the bounded fit over those (a near-X or other ill-conditioned fit
/// must not hand the tweak a curvature far beyond what the curves show,
/// vertex_curvature.hpp).
BoundedCurvatureFit fitPerIndependentCurve(const std::vector<CurveEnd> &ends, int curves,
                                           const FitOptions &fitOptions) {
  std::vector<double> curveOmega(curves), curveKappa(curves, 0.0), curveEnds(curves, 0.0);
  for (const CurveEnd &end : ends) {
    const int c = end.independentCurve;
    if (curveEnds[c] == 0) curveOmega[c] = end.omega;
    curveKappa[c] += end.normalCurvature;
    curveEnds[c] += 1;
  }
  for (int c = 0; c < curves; ++c) curveKappa[c] /= curveEnds[c];
  return fitBoundedCurvature(curveOmega, curveKappa, fitOptions);
}

VertexVerdict verdictOf(const VertexAnalysis &a, const AnalysisOptions &options) {
  if (a.tangentResidual > options.tangentTolerance) return VertexVerdict::NoTangentPlane;
  if (a.eulerResidualRelative <= options.curvatureTolerance) return VertexVerdict::G2Admissible;
  if (!a.enclosureApplies || a.enclosureResidualRelative <= options.curvatureTolerance)
    return VertexVerdict::G1Admissible;
  return VertexVerdict::NeedsTweaking;
}

VertexAnalysis analyzeWithFrame(const Network &network, int v, const VertexFrame &frame,
                                const AnalysisOptions &options) {
  const Vertex &vertex = network.vertices()[v];
  VertexAnalysis out;
  out.vertex = v;
  out.position = vertex.position;
  out.normal = frame.normal;
  out.tangentResidual = frame.residualAngle;
  out.valence = vertex.valence;
  out.onBoundary = vertex.onBoundary;
  const Vec3 n = frame.normal;
  const Vec3 x = tangentPlaneAxis(n, vertex.tangents.front()), y = cross(n, x);
  out.xAxis = x;
  out.ends = curveEndsAt(network, v, n, x, y);
  out.independentCurves = numberIndependentCurves(out.ends, options.straightTolerance);

  // The ends in order about the normal and the angles ψ between neighbours.
  const int m = int(out.ends.size());
  std::stable_sort(out.ends.begin(), out.ends.end(),
                   [](const CurveEnd &a, const CurveEnd &b) { return a.omega < b.omega; });
  out.psi.resize(m);
  for (int i = 0; i < m; ++i)
    out.psi[i] = i + 1 < m ? out.ends[i + 1].omega - out.ends[i].omega : 2 * pi + out.ends[0].omega - out.ends[i].omega;

  std::vector<double> omegas(m), kappas(m);
  double maxKappa = 0;
  for (int i = 0; i < m; ++i) {
    omegas[i] = out.ends[i].omega;
    kappas[i] = out.ends[i].normalCurvature;
    maxKappa = std::max(maxKappa, std::abs(kappas[i]));
  }
  out.curvatureScale = std::max(maxKappa, 1.0 / network.diagonal());

  // [HPS09] eq. (6) needs the ends to surround the vertex with 0 < ψ < π.
  const bool properAngles = std::all_of(out.psi.begin(), out.psi.end(), [&](double p) {
    return p > options.straightTolerance && p < pi - options.straightTolerance;
  });
  out.enclosureApplies = !vertex.onBoundary && m >= 3 && properAngles;
  if (out.enclosureApplies) {
    out.enclosureResidual = enclosureResidual(out.psi, kappas).raw;
    out.enclosureResidualRelative = std::abs(out.enclosureResidual) / out.curvatureScale;
    out.formsX = formsX(out.psi, options.straightTolerance);
  }

  // Eq. (26) in the least-squares sense over all ends. fitCurvature's residual
  // is exactly that: with ≤ 3 independent directions the fit matches each
  // direction's mean and the misfit is the disagreement of parallel ends;
  // with more it is the linear least squares over all ends.
  FitOptions fitOptions;
  fitOptions.parallelTolerance = std::sin(options.straightTolerance);
  out.eulerResidual = fitCurvature(omegas, kappas, fitOptions).rmsResidual;
  out.eulerResidualRelative = out.eulerResidual / out.curvatureScale;

  const BoundedCurvatureFit bounded = fitPerIndependentCurve(out.ends, out.independentCurves, fitOptions);
  out.fit = bounded.fit;
  out.regularizedModes = bounded.regularizedModes;
  out.principalDirection1 = std::cos(out.fit.tensor.lambda) * x + std::sin(out.fit.tensor.lambda) * y;
  out.verdict = verdictOf(out, options);
  return out;
}

} // namespace

std::vector<int> NetworkAnalysis::worstFirst() const {
  std::vector<int> order(vertices.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const VertexAnalysis &x = vertices[a], &y = vertices[b];
    if (x.verdict != y.verdict) return int(x.verdict) > int(y.verdict);
    if (x.eulerResidualRelative != y.eulerResidualRelative) return x.eulerResidualRelative > y.eulerResidualRelative;
    if (x.enclosureResidualRelative != y.enclosureResidualRelative)
      return x.enclosureResidualRelative > y.enclosureResidualRelative;
    return x.tangentResidual > y.tangentResidual;
  });
  return order;
}

VertexAnalysis analyzeVertex(const Network &network, int vertex, const AnalysisOptions &options) {
  requireOptions(options);
  if (vertex < 0 || vertex >= int(network.vertices().size()))
    throw InputError("", "vertex " + std::to_string(vertex),
                     "no such vertex (the network has " + std::to_string(network.vertices().size()) + ")");
  const std::vector<VertexFrame> frames = computeVertexFrames(network);
  return analyzeWithFrame(network, vertex, frames[vertex], options);
}

NetworkAnalysis analyzeNetwork(const Network &network, const AnalysisOptions &options) {
  requireOptions(options);
  NetworkAnalysis out;
  out.options = options;
  out.diagonal = network.diagonal();
  const std::vector<VertexFrame> frames = computeVertexFrames(network);
  for (int v = 0; v < int(network.vertices().size()); ++v) {
    VertexAnalysis a = analyzeWithFrame(network, v, frames[v], options);
    out.verdict = std::max(out.verdict, a.verdict);
    ++out.verdictCounts[int(a.verdict)];
    out.maxEnclosureResidualRelative = std::max(out.maxEnclosureResidualRelative, a.enclosureResidualRelative);
    out.maxEulerResidualRelative = std::max(out.maxEulerResidualRelative, a.eulerResidualRelative);
    out.maxTangentResidual = std::max(out.maxTangentResidual, a.tangentResidual);
    out.vertices.push_back(std::move(a));
  }
  return out;
}

} // namespace v1
} // namespace curvenet
