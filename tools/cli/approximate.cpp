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

/// Memory of the work: the two fitted surfaces tessellated at `resolution`
/// for the deviation figures and the output (as text), beside the mesh.
double estimateApproximationBytes(const Mesh &mesh, const NetworkDescription &curves, int resolution) {
  const Surface layout = Surface::build(Network::build(fitPolylineCurves(curves)), {Scheme::GregoryG1});
  const double meshBytes = static_cast<double>(mesh.positions.size()) * 48 + static_cast<double>(mesh.triangles.size()) * 12;
  return 3 * estimateMeshBytes(estimateMeshVertices(layout, resolution), true) + 4 * meshBytes;
}

/// A deviation measured on no mesh vertex means nothing (0 %): refused, naming both inputs.
void refuseEmptyDeviation(const ApproximationResult &result, const std::string &mesh, const std::string &network) {
  if (result.g1Deviation.samples > 0 && result.g2Deviation.samples > 0) return;
  throw InputError(mesh, {},
                   "no mesh vertex lies over the surfaces fitted to " + network + " (0 samples; " +
                       std::to_string(result.g2Deviation.excluded) +
                       " left out as beyond their boundary or facing away): are the curves drawn on this mesh?");
}

/// The curves are meant to lie on the mesh; further than this fraction of the
/// diagonal, the figures compare surfaces with a mesh they do not approximate.
constexpr double kCurvesApart = 0.01;

void warnIfApart(const ApproximationResult &result, const std::string &network) {
  if (result.curveDistance > kCurvesApart)
    std::fprintf(stderr,
                 "curvenet: warning: %s: the curves lie up to %.3g%% of the diagonal away from the mesh (more than "
                 "%.3g%%); the deviation figures then say little about the fit\n",
                 network.c_str(), 100 * result.curveDistance, 100 * kCurvesApart);
}

nlohmann::json deviationJson(const DeviationFigures &d) {
  return {{"min_signed", d.minSigned}, {"max_signed", d.maxSigned}, {"max_abs", d.maxAbs},
          {"mean_abs", d.meanAbs},     {"samples", d.samples},      {"excluded", d.excluded}};
}

} // namespace

