#include <cstdio>

#include "commands.hpp"

namespace curvenet::cli {

Command addPendingCommand(CLI::App &app, const std::string &name, const std::string &summary,
                          const std::string &missing) {
  CLI::App *sub = app.add_subcommand(name, summary + " [not available yet]");
  sub->allow_extras();
  return {sub, [name, missing] {
            std::fprintf(stderr, "curvenet %s: not available yet: %s is not part of this build\n", name.c_str(),
                         missing.c_str());
            return 2;
          }};
}

} // namespace curvenet::cli
