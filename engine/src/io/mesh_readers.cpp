// Triangle-mesh readers: Wavefront OBJ (v and f records), OFF, PLY (ASCII and
// binary) and STL (ASCII and binary).
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "text_tokens.hpp"

namespace curvenet {
inline namespace v1 {
namespace {

using text::integer;
using text::number;
using text::tokens;

using text::lines;

/// Fan triangulation of a polygon with at least 3 corners.
void addPolygon(Mesh &mesh, const std::vector<std::uint32_t> &corners) {
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) mesh.triangles.push_back({corners[0], corners[k], corners[k + 1]});
}

/// Mesh::faceTriangleStart from each triangle's network face (OBJ `g faceN`,
/// PLY `face`), kept only when every triangle has one and they run in order,
/// as the writers write them; otherwise the mesh simply has no face identity.
void recordFaceIdentity(Mesh &mesh, const std::vector<long long> &facePerTriangle) {
  if (facePerTriangle.empty() || facePerTriangle.size() != mesh.triangles.size()) return;
  for (std::size_t k = 0; k < facePerTriangle.size(); ++k)
    if (facePerTriangle[k] < 0 || (k > 0 && facePerTriangle[k] < facePerTriangle[k - 1])) return;
  if (facePerTriangle.back() >= (1ll << 24)) return; // more faces than any network has: not identity
  std::vector<std::uint32_t> start(static_cast<std::size_t>(facePerTriangle.back()) + 2, 0);
  std::size_t triangle = 0;
  for (std::size_t face = 0; face + 1 < start.size(); ++face) {
    start[face] = static_cast<std::uint32_t>(triangle);
    while (triangle < facePerTriangle.size() && facePerTriangle[triangle] == static_cast<long long>(face)) ++triangle;
  }
  start.back() = static_cast<std::uint32_t>(triangle);
  mesh.faceTriangleStart = std::move(start);
}

void finish(const Mesh &mesh, const std::string &file) {
  if (mesh.positions.empty() || mesh.triangles.empty())
    throw InputError(file, {}, "the mesh has no triangles");
}

} // namespace

Mesh parseObjMesh(const std::string &text, const std::string &file) {
  Mesh mesh;
  struct PendingFace {
    std::vector<long long> corners;
    std::size_t line;
    long long group; ///< N of the `g faceN` group it is in, -1 for none
  };
  long long group = -1;
  std::vector<PendingFace> faces;
  const auto all = lines(text);
  for (std::size_t n = 0; n < all.size(); ++n) {
    const auto t = tokens(all[n]);
    if (t.empty()) continue;
    const std::string where = "line " + std::to_string(n + 1);
    if (t[0] == "v") {
      if (t.size() < 4) throw InputError(file, where, "a vertex needs x y z");
      mesh.positions.push_back({number(t[1], file, where), number(t[2], file, where), number(t[3], file, where)});
    } else if (t[0] == "f") {
      if (t.size() < 4) throw InputError(file, where, "a face needs at least 3 vertices");
      PendingFace face{{}, n + 1, group};
      // "i", "i/t", "i//n", "i/t/n": the position index comes first; negative = relative.
      for (std::size_t k = 1; k < t.size(); ++k) {
        const long long index = integer(t[k].substr(0, t[k].find('/')), file, where);
        if (index == 0) throw InputError(file, where, "OBJ indices start at 1");
        face.corners.push_back(index < 0 ? static_cast<long long>(mesh.positions.size()) + index : index - 1);
      }
      faces.push_back(std::move(face));
    } else if (t[0] == "g") {
      // `g faceN` (as writeObj writes it) names the network face; other groups none.
      long long face = -1;
      if (t.size() == 2 && t[1].starts_with("face")) {
        const std::string_view digits = t[1].substr(4);
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), face);
        if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty()) face = -1;
      }
      group = face;
    }
    // Other records (vn, vt, o, s, usemtl, mtllib, l, …) carry nothing the fit uses.
  }
  std::vector<long long> facePerTriangle;
  for (const PendingFace &face : faces) {
    std::vector<std::uint32_t> corners;
    for (long long c : face.corners) {
      if (c < 0 || c >= static_cast<long long>(mesh.positions.size()))
        throw InputError(file, "line " + std::to_string(face.line), "vertex index out of range");
      corners.push_back(static_cast<std::uint32_t>(c));
    }
    addPolygon(mesh, corners);
    facePerTriangle.resize(mesh.triangles.size(), face.group);
  }
  recordFaceIdentity(mesh, facePerTriangle);
  finish(mesh, file);
  return mesh;
}

