// .lop loop files: one face bounded by a loop of B-spline curves.
//
//   n                      number of curves
//   then n times:
//   p                      degree
//   K k1 … kK              knot count, then the knots
//   C x1 y1 z1 … xC yC zC  control-point count, then the coordinates
//
// Curves come in loop order, each ending where the next starts. The layout
// above is how the files are written, but readers of the format have always
// been whitespace-agnostic, so this one is too; line numbers are kept per
// token only for error messages.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "curvenet/curve.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"

namespace curvenet {
inline namespace v1 {
namespace {

struct Token {
  std::string_view text;
  int line;
};

std::vector<Token> tokenize(std::string_view text) {
  std::vector<Token> tokens;
  int line = 1;
  std::size_t i = 0;
  auto isSpace = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; };
  while (i < text.size()) {
    if (isSpace(text[i])) {
      if (text[i] == '\n') ++line;
      ++i;
      continue;
    }
    std::size_t start = i;
    while (i < text.size() && !isSpace(text[i])) ++i;
    tokens.push_back({text.substr(start, i - start), line});
  }
  return tokens;
}

std::string lineElement(int line) { return "line " + std::to_string(line); }

// Sequential reader over the tokens. Every count is checked against the
// tokens that are left before anything is allocated for it, so a corrupt
// count cannot ask for gigabytes.
class LopReader {
public:
  /// A token as an error shows it: quoted and cut to 40 characters, or, for
  /// bytes that are not printable text, the first such byte (a binary file).
  static std::string shown(std::string_view token) {
    for (unsigned char c : token)
      if (c < 0x20 || c >= 0x7f) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "0x%02x", c);
        return std::string("binary data (byte ") + hex + "); a .lop file is text";
      }
    return "\"" + std::string(token.substr(0, 40)) + (token.size() > 40 ? "...\"" : "\"");
  }

  LopReader(std::string_view text, const std::string &file) : tokens_(tokenize(text)), file_(file) {
    lastLine_ = tokens_.empty() ? 1 : tokens_.back().line;
  }

  [[noreturn]] void fail(int line, const std::string &reason) const { throw InputError(file_, lineElement(line), reason); }

  std::size_t remaining() const { return tokens_.size() - next_; }
  bool done() const { return next_ == tokens_.size(); }
  /// Line of the token that will be read next (or of the last one).
  int nextLine() const { return done() ? lastLine_ : tokens_[next_].line; }

  const Token &take(const std::string &what) {
    if (done()) fail(lastLine_, "file ends early: expected " + what);
    return tokens_[next_++];
  }

  /// A non-negative integer in [min, max]; `what` names it in errors.
  long long integer(const std::string &what, long long min, long long max) {
    const Token &t = take(what);
    long long v = 0;
    auto [end, ec] = std::from_chars(t.text.data(), t.text.data() + t.text.size(), v);
    if (ec == std::errc::result_out_of_range) fail(t.line, what + " is too large: " + shown(t.text));
    if (ec != std::errc() || end != t.text.data() + t.text.size())
      fail(t.line, "expected " + what + " (an integer), found " + shown(t.text));
    if (v < min || v > max)
      fail(t.line, what + " is " + std::to_string(v) + ", outside [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    return v;
  }

  double number(const std::string &what) {
    const Token &t = take(what);
    std::string_view s = t.text;
    // from_chars rejects the leading '+' that printf-style writers may emit.
    if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
    double v = 0;
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec == std::errc::result_out_of_range)
      fail(t.line, "number \"" + std::string(t.text) + "\" is outside the range of a double");
    if (ec != std::errc() || end != s.data() + s.size())
      fail(t.line, "expected a number (" + what + "), found " + shown(t.text));
    if (!std::isfinite(v)) fail(t.line, "non-finite number \"" + std::string(t.text) + "\" (" + what + ")");
    return v;
  }

