// The native network format (docs/network-format.md): reader and writer.
//
// The reader is strict on purpose: a misspelt key ("weight" for "weights") or
// a duplicated one would otherwise silently change the surface, so every key
// is checked against the keys its object may hold, and every error names the
// element by its JSON path ("faces[1].sides[2]").
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <limits>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "curvenet/curve.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"

namespace curvenet {
inline namespace v1 {
namespace {

// ordered_json keeps document order, so the first unknown key reported is the
// first one in the file, and the writer emits keys in the documented order.
using Json = nlohmann::ordered_json;

constexpr const char *formatTag = "curvenet-network";
constexpr int formatVersion = 1;
// Used as the element of errors about the top-level object itself.
constexpr const char *documentElement = "document";
// Deepest nesting of arrays and objects a native document may have (the
// format itself needs 5; documented in io.hpp).
constexpr std::size_t kMaxJsonNesting = 64;

std::string indexed(const std::string &path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }
std::string member(const std::string &path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}
// Invalid UTF-8 (a name from code, not from a parsed file) is replaced rather
// than thrown on: a report name is not worth failing a write for.
std::string jsonString(std::string_view s) {
  return Json(std::string(s)).dump(-1, ' ', false, Json::error_handler_t::replace);
}

// nlohmann keeps the last of duplicated keys without a word. The parser
// callback sees every key in document order, so a stack of per-object key sets
// catches duplicates; the frames' keys and indices spell the JSON path of the
// current value, which makes the error point at the object holding the
// duplicate. The path is assembled only for an error, so the cost stays linear
// in the document whatever its nesting; nesting beyond kMaxJsonNesting (far
// more than the format uses) is refused as soon as it is reached.
class DuplicateKeyGuard {
public:
  explicit DuplicateKeyGuard(const std::string &file) : file_(file) {}

  bool operator()(int /*depth*/, Json::parse_event_t event, Json &parsed) {
    switch (event) {
    case Json::parse_event_t::object_start: open(false); break;
    case Json::parse_event_t::array_start: open(true); break;
    case Json::parse_event_t::key: {
      Frame &top = stack_.back();
      std::string key = parsed.get<std::string>();
      if (!top.keys.insert(key).second) {
        const std::string path = pathOf(stack_.size() - 1);
        throw InputError(file_, path.empty() ? documentElement : path, "duplicate key " + jsonString(key));
      }
      top.key = std::move(key);
      break;
    }
    case Json::parse_event_t::object_end:
    case Json::parse_event_t::array_end:
      stack_.pop_back();
      elementDone();
      break;
    case Json::parse_event_t::value: elementDone(); break;
    }
    return true;
  }

private:
  struct Frame {
    bool isArray;
    std::size_t index = 0; // elements completed so far (arrays)
    std::string key;       // key of the member being parsed (objects)
    std::set<std::string> keys;
  };
  void open(bool isArray) {
    if (stack_.size() >= kMaxJsonNesting)
      throw InputError(file_, pathOf(3) + "...",
                       "arrays and objects nested deeper than " + std::to_string(kMaxJsonNesting) + " levels");
    stack_.push_back({isArray});
  }
  /// The JSON path of the value frame `depth` holds (the frames below it name its position).
  std::string pathOf(std::size_t depth) const {
    std::string path;
    for (std::size_t k = 0; k < depth && k < stack_.size(); ++k)
      path = stack_[k].isArray ? indexed(path, stack_[k].index) : member(path, stack_[k].key);
    return path;
  }
  void elementDone() {
    if (!stack_.empty() && stack_.back().isArray) ++stack_.back().index;
  }
  const std::string &file_;
  std::vector<Frame> stack_;
};

// "line L, column C" from nlohmann's message, which counts lines and columns
// the way editors do; the byte offset is the fallback if the wording changes.
std::string parseErrorElement(const Json::parse_error &e, const std::string &text) {
  const std::string what = e.what();
  int line = 0, column = 0;
  if (auto at = what.find("at line "); at != std::string::npos &&
                                       std::sscanf(what.c_str() + at, "at line %d, column %d", &line, &column) == 2)
    return "line " + std::to_string(line) + " column " + std::to_string(column);
  std::size_t end = std::min<std::size_t>(e.byte, text.size());
  line = 1;
  std::size_t lineStart = 0;
  for (std::size_t i = 0; i + 1 < end; ++i)
    if (text[i] == '\n') ++line, lineStart = i + 1;
  return "line " + std::to_string(line) + " column " + std::to_string(end - lineStart);
}

std::string parseErrorReason(const Json::parse_error &e) {
  std::string what = e.what();
  // Drop "[json.exception.parse_error.101] parse error at line 3, column 4: ".
  if (auto colon = what.find(": ", what.find("parse error")); colon != std::string::npos) what.erase(0, colon + 2);
  return "JSON syntax error: " + what;
}

// A number literal too large for a double makes nlohmann throw out_of_range
// without a position; find the literal in the text to report its line.
std::string literalElement(const std::string &literal, const std::string &text) {
  auto isNumberChar = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+'; };
  for (std::size_t at = text.find(literal); at != std::string::npos; at = text.find(literal, at + 1)) {
    bool startsToken = at == 0 || !isNumberChar(text[at - 1]);
    bool endsToken = at + literal.size() >= text.size() || !isNumberChar(text[at + literal.size()]);
    if (!startsToken || !endsToken) continue;
    int line = 1;
    std::size_t lineStart = 0;
    for (std::size_t i = 0; i < at; ++i)
      if (text[i] == '\n') ++line, lineStart = i + 1;
    return "line " + std::to_string(line) + " column " + std::to_string(at - lineStart + 1);
  }
  return documentElement;
}

Json parseDocument(const std::string &text, const std::string &file) {
  DuplicateKeyGuard guard(file);
  try {
    return Json::parse(text, std::ref(guard), /*allow_exceptions=*/true, /*ignore_comments=*/false);
  } catch (const Json::parse_error &e) {
    throw InputError(file, parseErrorElement(e, text), parseErrorReason(e));
  } catch (const Json::out_of_range &e) {
    std::string what = e.what(), literal;
    if (auto open = what.find('\''), close = what.rfind('\''); open != std::string::npos && close > open)
      literal = what.substr(open + 1, close - open - 1);
    throw InputError(file, literal.empty() ? documentElement : literalElement(literal, text),
                     literal.empty() ? std::string("number out of range")
                                     : "number " + literal + " is outside the range of a double");
  }
}

// Typed access to a parsed document; every failure names `file` and the path.
class DocumentReader {
public:
  explicit DocumentReader(const std::string &file) : file_(file) {}

  [[noreturn]] void fail(const std::string &element, const std::string &reason) const {
    throw InputError(file_, element.empty() ? documentElement : element, reason);
  }

  void expectObject(const Json &j, const std::string &path) const {
    if (!j.is_object()) fail(path, "expected an object, found " + typeName(j));
  }
  void expectArray(const Json &j, const std::string &path) const {
    if (!j.is_array()) fail(path, "expected an array, found " + typeName(j));
  }

  /// Rejects keys outside `allowed`, listing the allowed ones.
  void checkKeys(const Json &object, const std::string &path, std::initializer_list<std::string_view> allowed,
                 std::string_view note = {}) const {
    for (const auto &item : object.items()) {
      bool known = false;
      for (std::string_view a : allowed) known = known || item.key() == a;
      if (known) continue;
      std::string list;
      for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      std::string reason = "unknown key " + jsonString(item.key()) + " (expected one of: " + list + ")";
      if (!note.empty()) reason += "; " + std::string(note);
      fail(path, reason);
    }
  }

  const Json &required(const Json &object, std::string_view key, const std::string &path) const {
    auto it = object.find(std::string(key));
    if (it == object.end()) fail(path, "missing required key " + jsonString(key));
    return *it;
  }
  const Json *optional(const Json &object, std::string_view key) const {
    auto it = object.find(std::string(key));
    return it == object.end() ? nullptr : &*it;
  }

  double number(const Json &j, const std::string &path) const {
    if (!j.is_number()) fail(path, "expected a number, found " + typeName(j));
    double v = j.get<double>();
    if (!std::isfinite(v)) fail(path, "number is not finite");
    return v;
  }

  std::int64_t integer(const Json &j, const std::string &path, std::int64_t min, std::int64_t max) const {
    if (!j.is_number_integer()) fail(path, "expected an integer, found " + shownValue(j));
    if (j.is_number_unsigned() && j.get<std::uint64_t>() > static_cast<std::uint64_t>(max))
      fail(path, "integer " + j.dump() + " is larger than " + std::to_string(max));
    std::int64_t v = j.get<std::int64_t>();
    if (v < min || v > max)
      fail(path, "integer " + std::to_string(v) + " is outside [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    return v;
  }

  /// A curve index into a document with `count` curves.
  int index(const Json &j, const std::string &path, std::size_t count) const {
    if (!j.is_number_integer()) fail(path, "expected an integer curve index, found " + shownValue(j));
    // Parsed non-negative integers are stored unsigned, negative ones signed.
    bool inRange = j.is_number_unsigned() ? j.get<std::uint64_t>() < count
                                          : j.get<std::int64_t>() >= 0 && static_cast<std::uint64_t>(j.get<std::int64_t>()) < count;
    if (!inRange)
      fail(path, "curve index " + j.dump() + " is out of range (the document has " + std::to_string(count) +
                     (count == 1 ? " curve)" : " curves)"));
    return static_cast<int>(j.get<std::int64_t>());
  }

  /// A face index (an edge's master face) into a document with `count` faces.
  int faceIndex(const Json &j, const std::string &path, std::size_t count) const {
    if (!j.is_number_integer()) fail(path, "expected an integer face index, found " + shownValue(j));
    const bool inRange = j.is_number_unsigned() ? j.get<std::uint64_t>() < count : false;
    if (!inRange)
      fail(path, "face " + j.dump() + " does not exist (the document has " + std::to_string(count) +
                     (count == 1 ? " face, numbered 0)" : " faces, numbered from 0)"));
    return static_cast<int>(j.get<std::int64_t>());
  }

  bool boolean(const Json &j, const std::string &path) const {
    if (!j.is_boolean()) fail(path, "expected true or false, found " + typeName(j));
    return j.get<bool>();
  }

  std::string string(const Json &j, const std::string &path) const {
    if (!j.is_string()) fail(path, "expected a string, found " + typeName(j));
    return j.get<std::string>();
  }

  std::vector<double> numbers(const Json &j, const std::string &path) const {
    expectArray(j, path);
    std::vector<double> values;
    values.reserve(j.size());
    for (std::size_t i = 0; i < j.size(); ++i) values.push_back(number(j[i], indexed(path, i)));
    return values;
  }

  Vec3 vec3(const Json &j, const std::string &path) const {
    expectArray(j, path);
    if (j.size() != 3) fail(path, "expected 3 coordinates [x, y, z], found " + std::to_string(j.size()));
    return {number(j[0], indexed(path, 0)), number(j[1], indexed(path, 1)), number(j[2], indexed(path, 2))};
  }

private:
  /// A scalar by its value ("1e+20", "\"x\""), anything else by its type.
  static std::string shownValue(const Json &j) {
    if (j.is_primitive()) return j.dump().substr(0, 40);
    return typeName(j);
  }
  static std::string typeName(const Json &j) {
    if (j.is_number_float()) return "a non-integer number";
    if (j.is_number()) return "a number";
    if (j.is_null()) return "null";
    return std::string(j.is_array() || j.is_object() ? "an " : "a ") + j.type_name();
  }
  const std::string &file_;
};

/// A sampled curve, {"samples": [[x, y, z], ...]}: the polyline through the
/// samples (degree 1, uniform knots on [0, 1]), a stroke for the sketch stage.
BSplineCurve readSampledCurve(const DocumentReader &r, const Json &j, const std::string &path) {
  r.checkKeys(j, path, {"samples"});
  const Json &samples = r.required(j, "samples", path);
  const std::string samplesPath = member(path, "samples");
  r.expectArray(samples, samplesPath);
  if (samples.size() < 2) r.fail(samplesPath, "a sampled curve needs at least 2 samples, found " + std::to_string(samples.size()));
  std::vector<Vec3> points;
  for (std::size_t i = 0; i < samples.size(); ++i) points.push_back(r.vec3(samples[i], indexed(samplesPath, i)));
  std::vector<double> knots{0.0};
  for (std::size_t i = 0; i < points.size(); ++i) knots.push_back(static_cast<double>(i) / static_cast<double>(points.size() - 1));
  knots.push_back(1.0);
  try {
    return BSplineCurve(1, std::move(knots), std::move(points));
  } catch (const InputError &e) {
    r.fail(path, e.reason());
  }
}

/// {"parameters": [t, ...], "vectors": [[x, y, z], ...]}: normals along a
/// curve (CurveNormals), at increasing parameters of its domain.
CurveNormals readCurveNormals(const DocumentReader &r, const Json &j, const std::string &path, const BSplineCurve &curve) {
  r.expectObject(j, path);
  r.checkKeys(j, path, {"parameters", "vectors"});
  CurveNormals out;
  out.parameters = r.numbers(r.required(j, "parameters", path), member(path, "parameters"));
  const Json &vectors = r.required(j, "vectors", path);
  const std::string vectorsPath = member(path, "vectors");
  r.expectArray(vectors, vectorsPath);
  for (std::size_t i = 0; i < vectors.size(); ++i) {
    const Vec3 n = r.vec3(vectors[i], indexed(vectorsPath, i));
    if (!(norm(n) > 0)) r.fail(indexed(vectorsPath, i), "a normal must not be the zero vector");
    out.normals.push_back(normalized(n));
  }
  if (out.normals.size() != out.parameters.size())
    r.fail(vectorsPath, "expected one vector per parameter (" + std::to_string(out.parameters.size()) + "), found " +
                            std::to_string(out.normals.size()));
  if (out.normals.size() < 2) r.fail(path, "normals along a curve need at least 2 samples");
  for (std::size_t i = 0; i < out.parameters.size(); ++i) {
    const double t = out.parameters[i];
    if (t < curve.domainStart() || t > curve.domainEnd() || (i > 0 && !(t > out.parameters[i - 1])))
      r.fail(indexed(member(path, "parameters"), i), "parameters must increase inside the curve's domain [" +
                                                         std::to_string(curve.domainStart()) + ", " +
                                                         std::to_string(curve.domainEnd()) + "]");
  }
  return out;
}

BSplineCurve readCurve(const DocumentReader &r, const Json &j, const std::string &path) {
  r.expectObject(j, path);
  if (j.contains("samples")) return readSampledCurve(r, j, path);
  r.checkKeys(j, path, {"degree", "knots", "points", "weights", "normals"});
  // The degree bound is BSplineCurve's; it is checked here too so that the
  // knot-count arithmetic below never sees absurd values.
  int degree = static_cast<int>(r.integer(r.required(j, "degree", path), member(path, "degree"), 1, BSplineCurve::maxDegree));
  std::vector<double> knots = r.numbers(r.required(j, "knots", path), member(path, "knots"));

  const Json &pointsJson = r.required(j, "points", path);
  const std::string pointsPath = member(path, "points");
  r.expectArray(pointsJson, pointsPath);
  std::vector<Vec3> points;
  points.reserve(pointsJson.size());
  for (std::size_t i = 0; i < pointsJson.size(); ++i) points.push_back(r.vec3(pointsJson[i], indexed(pointsPath, i)));
  if (points.size() < static_cast<std::size_t>(degree) + 1)
    r.fail(pointsPath, "a curve of degree " + std::to_string(degree) + " needs at least " +
                           std::to_string(degree + 1) + " control points, found " + std::to_string(points.size()));

  std::size_t expectedKnots = points.size() + static_cast<std::size_t>(degree) + 1;
  if (knots.size() != expectedKnots)
    r.fail(member(path, "knots"), "expected " + std::to_string(expectedKnots) + " knots (" +
                                      std::to_string(points.size()) + " points + degree " + std::to_string(degree) +
                                      " + 1), found " + std::to_string(knots.size()));

  std::vector<double> weights;
  if (const Json *w = r.optional(j, "weights")) {
    weights = r.numbers(*w, member(path, "weights"));
    if (weights.size() != points.size())
      r.fail(member(path, "weights"), "expected one weight per control point (" + std::to_string(points.size()) +
                                          "), found " + std::to_string(weights.size()));
  }

  // The curve's own validation knows the geometric rules (clamping, monotone
  // knots, positive weights); it only says "curve", so add the path.
  try {
    return BSplineCurve(degree, std::move(knots), std::move(points), std::move(weights));
  } catch (const InputError &e) {
    r.fail(path, e.reason());
  }
}

std::vector<SideDescription> readSides(const DocumentReader &r, const Json &sides, const std::string &sidesPath,
                                       const std::vector<BSplineCurve> &curves) {
  r.expectArray(sides, sidesPath);
  std::vector<SideDescription> loop;
  for (std::size_t k = 0; k < sides.size(); ++k) {
    const std::string sidePath = indexed(sidesPath, k);
    const Json &s = sides[k];
    r.expectObject(s, sidePath);
    r.checkKeys(s, sidePath, {"curve", "from", "to"});
    SideDescription side;
    side.curve = r.index(r.required(s, "curve", sidePath), member(sidePath, "curve"), curves.size());
    const BSplineCurve &curve = curves[static_cast<std::size_t>(side.curve)];
    const Json *from = r.optional(s, "from");
    const Json *to = r.optional(s, "to");
    side.from = from ? r.number(*from, member(sidePath, "from")) : curve.domainStart();
    side.to = to ? r.number(*to, member(sidePath, "to")) : curve.domainEnd();
    loop.push_back(side);
  }
  return loop;
}

FaceDescription readFace(const DocumentReader &r, const Json &j, const std::string &path,
                         const std::vector<BSplineCurve> &curves) {
  r.expectObject(j, path);
  r.checkKeys(j, path, {"name", "sides", "holes", "part_of"});
  FaceDescription face;
  if (const Json *name = r.optional(j, "name")) face.name = r.string(*name, member(path, "name"));
  face.sides = readSides(r, r.required(j, "sides", path), member(path, "sides"), curves);
  if (const Json *holes = r.optional(j, "holes")) {
    const std::string holesPath = member(path, "holes");
    r.expectArray(*holes, holesPath);
    for (std::size_t h = 0; h < holes->size(); ++h)
      face.holes.push_back(readSides(r, (*holes)[h], indexed(holesPath, h), curves));
  }
  if (const Json *partOf = r.optional(j, "part_of"))
    face.partOf = static_cast<int>(r.integer(*partOf, member(path, "part_of"), 0, std::numeric_limits<int>::max()));
  return face;
}

ReferenceSurface readReference(const DocumentReader &r, const Json &j, const std::string &path) {
  r.expectObject(j, path);
  r.checkKeys(j, path, {"kind", "center", "size"});
  ReferenceSurface reference;
  std::string kind = r.string(r.required(j, "kind", path), member(path, "kind"));
  auto parsedKind = ReferenceSurface::kindFromName(kind);
  if (!parsedKind) r.fail(member(path, "kind"), "unknown reference kind " + jsonString(kind) + " (expected ellipsoid, torus or graph)");
  reference.kind = *parsedKind;
  reference.center = r.vec3(r.required(j, "center", path), member(path, "center"));
  reference.size = r.vec3(r.required(j, "size", path), member(path, "size"));
  // Shapes that are not surfaces would make every deviation figure meaningless.
  const Vec3 &s = reference.size;
  if (reference.kind == ReferenceSurface::Kind::Ellipsoid && !(s.x > 0 && s.y > 0 && s.z > 0))
    r.fail(member(path, "size"), "ellipsoid semi-axes must be positive");
  if (reference.kind == ReferenceSurface::Kind::Torus && !(s.y > 0 && s.x > s.y))
    r.fail(member(path, "size"), "torus needs ring radius size[0] > tube radius size[1] > 0");
  return reference;
}

// ---- "surfaces": master surfaces given from outside ([SV14] Sec. 5.1) ----
//
// {"degree_u": p, "degree_v": q, "knots_u": [...], "knots_v": [...],
//  "points": [row_0, row_1, ...], "weights": [row_0, ...]}: row i holds the
// control points (i, 0 … n_v − 1) along v, rows along u (BSplineSurface).

BSplineSurface readSurface(const DocumentReader &r, const Json &j, const std::string &path) {
  r.expectObject(j, path);
  r.checkKeys(j, path, {"degree_u", "degree_v", "knots_u", "knots_v", "points", "weights"});
  const int degreeU = static_cast<int>(
      r.integer(r.required(j, "degree_u", path), member(path, "degree_u"), 1, BSplineSurface::maxDegree));
  const int degreeV = static_cast<int>(
      r.integer(r.required(j, "degree_v", path), member(path, "degree_v"), 1, BSplineSurface::maxDegree));
  std::vector<double> knotsU = r.numbers(r.required(j, "knots_u", path), member(path, "knots_u"));
  std::vector<double> knotsV = r.numbers(r.required(j, "knots_v", path), member(path, "knots_v"));
  // Rows of equal length: the net's shape is read off the nesting.
  auto grid = [&](const Json &rows, const std::string &gridPath, auto &&readEntry, auto &out) {
    r.expectArray(rows, gridPath);
    if (rows.empty()) r.fail(gridPath, "expected at least one row");
    std::size_t width = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const std::string rowPath = indexed(gridPath, i);
      r.expectArray(rows[i], rowPath);
      if (i == 0) width = rows[i].size();
      if (rows[i].size() != width)
        r.fail(rowPath, "row has " + std::to_string(rows[i].size()) + " entries, row 0 has " + std::to_string(width) +
                            " (the net must be rectangular)");
      for (std::size_t k = 0; k < rows[i].size(); ++k) out.push_back(readEntry(rows[i][k], indexed(rowPath, k)));
    }
    return std::pair<int, int>(static_cast<int>(rows.size()), static_cast<int>(width));
  };
  std::vector<Vec3> points;
  const auto [countU, countV] = grid(r.required(j, "points", path), member(path, "points"),
                                     [&](const Json &e, const std::string &p) { return r.vec3(e, p); }, points);
  std::vector<double> weights;
  if (const Json *w = r.optional(j, "weights")) {
    const auto [rows, width] = grid(*w, member(path, "weights"),
                                    [&](const Json &e, const std::string &p) { return r.number(e, p); }, weights);
    if (rows != countU || width != countV)
      r.fail(member(path, "weights"), "weights are " + std::to_string(rows) + " x " + std::to_string(width) +
                                          ", the control net " + std::to_string(countU) + " x " + std::to_string(countV));
  }
  // The surface's own validation knows the rules (knot counts, clamping,
  // positive weights); it only says "surface", so add the path.
  try {
    return BSplineSurface(degreeU, degreeV, std::move(knotsU), std::move(knotsV), countU, countV, std::move(points),
                          std::move(weights));
  } catch (const InputError &e) {
    r.fail(path, e.reason());
  }
}

/// A master surface index into a document with `count` surfaces.
int surfaceIndex(const DocumentReader &r, const Json &j, const std::string &path, std::size_t count) {
  if (!j.is_number_integer()) r.fail(path, "expected an integer surface index, found " + j.dump().substr(0, 40));
  if (!(j.is_number_unsigned() && j.get<std::uint64_t>() < count))
    r.fail(path, "surface " + j.dump() + " does not exist (the document has " + std::to_string(count) +
                     (count == 1 ? " surface, numbered 0)" : " surfaces, numbered from 0)"));
  return static_cast<int>(j.get<std::int64_t>());
}

// ---- end of "surfaces" ------------------------------------------------------

// "edges": per-curve settings. Unknown keys fail loudly, so a file written
// for a later version is never read with its settings ignored.
std::vector<EdgeDescription> readEdges(const DocumentReader &r, const Json &j, std::size_t curveCount,
                                       std::size_t faceCount, std::size_t surfaceCount) {
  r.expectArray(j, "edges");
  std::vector<EdgeDescription> edges;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string path = indexed("edges", i);
    r.expectObject(j[i], path);
    r.checkKeys(j[i], path, {"curve", "master", "connection", "master_surface"},
                "per-edge settings other than \"curve\", \"master\", \"master_surface\" and \"connection\" are "
                "reserved");
    EdgeDescription edge;
    edge.curve = r.index(r.required(j[i], "curve", path), member(path, "curve"), curveCount);
    if (const Json *master = r.optional(j[i], "master"))
      edge.masterFace = r.faceIndex(*master, member(path, "master"), faceCount);
    if (const Json *connection = r.optional(j[i], "connection"))
      edge.connection = r.boolean(*connection, member(path, "connection"));
    if (const Json *surface = r.optional(j[i], "master_surface"))
      edge.masterSurface = surfaceIndex(r, *surface, member(path, "master_surface"), surfaceCount);
    edges.push_back(edge);
  }
  return edges;
}

// Writer helpers: each scalar goes through nlohmann's dump, which prints the
// shortest text that parses back to the same double (and escapes strings).
std::string numberText(double v, const std::string &element) {
  if (!std::isfinite(v)) throw InputError({}, element, "non-finite value cannot be written");
  return Json(v).dump();
}
std::string vecText(const Vec3 &p, const std::string &element) {
  return "[" + numberText(p.x, element) + ", " + numberText(p.y, element) + ", " + numberText(p.z, element) + "]";
}
std::string listText(const std::vector<double> &values, const std::string &element) {
  std::string s = "[";
  for (std::size_t i = 0; i < values.size(); ++i) s += (i ? ", " : "") + numberText(values[i], indexed(element, i));
  return s + "]";
}

/// A master surface as written in "surfaces" (see readSurface).
std::string surfaceText(const BSplineSurface &m, const std::string &path) {
  auto rows = [&](auto &&entry, const std::string &gridPath) {
    std::string t = "[";
    for (int i = 0; i < m.countU(); ++i) {
      t += i ? ",\n        [" : "\n        [";
      for (int k = 0; k < m.countV(); ++k)
        t += (k ? ", " : "") +
             entry(size_t(i) * size_t(m.countV()) + size_t(k), indexed(indexed(gridPath, size_t(i)), size_t(k)));
      t += "]";
    }
    return t + "\n      ]";
  };
  std::string s = "    {\n";
  s += "      \"degree_u\": " + std::to_string(m.degreeU()) + ", \"degree_v\": " + std::to_string(m.degreeV()) + ",\n";
  s += "      \"knots_u\": " + listText(m.knotsU(), member(path, "knots_u")) + ",\n";
  s += "      \"knots_v\": " + listText(m.knotsV(), member(path, "knots_v")) + ",\n";
  s += "      \"points\": " +
       rows([&](size_t k, const std::string &e) { return vecText(m.controlPoints()[k], e); }, member(path, "points"));
  if (m.isRational())
    s += ",\n      \"weights\": " +
         rows([&](size_t k, const std::string &e) { return numberText(m.weights()[k], e); }, member(path, "weights"));
  return s + "\n    }";
}

// ---- end of "surfaces" ------------------------------------------------------

} // namespace

NetworkDescription parseNetworkJson(const std::string &text, const std::string &file) {
  const Json doc = parseDocument(text, file);
  DocumentReader r(file);
  r.expectObject(doc, documentElement);

  // Format and version first: a newer file should say it is newer rather than
  // fail on the first key this version does not know.
  std::string format = r.string(r.required(doc, "format", documentElement), "format");
  if (format != formatTag) r.fail("format", "expected " + jsonString(formatTag) + ", found " + jsonString(format));
  std::int64_t version = r.integer(r.required(doc, "version", documentElement), "version", 0,
                                   std::numeric_limits<std::int64_t>::max());
  if (version != formatVersion)
    r.fail("version", "unsupported version " + std::to_string(version) + " (this reader knows version " +
                          std::to_string(formatVersion) + ")");
  r.checkKeys(doc, documentElement, {"format", "version", "name", "tolerance", "curves", "faces", "reference", "edges",
                                      "connection_curves", "surfaces"});

  NetworkDescription d;
  if (const Json *name = r.optional(doc, "name")) d.name = r.string(*name, "name");
  if (const Json *tolerance = r.optional(doc, "tolerance")) {
    d.tolerance = r.number(*tolerance, "tolerance");
    // The usable upper bound is Network::build's business; a tolerance that
    // is not positive is wrong in any version.
    if (!(d.tolerance > 0)) r.fail("tolerance", "relative tolerance must be positive, found " + tolerance->dump());
  }

  const Json &curves = r.required(doc, "curves", documentElement);
  r.expectArray(curves, "curves");
  d.curves.reserve(curves.size());
  for (std::size_t i = 0; i < curves.size(); ++i) d.curves.push_back(readCurve(r, curves[i], indexed("curves", i)));
  for (std::size_t i = 0; i < curves.size(); ++i)
    if (curves[i].contains("normals")) {
      d.curveNormals.resize(curves.size());
      d.curveNormals[i] = readCurveNormals(r, curves[i]["normals"], member(indexed("curves", i), "normals"), d.curves[i]);
    }

  // No faces: a curve graph, whose faces the sketch stage finds.
  if (const Json *faces = r.optional(doc, "faces")) {
    r.expectArray(*faces, "faces");
    d.faces.reserve(faces->size());
    for (std::size_t f = 0; f < faces->size(); ++f) d.faces.push_back(readFace(r, (*faces)[f], indexed("faces", f), d.curves));
  }

  if (const Json *reference = r.optional(doc, "reference")) d.reference = readReference(r, *reference, "reference");
  if (const Json *surfaces = r.optional(doc, "surfaces")) {
    r.expectArray(*surfaces, "surfaces");
    for (std::size_t k = 0; k < surfaces->size(); ++k)
      d.surfaces.push_back(readSurface(r, (*surfaces)[k], indexed("surfaces", k)));
  }
  if (const Json *edges = r.optional(doc, "edges"))
    d.edges = readEdges(r, *edges, d.curves.size(), d.faces.size(), d.surfaces.size());
  if (const Json *connection = r.optional(doc, "connection_curves"))
    d.connectionCurves = r.boolean(*connection, "connection_curves");
  return d;
}

// Written by hand rather than with Json::dump(2) so that a control point or a
// knot vector stays on one line: dump(2) would put every number on its own.
std::string networkToJson(const NetworkDescription &d) {
  std::string s = "{\n";
  s += "  \"format\": " + jsonString(formatTag) + ",\n";
  s += "  \"version\": " + std::to_string(formatVersion) + ",\n";
  s += "  \"name\": " + jsonString(d.name) + ",\n";
  s += "  \"tolerance\": " + numberText(d.tolerance, "tolerance") + ",\n";
  if (!d.connectionCurves) s += "  \"connection_curves\": false,\n";

  s += "  \"curves\": [";
  for (std::size_t i = 0; i < d.curves.size(); ++i) {
    const BSplineCurve &c = d.curves[i];
    const std::string path = indexed("curves", i);
    s += i ? ",\n" : "\n";
    s += "    {\n";
    s += "      \"degree\": " + std::to_string(c.degree()) + ",\n";
    s += "      \"knots\": " + listText(c.knots(), member(path, "knots")) + ",\n";
    s += "      \"points\": [";
    for (std::size_t k = 0; k < c.controlPoints().size(); ++k)
      s += (k ? ",\n        " : "\n        ") + vecText(c.controlPoints()[k], indexed(member(path, "points"), k));
    s += "\n      ]";
    if (c.isRational()) s += ",\n      \"weights\": " + listText(c.weights(), member(path, "weights"));
    if (i < d.curveNormals.size() && !d.curveNormals[i].empty()) {
      const CurveNormals &cn = d.curveNormals[i];
      s += ",\n      \"normals\": {\"parameters\": " + listText(cn.parameters, member(path, "normals.parameters")) +
           ", \"vectors\": [";
      for (std::size_t k = 0; k < cn.normals.size(); ++k)
        s += (k ? ", " : "") + vecText(cn.normals[k], indexed(member(path, "normals.vectors"), k));
      s += "]}";
    }
    s += "\n    }";
  }
  s += d.curves.empty() ? "],\n" : "\n  ],\n";

  s += "  \"faces\": [";
  for (std::size_t f = 0; f < d.faces.size(); ++f) {
    const FaceDescription &face = d.faces[f];
    const std::string path = indexed("faces", f);
    s += f ? ",\n" : "\n";
    s += "    {\n";
    if (!face.name.empty()) s += "      \"name\": " + jsonString(face.name) + ",\n";
    auto loopText = [&](const std::vector<SideDescription> &loop, const std::string &loopPath,
                        const std::string &indent) {
      std::string t = "[";
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const SideDescription &side = loop[k];
        const std::string sidePath = indexed(loopPath, k);
        t += k ? ",\n" + indent : "\n" + indent;
        t += "{\"curve\": " + std::to_string(side.curve) +
             ", \"from\": " + numberText(side.from, member(sidePath, "from")) +
             ", \"to\": " + numberText(side.to, member(sidePath, "to")) + "}";
      }
      return t + (loop.empty() ? "]" : "\n" + indent.substr(2) + "]");
    };
    if (face.partOf >= 0) s += "      \"part_of\": " + std::to_string(face.partOf) + ",\n";
    s += "      \"sides\": " + loopText(face.sides, member(path, "sides"), "        ");
    if (!face.holes.empty()) {
      s += ",\n      \"holes\": [";
      for (std::size_t h = 0; h < face.holes.size(); ++h)
        s += (h ? ", " : "") + loopText(face.holes[h], indexed(member(path, "holes"), h), "          ");
      s += "]";
    }
    s += "\n    }";
  }
  s += d.faces.empty() ? "]" : "\n  ]";