Mesh parseOffMesh(const std::string &text, const std::string &file) {
  Mesh mesh;
  const auto all = lines(text);
  std::size_t n = 0;
  auto next = [&]() -> std::vector<std::string_view> {
    while (n < all.size()) {
      auto t = tokens(all[n++]);
      if (!t.empty()) return t;
    }
    throw InputError(file, "line " + std::to_string(n), "unexpected end of file");
  };
  auto header = next();
  // "OFF" alone or followed by the counts on the same line.
  if (header[0] != "OFF") throw InputError(file, "line " + std::to_string(n), "expected the OFF header");
  header.erase(header.begin());
  if (header.empty()) header = next();
  const std::string countsWhere = "line " + std::to_string(n);
  if (header.size() < 2) throw InputError(file, countsWhere, "expected vertex and face counts");
  const long long vertices = integer(header[0], file, countsWhere), faces = integer(header[1], file, countsWhere);
  if (vertices < 0 || faces < 0 || vertices > (1ll << 31))
    throw InputError(file, countsWhere,
                     "the vertex and face counts (" + std::string(header[0]) + " " + std::string(header[1]) +
                         ") must be non-negative, at most 2^31 vertices");
  for (long long v = 0; v < vertices; ++v) {
    const auto t = next();
    const std::string where = "line " + std::to_string(n);
    if (t.size() < 3) throw InputError(file, where, "a vertex needs x y z");
    mesh.positions.push_back({number(t[0], file, where), number(t[1], file, where), number(t[2], file, where)});
  }
  for (long long f = 0; f < faces; ++f) {
    const auto t = next();
    const std::string where = "line " + std::to_string(n);
    const long long count = integer(t[0], file, where);
    if (count < 3 || count >= static_cast<long long>(t.size())) // (count + 1 could overflow)
      throw InputError(file, where, "a face needs its corner count (≥ 3) and that many indices");
    std::vector<std::uint32_t> corners;
    for (long long k = 1; k <= count; ++k) {
      const long long index = integer(t[k], file, where);
      if (index < 0 || index >= vertices) throw InputError(file, where, "vertex index out of range");
      corners.push_back(static_cast<std::uint32_t>(index));
    }
    addPolygon(mesh, corners);
  }
  finish(mesh, file);
  return mesh;
}

namespace {

/// A little-endian (or big-endian) binary field or an ASCII token of a PLY body.
class PlyBody {
public:
  PlyBody(const std::string &text, std::size_t start, int format, const std::string &file)
      : text_(text), at_(start), format_(format), file_(file) {}

  /// The next value of PLY type `type` as a double; InputError naming `element` at the end of the data.
  double read(const std::string &type, const std::string &element) {
    if (format_ == kAscii) return asciiValue(element);
    const std::size_t size = typeSize(type);
    if (at_ + size > text_.size()) throw InputError(file_, element, "the binary data ends early");
    unsigned char bytes[8];
    std::memcpy(bytes, text_.data() + at_, size);
    at_ += size;
    if (format_ == kBigEndian) std::reverse(bytes, bytes + size);
    return decode(type, bytes);
  }

  static constexpr int kAscii = 0, kLittleEndian = 1, kBigEndian = 2;

  /// Bytes of a PLY scalar type, 0 for an unknown one.
  static std::size_t typeSize(const std::string &type) {
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
    if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" || type == "float32")
      return 4;
    if (type == "double" || type == "float64") return 8;
    return 0;
  }

private:
  static double decode(const std::string &type, const unsigned char *b) {
    auto as = [b]<class T>(T) { T v; std::memcpy(&v, b, sizeof v); return static_cast<double>(v); };
    if (type == "char" || type == "int8") return as(std::int8_t{});
    if (type == "uchar" || type == "uint8") return as(std::uint8_t{});
    if (type == "short" || type == "int16") return as(std::int16_t{});
    if (type == "ushort" || type == "uint16") return as(std::uint16_t{});
    if (type == "int" || type == "int32") return as(std::int32_t{});
    if (type == "uint" || type == "uint32") return as(std::uint32_t{});
    if (type == "float" || type == "float32") return as(float{});
    return as(double{});
  }
  double asciiValue(const std::string &element) {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
    std::size_t end = at_;
    while (end < text_.size() && !std::isspace(static_cast<unsigned char>(text_[end]))) ++end;
    if (end == at_) throw InputError(file_, element, "the data ends early");
    const std::string_view token(text_.data() + at_, end - at_);
    at_ = end;
    return number(token, file_, element);
  }
  const std::string &text_;
  std::size_t at_;
  int format_;
  const std::string &file_;
};

struct PlyProperty {
  std::string name, type, countType; ///< countType: the list length's type; empty for a scalar
};
struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

/// A whole number read as a double that must lie in [0, limit); InputError otherwise.
std::size_t plyIndex(double value, std::size_t limit, const std::string &file, const std::string &element,
                     const char *what) {
  if (!(value >= 0 && value < static_cast<double>(limit)) || value != std::floor(value))
    throw InputError(file, element, std::string(what) + " " + std::to_string(value) + " is out of range (limit " +
                                        std::to_string(limit) + ")");
  return static_cast<std::size_t>(value);
}

} // namespace