  /// Reads `count` numbers announced by the count token at `countLine`.
  std::vector<double> numbers(std::size_t count, int countLine, const std::string &what) {
    if (count > remaining())
      fail(countLine, "expected " + std::to_string(count) + " numbers (" + what + "), found " +
                          std::to_string(remaining()) + " before the end of the file");
    std::vector<double> values;
    values.reserve(count);
    for (std::size_t i = 0; i < count; ++i) values.push_back(number(what));
    return values;
  }

private:
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
  int lastLine_ = 1;
  const std::string &file_;
};

} // namespace

NetworkDescription parseLop(const std::string &text, const std::string &file) {
  LopReader r(text, file);
  if (r.done()) throw InputError(file, lineElement(1), "empty file: expected the number of curves");

  const int countLine = r.nextLine();
  // A curve takes at least 3 tokens (degree and two counts).
  const long long curveCount =
      r.integer("number of curves", 1, static_cast<long long>(std::numeric_limits<int>::max()));
  if (static_cast<unsigned long long>(curveCount) * 3 > r.remaining())
    r.fail(countLine, std::to_string(curveCount) + " curves announced, but only " + std::to_string(r.remaining()) +
                          " numbers follow (each curve needs at least 3)");

  NetworkDescription d;
  d.curves.reserve(static_cast<std::size_t>(curveCount));
  for (long long i = 0; i < curveCount; ++i) {
    const std::string curveName = "curve " + std::to_string(i);
    const int degreeLine = r.nextLine();
    const int degree = static_cast<int>(r.integer("degree of " + curveName, 1, BSplineCurve::maxDegree));

    const int knotLine = r.nextLine();
    const auto knotCount = static_cast<std::size_t>(
        r.integer("knot count of " + curveName, 0, std::numeric_limits<int>::max()));
    std::vector<double> knots = r.numbers(knotCount, knotLine, "knots of " + curveName);

    const int pointLine = r.nextLine();
    const auto pointCount = static_cast<std::size_t>(
        r.integer("control-point count of " + curveName, 0, std::numeric_limits<int>::max()));
    std::vector<double> coordinates = r.numbers(3 * pointCount, pointLine, "x y z of " + std::to_string(pointCount) +
                                                                               " control points of " + curveName);

    if (pointCount < static_cast<std::size_t>(degree) + 1)
      r.fail(pointLine, curveName + ": degree " + std::to_string(degree) + " needs at least " +
                            std::to_string(degree + 1) + " control points, found " + std::to_string(pointCount));
    if (knotCount != pointCount + static_cast<std::size_t>(degree) + 1)
      r.fail(knotLine, curveName + ": expected " + std::to_string(pointCount + degree + 1) + " knots (" +
                           std::to_string(pointCount) + " control points + degree " + std::to_string(degree) +
                           " + 1), found " + std::to_string(knotCount));

    std::vector<Vec3> points(pointCount);
    for (std::size_t k = 0; k < pointCount; ++k)
      points[k] = {coordinates[3 * k], coordinates[3 * k + 1], coordinates[3 * k + 2]};
    // BSplineCurve knows the remaining rules (clamped, non-decreasing knots);
    // its error says only "curve", so point at the curve's first line.
    try {
      d.curves.emplace_back(degree, std::move(knots), std::move(points));
    } catch (const InputError &e) {
      r.fail(degreeLine, curveName + ": " + e.reason());
    }
  }
  if (!r.done())
    r.fail(r.nextLine(), "unexpected data after the last curve: \"" + std::string(r.take("").text) + "\"");

  // One face: the loop of all curves, each over its whole domain.
  FaceDescription face;
  d.name = std::filesystem::path(file).stem().string();
  face.name = d.name;
  for (std::size_t i = 0; i < d.curves.size(); ++i)
    face.sides.push_back({static_cast<int>(i), d.curves[i].domainStart(), d.curves[i].domainEnd()});
  d.faces.push_back(std::move(face));
  return d;
}

} // namespace v1
} // namespace curvenet
