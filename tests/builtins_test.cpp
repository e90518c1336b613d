// Built-in networks and reference surfaces. Every property runs over every
// built-in through one parameterized fixture; nothing here uses Network::build,
// so the construction is checked independently of the network builder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "curvenet/builtins.hpp"
#include "curvenet/error.hpp"

using namespace curvenet;

namespace {

BoundingBox bounds(const NetworkDescription &net) {
  BoundingBox box;
  for (const BSplineCurve &c : net.curves)
    for (const Vec3 &p : c.controlPoints()) box.add(p);
  return box;
}

// Segments of the network as the faces' side ranges split the curves: every
// side end is a split parameter of its curve.
struct CurveRange {
  int curve;
  double from, to; // from < to
  int uses[2] = {0, 0}; // forward, backward traversals by faces
};

struct Split {
  std::vector<CurveRange> segments;
};

Split splitCurves(const NetworkDescription &net) {
  std::vector<std::set<double>> cuts(net.curves.size());
  for (const FaceDescription &f : net.faces)
    for (const SideDescription &s : f.sides) cuts[s.curve].insert(s.from), cuts[s.curve].insert(s.to);
  Split out;
  std::map<std::pair<int, double>, int> segmentAt; // (curve, start) → segment
  for (size_t c = 0; c < cuts.size(); ++c) {
    std::vector<double> t(cuts[c].begin(), cuts[c].end());
    for (size_t k = 0; k + 1 < t.size(); ++k) {
      segmentAt[{static_cast<int>(c), t[k]}] = static_cast<int>(out.segments.size());
      out.segments.push_back({static_cast<int>(c), t[k], t[k + 1]});
    }
  }
  for (const FaceDescription &f : net.faces)
    for (const SideDescription &s : f.sides) {
      double lo = std::min(s.from, s.to), hi = std::max(s.from, s.to);
      for (CurveRange &seg : out.segments)
        if (seg.curve == s.curve && seg.from >= lo && seg.to <= hi) ++seg.uses[s.from < s.to ? 0 : 1];
    }
  // Segments that no face uses are gaps between ranges, not segments.
  std::erase_if(out.segments, [](const CurveRange &s) { return s.uses[0] + s.uses[1] == 0; });
  return out;
}

std::map<int, int> sideCountHistogram(const NetworkDescription &net) {
  std::map<int, int> h;
  for (const FaceDescription &f : net.faces) ++h[static_cast<int>(f.sides.size())];
  return h;
}

class BuiltinTest : public testing::TestWithParam<std::string> {
protected:
  void SetUp() override {
    net = builtinNetwork(GetParam());
    diagonal = bounds(net).diagonal();
    ASSERT_GT(diagonal, 0);
    ASSERT_TRUE(net.reference.has_value());
  }
  NetworkDescription net;
  double diagonal = 0;
};

} // namespace

TEST(Builtins, NamesOrderAndDefault) {
  std::vector<std::string> names;
  for (const BuiltinInfo &b : builtinNetworks()) {
    names.push_back(b.name);
    EXPECT_FALSE(b.summary.empty());
  }
  EXPECT_EQ(names, (std::vector<std::string>{"pentagon", "sphere-dodecahedron", "ellipsoid-truncated-icosahedron",
                                              "torus-mixed", "saddle-nodes", "hemisphere-tjunction",
                                              "tjunction-surrounded", "tjunction-vertex", "hull-like", "concave-L",
                                              "ring", "uneven-loop", "many-sided", "setback-vertex-blend",
                                              "setback-external-masters"}));
  EXPECT_EQ(defaultBuiltinName(), "ellipsoid-truncated-icosahedron");
}

TEST(Builtins, UnknownNameThrowsListingTheKnownOnes) {
  try {
    builtinNetwork("nope");
    ADD_FAILURE() << "no error";
  } catch (const InputError &e) {
    EXPECT_EQ(e.element(), "builtin:nope");
    EXPECT_NE(e.reason().find("known: pentagon"), std::string::npos) << e.reason();
    EXPECT_NE(e.reason().find("saddle-nodes"), std::string::npos);
  }
  EXPECT_THROW(builtinVertexFacts("nope"), InputError);
}

