// The embedding facade (curvenet/curvenet.hpp). Every call is compared with
// the lower-level Surface / tessellate API it stands for — same bits — and
// every failure path must come back as a Status naming the element, with the
// model unchanged, instead of an exception.
#include <gtest/gtest.h>

#include <set>

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <numbers>
#include <random>

#include "curvenet/builtins.hpp"
#include "curvenet/curvenet.hpp"

using namespace curvenet;

namespace {

bool sameBits(const Vec3 &a, const Vec3 &b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
bool samePoint(const SurfacePoint &a, const SurfacePoint &b) {
  return sameBits(a.point, b.point) && sameBits(a.du, b.du) && sameBits(a.dv, b.dv) && sameBits(a.normal, b.normal);
}

/// Uniform random points of face f's domain polygon (fan triangles).
std::vector<Vec2> domainPoints(const Model &model, int face, std::size_t count, unsigned seed) {
  const int n = model.domainSides(face);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Vec2> points(count);
  for (Vec2 &p : points) {
    const int k = static_cast<int>(unit(rng) * n) % n;
    double a = unit(rng), b = unit(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    p = *model.domainCorner(face, k) * a + *model.domainCorner(face, k + 1) * b;
  }
  return points;
}

/// A dome-like loop of five cubic Bézier curves around the unit pentagon.
std::vector<BSplineCurve> pentagonLoop(double lift) {
  std::vector<BSplineCurve> curves;
  auto corner = [](int k) {
    const double a = 2 * std::numbers::pi * k / 5;
    return Vec3{std::cos(a), std::sin(a), 0};
  };
  for (int k = 0; k < 5; ++k) {
    const Vec3 a = corner(k), b = corner(k + 1), up{0, 0, lift};
    curves.push_back(*makeBezier({a, a + (b - a) / 3 + up, b + (a - b) / 3 + up, b}));
  }
  return curves;
}

} // namespace

TEST(Embed, EvaluationEqualsTheSurfaceItWraps) {
  for (Scheme scheme : {Scheme::GregoryG1, Scheme::CompositeRibbon, Scheme::GregoryG2}) {
    auto model = Model::load("builtin:sphere-dodecahedron", {.scheme = scheme});
    ASSERT_TRUE(model.ok()) << model.status().toString();
    const Surface direct = Surface::build(Network::build(builtinNetwork("sphere-dodecahedron")), {.scheme = scheme});
    for (int face : {0, 7}) {
      const std::vector<Vec2> uv = domainPoints(*model, face, 300, face + 1);
      std::vector<SurfacePoint> batch(uv.size()), directBatch(uv.size());
      ASSERT_TRUE(model->evaluate(face, uv, batch).ok());
      direct.evaluate(face, uv, directBatch);
      for (std::size_t k = 0; k < uv.size(); ++k) {
        ASSERT_TRUE(samePoint(batch[k], directBatch[k])) << schemeName(scheme) << " point " << k;
        ASSERT_TRUE(samePoint(*model->evaluate(face, uv[k]), direct.evaluate(face, uv[k])));
      }
    }
  }
}

/// How far a batched evaluation a is from the pointwise b, each part
/// relative to its scale: the position to the model's diagonal, the
/// derivatives to their own size (at least the diagonal's), and the unit
/// normal times sin θ, θ the angle between du and dv (a normal's error is
/// the derivatives' over sin θ).
struct Disagreement {
  double point = 0, derivatives = 0, normal = 0;
  void add(const SurfacePoint &a, const SurfacePoint &b, double diagonal) {
    const double scale = std::max({norm(b.du), norm(b.dv), diagonal});
    const double sine = norm(cross(b.du, b.dv)) / (norm(b.du) * norm(b.dv));
    point = std::max(point, norm(a.point - b.point) / diagonal);
    derivatives = std::max({derivatives, norm(a.du - b.du) / scale, norm(a.dv - b.dv) / scale});
    normal = std::max(normal, norm(a.normal - b.normal) * sine);
  }
};

/// Batched jets (Model::evaluate on a span: tables, batched roots, the
/// derivative kernels) and positions (evaluatePositions: the position
/// kernel) against Surface::evaluate on every face of `name` under each of
/// `schemes`, the curves as given and as repaired; random points, the
/// centre and the corners.
void expectBatchesAgreeWithPointwise(const std::string &name, const std::vector<SurfaceOptions> &schemes,
                                     const std::function<Result<Model>(const SurfaceOptions &)> &build) {
  // The curves as given and as repaired: the repair keeps a Bézier curve
  // one polynomial (it raises the degree instead of inserting a knot inside
  // the side), so the surface has no derivative kink for the two paths to
  // take from different sides.
  for (SurfaceOptions options : schemes) for (CurveHandling curves : {CurveHandling::Kept, CurveHandling::Repaired}) {
    options.curves = curves;
    auto model = build(options);
    if (!model.ok()) continue; // a scheme the network does not take (e.g. a G² master face)
    BoundingBox box;
    for (const Vertex &v : model->network().vertices()) box.add(v.position);
    Disagreement worst;
    double positions = 0;
    for (int face = 0; face < model->faceCount(); ++face) {
      std::vector<Vec2> uv = domainPoints(*model, face, 32, 11 * face + 1);
      uv.push_back({0, 0});
      for (int corner = 0; corner < model->domainSides(face); ++corner) uv.push_back(*model->domainCorner(face, corner));
      std::vector<SurfacePoint> batch(uv.size());
      std::vector<Vec3> points(uv.size());
      ASSERT_TRUE(model->evaluate(face, uv, batch, {.threads = 1}).ok()) << name;
      ASSERT_TRUE(model->evaluatePositions(face, uv, points, {.threads = 1}).ok()) << name;
      for (std::size_t k = 0; k < uv.size(); ++k) {
        const SurfacePoint pointwise = model->surface(face)->evaluate(face, uv[k]);
        worst.add(batch[k], pointwise, box.diagonal());
        positions = std::max(positions, norm(points[k] - pointwise.point) / box.diagonal());
      }
    }
    // The ribbon tables reproduce the ribbons to 1e-13 of their size and
    // their slopes to 1e-10 (ribbon_table.hpp; measured here: derivatives
    // ≤ 3e-12 of their scale, normals ≤ 3e-11 / sin θ).
    const std::string what = name + " " + schemeName(options.scheme) + " sweep " +
                             std::to_string(static_cast<int>(options.sweepline)) + " curves " +
                             curveHandlingName(curves);
    EXPECT_LE(worst.point, 1e-12) << what;
    EXPECT_LE(positions, 1e-12) << what << " (positions)";
    EXPECT_LE(worst.derivatives, 1e-11) << what;
    EXPECT_LE(worst.normal, 1e-10) << what;
  }
}

TEST(Embed, JetBatchesAgreeWithPointwiseEvaluationOnEveryBuiltin) {
  // Every transfinite scheme and sweep (gregory-g1's Hermite sweep takes the
  // roots and kernel of the two G² ones). saddle-nodes' gregory-g2 ribbons
  // saturate (kernels::GregorySamples::reach): the kernels take the reach.
  const std::vector<SurfaceOptions> schemes{{.scheme = Scheme::GregoryG1, .sweepline = Sweepline::Radial},
                                            {.scheme = Scheme::GregoryG2, .sweepline = Sweepline::Hermite},
                                            {.scheme = Scheme::GregoryG2, .sweepline = Sweepline::QuinticHermite},
                                            {.scheme = Scheme::CompositeRibbon}};
  for (const BuiltinInfo &info : builtinNetworks()) {
    const NetworkDescription description = builtinNetwork(info.name);
    expectBatchesAgreeWithPointwise(info.name, schemes,
                                    [&](const SurfaceOptions &options) { return Model::build(description, options); });
  }
}

TEST(Embed, JetBatchesAgreeWithPointwiseEvaluationOnARealNetworkWhoseRibbonsSaturate) {
  // The 3-sided pocket: gregory-g2 saturates its ribbons' cross parameters.
  // (The public sketches saturate too, but their largest curvature terms
  // take the tables' slope error of 1e-10 to 5e-10 of the derivatives.)
  const std::filesystem::path pocket =
      std::filesystem::path(CURVENET_SHARED_DATA_DIR) / "transfinite-models" / "pocket3sided.lop";
  if (!std::filesystem::exists(pocket)) GTEST_SKIP() << pocket << " absent (shared data)";
  expectBatchesAgreeWithPointwise(pocket.filename().string(), {{.scheme = Scheme::GregoryG2}},
                                  [&](const SurfaceOptions &options) { return Model::load(pocket.string(), options); });
}

// A side whose ribbon table cannot reach its tolerances (a rational
// quadratic with middle weight 1e4: its parameter speed is far from uniform,
// and the ribbon's derivatives grow too fast near its ends) stops the batched
// evaluation that builds the table as an input error naming the face as
// well as the side, through Model::evaluate and Model::tessellate alike.
TEST(Embed, ARibbonTableThatCannotBeBuiltNamesTheFaceThroughTheModel) {
  NetworkDescription d;
  d.name = "steep";
  d.curves.push_back(BSplineCurve(2, {0, 0, 0, 1, 1, 1}, {{0, 0, 0}, {0.5, -0.2, 0.3}, {1, 0, 0}}, {1, 1e4, 1}));
  d.curves.push_back(BSplineCurve(1, {0, 0, 1, 1}, {{1, 0, 0}, {0.5, 1, 0}}));
  d.curves.push_back(BSplineCurve(1, {0, 0, 1, 1}, {{0.5, 1, 0}, {0, 0, 0}}));
  d.faces.push_back({{{0, 0, 1}, {1, 0, 1}, {2, 0, 1}}});
  auto model = Model::build(d, {.scheme = Scheme::GregoryG2});
  ASSERT_TRUE(model.ok()) << model.status().toString();
  const std::vector<Vec2> uv(64, Vec2{0.1, 0.1});
  std::vector<SurfacePoint> out(uv.size());
  // The input's, not the engine's: derivatives and values agree.
  const Status evaluated = model->evaluate(0, uv, out, {.threads = 1});
  EXPECT_EQ(evaluated.code, StatusCode::InvalidInput);
  EXPECT_EQ(evaluated.element, "face 0 side 0") << evaluated.toString();
  EXPECT_EQ(evaluated.message.rfind("ribbon table: ", 0), 0u) << evaluated.toString();
  EXPECT_NE(evaluated.message.find("grow too fast"), std::string::npos) << evaluated.toString();
  auto again = Model::build(d, {.scheme = Scheme::GregoryG2});
  ASSERT_TRUE(again.ok());
  const Result<MeshSize> mesh = again->tessellate({.resolution = 40, .threads = 1});
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.status().element, "face 0 side 0") << mesh.status().toString();
}

TEST(Embed, BatchOutputDoesNotDependOnThreads) {
  auto model = Model::load("builtin:pentagon", {.scheme = Scheme::GregoryG2});
  ASSERT_TRUE(model.ok()) << model.status().toString();
  const std::vector<Vec2> uv = domainPoints(*model, 0, 20000, 3);
  std::vector<SurfacePoint> serial(uv.size()), parallel(uv.size()), two(uv.size());
  ASSERT_TRUE(model->evaluate(0, uv, serial, {.threads = 1}).ok());
  ASSERT_TRUE(model->evaluate(0, uv, parallel, {.threads = 0, .parallelThreshold = 1}).ok());
  ASSERT_TRUE(model->evaluate(0, uv, two, {.threads = 2}).ok());
  for (std::size_t k = 0; k < uv.size(); ++k) {
    ASSERT_TRUE(samePoint(serial[k], parallel[k])) << k;
    ASSERT_TRUE(samePoint(serial[k], two[k])) << k;
  }
  // A point's result does not depend on where in a batch (which vector
  // lane, which block) it comes.
  const std::span<const Vec2> shifted = std::span(uv).subspan(3, 1000);
  std::vector<SurfacePoint> alone(shifted.size());
  ASSERT_TRUE(model->evaluate(0, shifted, alone, {.threads = 1}).ok());
  for (std::size_t k = 0; k < shifted.size(); ++k) ASSERT_TRUE(samePoint(alone[k], serial[k + 3])) << k;
}

TEST(Embed, SecondOrderBatchMatchesSurfaceAndIsExactForG2Only) {
  auto model = Model::load("builtin:pentagon", {.scheme = Scheme::GregoryG2});
  ASSERT_TRUE(model.ok());
  EXPECT_TRUE(model->hasExactSecondDerivatives(0));
  const std::vector<Vec2> uv = domainPoints(*model, 0, 50, 4);
  std::vector<SurfacePoint2> out(uv.size());
  ASSERT_TRUE(model->evaluateSecondOrder(0, uv, out).ok());
  for (std::size_t k = 0; k < uv.size(); ++k) {
    const SurfacePoint2 ref = model->surface(0)->evaluateSecondOrder(0, uv[k]);
    EXPECT_TRUE(sameBits(out[k].duu, ref.duu) && sameBits(out[k].duv, ref.duv) && sameBits(out[k].dvv, ref.dvv));
  }
  ASSERT_TRUE(model->setFaceOptions(Model::allFaces, {.scheme = Scheme::GregoryG1}).ok());
  EXPECT_FALSE(model->hasExactSecondDerivatives(0));
  EXPECT_EQ(model->evaluateSecondOrder(0, {0, 0}, {.step = 1.0}).status().code, StatusCode::InvalidArgument);
}

TEST(Embed, PointsOutsideTheDomainAreReportedAndTheRestEvaluated) {
  auto model = Model::load("builtin:pentagon");
  ASSERT_TRUE(model.ok());
  const Vec2 corner = *model->domainCorner(0, 2);
  // A corner and a side midpoint lie on the polygon and must be accepted.
  const Vec2 mid = (*model->domainCorner(0, 0) + *model->domainCorner(0, 1)) * 0.5;
  std::vector<Vec2> uv{{0, 0}, corner, corner * 1.01, mid, {NAN, 0}, {0.1, 0.2}};
  std::vector<SurfacePoint> out(uv.size());
  const Status status = model->evaluate(0, uv, out);
  EXPECT_EQ(status.code, StatusCode::OutOfDomain);
  EXPECT_EQ(status.element, "point 2");
  EXPECT_NE(status.message.find("2 of 6"), std::string::npos) << status.message;
  for (std::size_t k : {0, 1, 3, 5}) EXPECT_TRUE(samePoint(out[k], model->surface(0)->evaluate(0, uv[k]))) << k;
  EXPECT_TRUE(std::isnan(out[2].point.x) && std::isnan(out[4].normal.z));

  EXPECT_EQ(model->evaluate(5, {0, 0}).status().code, StatusCode::InvalidArgument);
  EXPECT_EQ(model->evaluate(5, {0, 0}).status().element, "face 5");
  std::vector<SurfacePoint> tooFew(2);
  EXPECT_EQ(model->evaluate(0, uv, tooFew).code, StatusCode::InvalidArgument);
}

TEST(Embed, PositionBatchesMatchFullEvaluation) {
  for (Scheme scheme : {Scheme::GregoryG1, Scheme::CompositeRibbon, Scheme::GregoryG2}) {
    auto model = Model::load("builtin:hemisphere-tjunction", {.scheme = scheme});
    ASSERT_TRUE(model.ok()) << model.status().toString();
    for (int face = 0; face < model->faceCount(); ++face) {
      std::vector<Vec2> uv = domainPoints(*model, face, 3000, face + 5);
      uv.push_back({NAN, 0.1});                            // not a point: NaN and OutOfDomain
      uv.push_back(*model->domainCorner(face, 1) * 1.5); // outside: NaN and OutOfDomain
      std::vector<Vec3> serial(uv.size()), parallel(uv.size());
      EXPECT_EQ(model->evaluatePositions(face, uv, serial, {.threads = 1}).code, StatusCode::OutOfDomain);
      EXPECT_EQ(model->evaluatePositions(face, uv, parallel, {.threads = 0, .parallelThreshold = 1}).code,
                StatusCode::OutOfDomain);
      EXPECT_TRUE(std::isnan(serial.back().x) && std::isnan(parallel.back().z) && std::isnan(serial[uv.size() - 2].y));
      for (std::size_t k = 0; k + 2 < uv.size(); ++k) {
        ASSERT_TRUE(sameBits(serial[k], parallel[k])) << k;
        const Vec3 full = model->evaluate(face, uv[k])->point;
        ASSERT_LE(norm(serial[k] - full), 1e-12 * (1 + norm(full))) << schemeName(scheme) << " face " << face;
      }
    }
  }
}

TEST(Embed, BadNetworksComeBackAsStatusNotExceptions) {
  // A loop that does not close: the last curve ends away from the first start.
  std::vector<BSplineCurve> open = pentagonLoop(0.3);
  open[4] = *makeBezier({open[4].controlPoints().front(), Vec3{2, 2, 2}});
  auto model = Model::fromLoop(open);
  ASSERT_FALSE(model.ok());
  EXPECT_EQ(model.status().code, StatusCode::InvalidInput);
  EXPECT_NE(model.status().element.find("face 0"), std::string::npos) << model.status().toString();

  EXPECT_EQ(Model::load("no-such-file.json").status().code, StatusCode::InvalidInput);
  EXPECT_EQ(Model::load("builtin:no-such-network").status().code, StatusCode::InvalidInput);
  EXPECT_EQ(makeCurve(2, {0, 0, 1, 1}, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}).status().code, StatusCode::InvalidInput);
  EXPECT_EQ(makeBezier({{0, 0, 0}}).status().code, StatusCode::InvalidInput);
  // gregory-g2 refuses the radial sweep; the failed call leaves the options.
  auto ok = Model::fromLoop(pentagonLoop(0.3));
  ASSERT_TRUE(ok.ok());
  const Status refused = ok->setFaceOptions(0, {.scheme = Scheme::GregoryG2, .sweepline = Sweepline::Radial});
  EXPECT_EQ(refused.code, StatusCode::InvalidInput);
  EXPECT_EQ(ok->faceOptions(0).scheme, Scheme::GregoryG1);
}