Command addApproximateCommand(CLI::App &app) {
  struct Options {
    std::string mesh, network, output, format, g1Output, report, writeInputs;
    int resolution = 24, polyline = 32, threads = 0;
    double fitRadius = 0, edge = 0.015;
    bool quiet = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App *sub = app.add_subcommand("approximate", "G1/G2 surfaces fitted to a triangle mesh (Salvi and Varady 2014, Fig. 10)");
  sub->add_option("MESH", o->mesh,
                  "triangle mesh (.obj, .off, .ply, .stl; - = standard input), or builtin:NAME = that built-in's reference surface triangulated "
                  "(edges of --edge x its diagonal), the analytic form forgotten")
      ->required();
  sub->add_option("NETWORK", o->network,
                  "curve network on the mesh (.json, .lop; degree-1 curves are polylines, fitted by cubic "
                  "B-splines), or builtin:NAME = that built-in's curves as polylines of --polyline intervals")
      ->required();
  sub->add_option("-o,--output", o->output, "the G2 surface's mesh (.obj or .ply; - = standard output, with --format)")
      ->required();
  sub->add_option("--format", o->format, "mesh format when the output's extension does not say it")
      ->check(CLI::IsMember({"obj", "ply"}));
  sub->add_option("--g1-output", o->g1Output, "also write the G1 surface's mesh");
  sub->add_option("--report", o->report, "write the figures as JSON");
  sub->add_option("--resolution", o->resolution, "tessellation rows per face (output and deviation)")
      ->check(wholeNumberIn(2, 1024))
      ->capture_default_str();
  sub->add_option("--fit-radius", o->fitRadius, "quadric-fit radius in mesh units (0 = 3 mean edge lengths)")
      ->check(numberIn(0, 1e300))
      ->capture_default_str();
  sub->add_option("--edge", o->edge, "builtin MESH: edge length relative to the diagonal")
      ->check(numberIn(1e-4, 0.5))
      ->capture_default_str();
  sub->add_option("--polyline", o->polyline, "builtin NETWORK: intervals per polyline")
      ->check(wholeNumberIn(1, 100000))
      ->capture_default_str();
  sub->add_option("--write-inputs", o->writeInputs,
                  "write the mesh (.obj) and network (.json) actually used into this folder");
  addThreadsOption(sub, o->threads);
  addQuietFlag(sub, o->quiet);
  return {sub, [o] {
            checkMeshOutput(o->output, o->format, "--output");
            if (!o->g1Output.empty()) checkMeshOutput(o->g1Output, {}, "--g1-output");
            if (isStandardStream(o->mesh) && isStandardStream(o->network))
              throw InputError("-", {}, "MESH and NETWORK cannot both come from standard input");
            Mesh mesh;
            if (o->mesh.starts_with(kBuiltin)) {
              const NetworkDescription source = builtinNetwork(o->mesh.substr(kBuiltin.size()));
              if (!source.reference) throw InputError("", o->mesh, "this built-in has no reference surface");
              const Network net = Network::build(source, o->mesh);
              mesh = triangulateReference(*source.reference, o->edge * net.diagonal(), net.bounds());
            } else {
              mesh = readMeshArgument(o->mesh);
            }
            NetworkDescription curves = o->network.starts_with(kBuiltin)
                                            ? polylineNetwork(builtinNetwork(o->network.substr(kBuiltin.size())), o->polyline)
                                            : loadNetworkArgument(o->network);
            curves.reference.reset(); // the mesh is the reference
            if (!o->writeInputs.empty()) {
              createOutputFolder(o->writeInputs);
              const std::string stem = o->writeInputs + "/" + (curves.name.empty() ? "network" : curves.name);
              writeMeshFile(mesh, stem + "-mesh.obj");
              writeFileAtomically(stem + "-curves.json", [&](std::ostream &s) { s << networkToJson(curves); });
              std::fprintf(summaryStream(o->output), "wrote %s-mesh.obj and %s-curves.json\n", stem.c_str(), stem.c_str());
            }
            refuseIfTooLarge(estimateApproximationBytes(mesh, curves, o->resolution),
                             "--resolution " + std::to_string(o->resolution));
            ApproximationOptions options;
            options.resolution = o->resolution;
            options.fitRadius = o->fitRadius;
            options.threads = o->threads;
            const ApproximationResult result = approximateMesh(mesh, curves, options);
            refuseEmptyDeviation(result, o->mesh, o->network);
            warnIfApart(result, o->network);
            const bool show = progressWanted(o->quiet);
            writeMeshArgument(tessellateShowingProgress(result.g2, {o->resolution, o->threads}, "tessellate G2", show),
                              o->output, o->format);
            // With the mesh on standard output, the figures go to standard error.
            std::FILE *const summary = summaryStream(o->output);
            if (!o->g1Output.empty())
              writeMeshFile(tessellateShowingProgress(result.g1, {o->resolution, o->threads}, "tessellate G1", show),
                            o->g1Output);

            std::fprintf(summary, "mesh: %zu vertices, %zu triangles; network: %zu faces, %zu segments; curves within %.2e of "
                        "the mesh\n",
                        mesh.positions.size(), mesh.triangles.size(), result.network.faces().size(),
                        result.network.segments().size(), result.curveDistance);
            std::fprintf(summary, "deviation of the mesh vertices, relative to the bounding-box diagonal (Salvi and Varady 2014, Fig. 10):\n");
            std::fprintf(summary, "  %-28s %11s %11s %11s %11s %14s\n", "surface", "min", "max", "max |d|", "mean |d|",
                        "curv. jump");
            auto row = [summary](const char *name, const DeviationFigures &d, double jump) {
              std::fprintf(summary, "  %-28s %+10.4f%% %+10.4f%% %10.4f%% %10.4f%% %14.2e\n", name, 100 * d.minSigned,
                          100 * d.maxSigned, 100 * d.maxAbs, 100 * d.meanAbs, jump);
            };
            row("G1 (mesh normals)", result.g1Deviation, result.g1CurvatureJump);
            row("G2 (mesh normals+curvature)", result.g2Deviation, result.g2CurvatureJump);
            const double ratio = result.g2Deviation.maxAbs > 0 ? result.g1Deviation.maxAbs / result.g2Deviation.maxAbs : 0;
            std::fprintf(summary, "  G1/G2 max |d| ratio: %.2f\n", ratio);
            std::fprintf(summary, "wrote %s\n", o->output.c_str());
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
              std::fprintf(summary, "wrote %s\n", o->report.c_str());
            }
            return 0;
          }};
}

} // namespace curvenet::cli
