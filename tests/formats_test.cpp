// The readers' edges: every mesh format read back from the writers and from
// hand-made text (PLY ASCII and binary, STL ASCII and binary, recognition by
// content for standard input), nesting limits of the native format, and
// messages that name the file, the element and the value.
#include <chrono>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "input_errors.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"

namespace curvenet {
inline namespace v1 {
namespace {

using test::catchInputError;
using test::contains;

Mesh pentagonMesh() {
  return tessellate(Surface::build(Network::build(builtinNetwork("pentagon")), {}), {3, 1});
}

/// The same positions and triangles (readers drop normals).
void expectSameMesh(const Mesh &read, const Mesh &written) {
  ASSERT_EQ(read.positions.size(), written.positions.size());
  ASSERT_EQ(read.triangles.size(), written.triangles.size());
  for (std::size_t i = 0; i < read.positions.size(); ++i) {
    EXPECT_EQ(read.positions[i].x, written.positions[i].x) << "vertex " << i;
    EXPECT_EQ(read.positions[i].y, written.positions[i].y) << "vertex " << i;
    EXPECT_EQ(read.positions[i].z, written.positions[i].z) << "vertex " << i;
  }
  for (std::size_t t = 0; t < read.triangles.size(); ++t) EXPECT_EQ(read.triangles[t], written.triangles[t]) << "triangle " << t;
}

std::string asciiStl(const Mesh &mesh) {
  std::ostringstream s;
  s.precision(17);
  s << "solid test\n";
  for (const auto &t : mesh.triangles) {
    s << " facet normal 0 0 1\n  outer loop\n";
    for (std::uint32_t v : t) s << "   vertex " << mesh.positions[v].x << ' ' << mesh.positions[v].y << ' ' << mesh.positions[v].z << '\n';
    s << "  endloop\n endfacet\n";
  }
  s << "endsolid test\n";
  return s.str();
}

std::string binaryStl(const Mesh &mesh) {
  std::string bytes(80, ' ');
  const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
  bytes.append(reinterpret_cast<const char *>(&count), 4);
  for (const auto &t : mesh.triangles) {
    const float record[12] = {0, 0, 1,
                              float(mesh.positions[t[0]].x), float(mesh.positions[t[0]].y), float(mesh.positions[t[0]].z),
                              float(mesh.positions[t[1]].x), float(mesh.positions[t[1]].y), float(mesh.positions[t[1]].z),
                              float(mesh.positions[t[2]].x), float(mesh.positions[t[2]].y), float(mesh.positions[t[2]].z)};
    bytes.append(reinterpret_cast<const char *>(record), sizeof record);
    bytes.append(2, '\0'); // attribute byte count
  }
  return bytes;
}

TEST(MeshReaders, PlyReadsWhatWritePlyWrote) {
  const Mesh mesh = pentagonMesh();
  std::ostringstream out;
  writePly(mesh, out);
  expectSameMesh(parsePlyMesh(out.str(), "p.ply"), mesh);
  expectSameMesh(parseMeshText(out.str(), "stdin"), mesh);
}

TEST(MeshReaders, AsciiPlyWithOtherElementsAndProperties) {
  const std::string text = "ply\nformat ascii 1.0\ncomment hand made\n"
                           "element vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
                           "element face 1\nproperty list uchar int vertex_indices\nproperty int flags\n"
                           "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
                           "0 0 0 255\n1 0 0 0\n1 1 0 7\n0 1 0 9\n4 0 1 2 3 5\n0 2\n";
  const Mesh mesh = parsePlyMesh(text, "quad.ply");
  ASSERT_EQ(mesh.positions.size(), 4u);
  ASSERT_EQ(mesh.triangles.size(), 2u); // the quad fan-triangulated
  EXPECT_EQ(mesh.positions[2].x, 1.0);
  EXPECT_EQ(mesh.positions[2].y, 1.0);
}

TEST(MeshReaders, PlyErrorsNameTheFileAndElement) {
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\n"
                             "property double y\nproperty double z\nelement face 1\n"
                             "property list uchar uint32 vertex_indices\nend_header\n";
  const InputError early = catchInputError([&] { parsePlyMesh(header + std::string(30, '\0'), "cut.ply"); });
  EXPECT_EQ(early.file(), "cut.ply");
  EXPECT_EQ(early.element(), "vertex 1");
  EXPECT_TRUE(contains(early.reason(), "ends early")) << early.what();
  std::string body(3 * 24, '\0');
  body += '\3';
  for (std::uint32_t v : {0u, 1u, 7u}) body.append(reinterpret_cast<const char *>(&v), 4);
  const InputError index = catchInputError([&] { parsePlyMesh(header + body, "index.ply"); });
  EXPECT_EQ(index.element(), "face 0");
  EXPECT_TRUE(contains(index.reason(), "vertex index 7")) << index.what();
  const InputError magic = catchInputError([&] { parsePlyMesh("plx\n", "magic.ply"); });
  EXPECT_EQ(magic.element(), "header line 1");
}

TEST(MeshReaders, StlAsciiAndBinaryMergeEqualCorners) {
  const Mesh mesh = pentagonMesh();
  // The vertices come in the order the triangles first use them: compare
  // each triangle's corners, and the count of distinct vertices.
  auto expectSameTriangles = [&](const Mesh &read, double tolerance, const char *what) {
    ASSERT_EQ(read.positions.size(), mesh.positions.size()) << what;
    ASSERT_EQ(read.triangles.size(), mesh.triangles.size()) << what;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k)
        EXPECT_LE(norm(read.positions[read.triangles[t][k]] - mesh.positions[mesh.triangles[t][k]]), tolerance)
            << what << " triangle " << t;
  };
  expectSameTriangles(parseStlMesh(asciiStl(mesh), "a.stl"), 0, "ASCII");
  expectSameTriangles(parseStlMesh(binaryStl(mesh), "b.stl"), 1e-6, "binary"); // float corners still coincide
  EXPECT_EQ(parseMeshText(binaryStl(mesh), "stdin").triangles.size(), mesh.triangles.size());
  const InputError e = catchInputError([&] { parseStlMesh("hello world", "x.stl"); });
  EXPECT_EQ(e.file(), "x.stl");
  EXPECT_TRUE(contains(e.reason(), "binary STL")) << e.what();
}

TEST(MeshFaceIdentity, ObjGroupsAndPlyFacePropertyCarryTheNetworkFace) {
  const Network network = Network::build(builtinNetwork("hemisphere-tjunction"));
  const Mesh mesh = tessellate(Surface::build(network, {}), {3, 1});
  ASSERT_EQ(mesh.faceTriangleStart.size(), network.faces().size() + 1);
  std::ostringstream obj, ply;
  writeObj(mesh, obj);
  writePly(mesh, ply);
  for (std::size_t f = 0; f < network.faces().size(); ++f)
    EXPECT_TRUE(contains(obj.str(), "\ng face" + std::to_string(f) + "\nf ")) << "face " << f;
  EXPECT_TRUE(contains(ply.str(), "property uint32 face\n"));
  EXPECT_EQ(parseObjMesh(obj.str(), "m.obj").faceTriangleStart, mesh.faceTriangleStart);
  EXPECT_EQ(parsePlyMesh(ply.str(), "m.ply").faceTriangleStart, mesh.faceTriangleStart);
  // A mesh the tessellator did not make has no face identity to write, nor to read back.
  Mesh plain = mesh;
  plain.faceTriangleStart.clear();
  std::ostringstream plainObj;
  writeObj(plain, plainObj);
  EXPECT_FALSE(contains(plainObj.str(), "\ng ")) << "groups without faces";
  EXPECT_TRUE(parseObjMesh(plainObj.str(), "p.obj").faceTriangleStart.empty());
}

TEST(MeshReaders, OffCountsErrorSaysWhichCounts) {
  const InputError e = catchInputError([&] { parseOffMesh("OFF\n-3 1 0\n", "bad.off"); });
  EXPECT_EQ(e.file(), "bad.off");
  EXPECT_EQ(e.element(), "line 2");
  EXPECT_TRUE(contains(e.reason(), "-3 1")) << e.what();
}

TEST(NativeFormatLimits, DeepNestingIsRefusedInLinearTime) {
  // 200 000 levels took minutes and gigabytes when every frame kept its path.
  for (std::size_t depth : {100000u, 200000u}) {
    const std::string text = std::string(depth, '[') + std::string(depth, ']');
    const auto start = std::chrono::steady_clock::now();
    const InputError e = catchInputError([&] { parseNetworkJson(text, "deep.json"); });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(e.file(), "deep.json");
    EXPECT_TRUE(contains(e.reason(), "deeper than 64")) << e.what();
    EXPECT_LT(seconds, 1.0) << depth << " levels";
  }
  // 64 levels are still parsed (and then refused for what they hold, not their depth).
  const InputError shallow = catchInputError([&] { parseNetworkJson(std::string(64, '[') + std::string(64, ']'), "s.json"); });
  EXPECT_FALSE(contains(shallow.reason(), "deeper")) << shallow.what();
}

TEST(NativeFormatLimits, DuplicateKeyDeepInsideStillNamesItsPath) {
  const InputError e = catchInputError([&] { parseNetworkJson(R"({"a": [{}, {"b": {"c": 1, "c": 2}}]})", "d.json"); });
  EXPECT_EQ(e.element(), "a[1].b");
  EXPECT_TRUE(contains(e.reason(), "duplicate key \"c\"")) << e.what();
}

TEST(NativeFormatMessages, IndicesShowTheValueAndTheRange) {
  NetworkDescription d = builtinNetwork("hemisphere-tjunction");
  std::string text = networkToJson(d);
  // A curve index written as a float.
  const std::string firstCurve = "\"curve\": 0";
  ASSERT_TRUE(contains(text, firstCurve));
  std::string floatIndex = text;
  floatIndex.replace(floatIndex.find(firstCurve), firstCurve.size(), "\"curve\": 1e20");
  const InputError index = catchInputError([&] { parseNetworkJson(floatIndex, "i.json"); });
  EXPECT_TRUE(index.element().starts_with("faces[") && index.element().ends_with("].curve")) << index.what();
  EXPECT_TRUE(contains(index.reason(), "1e+20")) << index.what();
  // A master face that does not exist.
  d.edges.push_back({});
  d.edges.back().curve = 0;
  d.edges.back().masterFace = 0;
  text = networkToJson(d);
  const std::string master = "\"master\": 0";
  ASSERT_TRUE(contains(text, master));
  text.replace(text.find(master), master.size(), "\"master\": 9");
  const InputError face = catchInputError([&] { parseNetworkJson(text, "m.json"); });
  EXPECT_TRUE(contains(face.element(), "edges[0].master")) << face.what();
  EXPECT_TRUE(contains(face.reason(), "face 9 does not exist")) << face.what();
  EXPECT_TRUE(contains(face.reason(), std::to_string(d.faces.size()) + " faces")) << face.what();
}

TEST(LopMessages, BinaryBytesAreNamedNotPrinted) {
  const InputError e = catchInputError([] { parseLop(std::string("\x89PNG\r\n\x1a\n\0\0", 10), "b.lop"); });
  EXPECT_EQ(e.file(), "b.lop");
  EXPECT_TRUE(contains(e.reason(), "byte 0x89")) << e.what();
  for (char c : std::string(e.what())) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << "unprintable byte in the message";
}

} // namespace
} // namespace v1
} // namespace curvenet