TEST(Embed, PerFaceSchemesEvaluateAndTessellateByTheirOwnSurface) {
  auto model = Model::load("builtin:sphere-dodecahedron");
  ASSERT_TRUE(model.ok());
  ASSERT_TRUE(model->setFaceOptions(3, {.scheme = Scheme::GregoryG2}).ok());
  ASSERT_TRUE(model->setFaceOptions(5, {.scheme = Scheme::CompositeRibbon}).ok());
  EXPECT_EQ(model->surfaceCount(), 3);
  const Network network = Network::build(builtinNetwork("sphere-dodecahedron"));
  const Surface g1 = Surface::build(network, {.scheme = Scheme::GregoryG1});
  const Surface g2 = Surface::build(network, {.scheme = Scheme::GregoryG2});
  const Surface cr = Surface::build(network, {.scheme = Scheme::CompositeRibbon});
  const Vec2 uv{0.1, -0.2};
  EXPECT_TRUE(samePoint(*model->evaluate(3, uv), g2.evaluate(3, uv)));
  EXPECT_TRUE(samePoint(*model->evaluate(5, uv), cr.evaluate(5, uv)));
  EXPECT_TRUE(samePoint(*model->evaluate(4, uv), g1.evaluate(4, uv)));

  // The merged mesh: every vertex from the surface of the face it was
  // evaluated in, one shared index buffer (so still watertight).
  auto size = model->tessellate({.resolution = 6, .recordDomainPoints = true});
  ASSERT_TRUE(size.ok());
  const Mesh &mesh = model->mesh();
  const Mesh m1 = tessellate(g1, {.resolution = 6}), m2 = tessellate(g2, {.resolution = 6}),
             mc = tessellate(cr, {.resolution = 6});
  ASSERT_EQ(mesh.triangles, m1.triangles);
  int fromG2 = 0, fromCr = 0;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const int f = mesh.domainPoints[v].face;
    const Mesh &expected = f == 3 ? m2 : f == 5 ? mc : m1;
    ASSERT_TRUE(sameBits(mesh.positions[v], expected.positions[v]) && sameBits(mesh.normals[v], expected.normals[v]))
        << "vertex " << v << " of face " << f;
    fromG2 += f == 3;
    fromCr += f == 5;
  }
  EXPECT_GT(fromG2, 0);
  EXPECT_GT(fromCr, 0);
}

