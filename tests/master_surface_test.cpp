// Master surfaces given from outside ([SV14] Sec. 5.1): the NURBS surface
// type, the native format's "surfaces" and "master_surface", and the
// patches meeting their masters (setback-external-masters).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "curvenet/bspline_surface.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/io.hpp"
#include "curvenet/master_contact.hpp"
#include "curvenet/network.hpp"
#include "curvenet/surface.hpp"
#include "input_errors.hpp"

using namespace curvenet;
using curvenet::test::catchInputError;
using curvenet::test::contains;

namespace {

/// A rational bicubic × biquadratic surface with interior knots and uneven
/// weights: nothing in it is special, so derivatives are checked in general.
BSplineSurface wavyNurbs() {
  const int nu = 6, nv = 5;
  std::vector<Vec3> net;
  std::vector<double> weights;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      net.push_back({double(i), double(j) + 0.3 * std::sin(i), 0.4 * std::cos(1.3 * i + 0.7 * j)});
      weights.push_back(1.0 + 0.5 * std::sin(2.0 * i + j) * std::sin(2.0 * i + j));
    }
  return BSplineSurface(3, 2, {0, 0, 0, 0, 0.3, 0.7, 1, 1, 1, 1}, {0, 0, 0, 0.4, 0.55, 1, 1, 1}, nu, nv, net, weights);
}

/// The quarter cylinder of radius r about the z axis, θ ∈ [0, π/2] (u, the
/// exact rational quadratic) × z ∈ [0, h] (v, linear).
BSplineSurface quarterCylinder(double r, double h) {
  const double w = std::sqrt(0.5);
  return BSplineSurface(2, 1, {0, 0, 0, 1, 1, 1}, {0, 0, 1, 1}, 3, 2,
                        {{r, 0, 0}, {r, 0, h}, {r, r, 0}, {r, r, h}, {0, r, 0}, {0, r, h}}, {1, 1, w, w, 1, 1});
}

double relative(const Vec3 &a, const Vec3 &b) { return norm(a - b) / std::max(1.0, norm(b)); }

} // namespace

// Exact derivatives against fourth-order central differences of the exact
// lower-order ones (step 1e-5: truncation ~1e-18, rounding ~1e-11) in every span
// (the stencils stay 1e-2 from the knots, where the degree-2 direction's
// second derivative jumps); on a knot the jet is the right span's limit.
TEST(BSplineSurface, DerivativesAgreeWithCentralDifferences) {
  const BSplineSurface s = wavyNurbs();
  const double h = 1e-5;
  double worst = 0;
  for (double u : {0.05, 0.29, 0.51, 0.93})
    for (double v : {0.02, 0.41, 0.6, 0.97}) {
      const SurfaceJet j = s.jet(u, v);
      // Fourth-order central stencil of a jet member along u or v.
      auto along = [&](bool inU, Vec3 SurfaceJet::*member) {
        auto at = [&](double k) { return s.jet(inU ? u + k * h : u, inU ? v : v + k * h).*member; };
        return ((at(1) - at(-1)) * 8 - (at(2) - at(-2))) / (12 * h);
      };
      worst = std::max(worst, relative(j.du, along(true, &SurfaceJet::point)));
      worst = std::max(worst, relative(j.dv, along(false, &SurfaceJet::point)));
      worst = std::max(worst, relative(j.duu, along(true, &SurfaceJet::du)));
      worst = std::max(worst, relative(j.dvv, along(false, &SurfaceJet::dv)));
      worst = std::max(worst, relative(j.duv, along(true, &SurfaceJet::dv)));
      worst = std::max(worst, relative(j.duv, along(false, &SurfaceJet::du)));
    }
  std::printf("NURBS derivatives vs central differences: %.2e\n", worst);
  EXPECT_LE(worst, 1e-9);
  // On the knot v = 0.4 (degree 2: C¹) the second derivative in v jumps:
  // the jet takes the right limit.
  const double rightLimit = relative(s.jet(0.5, 0.4).dvv, s.jet(0.5, 0.4 + 1e-12).dvv);
  const double leftLimit = relative(s.jet(0.5, 0.4).dvv, s.jet(0.5, 0.4 - 1e-12).dvv);
  EXPECT_LE(rightLimit, 1e-9);
  EXPECT_GE(leftLimit, 1e-3);
  // Degree 3 × 2 with these knots: a polynomial surface would make this test
  // weaker; the weights must enter (the rational quotient rule is checked).
  EXPECT_TRUE(s.isRational());
}