Mesh parsePlyMesh(const std::string &text, const std::string &file) {
  // Header: lines up to "end_header".
  std::vector<PlyElement> elements;
  int format = -1;
  std::size_t at = 0, lineNumber = 0;
  bool ended = false;
  while (at < text.size() && !ended) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + at, end - at);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    at = end + 1;
    const std::string where = "header line " + std::to_string(++lineNumber);
    const auto t = tokens(line);
    if (lineNumber == 1) {
      if (t.size() != 1 || t[0] != "ply") throw InputError(file, where, "expected the \"ply\" magic word");
      continue;
    }
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "end_header") ended = true;
    else if (t[0] == "format") {
      if (t.size() < 2) throw InputError(file, where, "the format line names no format");
      if (t[1] == "ascii") format = PlyBody::kAscii;
      else if (t[1] == "binary_little_endian") format = PlyBody::kLittleEndian;
      else if (t[1] == "binary_big_endian") format = PlyBody::kBigEndian;
      else throw InputError(file, where, "unknown format \"" + std::string(t[1]) + "\"");
    } else if (t[0] == "element") {
      if (t.size() != 3) throw InputError(file, where, "expected \"element NAME COUNT\"");
      const long long count = integer(t[2], file, where);
      if (count < 0 || count > (1ll << 31)) throw InputError(file, where, "element count " + std::string(t[2]) + " is out of range");
      elements.push_back({std::string(t[1]), count, {}});
    } else if (t[0] == "property") {
      if (elements.empty()) throw InputError(file, where, "a property before any element");
      PlyProperty property;
      if (t.size() == 5 && t[1] == "list") property = {std::string(t[4]), std::string(t[3]), std::string(t[2])};
      else if (t.size() == 3) property = {std::string(t[2]), std::string(t[1]), {}};
      else throw InputError(file, where, "expected \"property TYPE NAME\" or \"property list COUNT TYPE NAME\"");
      for (const std::string &type : {property.type, property.countType})
        if (!type.empty() && PlyBody::typeSize(type) == 0) throw InputError(file, where, "unknown type \"" + type + "\"");
      elements.back().properties.push_back(property);
    } else {
      throw InputError(file, where, "unknown header line \"" + std::string(t[0]) + "\"");
    }
  }
  if (!ended) throw InputError(file, {}, "the header has no end_header line");
  if (format < 0) throw InputError(file, {}, "the header has no format line");

  Mesh mesh;
  std::vector<long long> facePerTriangle;
  PlyBody body(text, at, format, file);
  for (const PlyElement &element : elements) {
    const bool vertex = element.name == "vertex", face = element.name == "face";
    for (long long i = 0; i < element.count; ++i) {
      const std::string where = element.name + " " + std::to_string(i);
      Vec3 position;
      int coordinates = 0;
      long long faceOfThis = -1;
      for (const PlyProperty &property : element.properties) {
        if (property.countType.empty()) {
          const double value = body.read(property.type, where);
          if (face && property.name == "face")
            faceOfThis = value >= 0 && value < 1e12 && value == std::floor(value) ? static_cast<long long>(value) : -1;
          if (vertex && (property.name == "x" || property.name == "y" || property.name == "z")) {
            if (!std::isfinite(value)) throw InputError(file, where, property.name + " is not finite");
            (property.name == "x" ? position.x : property.name == "y" ? position.y : position.z) = value;
            ++coordinates;
          }
          continue;
        }
        const std::size_t count = plyIndex(body.read(property.countType, where), 1u << 16, file, where, "list length");
        std::vector<std::uint32_t> corners;
        for (std::size_t k = 0; k < count; ++k) {
          const double value = body.read(property.type, where);
          if (face && (property.name == "vertex_indices" || property.name == "vertex_index"))
            corners.push_back(static_cast<std::uint32_t>(plyIndex(value, mesh.positions.size(), file, where, "vertex index")));
        }
        if (face && (property.name == "vertex_indices" || property.name == "vertex_index")) {
          if (corners.size() < 3) throw InputError(file, where, "a face needs at least 3 vertices");
          addPolygon(mesh, corners);
        }
      }
      if (vertex) {
        if (coordinates != 3) throw InputError(file, where, "a vertex needs properties x, y and z");
        mesh.positions.push_back(position);
      }
      if (face) facePerTriangle.resize(mesh.triangles.size(), faceOfThis);
    }
  }
  recordFaceIdentity(mesh, facePerTriangle);
  finish(mesh, file);
  return mesh;
}

