// Triangle-mesh readers: Wavefront OBJ (v and f records) and OFF.
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "curvenet/error.hpp"
#include "curvenet/io.hpp"

namespace curvenet {
inline namespace v1 {
namespace {

/// Splits into whitespace-separated tokens.
std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    std::size_t j = i;
    while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

double number(std::string_view token, const std::string &file, const std::string &where) {
  double value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(value))
    throw InputError(file, where, "not a finite number: \"" + std::string(token) + "\"");
  return value;
}

long long integer(std::string_view token, const std::string &file, const std::string &where) {
  long long value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size())
    throw InputError(file, where, "not an integer: \"" + std::string(token) + "\"");
  return value;
}

/// Lines without comments (`#` to the end) and without trailing '\r'.
std::vector<std::string_view> lines(const std::string &text) {
  std::vector<std::string_view> out;
  std::string_view all(text);
  std::size_t start = 0;
  while (start <= all.size()) {
    std::size_t end = all.find('\n', start);
    if (end == std::string_view::npos) end = all.size();
    std::string_view line = all.substr(start, end - start);
    if (auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    out.push_back(line);
    start = end + 1;
  }
  return out;
}

/// Fan triangulation of a polygon with at least 3 corners.
void addPolygon(Mesh &mesh, const std::vector<std::uint32_t> &corners) {
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) mesh.triangles.push_back({corners[0], corners[k], corners[k + 1]});
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
  };
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
      PendingFace face{{}, n + 1};
      // "i", "i/t", "i//n", "i/t/n": the position index comes first; negative = relative.
      for (std::size_t k = 1; k < t.size(); ++k) {
        const long long index = integer(t[k].substr(0, t[k].find('/')), file, where);
        if (index == 0) throw InputError(file, where, "OBJ indices start at 1");
        face.corners.push_back(index < 0 ? static_cast<long long>(mesh.positions.size()) + index : index - 1);
      }
      faces.push_back(std::move(face));
    }
    // Other records (vn, vt, o, g, s, usemtl, mtllib, l, …) carry nothing the fit uses.
  }
  for (const PendingFace &face : faces) {
    std::vector<std::uint32_t> corners;
    for (long long c : face.corners) {
      if (c < 0 || c >= static_cast<long long>(mesh.positions.size()))
        throw InputError(file, "line " + std::to_string(face.line), "vertex index out of range");
      corners.push_back(static_cast<std::uint32_t>(c));
    }
    addPolygon(mesh, corners);
  }
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
  if (vertices < 0 || faces < 0 || vertices > (1ll << 31)) throw InputError(file, countsWhere, "bad counts");
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

Mesh readMeshFile(const std::string &path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char &c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".obj" && ext != ".off")
    throw InputError(path, {}, "unknown mesh file extension \"" + ext + "\" (expected .obj or .off)");
  const std::string text = readTextFile(path);
  return ext == ".obj" ? parseObjMesh(text, path) : parseOffMesh(text, path);
}

} // namespace v1
} // namespace curvenet