// An exact NURBS cylinder: every point at radius r, the normal radial, the
// principal curvatures ±1/r and 0 with e1 along the circle; the fundamental
// forms give the same normal curvature as Weingarten's −dN·dP differenced.
TEST(BSplineSurface, CylinderHasItsAnalyticFrame) {
  const double r = 0.7;
  const BSplineSurface s = quarterCylinder(r, 2.0);
  double radial = 0, normalError = 0, curvatureError = 0, weingarten = 0;
  for (double u : {0.0, 0.2, 0.5, 0.85, 1.0})
    for (double v : {0.0, 0.3, 1.0}) {
      const Vec3 p = s.point(u, v);
      radial = std::max(radial, std::abs(std::hypot(p.x, p.y) - r));
      const SurfaceFrame f = s.frame(u, v);
      normalError = std::max(normalError, norm(cross(f.normal, normalized(Vec3{p.x, p.y, 0}))));
      // |κ| = 1/r around, 0 along the axis (the sign follows the normal's side).
      curvatureError = std::max({curvatureError, std::abs(std::max(std::abs(f.k1), std::abs(f.k2)) - 1 / r),
                                 std::abs(std::min(std::abs(f.k1), std::abs(f.k2))), std::abs(f.direction1.z) *
                                     (std::abs(f.k1) > std::abs(f.k2) ? 1.0 : 0.0)});
      // II(t, t) from the forms against −dN·dP / |dP|² in the direction du + dv.
      if (u > 0 && u < 1 && v > 0 && v < 1) {
        const double h = 1e-6;
        const Vec3 dp = (s.point(u + h, v + h) - s.point(u - h, v - h)) / (2 * h);
        const Vec3 dn = (s.normal(u + h, v + h) - s.normal(u - h, v - h)) / (2 * h);
        const FundamentalForms ff = s.fundamentalForms(u, v);
        const double fromForms = (ff.L + 2 * ff.M + ff.N) / (ff.E + 2 * ff.F + ff.G);
        weingarten = std::max(weingarten, std::abs(fromForms + dot(dn, dp) / dot(dp, dp)) * r);
        // Euler's formula from the principal frame agrees with the forms.
        const SurfaceJet j = s.jet(u, v);
        EXPECT_NEAR(f.normalCurvature(j.du + j.dv), fromForms, 1e-13);
      }
    }
  std::printf("cylinder: radius %.1e, normal %.1e, curvatures %.1e, forms vs Weingarten %.1e\n", radial, normalError,
              curvatureError, weingarten);
  EXPECT_LE(radial, 1e-15);
  EXPECT_LE(normalError, 1e-14);
  EXPECT_LE(curvatureError, 1e-12);
  EXPECT_LE(weingarten, 1e-8);
}

// Points off the surface along its normal project back to where they came
// from; points beyond a boundary land on it; the warm start agrees.
TEST(BSplineSurface, ClosestPointRecoversTheFoot) {
  const BSplineSurface s = wavyNurbs();
  double worstParameter = 0, worstDistance = 0;
  for (double u : {0.1, 0.35, 0.62, 0.9})
    for (double v : {0.15, 0.5, 0.8}) {
      const Vec3 n = s.normal(u, v);
      for (double offset : {0.0, 0.02, -0.03}) {
        const SurfaceProjection foot = s.closestPoint(s.point(u, v) + n * offset);
        worstParameter = std::max({worstParameter, std::abs(foot.u - u), std::abs(foot.v - v)});
        worstDistance = std::max(worstDistance, std::abs(foot.distance - std::abs(offset)));
        const SurfaceProjection warm = s.closestPoint(s.point(u, v) + n * offset, u + 0.02, v - 0.02);
        worstParameter = std::max({worstParameter, std::abs(warm.u - u), std::abs(warm.v - v)});
      }
    }
  EXPECT_LE(worstParameter, 1e-9);
  EXPECT_LE(worstDistance, 1e-12);
  // Beyond the cylinder's end z = h: the foot is on the end circle.
  const BSplineSurface cylinder = quarterCylinder(1.0, 1.0);
  const SurfaceProjection end = cylinder.closestPoint({0.6, 0.6, 1.5});
  EXPECT_NEAR(end.v, 1.0, 1e-15);
  EXPECT_NEAR(end.distance, std::hypot(0.5, std::hypot(0.6, 0.6) - 1.0), 1e-12);
}

