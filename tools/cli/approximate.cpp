// curvenet approximate MESH NETWORK -o FILE [--report FILE.json] — G¹ and G²
// surfaces fitted to a triangle mesh over a curve network drawn on it
// ([SV14] Sec. 5.3, Fig. 10; curvenet/approximation.hpp).
#include <cstdio>
#include <filesystem>
#include <string_view>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "curvenet/approximation.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "curvenet/tessellate.hpp"
#include "progress.hpp"

namespace curvenet::cli {

namespace {

constexpr std::string_view kBuiltin = "builtin:";

nlohmann::json deviationJson(const DeviationFigures &d) {
  return {{"min_signed", d.minSigned}, {"max_signed", d.maxSigned}, {"max_abs", d.maxAbs},
          {"mean_abs", d.meanAbs},     {"samples", d.samples},      {"excluded", d.excluded}};
}

} // namespace

Command addApproximateCommand(CLI::App &app) {
  struct Options {
    std::string mesh, network, output, g1Output, report, writeInputs;
    int resolution = 24, polyline = 32, threads = 0;
    double fitRadius = 0, edge = 0.015;
    bool quiet = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App *sub = app.add_subcommand("approximate", "G1/G2 surfaces fitted to a triangle mesh (Salvi and Varady 2014, Fig. 10)");
  sub->add_option("MESH", o->mesh,
                  "triangle mesh (.obj, .off), or builtin:NAME = that built-in's reference surface triangulated "
                  "(edges of --edge x its diagonal), the analytic form forgotten")
      ->required();
  sub->add_option("NETWORK", o->network,
                  "curve network on the mesh (.json, .lop; degree-1 curves are polylines, fitted by cubic "
                  "B-splines), or builtin:NAME = that built-in's curves as polylines of --polyline intervals")
      ->required();
  sub->add_option("-o,--output", o->output, "the G2 surface's mesh (.obj or .ply)")->required();
  sub->add_option("--g1-output", o->g1Output, "also write the G1 surface's mesh");
  sub->add_option("--report", o->report, "write the figures as JSON");
  sub->add_option("--resolution", o->resolution, "tessellation rows per face (output and deviation)")
      ->check(CLI::Range(2, 1024))
      ->capture_default_str();
  sub->add_option("--fit-radius", o->fitRadius, "quadric-fit radius in mesh units (0 = 3 mean edge lengths)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  sub->add_option("--edge", o->edge, "builtin MESH: edge length relative to the diagonal")
      ->check(CLI::Range(1e-4, 0.5))
      ->capture_default_str();
  sub->add_option("--polyline", o->polyline, "builtin NETWORK: intervals per polyline")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sub->add_option("--write-inputs", o->writeInputs,
                  "write the mesh (.obj) and network (.json) actually used into this folder");
  sub->add_option("--threads", o->threads, "worker threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  addQuietFlag(sub, o->quiet);
  return {sub, [o] {
            Mesh mesh;
            if (o->mesh.starts_with(kBuiltin)) {
              const NetworkDescription source = builtinNetwork(o->mesh.substr(kBuiltin.size()));
              if (!source.reference) throw InputError("", o->mesh, "this built-in has no reference surface");
              const Network net = Network::build(source, o->mesh);
              mesh = triangulateReference(*source.reference, o->edge * net.diagonal(), net.bounds());
            } else {
              mesh = readMeshFile(o->mesh);
            }
            NetworkDescription curves = o->network.starts_with(kBuiltin)
                                            ? polylineNetwork(builtinNetwork(o->network.substr(kBuiltin.size())), o->polyline)
                                            : loadNetworkInput(o->network);
            curves.reference.reset(); // the mesh is the reference
            if (!o->writeInputs.empty()) {
              std::filesystem::create_directories(o->writeInputs);
              const std::string stem = o->writeInputs + "/" + (curves.name.empty() ? "network" : curves.name);
              writeMeshFile(mesh, stem + "-mesh.obj");
              writeFileAtomically(stem + "-curves.json", [&](std::ostream &s) { s << networkToJson(curves); });
              std::printf("wrote %s-mesh.obj and %s-curves.json\n", stem.c_str(), stem.c_str());
            }
            ApproximationOptions options;
            options.resolution = o->resolution;
            options.fitRadius = o->fitRadius;
            options.threads = o->threads;
            const ApproximationResult result = approximateMesh(mesh, curves, options);
            const bool show = progressWanted(o->quiet);
            writeMeshFile(tessellateShowingProgress(result.g2, {o->resolution, o->threads}, "tessellate G2", show), o->output);
            if (!o->g1Output.empty())
              writeMeshFile(tessellateShowingProgress(result.g1, {o->resolution, o->threads}, "tessellate G1", show),
                            o->g1Output);

            std::printf("mesh: %zu vertices, %zu triangles; network: %zu faces, %zu segments; curves within %.2e of "
                        "the mesh\n",
                        mesh.positions.size(), mesh.triangles.size(), result.network.faces().size(),
                        result.network.segments().size(), result.curveDistance);
            std::printf("deviation of the mesh vertices, relative to the bounding-box diagonal (Salvi and Varady 2014, Fig. 10):\n");
            std::printf("  %-28s %11s %11s %11s %11s %14s\n", "surface", "min", "max", "max |d|", "mean |d|",
                        "curv. jump");
            auto row = [](const char *name, const DeviationFigures &d, double jump) {
              std::printf("  %-28s %+10.4f%% %+10.4f%% %10.4f%% %10.4f%% %14.2e\n", name, 100 * d.minSigned,
                          100 * d.maxSigned, 100 * d.maxAbs, 100 * d.meanAbs, jump);
            };
            row("G1 (mesh normals)", result.g1Deviation, result.g1CurvatureJump);
            row("G2 (mesh normals+curvature)", result.g2Deviation, result.g2CurvatureJump);
            const double ratio = result.g2Deviation.maxAbs > 0 ? result.g1Deviation.maxAbs / result.g2Deviation.maxAbs : 0;
            std::printf("  G1/G2 max |d| ratio: %.2f\n", ratio);
            std::printf("wrote %s\n", o->output.c_str());
            if (!o->report.empty()) {
              nlohmann::json report = {
                  {"mesh", {{"input", o->mesh}, {"vertices", mesh.positions.size()}, {"triangles", mesh.triangles.size()}}},
                  {"network",
                   {{"input", o->network},
                    {"faces", result.network.faces().size()},
                    {"segments", result.network.segments().size()},
                    {"curve_distance", result.curveDistance}}},
                  {"diagonal", result.diagonal},
                  {"fit_radius", o->fitRadius},
                  {"resolution", o->resolution},
                  {"g1", {{"scheme", "gregory-g1"}, {"fence_normals", "reference"},
                          {"deviation", deviationJson(result.g1Deviation)},
                          {"max_curvature_jump", result.g1CurvatureJump}}},
                  {"g2", {{"scheme", "gregory-g2"}, {"fence_normals", "reference"}, {"edge_curvature", "reference"},
                          {"deviation", deviationJson(result.g2Deviation)},
                          {"max_curvature_jump", result.g2CurvatureJump}}},
                  {"g1_over_g2_max_deviation", ratio}};
              writeFileAtomically(o->report, [&](std::ostream &s) { s << report.dump(2) << "\n"; });
              std::printf("wrote %s\n", o->report.c_str());
            }
            return 0;
          }};
}

} // namespace curvenet::cli