TEST_P(BuiltinTest, FaceCountsBySideNumberAreAsDesigned) {
  const std::map<std::string, std::map<int, int>> designed = {
      {"pentagon", {{5, 1}}},
      {"sphere-dodecahedron", {{5, 12}}},
      {"ellipsoid-truncated-icosahedron", {{5, 12}, {6, 20}}},
      {"torus-mixed", {{3, 6}, {4, 50}, {5, 2}, {6, 2}}},
      {"saddle-nodes", {{2, 1}, {4, 6}}},
  };
  EXPECT_EQ(sideCountHistogram(net), designed.at(GetParam()));
  EXPECT_EQ(net.name, GetParam());
  for (const FaceDescription &f : net.faces) {
    EXPECT_GE(f.sides.size(), 2u);
    EXPECT_LE(f.sides.size(), 8u);
  }
}

TEST_P(BuiltinTest, CurvesLieOnTheReferenceSurface) {
  const ReferenceSurface &ref = *net.reference;
  double worst = 0;
  for (const BSplineCurve &c : net.curves) {
    EXPECT_EQ(c.degree(), 5);
    for (int i = 0; i <= 400; ++i) {
      double t = c.domainStart() + (c.domainEnd() - c.domainStart()) * i / 400;
      worst = std::max(worst, std::abs(ref.signedDistance(c.point(t))));
    }
  }
  RecordProperty("max_position_error_rel", std::to_string(worst / diagonal));
  std::printf("  %s: max |distance to surface| / diagonal = %.2e\n", GetParam().c_str(), worst / diagonal);
  EXPECT_LE(worst, 1e-8 * diagonal);
}

TEST_P(BuiltinTest, CurveNormalCurvatureMatchesTheSurface) {
  // κ_n = C''·N / |C'|² must equal II(t, t) of the reference (Meusnier).
  const ReferenceSurface &ref = *net.reference;
  double worst = 0;
  for (const BSplineCurve &c : net.curves)
    for (int i = 0; i <= 400; ++i) {
      double t = c.domainStart() + (c.domainEnd() - c.domainStart()) * i / 400;
      auto D = c.derivatives(t);
      SurfaceFrame f = ref.closest(D[0]);
      double curveKappa = dot(D[2], f.normal) / squaredNorm(D[1]);
      double scale = std::max(std::abs(f.k1), std::abs(f.k2));
      worst = std::max(worst, std::abs(curveKappa - f.normalCurvature(D[1])) / scale);
    }
  std::printf("  %s: max relative normal-curvature error = %.2e\n", GetParam().c_str(), worst);
  EXPECT_LE(worst, 1e-5);
}

TEST_P(BuiltinTest, LoopsCloseAndAreOrientedOutward) {
  const ReferenceSurface &ref = *net.reference;
  for (size_t fi = 0; fi < net.faces.size(); ++fi) {
    const FaceDescription &f = net.faces[fi];
    Vec3 area, centroid;
    int samples = 0;
    for (size_t k = 0; k < f.sides.size(); ++k) {
      const SideDescription &s = f.sides[k], &n = f.sides[(k + 1) % f.sides.size()];
      EXPECT_LE(norm(net.curves[s.curve].point(s.to) - net.curves[n.curve].point(n.from)), 1e-10 * diagonal)
          << "face " << fi << " side " << k;
      for (int i = 0; i < 16; ++i) {
        Vec3 a = net.curves[s.curve].point(s.from + (s.to - s.from) * i / 16);
        Vec3 b = net.curves[s.curve].point(s.from + (s.to - s.from) * (i + 1) / 16);
        area += cross(a, b);
        centroid += a;
        ++samples;
      }
    }
    // Vector area of the loop against the outward normal at its centre.
    SurfaceFrame frame = ref.closest(centroid / samples);
    EXPECT_GT(dot(area, frame.normal), 0) << "face " << fi << " is clockwise from outside";
  }
}

