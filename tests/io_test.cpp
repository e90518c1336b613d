// Reading and writing: the native format round trip, .lop files, every kind
// of bad input (each error must name the file, the element and the reason),
// atomic writes and the mesh writers.
#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "input_errors.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "curvenet/network.hpp"
#include "scratch.hpp"

namespace curvenet {
inline namespace v1 {
namespace {

namespace fs = std::filesystem;

const fs::path sharedModels = fs::path(CURVENET_SHARED_DATA_DIR) / "transfinite-models";
const fs::path testData = fs::path(CURVENET_TEST_DATA_DIR);

using test::catchInputError;
using test::contains;

using test::readFile;
using test::ScratchDir;

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

// Doubles chosen to break any writer that rounds: non-terminating binary
// fractions, a sum with a representation error, extreme exponents, -0.
NetworkDescription handBuiltDescription() {
  NetworkDescription d;
  d.name = "hand \"built\" ü";
  d.tolerance = 3.7e-9;
  const double third = 1.0 / 3.0, awkward = 0.1 + 0.2;
  // Rational quadratic with two spans.
  d.curves.emplace_back(2, std::vector<double>{0, 0, 0, third, 1, 1, 1},
                        std::vector<Vec3>{{1, 0, -0.0}, {1, awkward, 1e-300}, {0.5, 1, 2.5e-17}, {0, 1, 0}},
                        std::vector<double>{1, std::sqrt(0.5), 1.0 / 7.0, 1});
  // Polynomial cubic on a non-unit domain.
  d.curves.emplace_back(3, std::vector<double>{-1.5, -1.5, -1.5, -1.5, 0.7, 2.25, 2.25, 2.25, 2.25},
                        std::vector<Vec3>{{0, 1, 0}, {-0.3, 0.6, 1e5 / 3}, {-0.2, 0.2, std::nextafter(1.0, 2.0)},
                                          {0.1, -0.1, 0}, {1, 0, -0.0}});
  FaceDescription face;
  face.name = "face \\ 0";
  face.sides = {{0, 0.0, 1.0}, {1, -1.5, 2.25}};
  d.faces.push_back(face);
  FaceDescription partial;
  partial.sides = {{1, 2.25, third}, {0, 0.75, 0.0}};
  d.faces.push_back(partial);
  d.reference = ReferenceSurface{ReferenceSurface::Kind::Torus, {0.1, -2.0 / 3.0, 1e-12}, {3.0, 0.7, 0.0}, nullptr};
  return d;
}

void expectSameDoubles(const std::vector<double> &a, const std::vector<double> &b, const std::string &what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(bits(a[i]), bits(b[i])) << what << "[" << i << "]";
}
void expectSameVec(const Vec3 &a, const Vec3 &b, const std::string &what) {
  EXPECT_EQ(bits(a.x), bits(b.x)) << what;
  EXPECT_EQ(bits(a.y), bits(b.y)) << what;
  EXPECT_EQ(bits(a.z), bits(b.z)) << what;
}

void expectIdentical(const NetworkDescription &a, const NetworkDescription &b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(bits(a.tolerance), bits(b.tolerance));
  ASSERT_EQ(a.curves.size(), b.curves.size());
  for (std::size_t i = 0; i < a.curves.size(); ++i) {
    const BSplineCurve &ca = a.curves[i], &cb = b.curves[i];
    const std::string name = "curve " + std::to_string(i);
    EXPECT_EQ(ca.degree(), cb.degree()) << name;
    expectSameDoubles(ca.knots(), cb.knots(), name + " knots");
    expectSameDoubles(ca.weights(), cb.weights(), name + " weights");
    ASSERT_EQ(ca.controlPoints().size(), cb.controlPoints().size()) << name;
    for (std::size_t k = 0; k < ca.controlPoints().size(); ++k)
      expectSameVec(ca.controlPoints()[k], cb.controlPoints()[k], name + " point " + std::to_string(k));
  }
  ASSERT_EQ(a.faces.size(), b.faces.size());
  for (std::size_t f = 0; f < a.faces.size(); ++f) {
    EXPECT_EQ(a.faces[f].name, b.faces[f].name);
    ASSERT_EQ(a.faces[f].sides.size(), b.faces[f].sides.size());
    for (std::size_t k = 0; k < a.faces[f].sides.size(); ++k) {
      const SideDescription &sa = a.faces[f].sides[k], &sb = b.faces[f].sides[k];
      EXPECT_EQ(sa.curve, sb.curve);
      EXPECT_EQ(bits(sa.from), bits(sb.from)) << "face " << f << " side " << k;
      EXPECT_EQ(bits(sa.to), bits(sb.to)) << "face " << f << " side " << k;
    }
  }
  ASSERT_EQ(a.reference.has_value(), b.reference.has_value());
  if (a.reference) {
    EXPECT_EQ(a.reference->kind, b.reference->kind);
    expectSameVec(a.reference->center, b.reference->center, "reference center");
    expectSameVec(a.reference->size, b.reference->size, "reference size");
  }
}

// ---------------------------------------------------------------- native format

TEST(NativeFormat, RoundTripIsExact) {
  const NetworkDescription original = handBuiltDescription();
  const std::string text = networkToJson(original);
  const NetworkDescription parsed = parseNetworkJson(text, "round.json");
  expectIdentical(original, parsed);
  EXPECT_TRUE(parsed.curves[0].isRational());
  EXPECT_FALSE(parsed.curves[1].isRational());
  EXPECT_EQ(networkToJson(parsed), text);
}

TEST(NativeFormat, RoundTripThroughAFile) {
  ScratchDir dir;
  const NetworkDescription original = handBuiltDescription();
  const fs::path path = dir.path() / "net.json";
  writeFileAtomically(path.string(), [&](std::ostream &out) { out << networkToJson(original); });
  const NetworkDescription read = readNetworkFile(path.string());
  expectIdentical(original, read);
  EXPECT_EQ(dir.listing(), std::vector<std::string>{"net.json"});
}

TEST(NativeFormat, DocumentedExampleParses) {
  const fs::path path = testData / "quarter-sphere.json";
  const NetworkDescription d = readNetworkFile(path.string());
  EXPECT_EQ(d.name, "quarter-sphere");
  ASSERT_EQ(d.curves.size(), 2u);
  EXPECT_TRUE(d.curves[0].isRational());
  // The rational quadratic of the example is an exact quarter circle.
  for (double t : {0.1, 0.5, 0.9}) EXPECT_NEAR(norm(d.curves[0].point(t)), 1.0, 1e-14);
  ASSERT_EQ(d.faces.size(), 1u);
  EXPECT_EQ(d.faces[0].name, "cap");
  ASSERT_EQ(d.faces[0].sides.size(), 2u);
  ASSERT_TRUE(d.reference.has_value());
  EXPECT_EQ(d.reference->kind, ReferenceSurface::Kind::Ellipsoid);
}

TEST(NativeFormat, SideRangeDefaultsToCurveDomain) {
  const std::string text = R"({"format": "curvenet-network", "version": 1,
    "curves": [{"degree": 1, "knots": [2, 2, 5, 5], "points": [[0,0,0],[1,0,0]]}],
    "faces": [{"sides": [{"curve": 0}, {"curve": 0, "to": 3}]}],
    "edges": [{"curve": 0}]})";
  const NetworkDescription d = parseNetworkJson(text, "defaults.json");
  ASSERT_EQ(d.faces.size(), 1u);
  EXPECT_EQ(d.faces[0].sides[0].from, 2.0);
  EXPECT_EQ(d.faces[0].sides[0].to, 5.0);
  EXPECT_EQ(d.faces[0].sides[1].from, 2.0);
  EXPECT_EQ(d.faces[0].sides[1].to, 3.0);
  EXPECT_EQ(d.tolerance, NetworkDescription{}.tolerance);
  EXPECT_FALSE(d.reference.has_value());
}

// A valid document with one curve replaced, for the bad-input tests.
std::string withCurve(const std::string &curve, const std::string &extra = {}) {
  return R"({"format": "curvenet-network", "version": 1, "curves": [)" + curve +
         R"(], "faces": [{"sides": [{"curve": 0}]}])" + extra + "}";
}
const std::string goodCurve = R"({"degree": 1, "knots": [0, 0, 1, 1], "points": [[0, 0, 0], [1, 0, 0]]})";

TEST(NativeFormatErrors, TruncatedDocument) {
  const std::string text = "{\n  \"format\": \"curvenet-network\",\n  \"curves\": [\n    {\"degree\": 1";
  InputError e = catchInputError([&] { parseNetworkJson(text, "cut.json"); });
  EXPECT_EQ(e.file(), "cut.json");
  EXPECT_EQ(e.element(), "line 4 column 17");
  EXPECT_TRUE(contains(e.reason(), "unexpected end of input")) << e.reason();
}

TEST(NativeFormatErrors, SyntaxErrorNamesLineAndColumn) {
  const std::string text = "{\n  \"format\": \"curvenet-network\",\n  \"version\": 1,,\n}";
  InputError e = catchInputError([&] { parseNetworkJson(text, "syntax.json"); });
  EXPECT_EQ(e.file(), "syntax.json");
  EXPECT_EQ(e.element(), "line 3 column 16");
  EXPECT_TRUE(contains(e.reason(), "JSON syntax error")) << e.reason();
  EXPECT_TRUE(contains(e.what(), "syntax.json: line 3 column 16: ")) << e.what();
}

TEST(NativeFormatErrors, NumberTooLargeForADouble) {
  InputError e = catchInputError(
      [&] { parseNetworkJson(withCurve(R"({"degree": 1, "knots": [0, 0, 1, 1],
      "points": [[0, 0, 1e400], [1, 0, 0]]})"), "huge.json"); });
  EXPECT_EQ(e.file(), "huge.json");
  EXPECT_EQ(e.element(), "line 2 column 25");
  EXPECT_TRUE(contains(e.reason(), "1e400")) << e.reason();
}

TEST(NativeFormatErrors, UnknownKeys) {
  InputError top = catchInputError([&] { parseNetworkJson(withCurve(goodCurve, R"(, "tolerence": 1e-6)"), "k.json"); });
  EXPECT_EQ(top.file(), "k.json");
  EXPECT_EQ(top.element(), "document");
  EXPECT_TRUE(contains(top.reason(), "unknown key \"tolerence\"")) << top.reason();

  InputError curve = catchInputError([&] {
    parseNetworkJson(withCurve(R"({"degree": 1, "knots": [0, 0, 1, 1], "points": [[0,0,0],[1,0,0]], "weight": [1, 1]})"),
                     "k.json");
  });
  EXPECT_EQ(curve.element(), "curves[0]");
  EXPECT_TRUE(contains(curve.reason(), "unknown key \"weight\"")) << curve.reason();
  EXPECT_TRUE(contains(curve.reason(), "weights")) << "lists the allowed keys: " << curve.reason();

  const std::string sides = R"({"format": "curvenet-network", "version": 1, "curves": [)" + goodCurve + R"(],
    "faces": [{"sides": [{"curve": 0}]}, {"sides": [{"curve": 0}, {"curve": 0}, {"curve": 0, "form": 0}]}]})";
  InputError side = catchInputError([&] { parseNetworkJson(sides, "k.json"); });
  EXPECT_EQ(side.element(), "faces[1].sides[2]");
  EXPECT_TRUE(contains(side.reason(), "unknown key \"form\"")) << side.reason();

  InputError reference = catchInputError([&] {
    parseNetworkJson(withCurve(goodCurve, R"(, "reference": {"kind": "torus", "center": [0,0,0], "size": [2,1,0], "radius": 1})"),
                     "k.json");
  });
  EXPECT_EQ(reference.element(), "reference");
  EXPECT_TRUE(contains(reference.reason(), "\"radius\"")) << reference.reason();
}

TEST(NativeFormatErrors, ReservedEdgesRejectUnknownSettings) {
  InputError e = catchInputError(
      [&] { parseNetworkJson(withCurve(goodCurve, R"(, "edges": [{"curve": 0}, {"curve": 0, "continuity": 2}])"), "e.json"); });
  EXPECT_EQ(e.file(), "e.json");
  EXPECT_EQ(e.element(), "edges[1]");
  EXPECT_TRUE(contains(e.reason(), "unknown key \"continuity\"")) << e.reason();
  EXPECT_TRUE(contains(e.reason(), "reserved")) << e.reason();

  InputError index = catchInputError([&] { parseNetworkJson(withCurve(goodCurve, R"(, "edges": [{"curve": 4}])"), "e.json"); });
  EXPECT_EQ(index.element(), "edges[0].curve");
}

TEST(NativeFormatErrors, DuplicateKey) {
  InputError e = catchInputError([&] {
    parseNetworkJson(withCurve(R"({"degree": 1, "knots": [0, 0, 1, 1], "points": [[0,0,0],[1,0,0]], "knots": [0, 0, 2, 2]})"),
                     "dup.json");
  });
  EXPECT_EQ(e.file(), "dup.json");
  EXPECT_EQ(e.element(), "curves[0]");
  EXPECT_TRUE(contains(e.reason(), "duplicate key \"knots\"")) << e.reason();
}

TEST(NativeFormatErrors, WrongTypes) {
  InputError knot = catchInputError([&] {
    parseNetworkJson(withCurve(R"({"degree": 1, "knots": [0, 0, "1", 1], "points": [[0,0,0],[1,0,0]]})"), "t.json");
  });
  EXPECT_EQ(knot.file(), "t.json");
  EXPECT_EQ(knot.element(), "curves[0].knots[2]");
  EXPECT_TRUE(contains(knot.reason(), "expected a number, found a string")) << knot.reason();

  InputError degree = catchInputError([&] {
    parseNetworkJson(withCurve(R"({"degree": 1.0, "knots": [0, 0, 1, 1], "points": [[0,0,0],[1,0,0]]})"), "t.json");
  });
  EXPECT_EQ(degree.element(), "curves[0].degree");
  EXPECT_TRUE(contains(degree.reason(), "expected an integer")) << degree.reason();

  InputError faces = catchInputError([&] {
    parseNetworkJson(R"({"format": "curvenet-network", "version": 1, "curves": [], "faces": {}})", "t.json");
  });
  EXPECT_EQ(faces.element(), "faces");
  EXPECT_TRUE(contains(faces.reason(), "expected an array, found an object")) << faces.reason();

  InputError version = catchInputError(
      [&] { parseNetworkJson(R"({"format": "curvenet-network", "version": 2, "curves": [], "faces": []})", "t.json"); });
  EXPECT_EQ(version.element(), "version");
  EXPECT_TRUE(contains(version.reason(), "unsupported version 2")) << version.reason();

  InputError format = catchInputError([&] { parseNetworkJson(R"({"format": "obj", "version": 1})", "t.json"); });
  EXPECT_EQ(format.element(), "format");
}

TEST(NativeFormatErrors, MissingRequiredKey) {
  InputError e = catchInputError(
      [&] { parseNetworkJson(withCurve(R"({"degree": 1, "points": [[0,0,0],[1,0,0]]})"), "m.json"); });
  EXPECT_EQ(e.file(), "m.json");
  EXPECT_EQ(e.element(), "curves[0]");
  EXPECT_TRUE(contains(e.reason(), "missing required key \"knots\"")) << e.reason();
}

TEST(NativeFormatErrors, WrongCounts) {
  InputError knots = catchInputError([&] {
    parseNetworkJson(withCurve(R"({"degree": 2, "knots": [0, 0, 0, 1, 1], "points": [[0,0,0],[1,0,0],[1,1,0]]})"), "c.json");
  });
  EXPECT_EQ(knots.file(), "c.json");
  EXPECT_EQ(knots.element(), "curves[0].knots");
  EXPECT_TRUE(contains(knots.reason(), "expected 6 knots")) << knots.reason();
  EXPECT_TRUE(contains(knots.reason(), "found 5")) << knots.reason();

  InputError arity = catchInputError([&] {
    parseNetworkJson(withCurve(R"({"degree": 1, "knots": [0, 0, 1, 1], "points": [[0,0,0],[1,0]]})"), "c.json");
  });
  EXPECT_EQ(arity.element(), "curves[0].points[1]");
  EXPECT_TRUE(contains(arity.reason(), "expected 3 coordinates")) << arity.reason();

  InputError weights = catchInputError([&] {
    parseNetworkJson(withCurve(R"({"degree": 1, "knots": [0, 0, 1, 1], "points": [[0,0,0],[1,0,0]], "weights": [1]})"),
                     "c.json");
  });
  EXPECT_EQ(weights.element(), "curves[0].weights");
}

TEST(NativeFormatErrors, BadCurveIndex) {
  const std::string head = R"({"format": "curvenet-network", "version": 1, "curves": [)" + goodCurve + R"(],
    "faces": [{"sides": [{"curve": 0}, )";
  for (const char *bad : {"1", "-1", "18446744073709551615"}) {
    InputError e = catchInputError([&] { parseNetworkJson(head + R"({"curve": )" + bad + "}]}]}", "i.json"); });
    EXPECT_EQ(e.file(), "i.json");
    EXPECT_EQ(e.element(), "faces[0].sides[1].curve");
    EXPECT_TRUE(contains(e.reason(), "out of range")) << e.reason();
    EXPECT_TRUE(contains(e.reason(), "has 1 curve)")) << e.reason();
  }
}

TEST(NativeFormatErrors, CurveValidationIsWrappedWithItsElement) {
  // Knots that are not clamped pass the count check and fail in BSplineCurve.
  const std::string text = R"({"format": "curvenet-network", "version": 1, "curves": [)" + goodCurve + ", " +
                           R"({"degree": 2, "knots": [0, 0, 0.5, 1, 1, 1], "points": [[0,0,0],[1,0,0],[1,1,0]]})" +
                           R"(], "faces": []})";
  InputError e = catchInputError([&] { parseNetworkJson(text, "v.json"); });
  EXPECT_EQ(e.file(), "v.json");
  EXPECT_EQ(e.element(), "curves[1]");
  EXPECT_FALSE(e.reason().empty());
  EXPECT_TRUE(contains(e.reason(), "clamped")) << e.reason();

  InputError weight = catchInputError([&] {
    parseNetworkJson(withCurve(R"({"degree": 1, "knots": [0, 0, 1, 1], "points": [[0,0,0],[1,0,0]], "weights": [1, -2]})"),
                     "v.json");
  });
  EXPECT_EQ(weight.element(), "curves[0]");
  EXPECT_TRUE(contains(weight.reason(), "positive")) << weight.reason();
}

TEST(NativeFormatErrors, BadReference) {
  InputError kind = catchInputError([&] {
    parseNetworkJson(withCurve(goodCurve, R"(, "reference": {"kind": "sphere", "center": [0,0,0], "size": [1,1,1]})"), "r.json");
  });
  EXPECT_EQ(kind.element(), "reference.kind");
  EXPECT_TRUE(contains(kind.reason(), "\"sphere\"")) << kind.reason();

  InputError size = catchInputError([&] {
    parseNetworkJson(withCurve(goodCurve, R"(, "reference": {"kind": "ellipsoid", "center": [0,0,0], "size": [1,0,1]})"),
                     "r.json");
  });
  EXPECT_EQ(size.element(), "reference.size");
}

// ---------------------------------------------------------------- .lop files

void expectLoopCloses(const NetworkDescription &d) {
  ASSERT_EQ(d.faces.size(), 1u);
  const FaceDescription &face = d.faces[0];
  ASSERT_EQ(face.sides.size(), d.curves.size());
  BoundingBox box;
  for (const BSplineCurve &c : d.curves)
    for (const Vec3 &p : c.controlPoints()) box.add(p);
  for (std::size_t i = 0; i < face.sides.size(); ++i) {
    const SideDescription &side = face.sides[i], &next = face.sides[(i + 1) % face.sides.size()];
    EXPECT_EQ(side.curve, static_cast<int>(i));
    EXPECT_EQ(side.from, d.curves[i].domainStart());
    EXPECT_EQ(side.to, d.curves[i].domainEnd());
    const Vec3 end = d.curves[side.curve].point(side.to), start = d.curves[next.curve].point(next.from);
    EXPECT_LE(norm(end - start), 1e-9 * box.diagonal()) << "side " << i << " does not meet side " << (i + 1);
  }
}

TEST(Lop, FixtureParses) {
  const NetworkDescription d = readNetworkFile((testData / "triangle.lop").string());
  EXPECT_EQ(d.name, "triangle");
  ASSERT_EQ(d.curves.size(), 3u);
  EXPECT_EQ(d.curves[0].degree(), 2);
  EXPECT_EQ(d.curves[1].domainEnd(), 2.0);
  expectLoopCloses(d);
}

TEST(Lop, SharedExamplesParse) {
  if (!fs::exists(sharedModels)) GTEST_SKIP() << "shared models not present at " << sharedModels;
  const std::pair<const char *, std::size_t> models[] = {{"cagd86.lop", 5}, {"pocket3sided.lop", 3}};
  for (const auto &[file, curves] : models) {
    SCOPED_TRACE(file);
    const NetworkDescription d = readNetworkFile((sharedModels / file).string());
    EXPECT_EQ(d.curves.size(), curves);
    EXPECT_EQ(d.name, fs::path(file).stem().string());
    EXPECT_EQ(d.faces[0].name, d.name);
    expectLoopCloses(d);
  }
}

TEST(Lop, SharedExamplesBuildNetworks) {
  if (!fs::exists(sharedModels)) GTEST_SKIP() << "shared models not present at " << sharedModels;
  for (const char *file : {"cagd86.lop", "pocket3sided.lop"}) {
    SCOPED_TRACE(file);
    const std::string path = (sharedModels / file).string();
    const Network net = Network::build(readNetworkFile(path), path);
    ASSERT_EQ(net.faces().size(), 1u);
    EXPECT_EQ(net.faces()[0].sides.size(), readNetworkFile(path).curves.size());
  }
}

const std::string goodLop = "2\n1\n4 0 0 1 1\n2 0 0 0 1 0 0\n1\n4 0 0 1 1\n2 1 0 0 0 0 0\n";

TEST(Lop, WhitespaceLayoutDoesNotMatter) {
  const NetworkDescription d = parseLop("2 1 4 0 0 1 1 2\n0 0 0\n1 0 0\r\n1\t4 0 0 1 1 2 1 0 0 +0 0 0", "flat.lop");
  const NetworkDescription reference = parseLop(goodLop, "flat.lop");
  EXPECT_EQ(networkToJson(d), networkToJson(reference));
}

TEST(LopErrors, NonFiniteNumbers) {
  for (const char *bad : {"nan", "inf", "-Infinity", "1e999"}) {
    std::string text = goodLop;
    text.replace(text.find("2 1 0 0"), 7, std::string("2 1 ") + bad + " 0");
    InputError e = catchInputError([&] { parseLop(text, "nan.lop"); });
    EXPECT_EQ(e.file(), "nan.lop");
    EXPECT_EQ(e.element(), "line 7") << bad;
    EXPECT_TRUE(contains(e.reason(), bad)) << e.reason();
  }
}

TEST(LopErrors, TruncatedFile) {
  // Cut inside the coordinates of the second curve: 6 announced, 4 present.
  const std::string text = goodLop.substr(0, goodLop.rfind(" 0 0"));
  InputError e = catchInputError([&] { parseLop(text, "cut.lop"); });
  EXPECT_EQ(e.file(), "cut.lop");
  EXPECT_EQ(e.element(), "line 7");
  EXPECT_TRUE(contains(e.reason(), "expected 6 numbers")) << e.reason();
  EXPECT_TRUE(contains(e.reason(), "found 4")) << e.reason();

  // Cut right after a curve: the next degree is missing.
  InputError early = catchInputError([&] { parseLop("2\n1\n4 0 0 1 1\n2 0 0 0 1 0 0\n", "cut.lop"); });
  EXPECT_EQ(early.element(), "line 4");
  EXPECT_TRUE(contains(early.reason(), "ends early")) << early.reason();

  InputError empty = catchInputError([&] { parseLop("  \n", "empty.lop"); });
  EXPECT_EQ(empty.file(), "empty.lop");
  EXPECT_TRUE(contains(empty.reason(), "empty")) << empty.reason();
}

TEST(LopErrors, NonNumericToken) {
  std::string text = goodLop;
  text.replace(text.find("4 0 0 1 1\n2 1"), 9, "4 0 0 one 1");
  InputError e = catchInputError([&] { parseLop(text, "word.lop"); });
  EXPECT_EQ(e.file(), "word.lop");
  EXPECT_EQ(e.element(), "line 6");
  EXPECT_TRUE(contains(e.reason(), "\"one\"")) << e.reason();
}

TEST(LopErrors, AbsurdCountsDoNotAllocate) {
  InputError huge = catchInputError([&] { parseLop("1\n3\n2000000000 0 0 0 0 1 1 1 1\n", "huge.lop"); });
  EXPECT_EQ(huge.element(), "line 3");
  EXPECT_TRUE(contains(huge.reason(), "expected 2000000000 numbers")) << huge.reason();

  InputError negative = catchInputError([&] { parseLop("1\n3\n-8 0 0 0 0 1 1 1 1\n", "neg.lop"); });
  EXPECT_EQ(negative.element(), "line 3");
  EXPECT_TRUE(contains(negative.reason(), "-8")) << negative.reason();

  InputError curves = catchInputError([&] { parseLop("99999999999999999999\n", "many.lop"); });
  EXPECT_EQ(curves.element(), "line 1");

  InputError announced = catchInputError([&] { parseLop("1000\n1\n4 0 0 1 1\n2 0 0 0 1 0 0\n", "many.lop"); });
  EXPECT_EQ(announced.element(), "line 1");
  EXPECT_TRUE(contains(announced.reason(), "1000 curves")) << announced.reason();
}

TEST(LopErrors, DegreeAndKnotCount) {
  InputError degree = catchInputError([&] { parseLop("1\n0\n2 0 1\n1 0 0 0\n", "deg.lop"); });
  EXPECT_EQ(degree.element(), "line 2");
  EXPECT_TRUE(contains(degree.reason(), "degree")) << degree.reason();

  // Consistent on its own (5 knots, 5 numbers) but wrong for 2 points of degree 1.
  InputError knots = catchInputError([&] { parseLop("1\n1\n5 0 0 0.5 1 1\n2 0 0 0 1 0 0\n", "knots.lop"); });
  EXPECT_EQ(knots.file(), "knots.lop");
  EXPECT_EQ(knots.element(), "line 3");
  EXPECT_TRUE(contains(knots.reason(), "expected 4 knots")) << knots.reason();

  InputError trailing = catchInputError([&] { parseLop(goodLop + "7\n", "tail.lop"); });
  EXPECT_EQ(trailing.element(), "line 8");
}

TEST(LopErrors, CurveValidationNamesTheCurveLine) {
  // Decreasing knots: counts are right, BSplineCurve rejects it.
  InputError e = catchInputError([&] { parseLop("2\n1\n4 0 0 1 1\n2 0 0 0 1 0 0\n1\n4 0 1 0 1\n2 1 0 0 0 0 0\n", "v.lop"); });
  EXPECT_EQ(e.file(), "v.lop");
  EXPECT_EQ(e.element(), "line 5");
  EXPECT_TRUE(contains(e.reason(), "curve 1")) << e.reason();
}

// ---------------------------------------------------------------- files

TEST(Files, UnknownExtension) {
  InputError e = catchInputError([&] { readNetworkFile("model.step"); });
  EXPECT_EQ(e.file(), "model.step");
  EXPECT_TRUE(contains(e.reason(), "\".step\"")) << e.reason();
  EXPECT_TRUE(contains(e.reason(), ".json")) << e.reason();
}

TEST(Files, MissingFile) {
  ScratchDir dir;
  const std::string path = (dir.path() / "absent.json").string();
  InputError e = catchInputError([&] { readNetworkFile(path); });
  EXPECT_EQ(e.file(), path);
  EXPECT_TRUE(contains(e.reason(), std::strerror(ENOENT))) << e.reason();

  // A folder opens but cannot be read: the reason is the system's.
  fs::create_directory(dir.path() / "folder.lop");
  InputError directory = catchInputError([&] { readNetworkFile((dir.path() / "folder.lop").string()); });
  EXPECT_TRUE(contains(directory.reason(), std::strerror(EISDIR))) << directory.reason();
}

TEST(Files, LoadNetworkInputReadsFiles) {
  const NetworkDescription d = loadNetworkInput((testData / "triangle.lop").string());
  EXPECT_EQ(d.curves.size(), 3u);
}

TEST(Files, LoadNetworkInputResolvesBuiltins) {
  const NetworkDescription viaInput = loadNetworkInput("builtin:" + defaultBuiltinName());
  const NetworkDescription direct = builtinNetwork(defaultBuiltinName());
  EXPECT_EQ(networkToJson(viaInput), networkToJson(direct));
  EXPECT_FALSE(viaInput.curves.empty());

  InputError e = catchInputError([&] { loadNetworkInput("builtin:no-such-network"); });
  EXPECT_TRUE(contains(e.what(), "no-such-network")) << e.what();
}

TEST(Files, BuiltinSurvivesTheNativeFormat) {
  // Built-ins are the richest descriptions we have (many curves, a reference).
  const NetworkDescription d = builtinNetwork(defaultBuiltinName());
  const std::string text = networkToJson(d);
  const NetworkDescription parsed = parseNetworkJson(text, "builtin.json");
  expectIdentical(d, parsed);
  EXPECT_EQ(networkToJson(parsed), text);
}

TEST(Files, JsonNameDefaultsToStem) {
  ScratchDir dir;
  const fs::path path = dir.path() / "nameless.json";
  writeFileAtomically(path.string(), [](std::ostream &out) { out << withCurve(goodCurve); });
  EXPECT_EQ(readNetworkFile(path.string()).name, "nameless");
  // Errors from the parser carry the path.
  writeFileAtomically(path.string(), [](std::ostream &out) { out << "{"; });
  EXPECT_EQ(catchInputError([&] { readNetworkFile(path.string()); }).file(), path.string());
}

// ---------------------------------------------------------------- topology errors from Network::build

// A degree-2 curve from a to b through the control point m.
std::string arc(const Vec3 &a, const Vec3 &m, const Vec3 &b) {
  auto p = [](const Vec3 &v) {
    return "[" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + "]";
  };
  return R"({"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "points": [)" + p(a) + ", " + p(m) + ", " + p(b) + "]}";
}

std::string network(const std::vector<std::string> &curves, const std::string &faces, const std::string &tolerance = "1e-7") {
  std::string s = R"({"format": "curvenet-network", "version": 1, "tolerance": )" + tolerance + R"(, "curves": [)";
  for (std::size_t i = 0; i < curves.size(); ++i) s += (i ? ", " : "") + curves[i];
  return s + R"(], "faces": )" + faces + "}";
}

const Vec3 A{0, 0, 0}, B{1, 0, 0}, C{0, 1, 0};

TEST(NetworkBuildErrors, LoopDoesNotClose) {
  const std::string text = network({arc(A, {0.5, -0.1, 0.1}, B), arc(B, {0.6, 0.6, 0.1}, C), arc(C, {0, 0.7, 0.1}, {0, 0.4, 0})},
                                   R"([{"sides": [{"curve": 0}, {"curve": 1}, {"curve": 2}]}])");
  InputError e = catchInputError([&] { Network::build(parseNetworkJson(text, "bad.json"), "bad.json"); });
  EXPECT_EQ(e.file(), "bad.json");
  EXPECT_TRUE(contains(e.element(), "face 0")) << e.element();
  EXPECT_TRUE(contains(e.reason(), "close")) << e.reason();
}

TEST(NetworkBuildErrors, CurvesDoNotMeetWithinTolerance) {
  // The last curve stops 1e-4 short of A: far outside 1e-7 × diagonal, but
  // inside 1e-3 × diagonal, which must then build.
  const std::vector<std::string> curves = {arc(A, {0.5, -0.1, 0.1}, B), arc(B, {0.6, 0.6, 0.1}, C),
                                           arc(C, {-0.1, 0.5, 0.1}, {1e-4, 0, 0})};
  const std::string faces = R"([{"sides": [{"curve": 0}, {"curve": 1}, {"curve": 2}]}])";
  InputError e = catchInputError([&] { Network::build(parseNetworkJson(network(curves, faces), "bad.json"), "bad.json"); });
  EXPECT_EQ(e.file(), "bad.json");
  EXPECT_TRUE(contains(e.element(), "face 0")) << e.element();
  EXPECT_TRUE(contains(e.reason(), "close")) << e.reason();

  const Network net = Network::build(parseNetworkJson(network(curves, faces, "1e-3"), "ok.json"), "ok.json");
  EXPECT_EQ(net.vertices().size(), 3u);
}

TEST(NetworkBuildErrors, SegmentUsedByThreeFaces) {
  // Curve 0 runs A→B; three two-sided loops close over it with different arcs.
  const std::vector<std::string> curves = {arc(A, {0.5, 0, 0}, B), arc(B, {0.5, 0.5, 0.2}, A), arc(A, {0.5, -0.5, 0.2}, B),
                                           arc(B, {0.5, 0, 0.6}, A)};
  const std::string faces = R"([{"sides": [{"curve": 0}, {"curve": 1}]},
                                {"sides": [{"curve": 0, "from": 1, "to": 0}, {"curve": 2}]},
                                {"sides": [{"curve": 0}, {"curve": 3}]}])";
  InputError e = catchInputError([&] { Network::build(parseNetworkJson(network(curves, faces), "bad.json"), "bad.json"); });
  EXPECT_EQ(e.file(), "bad.json");
  EXPECT_TRUE(contains(e.element(), "face 2")) << e.element();
  EXPECT_TRUE(contains(e.reason(), "three faces")) << e.reason();
}

