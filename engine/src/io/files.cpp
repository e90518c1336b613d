// File-level I/O: choosing a reader by extension, atomic writes, mesh writers.
#include <algorithm>
#include <atomic>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <ext/stdio_filebuf.h>
#include <fcntl.h>
#include <unistd.h>

#include "curvenet/builtins.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "curvenet/sketch.hpp"
#include "parallel/fork_join.hpp"

namespace curvenet {
inline namespace v1 {
namespace {

std::string lowercaseExtension(const std::string &path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char &c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// stdio rather than ifstream: fopen/fread set errno, so the error can say
// why ("No such file or directory", "Permission denied", "Is a directory").
std::string readWholeFile(const std::string &path) {
  std::unique_ptr<std::FILE, int (*)(std::FILE *)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw InputError(path, {}, std::string("cannot open: ") + std::strerror(errno));
  std::string text;
  char buffer[1 << 16];
  for (;;) {
    std::size_t n = std::fread(buffer, 1, sizeof buffer, f.get());
    text.append(buffer, n);
    if (n < sizeof buffer) break;
  }
  if (std::ferror(f.get())) throw InputError(path, {}, std::string("cannot read: ") + std::strerror(errno));
  return text;
}

// Little-endian bytes whatever the host order, as the PLY header promises.
template <typename T> void putLittleEndian(std::string &out, T value) {
  static_assert(std::is_trivially_copyable_v<T>);
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  out.append(reinterpret_cast<const char *>(bytes), sizeof(T));
}

void checkMesh(const Mesh &mesh) {
  CURVENET_CHECK(mesh.normals.empty() || mesh.normals.size() == mesh.positions.size(),
                 "normals " + std::to_string(mesh.normals.size()) + " vs positions " + std::to_string(mesh.positions.size()));
  for (const auto &t : mesh.triangles)
    for (std::uint32_t v : t)
      CURVENET_CHECK(v < mesh.positions.size(),
                     "triangle index " + std::to_string(v) + " vs " + std::to_string(mesh.positions.size()) + " positions");
}

} // namespace

std::string readTextFile(const std::string &path) { return readWholeFile(path); }

NetworkDescription readNetworkFile(const std::string &path) {
  const std::string ext = lowercaseExtension(path);
  // An OBJ curve graph (a sketch): its network is found (curvenet/sketch.hpp).
  if (ext == ".obj") return networkFromCurveGraph(readCurveGraphFile(path), {}, path).description;
  if (ext != ".json" && ext != ".lop")
    throw InputError(path, {}, "unknown network file extension \"" + ext + "\" (expected .json, .lop or .obj)");
  const std::string text = readWholeFile(path);
  if (ext == ".lop") return parseLop(text, path);
  NetworkDescription d = parseNetworkJson(text, path);
  // The name is optional in the document; reports still want one.
  if (d.name.empty()) d.name = std::filesystem::path(path).stem().string();
  // Curves and no faces: a curve graph, its network found as for a sketch.
  if (d.faces.empty() && !d.curves.empty()) {
    const std::string name = d.name;
    d = networkFromCurveGraph(curveGraphFromCurves(d), {}, path).description;
    d.name = name;
  }
  return d;
}

NetworkDescription loadNetworkInput(const std::string &input) {
  constexpr std::string_view prefix = "builtin:";
  if (input.starts_with(prefix)) return builtinNetwork(input.substr(prefix.size()));
  return readNetworkFile(input);
}

namespace {

/// Writes through `writer` into a file that has no name yet (O_TMPFILE in the
/// target's folder) and gives it the final name only when complete: a
/// process killed at any point (Ctrl-C, SIGKILL, a crash) leaves nothing
/// behind. Returns false where the file system has no unnamed files.
bool writeUnnamedThenLink(const std::string &path, const std::function<void(std::ostream &)> &writer) {
  const std::filesystem::path target(path);
  const std::string folder = target.has_parent_path() ? target.parent_path().string() : ".";
  const int fd = ::open(folder.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666); // the umask applies
  if (fd < 0) {
    if (errno == EOPNOTSUPP || errno == EISDIR || errno == EINVAL) return false;
    throw InputError(path, {}, std::string("cannot create the output file: ") + std::strerror(errno));
  }
  {
    __gnu_cxx::stdio_filebuf<char> buffer(fd, std::ios::out | std::ios::binary); // owns and closes fd
    std::ostream out(&buffer);
    writer(out);
    out.flush();
    if (!out) throw InputError(path, {}, std::string("write failed: ") + std::strerror(errno));
    if (::fsync(fd) != 0) throw InputError(path, {}, std::string("write failed: ") + std::strerror(errno));
    // linkat cannot replace an existing file: link under a unique temporary
    // name, then rename over the target (atomic).
    static std::atomic<std::uint64_t> counter{0};
    const std::string temp = path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    const std::string procPath = "/proc/self/fd/" + std::to_string(fd);
    if (::linkat(AT_FDCWD, procPath.c_str(), AT_FDCWD, temp.c_str(), AT_SYMLINK_FOLLOW) != 0)
      throw InputError(path, {}, std::string("cannot name the finished file: ") + std::strerror(errno));
    std::error_code ec;
    std::filesystem::rename(temp, path, ec);
    if (ec) {
      std::filesystem::remove(temp, ec);
      throw InputError(path, {}, "cannot move the finished file into place: " + ec.message());
    }
  }
  return true;
}

} // namespace

void writeFileAtomically(const std::string &path, const std::function<void(std::ostream &)> &writer) {
  if (writeUnnamedThenLink(path, writer)) return;
  // Fallback (file systems without O_TMPFILE): a named temporary beside the
  // target, renamed when complete and removed on any error. pid + a
  // process-wide counter make it unique among concurrent writers.
  static std::atomic<std::uint64_t> counter{0};
  const std::string temp = path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  try {
    {
      std::ofstream out(temp, std::ios::binary | std::ios::trunc);
      if (!out) throw InputError(path, {}, "cannot create temporary file " + temp + ": " + std::strerror(errno));
      writer(out);
      out.flush();
      if (!out) throw InputError(path, {}, std::string("write failed: ") + std::strerror(errno));
      out.close();
      if (out.fail()) throw InputError(path, {}, std::string("closing the file failed: ") + std::strerror(errno));
    }
    std::error_code ec;
    std::filesystem::rename(temp, path, ec);
    if (ec) throw InputError(path, {}, "cannot move the finished file into place: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    throw;
  }
}

namespace {

/// Appends a double in its shortest round-trip form (std::to_chars).
char *putNumber(char *at, double x) { return std::to_chars(at, at + 32, x).ptr; }
char *putNumber(char *at, unsigned long x) { return std::to_chars(at, at + 24, x).ptr; }

} // namespace

void writeObj(const Mesh &mesh, std::ostream &out) {
  checkMesh(mesh);
  const bool hasNormals = !mesh.normals.empty();
  // Face identity: a group `g faceN` opens the triangles of network face N.
  const std::vector<std::uint32_t> &faceStart = mesh.faceTriangleStart;
  const bool grouped = faceStart.size() >= 2 && faceStart.back() == mesh.triangles.size();
  const std::string header = "# curvenet mesh: " + std::to_string(mesh.positions.size()) + " vertices, " +
                             std::to_string(mesh.triangles.size()) + " triangles" +
                             (grouped ? "; group faceN holds the triangles of network face N" : "") + "\n";
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  // Lines are formatted by std::to_chars (the shortest text that reads back
  // as the same double) in chunks on all threads, a batch of chunks at a
  // time written in order: a mesh of millions of vertices is written at
  // disk speed while the text in memory stays a few megabytes per thread.
  const std::size_t vertices = mesh.positions.size(), normals = mesh.normals.size();
  const std::size_t lines = vertices + normals + mesh.triangles.size();
  auto formatLine = [&](std::size_t line, char *at) {
    if (line < vertices + normals) {
      const bool normal = line >= vertices;
      const Vec3 &p = normal ? mesh.normals[line - vertices] : mesh.positions[line];
      *at++ = 'v';
      if (normal) *at++ = 'n';
      for (double x : {p.x, p.y, p.z}) *at++ = ' ', at = putNumber(at, x);
    } else {
      // OBJ indices are 1-based; with normals, each vertex uses its own normal.
      const std::size_t triangle = line - vertices - normals;
      const auto &t = mesh.triangles[triangle];
      if (grouped) {
        // The last face whose range starts at or before this triangle; the
        // group opens when its range starts here (empty faces have none).
        const auto next = std::upper_bound(faceStart.begin(), faceStart.end() - 1, triangle);
        const std::size_t face = static_cast<std::size_t>(next - faceStart.begin()) - 1;
        if (faceStart[face] == triangle) {
          for (char c : std::string_view("g face")) *at++ = c;
          at = putNumber(at, static_cast<unsigned long>(face));
          *at++ = '\n';
        }
      }
      *at++ = 'f';
      for (std::uint32_t v : t) {
        *at++ = ' ', at = putNumber(at, v + 1ul);
        if (hasNormals) *at++ = '/', *at++ = '/', at = putNumber(at, v + 1ul);
      }
    }
    *at++ = '\n';
    return at;
  };
  constexpr std::size_t kChunkLines = 1 << 14, kBatchChunks = 32;
  std::vector<std::string> chunks(kBatchChunks);
  for (std::size_t batchStart = 0; batchStart < lines; batchStart += kChunkLines * kBatchChunks) {
    const std::size_t batchChunks = std::min(kBatchChunks, (lines - batchStart + kChunkLines - 1) / kChunkLines);
    parallel::parallelFor(tbb::blocked_range<std::size_t>(0, batchChunks, 1), [&](const auto &range) {
      char line[192];
      for (std::size_t chunk = range.begin(); chunk != range.end(); ++chunk) {
        std::string &text = chunks[chunk];
        text.clear();
        const std::size_t from = batchStart + chunk * kChunkLines, to = std::min(lines, from + kChunkLines);
        for (std::size_t k = from; k < to; ++k) text.append(line, formatLine(k, line));
      }
    });
    for (std::size_t chunk = 0; chunk < batchChunks; ++chunk)
      out.write(chunks[chunk].data(), static_cast<std::streamsize>(chunks[chunk].size()));
  }
}

void writePly(const Mesh &mesh, std::ostream &out) {
  checkMesh(mesh);
  const bool hasNormals = !mesh.normals.empty();
  std::string data = "ply\nformat binary_little_endian 1.0\ncomment written by curvenet\n";
  data += "element vertex " + std::to_string(mesh.positions.size()) + "\n";
  data += "property float64 x\nproperty float64 y\nproperty float64 z\n";
  if (hasNormals) data += "property float64 nx\nproperty float64 ny\nproperty float64 nz\n";
  data += "element face " + std::to_string(mesh.triangles.size()) + "\n";
  data += "property list uchar uint32 vertex_indices\n";
  // Face identity: each triangle's network face, when the mesh records them.
  const std::vector<std::uint32_t> &faceStart = mesh.faceTriangleStart;
  const bool grouped = faceStart.size() >= 2 && faceStart.back() == mesh.triangles.size();
  if (grouped) data += "property uint32 face\n";
  data += "end_header\n";

  const std::size_t vertexBytes = (hasNormals ? 6 : 3) * sizeof(double);
  data.reserve(data.size() + mesh.positions.size() * vertexBytes +
               mesh.triangles.size() * (1 + (grouped ? 4 : 3) * sizeof(std::uint32_t)));
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3 &p = mesh.positions[i];
    putLittleEndian(data, p.x), putLittleEndian(data, p.y), putLittleEndian(data, p.z);
    if (hasNormals) {
      const Vec3 &n = mesh.normals[i];
      putLittleEndian(data, n.x), putLittleEndian(data, n.y), putLittleEndian(data, n.z);
    }
  }
  std::uint32_t face = 0;
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    putLittleEndian(data, std::uint8_t{3});
    for (std::uint32_t v : mesh.triangles[k]) putLittleEndian(data, v);
    if (!grouped) continue;
    while (faceStart[face + 1] <= k) ++face;
    putLittleEndian(data, face);
  }
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
}

void writeMeshFile(const Mesh &mesh, const std::string &path) {
  const std::string ext = lowercaseExtension(path);
  if (ext == ".obj") return writeFileAtomically(path, [&](std::ostream &out) { writeObj(mesh, out); });
  if (ext == ".ply") return writeFileAtomically(path, [&](std::ostream &out) { writePly(mesh, out); });
  throw InputError(path, {}, "unknown mesh file extension \"" + ext + "\" (expected .obj or .ply)");
}

} // namespace v1
} // namespace curvenet
