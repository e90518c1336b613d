// Writes seed corpora: every built-in network into DIR, as `curvenet` would
// save it (the native-format harness), and, given MESH_DIR, the pentagon
// built-in's tessellation as OBJ and OFF (the mesh harness, whose curves are
// the pentagon's). Usage: fuzz_seed_corpus DIR [MESH_DIR]
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "curvenet/builtins.hpp"
#include "curvenet/io.hpp"
#include "curvenet/tessellate.hpp"

int main(int argc, char **argv) {
  if (argc != 2 && argc != 3) {
    std::fprintf(stderr, "usage: fuzz_seed_corpus DIR [MESH_DIR]\n");
    return 2;
  }
  std::filesystem::create_directories(argv[1]);
  for (const curvenet::BuiltinInfo &info : curvenet::builtinNetworks()) {
    std::ofstream(std::filesystem::path(argv[1]) / (info.name + ".json"))
        << curvenet::networkToJson(curvenet::builtinNetwork(info.name));
  }
  if (argc == 3) {
    const std::filesystem::path meshes = argv[2];
    std::filesystem::create_directories(meshes);
    const curvenet::Network network = curvenet::Network::build(curvenet::builtinNetwork("pentagon"));
    for (int resolution : {2, 4}) {
      const curvenet::Mesh mesh = curvenet::tessellate(curvenet::Surface::build(network, {}), {resolution, 1});
      const std::string name = "pentagon-r" + std::to_string(resolution);
      std::ofstream obj(meshes / (name + ".obj"));
      curvenet::writeObj(mesh, obj);
      std::ofstream off(meshes / (name + ".off"));
      off.precision(17);
      off << "OFF\n" << mesh.positions.size() << ' ' << mesh.triangles.size() << " 0\n";
      for (const curvenet::Vec3 &p : mesh.positions) off << p.x << ' ' << p.y << ' ' << p.z << '\n';
      for (const auto &t : mesh.triangles) off << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
      std::ofstream ply(meshes / (name + ".ply"), std::ios::binary);
      curvenet::writePly(mesh, ply);
      std::ofstream stl(meshes / (name + ".stl"));
      stl.precision(17);
      stl << "solid " << name << '\n';
      for (const auto &t : mesh.triangles) {
        stl << "facet normal 0 0 0\nouter loop\n";
        for (std::uint32_t v : t)
          stl << "vertex " << mesh.positions[v].x << ' ' << mesh.positions[v].y << ' ' << mesh.positions[v].z << '\n';
        stl << "endloop\nendfacet\n";
      }
      stl << "endsolid " << name << '\n';
    }
  }
  return 0;
}