TEST(BSplineSurface, InconsistentDataIsRefusedWithTheReason) {
  const std::vector<Vec3> net(6, Vec3{});
  EXPECT_TRUE(contains(catchInputError([&] { BSplineSurface(2, 1, {0, 0, 0, 1, 1}, {0, 0, 1, 1}, 3, 2, net); }).reason(),
                       "knots in u"));
  EXPECT_TRUE(contains(catchInputError([&] { BSplineSurface(2, 1, {0, 0, 0, 1, 1, 1}, {0, 0, 1, 1}, 3, 3, net); }).reason(),
                       "knots in v"));
  EXPECT_TRUE(contains(catchInputError([&] { BSplineSurface(2, 1, {0, 0, 0, 1, 1, 1}, {0, 0, 1, 1}, 2, 3, net); }).reason(),
                       "too few"));
  EXPECT_TRUE(contains(
      catchInputError([&] { BSplineSurface(2, 1, {0, 0, 0, 1, 1, 1}, {0, 0, 1, 1}, 3, 2, net, {1, 1, 1, 0, 1, 1}); }).reason(),
      "weight 3"));
  EXPECT_TRUE(contains(
      catchInputError([&] { BSplineSurface(2, 1, {0, 0, 0, 1, 1, 1}, {0, 0, 1, 1}, 3, 2, {{0, 0, 0}}); }).reason(),
      "expected 3 x 2"));
  EXPECT_TRUE(contains(catchInputError([&] { BSplineSurface(2, 1, {0, 0.5, 0, 1, 1, 1}, {0, 0, 1, 1}, 3, 2, net); }).reason(),
                       "decrease"));
}

namespace {

/// The external-master built-in's figures under one scheme, measured
/// against the master surfaces themselves.
struct ContactFigures {
  double normalAngleDeg = 0, curvatureJump = 0, distance = 0;
  int contacts = 0;
};

ContactFigures contactFigures(const Surface &surface) {
  ContactFigures f;
  for (const MasterSurfaceContact &c : measureMasterSurfaceContact(surface)) {
    f.normalAngleDeg = std::max(f.normalAngleDeg, c.maxNormalAngleDeg);
    f.curvatureJump = std::max(f.curvatureJump, c.maxCurvatureJump);
    f.distance = std::max(f.distance, c.maxDistance);
    ++f.contacts;
  }
  return f;
}

/// The same network with its master surfaces dropped from the edges: what
/// the blend is when the master data are ignored.
NetworkDescription withoutMasters(NetworkDescription d) {
  for (EdgeDescription &edge : d.edges) edge.masterSurface = -1;
  return d;
}

/// Measures `plain` (no master data) against the masters of `masters` by
/// evaluating its patches where `masters` names them (same faces, segments).
ContactFigures ignoredMasterFigures(const Network &masters, const SurfaceOptions &options) {
  const Surface plain = Surface::build(Network::build(withoutMasters(masters.description())), options);
  ContactFigures f;
  for (size_t e = 0; e < masters.segments().size(); ++e) {
    const Segment &seg = masters.segments()[e];
    if (seg.masterSurface < 0) continue;
    const BSplineSurface &m = masters.description().surfaces[size_t(seg.masterSurface)];
    for (int j = 1; j < 16; ++j) {
      const double u = j / 16.0;
      const SurfacePoint2 p = plain.evaluateSecondOrder(seg.faces[0], plain.domainPointOnSegment(seg.faces[0], int(e), u));
      const SurfaceProjection foot = m.closestPoint(p.point);
      const SurfaceFrame frame = m.frame(foot.u, foot.v);
      const Vec3 n = dot(frame.normal, p.normal) < 0 ? -frame.normal : frame.normal;
      f.normalAngleDeg = std::max(f.normalAngleDeg, angleBetween(p.normal, n) * 180 / std::numbers::pi);
      const Vec3 d = cross(n, seg.curve.derivatives(u)[1]);
      const double kf = p.normalCurvature(d), km = (dot(frame.normal, n) < 0 ? -1.0 : 1.0) * frame.normalCurvature(d);
      f.curvatureJump = std::max(f.curvatureJump, std::abs(kf - km) / std::max({std::abs(kf), std::abs(km), 1 / masters.diagonal()}));
    }
  }
  return f;
}

} // namespace