TEST(Embed, OneFaceMeshIsThePieceOfTheWholeMesh) {
  auto model = Model::load("builtin:sphere-dodecahedron");
  ASSERT_TRUE(model.ok());
  const int r = 5;
  auto whole = model->tessellate({.resolution = r});
  ASSERT_TRUE(whole.ok());
  const Mesh all = model->mesh();
  auto one = model->tessellate({.resolution = r}, 4);
  ASSERT_TRUE(one.ok());
  // A pentagon: 5 r boundary samples, 1 + 5 (r − 1) + 5 (r − 1)(r − 2) / 2 inside.
  EXPECT_EQ(one->vertices, std::size_t(5 * r + 1 + 5 * (r - 1) + 5 * (r - 1) * (r - 2) / 2));
  EXPECT_EQ(one->triangles, std::size_t(5 * r * r));
  const Mesh &piece = model->mesh();
  for (std::uint32_t t = all.faceTriangleStart[4]; t < all.faceTriangleStart[5]; ++t)
    for (int c = 0; c < 3; ++c)
      EXPECT_TRUE(sameBits(all.positions[all.triangles[t][c]],
                           piece.positions[piece.triangles[t - all.faceTriangleStart[4]][c]]));

  // Caller buffers: too small is refused, exact size is filled.
  std::vector<Vec3> positions(one->vertices - 1), normals(one->vertices);
  std::vector<std::array<std::uint32_t, 3>> triangles(one->triangles);
  EXPECT_EQ(model->copyMesh(positions, normals, triangles).code, StatusCode::BufferTooSmall);
  positions.resize(one->vertices);
  ASSERT_TRUE(model->copyMesh(positions, normals, triangles).ok());
  EXPECT_TRUE(sameBits(positions.back(), piece.positions.back()) && triangles == piece.triangles);
  EXPECT_TRUE(model->copyMesh(positions, {}, triangles).ok());
  EXPECT_EQ(model->tessellate({.resolution = 0}).status().code, StatusCode::InvalidArgument);
}

