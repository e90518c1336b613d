// curvenet check INPUT [--scheme S] [--json] — network analysis and, once
// patches exist for the scheme, the continuity report.
#include <cstdio>

#include "commands.hpp"
#include "curvenet/io.hpp"
#include "curvenet/network.hpp"
#include "curvenet/surface.hpp"
#include "report.hpp"

namespace curvenet::cli {

Command addCheckCommand(CLI::App &app) {
  struct Options {
    std::string input;
    std::string scheme = "gregory-g1";
    int samples = 64, resolution = 32;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App *sub = app.add_subcommand("check", "Network analysis and continuity report");
  sub->add_option("INPUT", options->input, "network file (.json, .lop) or builtin:NAME")->required();
  sub->add_flag("--json", options->json, "print one JSON object instead of tables");
  sub->add_option("--scheme", options->scheme, "surface scheme whose continuity is measured")
      ->capture_default_str();
  sub->add_option("--samples", options->samples, "points per segment for the continuity figures")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--resolution", options->resolution, "tessellation resolution for the reference deviation")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  return {sub, [options] {
            const Network network = Network::build(loadNetworkInput(options->input), options->input);
            nlohmann::json report = networkReport(network, options->input);
            const Surface surface = Surface::build(network, {parseScheme(options->scheme)});
            addSurfaceReport(report, surface, options->samples, options->resolution);
            if (options->json) std::printf("%s\n", report.dump(2).c_str());
            else printReportTable(report);
            return 0;
          }};
}

} // namespace curvenet::cli