TEST_P(BuiltinTest, EachSegmentIsUsedOnceOrTwiceInOppositeDirections) {
  Split split = splitCurves(net);
  int boundary = 0;
  for (const CurveRange &s : split.segments) {
    EXPECT_LE(s.uses[0], 1) << "curve " << s.curve << " [" << s.from << ", " << s.to << "]";
    EXPECT_LE(s.uses[1], 1) << "curve " << s.curve << " [" << s.from << ", " << s.to << "]";
    boundary += s.uses[0] + s.uses[1] == 1;
  }
  const bool closed = GetParam() != "pentagon" && GetParam() != "saddle-nodes";
  if (closed) EXPECT_EQ(boundary, 0);
  else EXPECT_GT(boundary, 0);
}

TEST_P(BuiltinTest, VertexFactsMatchTheFacesAndTopology) {
  const std::vector<BuiltinVertexFact> facts = builtinVertexFacts(GetParam());
  Split split = splitCurves(net);
  auto vertexAt = [&](const Vec3 &p) {
    int found = -1;
    for (size_t v = 0; v < facts.size(); ++v)
      if (norm(facts[v].position - p) <= 1e-9 * diagonal) {
        EXPECT_EQ(found, -1) << "two facts at one point";
        found = static_cast<int>(v);
      }
    return found;
  };
  // Segment ends per vertex with their outgoing tangents; a curve continuing
  // through a vertex contributes two ends with opposite tangents.
  std::vector<int> valence(facts.size(), 0), passes(facts.size(), 0);
  std::vector<std::vector<Vec3>> tangents(facts.size());
  std::map<std::pair<int, double>, int> endsAtCut; // (curve, parameter) → segment ends there
  for (const CurveRange &s : split.segments) {
    const BSplineCurve &c = net.curves[s.curve];
    for (int e = 0; e < 2; ++e) {
      double t = e == 0 ? s.from : s.to;
      int v = vertexAt(c.point(t));
      ASSERT_GE(v, 0) << "segment end of curve " << s.curve << " at t = " << t << " is no vertex";
      ++valence[v];
      Vec3 d = c.derivatives(e == 0 ? t + 1e-9 * (s.to - s.from) : t - 1e-9 * (s.to - s.from))[1];
      tangents[v].push_back(normalized(e == 0 ? d : -1.0 * d));
      if (++endsAtCut[{s.curve, t}] == 2) ++passes[v];
    }
  }
  for (size_t v = 0; v < facts.size(); ++v) {
    EXPECT_EQ(valence[v], facts[v].valence) << "vertex " << v;
    EXPECT_EQ(valence[v] - passes[v], facts[v].independentCurves) << "vertex " << v;
    // Only curves passing through are straight: every other pair of edges
    // makes a clear corner (no accidental T- or X-node).
    int straight = 0;
    double worst = 180;
    for (size_t a = 0; a < tangents[v].size(); ++a)
      for (size_t b = a + 1; b < tangents[v].size(); ++b) {
        double deviation = 180 - angleBetween(tangents[v][a], tangents[v][b]) * 180 / std::numbers::pi;
        if (deviation < 1e-4) ++straight;
        else worst = std::min(worst, deviation);
      }
    EXPECT_EQ(straight, passes[v]) << "vertex " << v;
    EXPECT_GT(worst, 5.0) << "vertex " << v << " has nearly collinear edges";
  }
  // Euler characteristic: sphere 2, torus 0, disk 1.
  const std::map<std::string, int> euler = {{"pentagon", 1}, {"sphere-dodecahedron", 2},
                                            {"ellipsoid-truncated-icosahedron", 2}, {"torus-mixed", 0},
                                            {"saddle-nodes", 1}};
  EXPECT_EQ(static_cast<int>(facts.size()) - static_cast<int>(split.segments.size()) +
                static_cast<int>(net.faces.size()),
            euler.at(GetParam()));
}

