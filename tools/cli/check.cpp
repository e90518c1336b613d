// curvenet check INPUT [--scheme S] [--json] — network analysis and, once
// patches exist for the scheme, the continuity report.
#include <cstdio>

#include "commands.hpp"
#include "curvenet/io.hpp"
#include "curvenet/network.hpp"
#include "report.hpp"

namespace curvenet::cli {

Command addCheckCommand(CLI::App &app) {
  struct Options {
    std::string input;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App *sub = app.add_subcommand("check", "Network analysis and continuity report");
  sub->add_option("INPUT", options->input, "network file (.json, .lop) or builtin:NAME")->required();
  sub->add_flag("--json", options->json, "print one JSON object instead of tables");
  return {sub, [options] {
            const Network network = Network::build(loadNetworkInput(options->input), options->input);
            nlohmann::json report = networkReport(network, options->input);
            if (options->json) std::printf("%s\n", report.dump(2).c_str());
            else printReportTable(report);
            return 0;
          }};
}

} // namespace curvenet::cli