// Fig. 8 with external primaries: the blend meets each NURBS cylinder with
// its tangent plane (≤ 1e-6°) under gregory-g1 and gregory-g2, and with its
// curvature (jump ≤ 1e-4) under gregory-g2; gregory-g1's jump is reported.
// With the master data ignored (the same curves, no master_surface) the
// blend misses the cylinders by far more in both, so the figures come from
// the masters and not from the curves alone.
TEST(ExternalMasters, SetbackBlendMeetsItsCylinders) {
  const Network net = Network::build(builtinNetwork("setback-external-masters"));
  ASSERT_EQ(net.faces().size(), 1u);
  ASSERT_EQ(net.description().surfaces.size(), 3u);
  SurfaceOptions g2;
  g2.scheme = Scheme::GregoryG2;
  const Surface surfaceG2 = Surface::build(net, g2);
  const Surface surfaceG1 = Surface::build(net, {});
  EXPECT_TRUE(surfaceG2.foldedFaces().empty());
  EXPECT_TRUE(surfaceG1.foldedFaces().empty());
  const ContactFigures f2 = contactFigures(surfaceG2), f1 = contactFigures(surfaceG1);
  const ContactFigures ignored2 = ignoredMasterFigures(net, g2), ignored1 = ignoredMasterFigures(net, {});
  std::printf("setback-external-masters: gregory-g2 angle %.2e deg jump %.2e distance %.1e | gregory-g1 angle %.2e deg "
              "jump %.2e | masters ignored: g2 angle %.2e jump %.2e, g1 angle %.2e\n",
              f2.normalAngleDeg, f2.curvatureJump, f2.distance, f1.normalAngleDeg, f1.curvatureJump,
              ignored2.normalAngleDeg, ignored2.curvatureJump, ignored1.normalAngleDeg);
  EXPECT_EQ(f2.contacts, 3);
  EXPECT_LE(f2.normalAngleDeg, 1e-6);
  EXPECT_LE(f2.curvatureJump, 1e-4);
  EXPECT_LE(f2.distance, 1e-12);
  EXPECT_LE(f1.normalAngleDeg, 1e-6);
  EXPECT_GE(f1.curvatureJump, 100 * f2.curvatureJump);
  EXPECT_GE(ignored2.curvatureJump, 100 * std::max(f2.curvatureJump, 1e-8));
  EXPECT_GE(ignored1.normalAngleDeg, 1e3 * std::max(f1.normalAngleDeg, 1e-9));
}

// The native format carries the surfaces and the edges' master_surface:
// written and read back, the network is the same and so is the blend.
TEST(ExternalMasters, NativeFormatRoundTrips) {
  const NetworkDescription original = builtinNetwork("setback-external-masters");
  const NetworkDescription back = parseNetworkJson(networkToJson(original));
  ASSERT_EQ(back.surfaces.size(), original.surfaces.size());
  for (size_t k = 0; k < back.surfaces.size(); ++k) {
    EXPECT_EQ(back.surfaces[k].controlPoints(), original.surfaces[k].controlPoints());
    EXPECT_EQ(back.surfaces[k].weights(), original.surfaces[k].weights());
    EXPECT_EQ(back.surfaces[k].knotsU(), original.surfaces[k].knotsU());
  }
  ASSERT_EQ(back.edges.size(), original.edges.size());
  for (size_t k = 0; k < back.edges.size(); ++k) EXPECT_EQ(back.edges[k].masterSurface, original.edges[k].masterSurface);
  SurfaceOptions g2;
  g2.scheme = Scheme::GregoryG2;
  const Surface a = Surface::build(Network::build(original), g2), b = Surface::build(Network::build(back), g2);
  const Vec2 centre{0, 0};
  EXPECT_EQ(a.evaluate(0, centre).point, b.evaluate(0, centre).point);
}

namespace {

/// The built-in as a JSON document, edited by `edit`, parsed and built.
void buildEdited(const std::function<void(nlohmann::json &)> &edit) {
  nlohmann::json doc = nlohmann::json::parse(networkToJson(builtinNetwork("setback-external-masters")));
  edit(doc);
  Network::build(parseNetworkJson(doc.dump(), "masters.json"), "masters.json");
}

} // namespace

