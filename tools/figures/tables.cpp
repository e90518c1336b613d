#include "tables.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>

#include "curvenet/approximation.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/continuity.hpp"
#include "curvenet/curvature_jump.hpp"
#include "curvenet/io.hpp"
#include "curvenet/master_contact.hpp"
#include "curvenet/network.hpp"
#include "curvenet/surface.hpp"

namespace curvenet::figures {

namespace {

// `curvenet check` defaults: 64 samples per segment, resolution 32.
constexpr int kCheckSamples = 64;
constexpr int kCheckResolution = 32;

std::string format(const char *pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}
std::string sci(double value) { return format("%.1e", value); }
std::string percent(double fraction) { return format("%.2f %%", 100 * fraction); }
std::string signedPercent(double fraction) { return format("%+.4f %%", 100 * fraction); }
std::string code(const std::string &text) { return "`" + text + "`"; }

std::string row(const std::vector<std::string> &cells) {
  std::string line = "|";
  for (const std::string &cell : cells) line += " " + cell + " |";
  return line;
}
std::string header(const std::vector<std::string> &cells) {
  return row(cells) + "\n" + row(std::vector<std::string>(cells.size(), "---"));
}

std::string foldedList(const Surface &surface) {
  if (surface.foldedFaces().empty()) return "none";
  std::string list;
  for (int face : surface.foldedFaces()) list += (list.empty() ? "" : ", ") + std::to_string(face);
  return list;
}

Network builtin(const std::string &name) { return Network::build(builtinNetwork(name), "builtin:" + name); }

/// What `curvenet check NETWORK --scheme S --json` reports under "continuity"
/// and "reference".
struct CheckFigures {
  ContinuityReport continuity;
  CurvatureJumpReport jump;
  std::optional<ReferenceDeviation> reference;
  std::vector<int> folded;
};

CheckFigures checkFigures(const Surface &surface) {
  return {measureContinuity(surface, {kCheckSamples}), measureCurvatureJump(surface),
          measureReferenceDeviation(surface, kCheckResolution), surface.foldedFaces()};
}

/// The check figures of built-in surfaces, each measured once.
class AnalyticFigures {
public:
  const CheckFigures &of(const std::string &network, Scheme scheme) {
    auto [it, inserted] = measured_.try_emplace({network, scheme});
    if (inserted) it->second = checkFigures(Surface::build(builtin(network), {scheme}));
    return it->second;
  }

private:
  std::map<std::pair<std::string, Scheme>, CheckFigures> measured_;
};

const std::vector<std::string> kAnalyticBuiltins = {"pentagon", "sphere-dodecahedron",
                                                    "ellipsoid-truncated-icosahedron", "torus-mixed",
                                                    "saddle-nodes"};
const std::vector<Scheme> kTransfiniteSchemes = {Scheme::GregoryG1, Scheme::CompositeRibbon, Scheme::GregoryG2};

std::vector<std::string> builtinsTable() {
  std::vector<std::string> lines = {header({"network", "faces", "sides: faces", "what it is"})};
  for (const BuiltinInfo &info : builtinNetworks()) {
    const Network network = builtin(info.name);
    std::map<int, int> bySides;
    for (const Face &face : network.faces()) ++bySides[face.sideCount()];
    std::string counts;
    for (auto [sides, count] : bySides)
      counts += (counts.empty() ? "" : ", ") + std::to_string(sides) + ": " + std::to_string(count);
    lines.push_back(row({code(info.name), std::to_string(network.faces().size()), counts, info.summary}));
  }
  return lines;
}

std::vector<std::string> continuityTable(AnalyticFigures &figures) {
  std::vector<std::string> lines = {header({"network", "scheme", "position gap", "max normal angle (°)",
                                            "max curvature jump", "boundary", "reference max", "reference mean",
                                            "folded faces"})};
  for (const std::string &network : kAnalyticBuiltins)
    for (Scheme scheme : kTransfiniteSchemes) {
      const CheckFigures &f = figures.of(network, scheme);
      const bool shared = f.continuity.sharedSegments > 0;
      lines.push_back(row({code(network), code(schemeName(scheme)), sci(f.continuity.maxPositionGap),
                           sci(f.continuity.maxNormalAngleDeg), shared ? sci(f.jump.maxJump) : "—",
                           sci(f.continuity.maxBoundaryDeviation), percent(f.reference->maxDeviation),
                           percent(f.reference->meanDeviation), format("%.0f", double(f.folded.size()))}));
    }
  return lines;
}

std::vector<std::string> bezierTable() {
  std::vector<std::string> lines = {header({"network", "bezier-g1 max / mean (°)", "coons-c0 max / mean (°)"})};
  for (const std::string name : {"hemisphere-tjunction", "tjunction-surrounded", "tjunction-vertex", "hull-like"}) {
    const Network network = builtin(name);
    const ContinuityReport g1 = measureContinuity(Surface::build(network, {Scheme::BezierG1}), {kCheckSamples});
    const ContinuityReport c0 = measureContinuity(Surface::build(network, {Scheme::CoonsC0}), {kCheckSamples});
    lines.push_back(row({code(name), sci(g1.maxNormalAngleDeg) + " / " + sci(g1.meanNormalAngleDeg),
                         format("%.2f", c0.maxNormalAngleDeg) + " / " + format("%.2f", c0.meanNormalAngleDeg)}));
  }
  return lines;
}

std::vector<std::string> mastersTable() {
  const Network network = builtin("setback-vertex-blend");
  std::vector<std::string> columns = {"`curvenet check builtin:setback-vertex-blend`"};
  std::vector<int> masterFaces;
  for (const Segment &segment : network.segments())
    if (segment.masterFace >= 0 && std::find(masterFaces.begin(), masterFaces.end(), segment.masterFace) == masterFaces.end())
      masterFaces.push_back(segment.masterFace);
  std::sort(masterFaces.begin(), masterFaces.end());
  for (int face : masterFaces) columns.push_back("max jump to " + network.faces()[size_t(face)].name);
  columns.insert(columns.end(), {"max normal angle (°)", "folded faces"});
  std::vector<std::string> lines = {header(columns)};
  struct Variant {
    std::string label;
    SurfaceOptions options;
  };
  const std::vector<Variant> variants = {
      {"`--scheme gregory-g2`", {Scheme::GregoryG2}},
      {"`--scheme gregory-g2 --masters kept-g1`", [] {
         SurfaceOptions kept{Scheme::GregoryG2};
         kept.masterFaces = MasterFaces::KeptG1;
         return kept;
       }()},
      {"`--scheme gregory-g1`", {Scheme::GregoryG1}},
      {"`--scheme composite-ribbon`", {Scheme::CompositeRibbon}}};
  for (const Variant &variant : variants) {
    const Surface surface = Surface::build(network, variant.options);
    const CurvatureJumpReport jump = measureCurvatureJump(surface);
    std::map<int, double> worstByMaster;
    for (const MasterEdgeJump &edge : masterEdgeJumps(surface, jump))
      worstByMaster[edge.masterFace] = std::max(worstByMaster[edge.masterFace], edge.maxJump);
    std::vector<std::string> cells = {variant.label};
    for (int face : masterFaces) cells.push_back(sci(worstByMaster[face]));
    cells.push_back(sci(measureContinuity(surface, {kCheckSamples}).maxNormalAngleDeg));
    cells.push_back(foldedList(surface));
    lines.push_back(row(cells));
  }
  return lines;
}

/// setback-external-masters: each scheme's faces against the NURBS master
/// surfaces their edges name (what `curvenet check` lists as master_surfaces).
std::vector<std::string> externalMastersTable() {
  const Network network = builtin("setback-external-masters");
  std::vector<std::string> lines = {header({"`curvenet check builtin:setback-external-masters`",
                                            "max normal angle to the masters (°)", "max curvature jump to the masters",
                                            "max distance", "folded faces"})};
  for (Scheme scheme : kTransfiniteSchemes) {
    const Surface surface = Surface::build(network, {scheme});
    double angle = 0, jump = 0, distance = 0;
    for (const MasterSurfaceContact &c : measureMasterSurfaceContact(surface)) {
      angle = std::max(angle, c.maxNormalAngleDeg);
      jump = std::max(jump, c.maxCurvatureJump);
      distance = std::max(distance, c.maxDistance);
    }
    lines.push_back(row({code("--scheme " + schemeName(scheme)), sci(angle), sci(jump), sci(distance),
                         foldedList(surface)}));
  }
  return lines;
}

std::vector<std::string> connectionCurvesTable() {
  std::vector<std::string> lines = {header({"network", "patches", "hidden seams", "seam jump gregory-g1",
                                            "seam jump gregory-g2", "folded faces (g1 / g2)"})};
  for (const std::string name : {"concave-L", "ring", "uneven-loop", "many-sided"}) {
    const Network network = builtin(name);
    std::vector<int> seams;
    for (size_t e = 0; e < network.segments().size(); ++e)
      if (network.segments()[e].connection && !network.segments()[e].isBoundary()) seams.push_back(int(e));
    auto seamJump = [&](const Surface &surface) {
      double worst = 0;
      for (const CurvatureJumpSample &sample : measureCurvatureJump(surface).samples)
        if (std::find(seams.begin(), seams.end(), sample.segment) != seams.end()) worst = std::max(worst, sample.jump);
      return worst;
    };
    const Surface g1 = Surface::build(network, {Scheme::GregoryG1});
    const Surface g2 = Surface::build(network, {Scheme::GregoryG2});
    lines.push_back(row({code(name), std::to_string(network.faces().size()), std::to_string(seams.size()),
                         sci(seamJump(g1)), sci(seamJump(g2)), foldedList(g1) + " / " + foldedList(g2)}));
  }
  return lines;
}

/// `curvenet approximate builtin:NAME builtin:NAME`: the built-in's surface
/// triangulated with edges of 1.5% of the diagonal, its curves as polylines
/// of 32 intervals (the command's defaults).
std::vector<std::string> approximationTable() {
  constexpr double kEdge = 0.015;
  constexpr int kPolylineIntervals = 32;
  std::vector<std::string> lines = {header({"mesh and network", "surface", "min", "max", "max |d|", "mean |d|",
                                            "max curvature jump", "G1/G2 max |d|"})};
  for (const std::string name : {"ellipsoid-truncated-icosahedron", "torus-mixed"}) {
    const NetworkDescription source = builtinNetwork(name);
    const Network network = Network::build(source, "builtin:" + name);
    const Mesh mesh = triangulateReference(*source.reference, kEdge * network.diagonal(), network.bounds());
    NetworkDescription curves = polylineNetwork(source, kPolylineIntervals);
    curves.reference.reset();
    const ApproximationResult result = approximateMesh(mesh, curves);
    const std::string ratio = format("%.2f", result.g1Deviation.maxAbs / result.g2Deviation.maxAbs);
    auto figures = [&](const std::string &surface, const DeviationFigures &d, double jump) {
      lines.push_back(row({code(name), surface, signedPercent(d.minSigned), signedPercent(d.maxSigned),
                           percent(d.maxAbs), percent(d.meanAbs), sci(jump), ratio}));
    };
    figures("G1 (mesh normals)", result.g1Deviation, result.g1CurvatureJump);
    figures("G2 (mesh normals + curvature)", result.g2Deviation, result.g2CurvatureJump);
  }
  return lines;
}

std::vector<std::string> edgeCurvatureTable() {
  const Network network = builtin(defaultBuiltinName());
  std::vector<std::string> lines = {header({"source", "reference max", "reference mean", "folded faces"})};
  struct Source {
    std::string label;
    Scheme scheme;
    EdgeCurvature curvature;
  };
  for (const Source &source : std::vector<Source>{
           {"`gregory-g1` (for comparison)", Scheme::GregoryG1, EdgeCurvature::Direct},
           {"(b) `averaging` (samples the G¹ patches)", Scheme::GregoryG2, EdgeCurvature::Averaging},
           {"(c) `direct` (vertex tensors blended)", Scheme::GregoryG2, EdgeCurvature::Direct},
           {"(d) `reference` (analytic curvature)", Scheme::GregoryG2, EdgeCurvature::Reference}}) {
    SurfaceOptions options{source.scheme};
    options.edgeCurvature = source.curvature;
    const Surface surface = Surface::build(network, options);
    const ReferenceDeviation deviation = *measureReferenceDeviation(surface, kCheckResolution);
    lines.push_back(row({source.label, percent(deviation.maxDeviation), percent(deviation.meanDeviation),
                         foldedList(surface)}));
  }
  return lines;
}

/// The JSON example of docs/network-format.md, as the document shows it.
NetworkDescription formatExample(const std::filesystem::path &repository) {
  const std::filesystem::path path = repository / "docs" / "network-format.md";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::stringstream text;
  text << in.rdbuf();
  const std::string document = text.str();
  const size_t start = document.find("```json\n");
  if (start == std::string::npos) throw std::runtime_error(path.string() + ": no ```json example");
  const size_t body = start + 8, end = document.find("```", body);
  return parseNetworkJson(document.substr(body, end - body), path.string());
}

std::vector<std::string> formatExampleTable(const std::filesystem::path &repository) {
  const Network network = Network::build(formatExample(repository), "docs/network-format.md");
  std::vector<std::string> lines = {
      header({"`curvenet check example.json --scheme S`", "reference max", "reference mean", "folded faces"})};
  for (Scheme scheme : kTransfiniteSchemes) {
    const Surface surface = Surface::build(network, {scheme});
    const ReferenceDeviation deviation = *measureReferenceDeviation(surface, kCheckResolution);
    lines.push_back(row({code(schemeName(scheme)), percent(deviation.maxDeviation), percent(deviation.meanDeviation),
                         foldedList(surface)}));
  }
  return lines;
}

/// The deterministic rows of README's headline table, keyed by their first cell.
std::vector<std::string> headlineRows(AnalyticFigures &figures) {
  const std::string network = defaultBuiltinName();
  const CheckFigures &g1 = figures.of(network, Scheme::GregoryG1);
  const CheckFigures &g2 = figures.of(network, Scheme::GregoryG2);
  const std::string check = "`curvenet check builtin:" + network + " --scheme ";
  return {row({"G¹: largest normal angle across an edge", sci(g1.continuity.maxNormalAngleDeg) + "°",
               check + "gregory-g1`"}),
          row({"G²: largest curvature jump across an edge", sci(g2.jump.maxJump) + " (G¹: " + sci(g1.jump.maxJump) + ")",
               check + "gregory-g2`"}),
          row({"distance from the ellipsoid, max / mean", percent(g2.reference->maxDeviation) + " / " +
                                                                 percent(g2.reference->meanDeviation) + " (G¹: " +
                                                                 percent(g1.reference->maxDeviation) + " / " +
                                                                 percent(g1.reference->meanDeviation) + ")",
               check + "gregory-g2`"})};
}

} // namespace

std::vector<std::string> tableNames() {
  return {"headline",         "builtins",          "continuity",    "bezier",        "edge-curvature", "masters",
          "external-masters", "connection-curves", "approximation", "format-example"};
}

struct TableMaker::Measured {
  AnalyticFigures analytic;
};

TableMaker::TableMaker(std::filesystem::path repository)
    : repository_(std::move(repository)), measured_(std::make_unique<Measured>()) {}

TableMaker::~TableMaker() = default;

Table TableMaker::compute(const std::string &name) {
  AnalyticFigures &analytic = measured_->analytic;
  const std::map<std::string, std::function<std::vector<std::string>()>> tables = {
      {"headline", [&] { return headlineRows(analytic); }},
      {"builtins", builtinsTable},
      {"continuity", [&] { return continuityTable(analytic); }},
      {"bezier", bezierTable},
      {"edge-curvature", edgeCurvatureTable},
      {"masters", mastersTable},
      {"external-masters", externalMastersTable},
      {"connection-curves", connectionCurvesTable},
      {"approximation", approximationTable},
      {"format-example", [&] { return formatExampleTable(repository_); }}};
  const auto it = tables.find(name);
  if (it == tables.end()) throw std::runtime_error("no table named \"" + name + "\"");
  Table table{name, name == "headline", {}};
  for (const std::string &text : it->second()) {
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) table.lines.push_back(line);
  }
  return table;
}

} // namespace curvenet::figures