// ---------------------------------------------------------------- atomic writes

TEST(AtomicWrite, ThrowingWriterLeavesNothing) {
  ScratchDir dir;
  const std::string path = (dir.path() / "out.obj").string();
  EXPECT_THROW(writeFileAtomically(path,
                                   [](std::ostream &out) {
                                     out << "partial content\n";
                                     throw std::runtime_error("writer failed");
                                   }),
               std::runtime_error);
  EXPECT_TRUE(dir.listing().empty());
}

TEST(AtomicWrite, ExistingTargetIsUntouchedOnFailure) {
  ScratchDir dir;
  const fs::path path = dir.path() / "out.obj";
  writeFileAtomically(path.string(), [](std::ostream &out) { out << "original\n"; });
  EXPECT_THROW(writeFileAtomically(path.string(),
                                   [](std::ostream &out) {
                                     out << "replacement";
                                     throw std::runtime_error("writer failed");
                                   }),
               std::runtime_error);
  EXPECT_EQ(readFile(path), "original\n");
  EXPECT_EQ(dir.listing(), std::vector<std::string>{"out.obj"});

  // A success replaces it and leaves no temporary.
  writeFileAtomically(path.string(), [](std::ostream &out) { out << "replacement\n"; });
  EXPECT_EQ(readFile(path), "replacement\n");
  EXPECT_EQ(dir.listing(), std::vector<std::string>{"out.obj"});
}

