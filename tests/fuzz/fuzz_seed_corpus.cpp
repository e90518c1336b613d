// Writes the seed corpus of the native-format harness: every built-in
// network, as `curvenet` would save it. Usage: fuzz_seed_corpus DIR
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "curvenet/builtins.hpp"
#include "curvenet/io.hpp"

int main(int argc, char **argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_seed_corpus DIR\n");
    return 2;
  }
  std::filesystem::create_directories(argv[1]);
  for (const curvenet::BuiltinInfo &info : curvenet::builtinNetworks()) {
    std::ofstream(std::filesystem::path(argv[1]) / (info.name + ".json"))
        << curvenet::networkToJson(curvenet::builtinNetwork(info.name));
  }
  return 0;
}
