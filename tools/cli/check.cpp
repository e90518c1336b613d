// curvenet check INPUT [--scheme S] [--masters M] [--curves C] [--strict] [--json] [--threads T] [--tweak -o FILE] — network
// analysis (vertex enclosure, Euler constraint, curvature fit per vertex),
// optionally the tweaked network, and the continuity and reference figures
// of the surface built with scheme S.
#include <tbb/global_control.h>

#include <cstdio>
#include <filesystem>
#include <optional>

#include "commands.hpp"
#include "progress.hpp"
#include "curvenet/analysis.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "curvenet/network.hpp"
#include "curvenet/surface.hpp"
#include "report.hpp"

namespace curvenet::cli {

namespace {

/// --tweak: repair, write atomically in the native format, re-analyse the result.
void runTweak(const Network &network, const std::string &output, nlohmann::json &report) {
  const TweakResult tweak = tweakNetwork(network);
  writeFileAtomically(output, [&](std::ostream &out) { out << networkToJson(tweak.network); });
  const Network repaired = Network::build(tweak.network, output);
  addTweakReport(report, tweak, analyzeNetwork(repaired), output);
}

} // namespace

nlohmann::json checkReport(const Network &network, const std::string &input, const CheckOptions &options) {
  nlohmann::json report = networkReport(network, input);
  addVertexAnalysis(report, namingInput(input, [&] { return analyzeNetwork(network); }));
  const Surface surface = buildSurface(network, options.surface, input);
  refuseIfTooLarge(estimateReportBytes(surface, options.resolution), "--resolution " + std::to_string(options.resolution));
  warnAboutFolds(surface);
  const ShapeReport shape = measureShape(surface);
  enforceShape(surface, shape, options.strict);
  addSurfaceReport(report, surface, shape, options.samples, options.resolution);
  if (options.surface.scheme == Scheme::BezierG1) {
    // [OSK11]'s comparison: the C⁰ Coons patches of the same network beside the G¹ figures.
    nlohmann::json coons;
    addSurfaceReport(coons, Surface::build(network, {Scheme::CoonsC0}), options.samples, options.resolution);
    report["baseline"] = coons;
  }
  return report;
}

Command addCheckCommand(CLI::App &app) {
  struct Options {
    std::string input;
    std::string scheme = "gregory-g1", masters = "rebuilt", curves = "repaired";
    int samples = 64, resolution = 32, threads = 0;
    bool json = false;
    bool tweak = false, quiet = false, strict = false;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  CLI::App *sub = app.add_subcommand("check", "Network analysis and continuity report");
  sub->add_option("INPUT", options->input, "network file (.json, .lop), - (standard input) or builtin:NAME")->required();
  sub->add_flag("--json", options->json, "print one JSON object instead of tables");
  sub->add_option("--scheme", options->scheme, "surface scheme whose continuity is measured: " + schemeChoices())
      ->capture_default_str();
  addMastersOption(sub, options->masters);
  addCurvesOption(sub, options->curves);
  addStrictFlag(sub, options->strict);
  sub->add_option("--samples", options->samples, "points per segment for the continuity figures")
      ->check(wholeNumberIn(1, 100000))
      ->capture_default_str();
  sub->add_option("--resolution", options->resolution, "tessellation resolution for the reference deviation")
      ->check(wholeNumberIn(1, 4096))
      ->capture_default_str();
  addThreadsOption(sub, options->threads);
  CLI::Option *tweak = sub->add_flag("--tweak", options->tweak,
                                     "repair the curvatures at vertices that fail the Euler constraint "
                                     "(moves one control point per curve end along the vertex normal)");
  CLI::Option *output = sub->add_option("-o,--output", options->output, "where --tweak writes the repaired network (.json)");
  tweak->needs(output);
  output->needs(tweak);
  addQuietFlag(sub, options->quiet); // accepted everywhere; check shows no progress line
  return {sub, [options] {
            // Every parallel stage of the report (continuity, curvature,
            // tessellation, reference deviation) runs under this limit; the
            // figures do not depend on it.
            std::optional<tbb::global_control> limit;
            if (options->threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, options->threads);
            const SurfaceOptions surfaceOptions =
                parseSurfaceOptions(options->scheme, options->masters, options->curves);
            if (options->tweak && std::filesystem::path(options->output).extension() != ".json")
              throw InputError(options->output, "-o", "the repaired network is written in the native format: "
                                                      "give a .json file");
            const Network network = Network::build(loadNetworkArgument(options->input), options->input);
            // The surface first: --strict refuses before --tweak writes its file.
            nlohmann::json report = checkReport(
                network, options->input, {surfaceOptions, options->samples, options->resolution, options->strict});
            if (options->tweak) runTweak(network, options->output, report);
            if (options->json) std::printf("%s\n", report.dump(2).c_str());
            else printReportTable(report);
            return 0;
          }};
}

} // namespace curvenet::cli