TEST_P(BuiltinTest, CurveEndsAreExactVertexPoints) {
  const std::vector<BuiltinVertexFact> facts = builtinVertexFacts(GetParam());
  for (const BSplineCurve &c : net.curves)
    for (const Vec3 &end : {c.controlPoints().front(), c.controlPoints().back()}) {
      bool exact = std::any_of(facts.begin(), facts.end(), [&](const BuiltinVertexFact &f) { return f.position == end; });
      EXPECT_TRUE(exact);
      EXPECT_LE(std::abs(net.reference->implicit(end)), 1e-14);
    }
}

INSTANTIATE_TEST_SUITE_P(All, BuiltinTest,
                         testing::Values("pentagon", "sphere-dodecahedron", "ellipsoid-truncated-icosahedron",
                                         "torus-mixed", "saddle-nodes"),
                         [](const testing::TestParamInfo<std::string> &param) {
                           std::string s = param.param;
                           std::replace(s.begin(), s.end(), '-', '_');
                           return s;
                         });

TEST(Builtins, ExpectedVertexKinds) {
  auto histogram = [](const std::string &name) {
    std::map<std::pair<int, int>, int> h;
    for (const BuiltinVertexFact &f : builtinVertexFacts(name)) ++h[{f.valence, f.independentCurves}];
    return h;
  };
  using H = std::map<std::pair<int, int>, int>;
  EXPECT_EQ(histogram("pentagon"), (H{{{2, 2}, 5}}));
  EXPECT_EQ(histogram("sphere-dodecahedron"), (H{{{3, 3}, 20}}));
  EXPECT_EQ(histogram("ellipsoid-truncated-icosahedron"), (H{{{3, 3}, 60}}));
  EXPECT_EQ(histogram("torus-mixed"), (H{{{3, 3}, 6}, {{4, 4}, 48}, {{5, 5}, 6}}));
  // X-node, T-node, lens ends on curves passing through, boundary T's, corners.
  EXPECT_EQ(histogram("saddle-nodes"), (H{{{4, 2}, 1}, {{3, 2}, 6}, {{4, 3}, 2}, {{2, 2}, 4}}));
}

TEST(Builtins, TorusHasFacesInTheHyperbolicRegion) {
  NetworkDescription net = builtinNetwork("torus-mixed");
  const ReferenceSurface &ref = *net.reference;
  int hyperbolicNonQuads = 0, ellipticNonQuads = 0;
  for (const FaceDescription &f : net.faces) {
    Vec3 c;
    for (const SideDescription &s : f.sides) c += net.curves[s.curve].point(0.5 * (s.from + s.to));
    SurfaceFrame frame = ref.closest(c / static_cast<double>(f.sides.size()));
    if (f.sides.size() != 4) ++(frame.k1 * frame.k2 < 0 ? hyperbolicNonQuads : ellipticNonQuads);
  }
  EXPECT_GE(hyperbolicNonQuads, 3);
  EXPECT_GE(ellipticNonQuads, 3);
}

// ---- Reference surfaces -------------------------------------------------

namespace {

struct SurfaceSample {
  Vec3 point, normal;
};

// Points on each kind from its parameterization, with the analytic outward normal.
std::vector<SurfaceSample> samples(const ReferenceSurface &s) {
  std::vector<SurfaceSample> out;
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 9; ++j) {
      double u = 0.3 + i * 0.41, v = 0.2 + j * 0.7;
      Vec3 p, n;
      switch (s.kind) {
      case ReferenceSurface::Kind::Ellipsoid: {
        Vec3 d{std::sin(u) * std::cos(v), std::sin(u) * std::sin(v), std::cos(u)};
        p = {s.size.x * d.x, s.size.y * d.y, s.size.z * d.z};
        n = normalized({p.x / (s.size.x * s.size.x), p.y / (s.size.y * s.size.y), p.z / (s.size.z * s.size.z)});
        break;
      }
      case ReferenceSurface::Kind::Torus: {
        double rho = s.size.x + s.size.y * std::cos(u);
        p = {rho * std::cos(v), rho * std::sin(v), s.size.y * std::sin(u)};
        n = {std::cos(u) * std::cos(v), std::cos(u) * std::sin(v), std::sin(u)};
        break;
      }
      case ReferenceSurface::Kind::Graph: {
        double x = (i - 3) * 0.3, y = (j - 4) * 0.25;
        p = {x, y, s.size.x * x * x + s.size.y * y * y};
        n = normalized({-2 * s.size.x * x, -2 * s.size.y * y, 1});
        break;
      }
      case ReferenceSurface::Kind::Mesh: break; // no built-in carries one
      }
      out.push_back({p + s.center, n});
    }
  return out;
}