TEST(AtomicWrite, UnwritableFolderIsAnInputError) {
  ScratchDir dir;
  const std::string path = (dir.path() / "missing-folder" / "out.obj").string();
  InputError e = catchInputError([&] { writeFileAtomically(path, [](std::ostream &out) { out << "x"; }); });
  EXPECT_EQ(e.file(), path);
  EXPECT_TRUE(contains(e.reason(), std::strerror(ENOENT))) << e.reason();
}

// ---------------------------------------------------------------- mesh writers

Mesh smallMesh() {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0.1}, {1.0 / 3.0, 1, -2.5e-9}};
  for (const Vec3 &p : m.positions) m.normals.push_back(normalized(Vec3{-0.1 * p.x, 0.05, 1}));
  m.triangles = {{0, 1, 2}, {1, 3, 2}};
  return m;
}

TEST(MeshWriters, ObjParsesBack) {
  ScratchDir dir;
  const Mesh mesh = smallMesh();
  const fs::path path = dir.path() / "mesh.obj";
  writeMeshFile(mesh, path.string());
  std::istringstream in(readFile(path));
  std::vector<Vec3> positions, normals;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (std::string line; std::getline(in, line);) {
    std::istringstream s(line);
    std::string tag;
    s >> tag;
    if (tag == "v" || tag == "vn") {
      std::string x, y, z;
      s >> x >> y >> z;
      (tag == "v" ? positions : normals).push_back({std::stod(x), std::stod(y), std::stod(z)});
    } else if (tag == "f") {
      std::array<std::uint32_t, 3> t{};
      for (auto &v : t) {
        std::string ref;
        s >> ref;
        const auto slashes = ref.find("//");
        ASSERT_NE(slashes, std::string::npos) << ref;
        EXPECT_EQ(ref.substr(0, slashes), ref.substr(slashes + 2)) << "normal index = vertex index";
        v = static_cast<std::uint32_t>(std::stoul(ref.substr(0, slashes))) - 1;
      }
      triangles.push_back(t);
    } else {
      EXPECT_TRUE(tag.empty() || tag[0] == '#') << line;
    }
  }
  ASSERT_EQ(positions.size(), mesh.positions.size());
  ASSERT_EQ(normals.size(), mesh.normals.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    expectSameVec(positions[i], mesh.positions[i], "position"); // %.17g round-trips
    expectSameVec(normals[i], mesh.normals[i], "normal");
  }
  EXPECT_EQ(triangles, mesh.triangles);
}