  if (!d.edges.empty()) {
    s += ",\n  \"edges\": [";
    for (std::size_t k = 0; k < d.edges.size(); ++k) {
      s += k ? ",\n    " : "\n    ";
      s += "{\"curve\": " + std::to_string(d.edges[k].curve);
      if (d.edges[k].masterFace >= 0) s += ", \"master\": " + std::to_string(d.edges[k].masterFace);
      if (d.edges[k].connection) s += ", \"connection\": true";
      if (d.edges[k].masterSurface >= 0) s += ", \"master_surface\": " + std::to_string(d.edges[k].masterSurface);
      s += "}";
    }
    s += "\n  ]";
  }
  if (!d.surfaces.empty()) {
    s += ",\n  \"surfaces\": [\n";
    for (std::size_t k = 0; k < d.surfaces.size(); ++k)
      s += (k ? ",\n" : "") + surfaceText(d.surfaces[k], indexed("surfaces", k));
    s += "\n  ]";
  }
  // A mesh reference is a separate input (curvenet approximate), never part of the file.
  if (d.reference && d.reference->kind != ReferenceSurface::Kind::Mesh) {
    const ReferenceSurface &ref = *d.reference;
    s += ",\n  \"reference\": {\"kind\": " + jsonString(ReferenceSurface::kindName(ref.kind)) +
         ", \"center\": " + vecText(ref.center, "reference.center") + ", \"size\": " + vecText(ref.size, "reference.size") + "}";
  }
  s += "\n}\n";
  return s;
}

} // namespace v1
} // namespace curvenet