std::vector<ReferenceSurface> someSurfaces() {
  return {ReferenceSurface{ReferenceSurface::Kind::Ellipsoid, {0.5, -1, 2}, {1.2, 1.0, 0.8}, nullptr},
          ReferenceSurface{ReferenceSurface::Kind::Torus, {0, 0, 1}, {1.0, 0.45, 0}, nullptr},
          ReferenceSurface{ReferenceSurface::Kind::Graph, {1, 2, 3}, {1, -1, 0}, nullptr},
          ReferenceSurface{ReferenceSurface::Kind::Graph, {}, {0.7, 0.3, 0}, nullptr}};
}

} // namespace

TEST(Reference, KindNamesRoundTrip) {
  for (auto k : {ReferenceSurface::Kind::Ellipsoid, ReferenceSurface::Kind::Torus, ReferenceSurface::Kind::Graph})
    EXPECT_EQ(ReferenceSurface::kindFromName(ReferenceSurface::kindName(k)), k);
  EXPECT_FALSE(ReferenceSurface::kindFromName("cylinder").has_value());
}

TEST(Reference, ClosestPointOfAnOffsetPointReturnsToTheSurface) {
  for (const ReferenceSurface &s : someSurfaces())
    for (const SurfaceSample &q : samples(s)) {
      EXPECT_NEAR(s.implicit(q.point), 0.0, 1e-12);
      for (double d : {-0.05, 0.0, 0.03, 0.1}) {
        Vec3 p = q.point + d * q.normal;
        SurfaceFrame f = s.closest(p);
        EXPECT_LE(norm(f.point - q.point), 1e-10) << ReferenceSurface::kindName(s.kind) << " offset " << d;
        EXPECT_LE(norm(f.normal - q.normal), 1e-10);
        EXPECT_NEAR(s.signedDistance(p), d, 1e-10);
        if (d != 0) {
          EXPECT_EQ(s.implicit(p) > 0, d > 0); // positive on the normal side
        }
      }
    }
}