Mesh parseStlMesh(const std::string &text, const std::string &file) {
  // STL stores three corners per triangle; equal corners are merged so the
  // triangles share vertices as in the other formats.
  Mesh mesh;
  std::map<std::array<double, 3>, std::uint32_t> indexOf;
  auto corner = [&](const Vec3 &p) {
    const auto [it, added] = indexOf.try_emplace({p.x, p.y, p.z}, static_cast<std::uint32_t>(mesh.positions.size()));
    if (added) mesh.positions.push_back(p);
    return it->second;
  };
  auto addTriangle = [&](const std::array<Vec3, 3> &p, const std::string &where) {
    for (const Vec3 &q : p)
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
        throw InputError(file, where, "a corner is not finite");
    mesh.triangles.push_back({corner(p[0]), corner(p[1]), corner(p[2])});
  };
  std::uint32_t binaryCount = 0;
  if (text.size() >= 84) std::memcpy(&binaryCount, text.data() + 80, 4);
  const bool binary = text.size() >= 84 && text.size() == 84 + 50ull * binaryCount;
  if (binary) {
    for (std::uint32_t i = 0; i < binaryCount; ++i) {
      const char *record = text.data() + 84 + 50ull * i + 12; // after the facet normal
      std::array<Vec3, 3> p;
      for (int k = 0; k < 3; ++k) {
        float xyz[3];
        std::memcpy(xyz, record + 12 * k, 12);
        p[k] = {xyz[0], xyz[1], xyz[2]};
      }
      addTriangle(p, "triangle " + std::to_string(i));
    }
  } else {
    const auto all = lines(text);
    if (all.empty() || tokens(all[0]).empty() || tokens(all[0])[0] != "solid")
      throw InputError(file, "line 1",
                       "neither ASCII STL (\"solid\") nor binary STL (84 + 50 x triangles bytes, here " +
                           std::to_string(text.size()) + ")");
    std::vector<Vec3> corners;
    for (std::size_t n = 0; n < all.size(); ++n) {
      const auto t = tokens(all[n]);
      if (t.empty() || t[0] != "vertex") continue;
      const std::string where = "line " + std::to_string(n + 1);
      if (t.size() != 4) throw InputError(file, where, "a vertex needs x y z");
      corners.push_back({number(t[1], file, where), number(t[2], file, where), number(t[3], file, where)});
      if (corners.size() == 3) addTriangle({corners[0], corners[1], corners[2]}, where), corners.clear();
    }
    if (!corners.empty()) throw InputError(file, {}, "the last facet has fewer than 3 vertices");
  }
  finish(mesh, file);
  return mesh;
}

Mesh parseMeshText(const std::string &text, const std::string &file) {
  const auto first = tokens(std::string_view(text).substr(0, std::min<std::size_t>(text.size(), 80)));
  const std::string_view word = first.empty() ? std::string_view{} : first[0];
  if (word == "ply") return parsePlyMesh(text, file);
  if (word.starts_with("OFF")) return parseOffMesh(text, file);
  if (word == "solid" || (!text.empty() && std::memchr(text.data(), 0, std::min<std::size_t>(text.size(), 84))))
    return parseStlMesh(text, file);
  return parseObjMesh(text, file);
}

Mesh readMeshFile(const std::string &path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char &c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".obj" && ext != ".off" && ext != ".ply" && ext != ".stl")
    throw InputError(path, {}, "unknown mesh file extension \"" + ext + "\" (expected .obj, .off, .ply or .stl)");
  const std::string text = readTextFile(path);
  if (ext == ".obj") return parseObjMesh(text, path);
  if (ext == ".off") return parseOffMesh(text, path);
  if (ext == ".ply") return parsePlyMesh(text, path);
  return parseStlMesh(text, path);
}

} // namespace v1
} // namespace curvenet