TEST(MeshWriters, PlyHeaderAndBinaryBody) {
  ScratchDir dir;
  const Mesh mesh = smallMesh();
  const fs::path path = dir.path() / "mesh.PLY";
  writeMeshFile(mesh, path.string());
  const std::string data = readFile(path);
  const std::string endHeader = "end_header\n";
  const auto headerEnd = data.find(endHeader);
  ASSERT_NE(headerEnd, std::string::npos);
  const std::string header = data.substr(0, headerEnd + endHeader.size());
  EXPECT_EQ(header.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u) << header;
  EXPECT_TRUE(contains(header, "element vertex 4\n")) << header;
  EXPECT_TRUE(contains(header, "property float64 x\nproperty float64 y\nproperty float64 z\n"
                               "property float64 nx\nproperty float64 ny\nproperty float64 nz\n"))
      << header;
  EXPECT_TRUE(contains(header, "element face 2\nproperty list uchar uint32 vertex_indices\n")) << header;

  const std::size_t vertexBytes = 6 * 8, faceBytes = 1 + 3 * 4;
  ASSERT_EQ(data.size() - header.size(), mesh.positions.size() * vertexBytes + mesh.triangles.size() * faceBytes);
  // Decode explicitly as little-endian so the check holds on any host.
  const auto *body = reinterpret_cast<const unsigned char *>(data.data() + header.size());
  auto u64 = [](const unsigned char *p) {
    std::uint64_t v = 0;
    for (int b = 7; b >= 0; --b) v = (v << 8) | p[b];
    return v;
  };
  auto u32 = [](const unsigned char *p) {
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
  };
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const unsigned char *v = body + i * vertexBytes;
    const Vec3 &p = mesh.positions[i], &n = mesh.normals[i];
    const double expected[6] = {p.x, p.y, p.z, n.x, n.y, n.z};
    for (int k = 0; k < 6; ++k) EXPECT_EQ(u64(v + 8 * k), bits(expected[k])) << "vertex " << i << " value " << k;
  }
  const unsigned char *faces = body + mesh.positions.size() * vertexBytes;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const unsigned char *f = faces + t * faceBytes;
    EXPECT_EQ(f[0], 3);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(u32(f + 1 + 4 * k), mesh.triangles[t][k]);
  }
}

TEST(MeshWriters, MeshWithoutNormals) {
  Mesh mesh = smallMesh();
  mesh.normals.clear();
  std::ostringstream obj;
  writeObj(mesh, obj);
  EXPECT_FALSE(contains(obj.str(), "vn ")) << obj.str();
  EXPECT_TRUE(contains(obj.str(), "\nf 2 4 3\n")) << obj.str();
  std::ostringstream ply;
  writePly(mesh, ply);
  EXPECT_FALSE(contains(ply.str(), "property float64 nx"));
  const std::string header = ply.str().substr(0, ply.str().find("end_header\n") + 11);
  EXPECT_EQ(ply.str().size() - header.size(), 4 * 24 + 2 * 13u);
}

TEST(MeshWriters, UnknownExtension) {
  ScratchDir dir;
  const std::string path = (dir.path() / "mesh.stl").string();
  InputError e = catchInputError([&] { writeMeshFile(smallMesh(), path); });
  EXPECT_EQ(e.file(), path);
  EXPECT_TRUE(contains(e.reason(), "\".stl\"")) << e.reason();
  EXPECT_TRUE(dir.listing().empty());
}

} // namespace
} // namespace v1
} // namespace curvenet