TEST(Embed, EditingACurveRebuildsAsAFreshModelWould) {
  auto model = Model::fromLoop(pentagonLoop(0.3), {.scheme = Scheme::GregoryG2});
  ASSERT_TRUE(model.ok());
  ASSERT_TRUE(model->tessellate({.resolution = 4}).ok());
  const SurfacePoint before = *model->evaluate(0, {0, 0});

  // Raise the inner control points of curve 2: the ends stay, so the loop closes.
  std::vector<Vec3> points = model->description().curves[2].controlPoints();
  points[1].z += 0.2;
  points[2].z += 0.2;
  ASSERT_TRUE(model->setControlPoints(2, points).ok());
  EXPECT_TRUE(model->mesh().positions.empty()) << "an edit clears the kept mesh";
  EXPECT_EQ(model->copyMesh({}, {}, {}).code, StatusCode::NoMesh);

  std::vector<BSplineCurve> edited = pentagonLoop(0.3);
  edited[2] = *makeBezier(points);
  auto fresh = Model::fromLoop(edited, {.scheme = Scheme::GregoryG2});
  ASSERT_TRUE(fresh.ok());
  for (const Vec2 &uv : domainPoints(*model, 0, 50, 9))
    ASSERT_TRUE(samePoint(*model->evaluate(0, uv), *fresh->evaluate(0, uv)));
  EXPECT_GT(model->evaluate(0, {0, 0})->point.z, before.point.z);
  // The boundary follows the new curve: domain side 2 shows curve 2.
  const Vec2 side = model->surface(0)->domainPointOnFaceSide(0, 2, 0.5);
  EXPECT_LT(norm(model->evaluate(0, side)->point - edited[2].point(0.5)), 1e-12);

  // An edit that opens the loop is refused and changes nothing.
  const SurfacePoint kept = *model->evaluate(0, {0.1, 0.1});
  points.front().z += 0.5;
  const Status refused = model->setControlPoints(2, points);
  EXPECT_EQ(refused.code, StatusCode::InvalidInput) << refused.toString();
  EXPECT_TRUE(samePoint(*model->evaluate(0, {0.1, 0.1}), kept));
  EXPECT_EQ(model->setControlPoints(2, std::span(points).first(2)).code, StatusCode::InvalidArgument);
  EXPECT_EQ(model->setControlPoints(9, points).code, StatusCode::InvalidArgument);
}