TEST(Reference, PrincipalCurvaturesAgainstClosedForms) {
  auto frame = [](ReferenceSurface::Kind kind, Vec3 size, Vec3 p) {
    return ReferenceSurface{kind, {}, size, nullptr}.closest(p);
  };
  // Sphere of radius 2 with outward normal: κ1 = κ2 = −1/2.
  SurfaceFrame sphere = frame(ReferenceSurface::Kind::Ellipsoid, {2, 2, 2}, {1, 1, 1.4142135623730951});
  EXPECT_NEAR(sphere.k1, -0.5, 1e-12);
  EXPECT_NEAR(sphere.k2, -0.5, 1e-12);
  // Ellipsoid vertex (a, 0, 0): κ along y = −a/b², along z = −a/c².
  SurfaceFrame ell = frame(ReferenceSurface::Kind::Ellipsoid, {1.2, 1.0, 0.8}, {1.5, 0, 0});
  EXPECT_NEAR(ell.k1, -1.2, 1e-12);
  EXPECT_NEAR(ell.k2, -1.2 / 0.64, 1e-12);
  EXPECT_NEAR(std::abs(ell.direction1.y), 1.0, 1e-12);
  // Torus R = 1, r = 0.45: outer equator −1/(R + r), −1/r; inner equator 1/(R − r), −1/r.
  const double R = 1.0, r = 0.45;
  SurfaceFrame outer = frame(ReferenceSurface::Kind::Torus, {R, r, 0}, {2, 0, 0});
  EXPECT_NEAR(outer.k1, -1 / (R + r), 1e-12);
  EXPECT_NEAR(outer.k2, -1 / r, 1e-12);
  EXPECT_NEAR(std::abs(outer.direction1.y), 1.0, 1e-12);
  EXPECT_NEAR(outer.normal.x, 1.0, 1e-12);
  SurfaceFrame inner = frame(ReferenceSurface::Kind::Torus, {R, r, 0}, {0, 0.5, 0});
  EXPECT_NEAR(inner.k1, 1 / (R - r), 1e-12);
  EXPECT_NEAR(inner.k2, -1 / r, 1e-12);
  EXPECT_NEAR(std::abs(inner.direction1.x), 1.0, 1e-12);
  EXPECT_NEAR(inner.normal.y, -1.0, 1e-12);
  // Saddle z = x² − y² at the origin: κ1 = 2 along x, κ2 = −2; Euler at 45° gives 0.
  SurfaceFrame saddle = frame(ReferenceSurface::Kind::Graph, {1, -1, 0}, {0, 0, 0.2});
  EXPECT_NEAR(saddle.k1, 2.0, 1e-12);
  EXPECT_NEAR(saddle.k2, -2.0, 1e-12);
  EXPECT_NEAR(std::abs(saddle.direction1.x), 1.0, 1e-12);
  EXPECT_NEAR(saddle.normalCurvature({1, 1, 0}), 0.0, 1e-12);
  EXPECT_NEAR(saddle.normalCurvature({0, 3, 0}), -2.0, 1e-12);
}

TEST(Reference, GaussCurvatureAtGenericPoints) {
  // Ellipsoid: K = 1 / (a²b²c² (x²/a⁴ + y²/b⁴ + z²/c⁴)²); torus: K = cos φ / (r (R + r cos φ)).
  ReferenceSurface ell{ReferenceSurface::Kind::Ellipsoid, {}, {1.2, 1.0, 0.8}, nullptr};
  for (const SurfaceSample &q : samples(ell)) {
    SurfaceFrame f = ell.closest(q.point);
    const Vec3 &p = q.point;
    double a2 = 1.44, b2 = 1.0, c2 = 0.64;
    double s = p.x * p.x / (a2 * a2) + p.y * p.y / (b2 * b2) + p.z * p.z / (c2 * c2);
    EXPECT_NEAR(f.k1 * f.k2, 1 / (a2 * b2 * c2 * s * s), 1e-10);
    EXPECT_GE(f.k1, f.k2);
    EXPECT_NEAR(dot(f.direction1, f.normal), 0.0, 1e-12);
    EXPECT_NEAR(norm(f.direction1), 1.0, 1e-12);
    // e1 really is a principal direction: the normal curvature is extremal there.
    EXPECT_NEAR(f.normalCurvature(f.direction1), f.k1, 1e-12);
    EXPECT_NEAR(f.normalCurvature(cross(f.normal, f.direction1)), f.k2, 1e-12);
  }
  const double R = 1.0, r = 0.45;
  ReferenceSurface torus{ReferenceSurface::Kind::Torus, {}, {R, r, 0}, nullptr};
  for (const SurfaceSample &q : samples(torus)) {
    SurfaceFrame f = torus.closest(q.point);
    double cosPhi = dot(f.normal, normalized({q.point.x, q.point.y, 0}));
    EXPECT_NEAR(f.k1 * f.k2, cosPhi / (r * (R + r * cosPhi)), 1e-10);
    EXPECT_NEAR(f.k1 + f.k2, -1 / r - cosPhi / (R + r * cosPhi), 1e-10);
  }
}
