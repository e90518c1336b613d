// Every rule of a curve's validity (clamped end knots, non-decreasing knots,
// interior multiplicity at most the degree, finite positive weights, a domain
// of positive length) refused the same way through the three doors a curve
// comes in by: the API (BSplineCurve), the native format and .lop files. Each
// refusal names the rule, and the readers name the file and the curve.
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "curvenet/curve.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"

namespace curvenet {
inline namespace v1 {
namespace {

struct BrokenCurve {
  std::string rule;   ///< what the refusal must say
  int degree;
  std::vector<double> knots;
  std::vector<double> weights; ///< empty: polynomial
};

// Cubics with five control points (nine knots) unless the rule needs otherwise.
std::vector<BrokenCurve> brokenCurves() {
  return {
      {"not clamped", 3, {0, 0, 0, 0.2, 0.4, 0.6, 1, 1, 1}, {}},
      {"not clamped", 3, {0, 0, 0, 0, 0.5, 0.8, 1, 1, 1}, {}},
      {"knots decrease", 3, {0, 0, 0, 0, 0.7, 0.3, 1, 1, 1}, {}},
      {"multiplicity exceeds the degree", 2, {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1}, {}},
      {"weights must be finite and positive", 3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1}, {1, 1, 0, 1, 1}},
      {"weights must be finite and positive", 3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1}, {1, -2, 1, 1, 1}},
      {"zero-length parameter domain", 3, {1, 1, 1, 1, 1, 1, 1, 1, 1}, {}},
  };
}

std::size_t pointCount(const BrokenCurve &c) { return c.knots.size() - static_cast<std::size_t>(c.degree) - 1; }

std::vector<Vec3> points(std::size_t n) {
  std::vector<Vec3> p;
  for (std::size_t k = 0; k < n; ++k) p.push_back({double(k), 0.1 * double(k * k), 0});
  return p;
}

bool contains(const std::string &haystack, const std::string &needle) { return haystack.find(needle) != std::string::npos; }

template <typename F> InputError refusal(F &&f, const std::string &rule) {
  try {
    f();
  } catch (const InputError &e) {
    return e;
  }
  ADD_FAILURE() << "accepted a curve that breaks: " << rule;
  return InputError("", "", "");
}

std::string numbers(const std::vector<double> &values) {
  std::ostringstream s;
  s.precision(17);
  for (std::size_t i = 0; i < values.size(); ++i) s << (i ? ", " : "") << values[i];
  return s.str();
}

TEST(CurveValidity, TheApiRefusesEveryRule) {
  for (const BrokenCurve &c : brokenCurves()) {
    const InputError e = refusal([&] { BSplineCurve(c.degree, c.knots, points(pointCount(c)), c.weights); }, c.rule);
    EXPECT_TRUE(contains(e.reason(), c.rule)) << c.rule << " <- " << e.what();
  }
}

TEST(CurveValidity, TheNativeFormatRefusesEveryRuleNamingTheCurve) {
  for (const BrokenCurve &c : brokenCurves()) {
    std::ostringstream doc;
    doc << R"({"format": "curvenet-network", "version": 1, "curves": [{"degree": )" << c.degree
        << R"(, "knots": [)" << numbers(c.knots) << R"(], "points": [)";
    const std::vector<Vec3> p = points(pointCount(c));
    for (std::size_t k = 0; k < p.size(); ++k) doc << (k ? ", " : "") << "[" << p[k].x << ", " << p[k].y << ", " << p[k].z << "]";
    doc << "]";
    if (!c.weights.empty()) doc << R"(, "weights": [)" << numbers(c.weights) << "]";
    doc << R"(}], "faces": []})";
    const InputError e = refusal([&] { parseNetworkJson(doc.str(), "broken.json"); }, c.rule);
    EXPECT_EQ(e.file(), "broken.json") << c.rule;
    EXPECT_EQ(e.element(), "curves[0]") << c.rule;
    EXPECT_TRUE(contains(e.reason(), c.rule)) << c.rule << " <- " << e.what();
  }
}

// .lop curves are polynomial: every rule but the weights'.
TEST(CurveValidity, LopFilesRefuseEveryRuleNamingTheCurveLine) {
  for (const BrokenCurve &c : brokenCurves()) {
    if (!c.weights.empty()) continue;
    std::ostringstream lop;
    lop.precision(17);
    lop << "1\n" << c.degree << "\n" << c.knots.size();
    for (double k : c.knots) lop << ' ' << k;
    const std::vector<Vec3> p = points(pointCount(c));
    lop << "\n" << p.size();
    for (const Vec3 &q : p) lop << ' ' << q.x << ' ' << q.y << ' ' << q.z;
    lop << "\n";
    const InputError e = refusal([&] { parseLop(lop.str(), "broken.lop"); }, c.rule);
    EXPECT_EQ(e.file(), "broken.lop") << c.rule;
    EXPECT_EQ(e.element(), "line 2") << c.rule; // the curve's first line
    EXPECT_TRUE(contains(e.reason(), "curve 0") && contains(e.reason(), c.rule)) << c.rule << " <- " << e.what();
  }
}

// The boundary of each rule is accepted: the refusals above are about the rule, not the shape.
TEST(CurveValidity, CurvesAtTheLimitOfEachRuleAreAccepted) {
  EXPECT_NO_THROW(BSplineCurve(2, {0, 0, 0, 0.5, 0.5, 1, 1, 1}, points(5)));    // multiplicity = degree
  EXPECT_NO_THROW(BSplineCurve(3, {0, 0, 0, 0, 0.5, 0.5, 1, 1, 1, 1}, points(6))); // repeated, non-decreasing
  EXPECT_NO_THROW(BSplineCurve(3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1}, points(5), {1, 1e-3, 1e3, 1, 1})); // tiny and huge
  EXPECT_NO_THROW(BSplineCurve(3, {2, 2, 2, 2, 2.5, 3, 3, 3, 3}, points(5)));    // domain not starting at 0
}

} // namespace
} // namespace v1
} // namespace curvenet