TEST(Embed, EditingACurveRebuildsOnlyTheFacesAroundIt) {
  // Two groups (gregory-g2 everywhere, gregory-g1 on face 5): each group's
  // surface is rebuilt near the edited curve only, and the model evaluates
  // as a freshly built one.
  // On the curves as given: the edit turns the curve's end tangents out of
  // their planes, which the vertex repair would mend on the neighbours too.
  const CurveHandling kept = CurveHandling::Kept;
  auto model = Model::load("builtin:ellipsoid-truncated-icosahedron", {.scheme = Scheme::GregoryG2, .curves = kept});
  ASSERT_TRUE(model.ok());
  ASSERT_TRUE(model->setFaceOptions(5, {.scheme = Scheme::GregoryG1, .curves = kept}).ok());
  ASSERT_EQ(model->surfaceCount(), 2);
  EXPECT_TRUE(model->lastEditedFaces().empty());

  const Segment &seg = model->network().segments()[0];
  const int curve = seg.sourceCurve;
  std::set<int> expected; // faces at the segment's two end vertices (valence 3: four faces)
  for (int v : {seg.start, seg.end})
    for (int e : model->network().vertices()[v].segments)
      for (int f : model->network().segments()[e].faces) expected.insert(f);
  ASSERT_EQ(expected.size(), 4u);

  std::vector<Vec3> points = model->description().curves[curve].controlPoints();
  for (std::size_t k = 1; k + 1 < points.size(); ++k) points[k].z += 0.02;
  ASSERT_TRUE(model->setControlPoints(curve, points).ok());
  EXPECT_EQ(model->lastEditedFaces(), std::vector<int>(expected.begin(), expected.end()));

  auto fresh = Model::build(model->description(), {.scheme = Scheme::GregoryG2, .curves = kept});
  ASSERT_TRUE(fresh.ok());
  ASSERT_TRUE(fresh->setFaceOptions(5, {.scheme = Scheme::GregoryG1, .curves = kept}).ok());
  for (int f = 0; f < model->faceCount(); ++f)
    for (const Vec2 &uv : domainPoints(*model, f, 20, 11))
      ASSERT_TRUE(samePoint(*model->evaluate(f, uv), *fresh->evaluate(f, uv))) << "face " << f;
}

