// curvenet list — the built-in networks with their face counts by side number.
#include <cstdio>
#include <map>
#include <memory>

#include "commands.hpp"
#include "progress.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/network.hpp"

namespace curvenet::cli {

Command addListCommand(CLI::App &app) {
  CLI::App *sub = app.add_subcommand("list", "The built-in networks (use as builtin:NAME)");
  auto quiet = std::make_shared<bool>(false);
  addQuietFlag(sub, *quiet); // accepted everywhere; list shows no progress line
  return {sub, [quiet] {
            std::printf("%-34s %-7s %s\n", "name", "faces", "sides: faces");
            for (const BuiltinInfo &info : builtinNetworks()) {
              const Network network = Network::build(builtinNetwork(info.name));
              std::map<int, int> bySides;
              for (const Face &face : network.faces()) ++bySides[face.sideCount()];
              std::string counts;
              for (auto [sides, count] : bySides)
                counts += (counts.empty() ? "" : ", ") + std::to_string(sides) + ": " + std::to_string(count);
              std::printf("%-34s %-7zu %s\n", ("builtin:" + info.name).c_str(), network.faces().size(),
                          counts.c_str());
              std::printf("    %s\n", info.summary.c_str());
            }
            std::printf("default (curvenet demo): builtin:%s\n", defaultBuiltinName().c_str());
            return 0;
          }};
}

} // namespace curvenet::cli
