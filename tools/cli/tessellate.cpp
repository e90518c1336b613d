// curvenet tessellate INPUT -o FILE.{obj,ply} [--scheme S] [--masters M] [--curves C] [--strict] [--resolution R] [--threads T]
//                    [--tolerance T [--angle DEG]] [--json]
// and curvenet demo [--out DIR]: the default network's mesh and report.
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>

#include "commands.hpp"
#include "curvenet/bezier.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"
#include "progress.hpp"
#include "report.hpp"

namespace curvenet::cli {

Command addTessellateCommand(CLI::App &app) {
  struct Options {
    std::string input, output, format, scheme = "gregory-g1", masters = "rebuilt", curves = "repaired", controlNets;
    int resolution = 16, threads = 0;
    double tolerance = 0, angle = 0;
    bool quiet = false, strict = false, json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App *sub = app.add_subcommand("tessellate", "Tessellate every face into one watertight mesh");
  sub->add_option("INPUT", o->input, "network file (.json, .lop), - (standard input) or builtin:NAME")->required();
  sub->add_option("-o,--output", o->output,
                  "output mesh (.obj or .ply; - = standard output, with --format); required unless --json");
  sub->add_option("--format", o->format, "mesh format when the output's extension does not say it")
      ->check(CLI::IsMember({"obj", "ply"}));
  sub->add_option("--scheme", o->scheme, schemeChoices())->capture_default_str();
  addMastersOption(sub, o->masters);
  addCurvesOption(sub, o->curves);
  addStrictFlag(sub, o->strict);
  sub->add_option("--control-nets", o->controlNets, "also write the quintic control nets as JSON (bezier-g1, coons-c0)");
  sub->add_option("--resolution", o->resolution, "intervals per segment")
      ->check(wholeNumberIn(1, 4096))
      ->capture_default_str();
  addThreadsOption(sub, o->threads);
  sub->add_option("--tolerance", o->tolerance,
                  "chordal tolerance relative to the diagonal: each face and segment gets its own resolution")
      ->check(numberIn(0.0, 1.0));
  sub->add_option("--angle", o->angle, "with --tolerance: largest angle between an edge's end normals, degrees")
      ->check(numberIn(0.0, 90.0));
  sub->add_flag("--json", o->json, "print the mesh sizes and the measured deviation as one JSON object");
  addQuietFlag(sub, o->quiet);
  return {sub, [o] {
            if (!o->output.empty()) checkMeshOutput(o->output, o->format, "--output");
            const SurfaceOptions options = parseSurfaceOptions(o->scheme, o->masters, o->curves);
            const Scheme scheme = options.scheme;
            if (!o->controlNets.empty() && scheme != Scheme::BezierG1 && scheme != Scheme::CoonsC0)
              throw UsageError("--control-nets", "needs --scheme bezier-g1 or coons-c0");
            if (o->output.empty() && !o->json) throw UsageError("-o/--output", "is required (or give --json)");
            if (o->angle > 0 && !(o->tolerance > 0)) throw UsageError("--angle", "needs --tolerance");
            const Network network = Network::build(loadNetworkArgument(o->input), o->input);
            const Surface surface = buildSurface(network, options, o->input);
            warnAboutFolds(surface);
            noteRepair(surface);
            enforceShape(surface, measureShape(surface), o->strict);
            TessellationOptions tessellation{o->resolution, o->threads};
            tessellation.tolerance = o->tolerance, tessellation.angle = o->angle;
            if (!(o->tolerance > 0))
              refuseIfTooLarge(estimateMeshBytes(estimateMeshVertices(surface, o->resolution), true),
                               "--resolution " + std::to_string(o->resolution));
            TessellationReport report;
            const Mesh mesh = o->tolerance > 0 || o->json ? tessellate(surface, tessellation, report)
                                                          : tessellateShowingProgress(surface, tessellation, "tessellate",
                                                                                      progressWanted(o->quiet));
            // What stopped a tolerance short, on the error stream whatever
            // the output format (the mesh is written: it is the best reached).
            if (!report.angleUnreachableFaces.empty()) {
              std::string list;
              for (int f : report.angleUnreachableFaces) list += (list.empty() ? "" : ", ") + std::to_string(f);
              std::fprintf(stderr,
                           "curvenet: warning: the normal angle does not fall with the resolution on face%s %s "
                           "(normals turning over near a point: a fold, or a corner whose curves leave it in "
                           "nearly the same direction); refined for the tolerance alone there\n",
                           report.angleUnreachableFaces.size() > 1 ? "s" : "", list.c_str());
            }
            if (report.memoryLimited)
              std::fprintf(stderr, "curvenet: warning: refinement stopped at the memory available; measured "
                                   "deviation %.3g (tolerance %g)\n",
                           report.deviation, o->tolerance);
            else if (!report.met)
              std::fprintf(stderr, "curvenet: warning: the tolerance was not met within %d passes; measured "
                                   "deviation %.3g (tolerance %g)\n",
                           report.passes, report.deviation, o->tolerance);
            if (!o->output.empty()) writeMeshArgument(mesh, o->output, o->format);
            if (!o->controlNets.empty()) writeControlNets(surface, o->controlNets);
            if (o->json) {
              nlohmann::json out = {{"input", o->input},
                                    {"scheme", o->scheme},
                                    {"vertices", mesh.positions.size()},
                                    {"triangles", mesh.triangles.size()},
                                    {"deviation", report.deviation},
                                    {"max_normal_angle_deg", report.angle},
                                    {"min_resolution", report.minResolution},
                                    {"max_resolution", report.maxResolution},
                                    {"passes", report.passes},
                                    {"uniform_resolution", report.uniformResolution},
                                    {"uniform_triangles", report.uniformTriangles}};
              if (o->tolerance > 0) {
                out["tolerance"] = o->tolerance;
                out["met"] = report.met;
                out["angle_unreachable_faces"] = report.angleUnreachableFaces;
                out["memory_limited"] = report.memoryLimited;
              }
              if (o->angle > 0) out["angle_deg"] = o->angle;
              if (!o->output.empty()) out["output"] = o->output;
              std::fprintf(o->output == "-" ? stderr : stdout, "%s\n", out.dump(2).c_str());
              return 0;
            }
            if (o->tolerance > 0) {
              std::fprintf(summaryStream(o->output),
                           "%s: %zu vertices, %zu triangles (%s, tolerance %g: face resolutions %d-%d, measured "
                           "deviation %.3g, normal angle %.3g deg; uniform resolution %d would need %zu triangles)\n",
                           o->output.c_str(), mesh.positions.size(), mesh.triangles.size(), o->scheme.c_str(),
                           o->tolerance, report.minResolution, report.maxResolution, report.deviation, report.angle,
                           report.uniformResolution, report.uniformTriangles);
              return 0;
            }
            std::fprintf(summaryStream(o->output), "%s: %zu vertices, %zu triangles (%s, resolution %d)\n", o->output.c_str(),
                        mesh.positions.size(), mesh.triangles.size(), o->scheme.c_str(), o->resolution);
            return 0;
          }};
}

Command addDemoCommand(CLI::App &app) {
  struct Options {
    std::string out = "demo-output";
    bool quiet = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App *sub = app.add_subcommand("demo", "The main job on the built-in default network");
  sub->add_option("--out", o->out, "output folder")->capture_default_str();
  addQuietFlag(sub, o->quiet);
  return {sub, [o] {
            const std::string *out = &o->out;
            const bool showProgress = progressWanted(o->quiet);
            const std::string input = "builtin:" + defaultBuiltinName();
            const Network network = Network::build(builtinNetwork(defaultBuiltinName()), input);
            createOutputFolder(*out);
            nlohmann::json report = networkReport(network, input);
            for (Scheme scheme : availableSchemes()) {
              if (!acceptsAnyLoop(scheme)) continue; // the default network has 5- and 6-sided loops
              const Surface surface = Surface::build(network, {scheme});
              warnAboutFolds(surface);
              nlohmann::json figures;
              addSurfaceReport(figures, surface, 64, 32);
              report["schemes"][schemeName(scheme)] = figures;
              std::printf("%s: max normal angle %.3g deg, max position gap %.3g, reference deviation max %.3g mean %.3g "
                          "(relative to the diagonal)\n",
                          schemeName(scheme).c_str(), figures["continuity"]["max_normal_angle_deg"].get<double>(),
                          figures["continuity"]["max_position_gap"].get<double>(),
                          figures.contains("reference") ? figures["reference"]["max_deviation"].get<double>() : 0.0,
                          figures.contains("reference") ? figures["reference"]["mean_deviation"].get<double>() : 0.0);
              const Mesh mesh = tessellateShowingProgress(surface, {32, 0}, "tessellate " + schemeName(scheme), showProgress);
              const std::string path = *out + "/" + defaultBuiltinName() + "-" + schemeName(scheme) + ".obj";
              writeMeshFile(mesh, path);
              report["meshes"][schemeName(scheme)] = {{"file", path},
                                                       {"vertices", mesh.positions.size()},
                                                       {"triangles", mesh.triangles.size()}};
              std::printf("wrote %s (%zu triangles)\n", path.c_str(), mesh.triangles.size());
            }
            // Pictures: one reflection-line image per scheme in this list (a
            // scheme this build does not know is skipped), and a mean
            // curvature map of the first.
            const std::vector<std::string> pictureSchemes = {"gregory-g1", "gregory-g2"};
            bool curvatureDone = false;
            for (const std::string &name : pictureSchemes) {
              const auto scheme = schemeFromName(name);
              if (!scheme) continue;
              const Surface surface = Surface::build(network, {*scheme});
              std::vector<render::Mode> modes = {render::Mode::Reflection};
              if (!curvatureDone) modes.push_back(render::Mode::Mean), curvatureDone = true;
              for (render::Mode mode : modes) {
                render::RenderOptions options;
                options.width = 640;
                options.height = 480;
                options.mode = mode;
                options.boundaries = true;
                const RenderedPicture picture = renderPicture(surface, options, 32, showProgress);
                const std::string path = *out + "/" + render::modeName(mode) + "-" + name + ".png";
                render::writeImage(picture.image, path);
                report["pictures"].push_back({{"file", path}, {"scheme", name}, {"mode", render::modeName(mode)},
                                              {"value_range", picture.image.valueRange}});
                printPictureLine(path, picture);
              }
            }
            // [OSK11]'s pictures: C⁰ Coons vs G¹ Bézier patches over a
            // network with a T-junction, reflection lines side by side.
            {
              const std::string tName = "hemisphere-tjunction";
              const Network tNetwork = Network::build(builtinNetwork(tName), "builtin:" + tName);
              for (Scheme scheme : {Scheme::CoonsC0, Scheme::BezierG1}) {
                const Surface surface = Surface::build(tNetwork, {scheme});
                render::RenderOptions options;
                options.width = 480;
                options.height = 360;
                options.mode = render::Mode::Reflection;
                options.boundaries = true;
                const RenderedPicture picture = renderPicture(surface, options, 32, showProgress);
                const std::string path = *out + "/reflection-" + tName + "-" + schemeName(scheme) + ".png";
                render::writeImage(picture.image, path);
                report["pictures"].push_back({{"file", path}, {"scheme", schemeName(scheme)}, {"network", tName},
                                              {"mode", "reflection"}});
                printPictureLine(path, picture);
              }
            }
            const std::string reportPath = *out + "/report.json";
            writeFileAtomically(reportPath, [&](std::ostream &s) { s << report.dump(2) << "\n"; });
            std::printf("wrote %s\n", reportPath.c_str());
            return 0;
          }};
}

} // namespace curvenet::cli