TEST(Embed, AnEditUpdatesTheCachedTessellationOnItsFacesOnly) {
  // On the curves as given (see EditingACurveRebuildsOnlyTheFacesAroundIt).
  const SurfaceOptions keptG2{.scheme = Scheme::GregoryG2, .curves = CurveHandling::Kept};
  auto model = Model::load("builtin:ellipsoid-truncated-icosahedron", keptG2);
  ASSERT_TRUE(model.ok());
  ASSERT_TRUE(model->tessellate({.resolution = 8}).ok());
  const int curve = model->network().segments()[0].sourceCurve;
  std::vector<Vec3> points = model->description().curves[curve].controlPoints();
  for (std::size_t k = 1; k + 1 < points.size(); ++k) points[k].z += 0.02;
  ASSERT_TRUE(model->setControlPoints(curve, points).ok());
  EXPECT_EQ(model->lastEditedFaces().size(), 4u);
  EXPECT_TRUE(model->mesh().positions.empty());
  ASSERT_TRUE(model->tessellate({.resolution = 8}).ok());

  auto fresh = Model::build(model->description(), keptG2);
  ASSERT_TRUE(fresh.ok());
  ASSERT_TRUE(fresh->tessellate({.resolution = 8}).ok());
  EXPECT_EQ(model->mesh().positions, fresh->mesh().positions);
  EXPECT_EQ(model->mesh().normals, fresh->mesh().normals);
  EXPECT_EQ(model->mesh().triangles, fresh->mesh().triangles);
}

