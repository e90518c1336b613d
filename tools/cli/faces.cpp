// curvenet faces INPUT -o NET.json [--weld W] [--fit-tolerance F] [--json]:
// a sketch or curve graph becomes a network in the native format, with a
// summary of what was found (curvenet/sketch.hpp).
#include <cstdio>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "curvenet/sketch.hpp"

namespace curvenet::cli {
namespace {

CurveGraph readCurveGraphInput(const std::string &input) {
  const std::string ext = std::filesystem::path(input).extension().string();
  if (ext == ".obj" || ext == ".OBJ") return readCurveGraphFile(input);
  // A network file: its curves are the strokes (its faces, if any, are found afresh).
  CurveGraph graph = curveGraphFromCurves(loadNetworkInput(input));
  if (graph.name.empty()) graph.name = std::filesystem::path(input).stem().string();
  return graph;
}

template <typename Map> nlohmann::json countsByKey(const Map &map) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto &[key, count] : map) out[std::to_string(key)] = count;
  return out;
}

nlohmann::json summaryJson(const SketchResult &r, const SketchOptions &options) {
  nlohmann::json s;
  s["weld_relative"] = options.weld;
  s["weld_distance"] = r.weldDistance;
  s["fit_tolerance_relative"] = options.fitTolerance;
  s["nodes_by_valence"] = countsByKey(r.nodesByValence);
  nlohmann::json kinds = nlohmann::json::object();
  for (const SketchNode &n : r.nodes) kinds[toString(n.kind)] = kinds.value(toString(n.kind), 0) + 1;
  s["nodes_by_kind"] = kinds;
  s["nodes"] = nlohmann::json::array();
  for (const SketchNode &n : r.nodes)
    s["nodes"].push_back({{"position", {n.position.x, n.position.y, n.position.z}}, {"valence", n.valence},
                          {"kind", toString(n.kind)}, {"tangent_plane_enforced", n.planeEnforced},
                          {"crease", n.crease}});
  s["curves"] = nlohmann::json::array();
  double worst = 0;
  for (const SketchCurve &c : r.curves) {
    s["curves"].push_back({{"points", c.pointCount}, {"control_points", c.controlPoints}, {"max_error", c.maxError},
                           {"closed", c.closed}});
    worst = std::max(worst, c.maxError);
  }
  s["max_fit_error"] = worst;
  s["faces"] = r.description.faces.size();
  s["faces_by_sides"] = countsByKey(r.facesBySides);
  int creases = 0;
  for (const SketchNode &n : r.nodes) creases += n.crease ? 1 : 0;
  s["crease_nodes"] = creases;
  s["g1_edges"] = r.g1Edges;
  s["crease_edges"] = r.creaseEdges;
  s["dangling"] = r.dangling;
  s["open_loops"] = r.openLoops;
  s["not_discs"] = r.notDiscs;
  s["refused_faces"] = r.refusedFaces;
  s["edges"] = r.edges;
  s["faced_nodes"] = r.facedNodes;
  s["euler_characteristic"] = r.eulerCharacteristic;
  return s;
}

void printSummary(const SketchResult &r, const SketchOptions &options, const std::string &output) {
  std::printf("weld distance %.3g (%.3g of the diagonal %.4g)\n", r.weldDistance, options.weld, r.diagonal);
  std::printf("nodes by valence:");
  for (const auto &[valence, count] : r.nodesByValence) std::printf(" %d x %d", count, valence);
  std::printf("\n");
  double worst = 0;
  for (const SketchCurve &c : r.curves) worst = std::max(worst, c.maxError);
  std::printf("curves: %zu, largest fit error %.3g of the diagonal (tolerance %.3g)\n", r.curves.size(), worst,
              options.fitTolerance);
  std::printf("faces: %zu by sides:", r.description.faces.size());
  for (const auto &[sides, count] : r.facesBySides) std::printf(" %d x %d", count, sides);
  std::printf("\n");
  int creases = 0;
  for (const SketchNode &n : r.nodes) creases += n.crease ? 1 : 0;
  std::printf("crease nodes: %d (no tangent plane: each face corner keeps its own)\n", creases);
  std::printf("edges between faces: %d G1, %zu creases (sharp)\n", r.g1Edges, r.creaseEdges.size());
  for (const std::string &c : r.creaseEdges) std::printf("crease: %s\n", c.c_str());
  for (const std::string &d : r.dangling) std::printf("dangling: %s\n", d.c_str());
  for (const std::string &l : r.openLoops) std::printf("left open: %s\n", l.c_str());
  for (const std::string &l : r.notDiscs) std::printf("not a disc: %s\n", l.c_str());
  for (const std::string &f : r.refusedFaces) std::printf("refused: %s\n", f.c_str());
  std::printf("Euler characteristic %d (%d nodes, %d edges, %zu loops)\n", r.eulerCharacteristic, r.facedNodes, r.edges,
              r.description.faces.size() + r.openLoops.size() + r.refusedFaces.size() + r.notDiscs.size());
  std::printf("wrote %s\n", output.c_str());
}

} // namespace

Command addFacesCommand(CLI::App &app) {
  struct Options {
    std::string input, output;
    SketchOptions sketch;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App *sub = app.add_subcommand("faces", "Find the network of a sketch or curve graph (nodes, curves, faces)");
  sub->add_option("INPUT", o->input, "curve graph (.obj with l elements) or network file whose curves are strokes")
      ->required();
  sub->add_option("-o,--output", o->output, "the network found (.json, the native format)")->required();
  sub->add_option("--weld", o->sketch.weld, "weld distance relative to the diagonal")->check(CLI::Range(0.0, 0.099));
  sub->add_option("--fit-tolerance", o->sketch.fitTolerance, "curve fit tolerance relative to the diagonal")
      ->check(CLI::Range(1e-9, 0.1));
  sub->add_flag("--json", o->json, "print the summary as one JSON object");
  return {sub, [o] {
            const SketchResult result = networkFromCurveGraph(readCurveGraphInput(o->input), o->sketch, o->input);
            if (result.description.faces.empty())
              throw InputError(o->input, {}, "no faces found (every stroke is dangling or every loop open)");
            const std::string text = networkToJson(result.description);
            writeFileAtomically(o->output, [&](std::ostream &out) { out << text; });
            if (o->json) std::printf("%s\n", summaryJson(result, o->sketch).dump(2).c_str());
            else printSummary(result, o->sketch, o->output);
            return 0;
          }};
}

} // namespace curvenet::cli