TEST(ExternalMasters, BadMasterDataIsNamed) {
  // An unknown surface index.
  InputError e = catchInputError([] { buildEdited([](nlohmann::json &d) { d["edges"][1]["master_surface"] = 7; }); });
  EXPECT_EQ(e.element(), "edges[1].master_surface");
  EXPECT_TRUE(contains(e.reason(), "surface 7 does not exist")) << e.what();
  // A curve that does not lie on its master: the edge and the distance.
  e = catchInputError([] { buildEdited([](nlohmann::json &d) { d["edges"][0]["master_surface"] = 1; }); });
  EXPECT_EQ(e.element(), "edges[0]");
  EXPECT_TRUE(contains(e.reason(), "curve 0 is ")) << e.what();
  EXPECT_TRUE(contains(e.reason(), "from master surface 1")) << e.what();
  // The z fillet moved by 1e-4 across its axis (along x, its normal at
  // θ = 0): the distance is named.
  e = catchInputError([] {
    buildEdited([](nlohmann::json &d) {
      for (auto &row : d["surfaces"][2]["points"])
        for (auto &p : row) p[0] = p[0].get<double>() + 1e-4;
    });
  });
  EXPECT_TRUE(contains(e.reason(), "curve 2 is 0.0001 from master surface 2")) << e.what();
  // Bad knots, a ragged net, weights of the wrong shape.
  e = catchInputError([] { buildEdited([](nlohmann::json &d) { d["surfaces"][0]["knots_u"][4] = 0.5; }); });
  EXPECT_EQ(e.element(), "surfaces[0]");
  EXPECT_TRUE(contains(e.reason(), "not clamped")) << e.what();
  e = catchInputError([] { buildEdited([](nlohmann::json &d) { d["surfaces"][0]["points"][1].erase(0); }); });
  EXPECT_EQ(e.element(), "surfaces[0].points[1]");
  e = catchInputError([] { buildEdited([](nlohmann::json &d) { d["surfaces"][0]["weights"].erase(0); }); });
  EXPECT_EQ(e.element(), "surfaces[0].weights");
  e = catchInputError([] { buildEdited([](nlohmann::json &d) { d["surfaces"][0]["weights"][0][0] = -1; }); });
  EXPECT_TRUE(contains(e.reason(), "weight 0 is not a positive")) << e.what();
  // A master face and a master surface on one edge.
  e = catchInputError([] { buildEdited([](nlohmann::json &d) { d["edges"][0]["master"] = 0; }); });
  EXPECT_TRUE(contains(e.reason(), "both a master face and a master surface")) << e.what();
}

// `curvenet check` reports each face against each master surface.
TEST(ExternalMasters, CheckReportsTheMasterSurfaces) {
  const curvenet::test::CliRun run = curvenet::test::runCli("check builtin:setback-external-masters --json --scheme gregory-g2");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  ASSERT_TRUE(report.contains("master_surfaces"));
  ASSERT_EQ(report["master_surfaces"].size(), 3u);
  for (const auto &m : report["master_surfaces"]) {
    EXPECT_LE(m["max_normal_angle_deg"].get<double>(), 1e-6);
    EXPECT_LE(m["max_curvature_jump"].get<double>(), 1e-4);
    EXPECT_EQ(m["face"].get<int>(), 0);
  }
  const curvenet::test::CliRun text = curvenet::test::runCli("check builtin:setback-external-masters --scheme gregory-g2");
  EXPECT_TRUE(contains(text.out, "master surface 0, face 0")) << text.out;
}

// An edit next to the master edges rebuilds in part and evaluates bit for
// bit like a full build: the edited curve's vertices take their master's
// tensor again, the master edges there their master's fence.
TEST(ExternalMasters, PartialRebuildMatchesAFullBuild) {
  NetworkDescription d = builtinNetwork("setback-external-masters");
  SurfaceOptions g2;
  g2.scheme = Scheme::GregoryG2;
  g2.curves = CurveHandling::Kept;
  const Surface before = Surface::build(Network::build(d), g2);
  // Move a setback curve's inner control points a little within its plane.
  BSplineCurve &setback = d.curves[3];
  std::vector<Vec3> points = setback.controlPoints();
  points[1] = points[1] * 0.97;
  points[2] = points[2] * 1.02;
  setback = BSplineCurve(setback.degree(), setback.knots(), points, setback.weights());
  const Network edited = Network::build(d);
  const SurfaceEdit edit = before.rebuildAfterEdit(edited);
  EXPECT_TRUE(edit.partial);
  const Surface full = Surface::build(edited, g2);
  for (const Vec2 &uv : {Vec2{0, 0}, Vec2{0.3, -0.2}, Vec2{-0.5, 0.4}}) {
    EXPECT_EQ(edit.surface.evaluate(0, uv).point, full.evaluate(0, uv).point);
    EXPECT_EQ(edit.surface.evaluate(0, uv).du, full.evaluate(0, uv).du);
  }
  EXPECT_LE(contactFigures(edit.surface).curvatureJump, 1e-4);
}