// Connection curves split a concave face (and a face with a hole) into
// several: the model's faces are the network's, not the description's. An
// edit that changes the split renumbers the faces: with one option set it is
// a fresh build, with per-face options it is refused and nothing changes.
TEST(Embed, FacesSplitByConnectionCurvesAreTheModelsFaces) {
  for (const char *name : {"concave-L", "ring"}) {
    SCOPED_TRACE(name);
    auto model = Model::load(std::string("builtin:") + name);
    ASSERT_TRUE(model.ok()) << model.status().toString();
    const Network network = Network::build(builtinNetwork(name));
    ASSERT_GT(network.faces().size(), builtinNetwork(name).faces.size());
    ASSERT_EQ(model->faceCount(), static_cast<int>(network.faces().size()));
    const Surface surface = Surface::build(network, {});
    for (int f = 0; f < model->faceCount(); ++f)
      for (const Vec2 &uv : domainPoints(*model, f, 10, 3))
        ASSERT_TRUE(samePoint(*model->evaluate(f, uv), surface.evaluate(f, uv))) << "face " << f;
    EXPECT_TRUE(model->tessellate({.resolution = 4}).ok());
  }

  // concave-L's concave corner is where curve 2 ends and curve 3 starts.
  // Turning curve 3's start tangent from +y to down-left makes the corner
  // convex: the loop is then one 6-sided face.
  auto model = Model::load("builtin:concave-L");
  auto perFace = Model::load("builtin:concave-L");
  ASSERT_TRUE(model.ok() && perFace.ok());
  ASSERT_EQ(model->faceCount(), 2);
  std::vector<Vec3> points = model->description().curves[3].controlPoints();
  const double step = norm(points[1] - points[0]);
  points[1] = points[0] + Vec3{-step, -0.3 * step, 0};

  ASSERT_TRUE(perFace->setFaceOptions(1, {.scheme = Scheme::GregoryG2}).ok());
  const SurfacePoint kept = *perFace->evaluate(1, {0.1, 0.1});
  const Status refused = perFace->setControlPoints(3, points);
  EXPECT_EQ(refused.code, StatusCode::InvalidInput) << refused.toString();
  EXPECT_EQ(perFace->faceCount(), 2);
  EXPECT_TRUE(samePoint(*perFace->evaluate(1, {0.1, 0.1}), kept));

  ASSERT_TRUE(model->setControlPoints(3, points).ok());
  ASSERT_EQ(model->faceCount(), 1);
  EXPECT_EQ(model->domainSides(0), 6);
  auto fresh = Model::build(model->description());
  ASSERT_TRUE(fresh.ok());
  for (const Vec2 &uv : domainPoints(*model, 0, 20, 5))
    ASSERT_TRUE(samePoint(*model->evaluate(0, uv), *fresh->evaluate(0, uv)));
}

// A tessellation that could not fit in memory is refused before any work,
// with the estimate, and the model keeps its mesh: an embedding program gets
// a status rather than the system's out-of-memory killer.
TEST(Embed, TessellationsBeyondTheMachinesMemoryAreRefused) {
  auto model = Model::fromLoop(pentagonLoop(0.3));
  ASSERT_TRUE(model.ok());
  const Result<MeshSize> kept = model->tessellate({.resolution = 4});
  ASSERT_TRUE(kept.ok());
  for (int resolution : {40000, 1 << 24, std::numeric_limits<int>::max()}) {
    const Result<MeshSize> refused = model->tessellate({.resolution = resolution});
    ASSERT_FALSE(refused.ok()) << resolution;
    EXPECT_EQ(refused.status().code, StatusCode::OutOfMemory) << refused.status().toString();
    EXPECT_NE(refused.status().toString().find("GiB"), std::string::npos) << refused.status().toString();
  }
  EXPECT_EQ(model->mesh().positions.size(), kept->vertices);
  EXPECT_EQ(model->mesh().triangles.size(), kept->triangles);
}
