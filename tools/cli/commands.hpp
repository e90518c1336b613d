// The subcommands of the curvenet program (DESIGN.md §6). Each registers its
// options on the CLI11 app and returns the process exit code when run.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

#include "curvenet/surface.hpp"

namespace curvenet::cli {

/// A registered subcommand and what it does after parsing (returns the exit code).
struct Command {
  CLI::App *app = nullptr;
  std::function<int()> run;
};

Command addListCommand(CLI::App &app);
Command addCheckCommand(CLI::App &app);
Command addTessellateCommand(CLI::App &app);
Command addDemoCommand(CLI::App &app);
/// The scheme named on the command line; InputError listing the available ones otherwise.
Scheme parseScheme(const std::string &name);

/// Commands whose engine part is not built yet: they say so and exit 2.
Command addPendingCommand(CLI::App &app, const std::string &name, const std::string &summary,
                          const std::string &missing);

} // namespace curvenet::cli
