// Builds a network from a built-in through the installed headers and checks
// that the topology came through: the pentagon is one 5-sided face.
#include <curvenet/builtins.hpp>
#include <curvenet/network.hpp>

#include <cstdio>

int main() {
  curvenet::Network network = curvenet::Network::build(curvenet::builtinNetwork("pentagon"));
  if (network.faces().size() != 1 || network.faces()[0].sideCount() != 5) {
    std::fprintf(stderr, "unexpected topology\n");
    return 1;
  }
  std::printf("pentagon: %zu vertices, %zu segments\n", network.vertices().size(), network.segments().size());
  return 0;
}
