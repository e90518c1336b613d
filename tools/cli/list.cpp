// curvenet list [--json] — the built-in networks with their face counts by side number.
#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "progress.hpp"
#include "curvenet/builtins.hpp"
#include "curvenet/network.hpp"

namespace curvenet::cli {

namespace {

struct BuiltinRow {
  std::string input, summary;
  std::size_t faces = 0;
  std::map<int, int> facesBySides;
};

std::vector<BuiltinRow> builtinRows() {
  std::vector<BuiltinRow> rows;
  for (const BuiltinInfo &info : builtinNetworks()) {
    const Network network = Network::build(builtinNetwork(info.name));
    BuiltinRow row{"builtin:" + info.name, info.summary, network.faces().size(), {}};
    for (const Face &face : network.faces()) ++row.facesBySides[face.sideCount()];
    rows.push_back(std::move(row));
  }
  return rows;
}

void printJson(const std::vector<BuiltinRow> &rows) {
  nlohmann::json list = nlohmann::json::array();
  for (const BuiltinRow &row : rows) {
    nlohmann::json bySides = nlohmann::json::object();
    for (auto [sides, count] : row.facesBySides) bySides[std::to_string(sides)] = count;
    list.push_back({{"input", row.input}, {"faces", row.faces}, {"faces_by_sides", bySides}, {"summary", row.summary}});
  }
  const nlohmann::json out = {{"builtins", list}, {"default", "builtin:" + defaultBuiltinName()}};
  std::printf("%s\n", out.dump(2).c_str());
}

void printTable(const std::vector<BuiltinRow> &rows) {
  // Columns as wide as their longest entry, so every row lines up.
  int nameWidth = 4;
  for (const BuiltinRow &row : rows) nameWidth = std::max(nameWidth, static_cast<int>(row.input.size()));
  std::printf("%-*s %5s  %s\n", nameWidth, "name", "faces", "sides: faces");
  for (const BuiltinRow &row : rows) {
    std::string counts;
    for (auto [sides, count] : row.facesBySides)
      counts += (counts.empty() ? "" : ", ") + std::to_string(sides) + ": " + std::to_string(count);
    std::printf("%-*s %5zu  %s\n", nameWidth, row.input.c_str(), row.faces, counts.c_str());
    std::printf("    %s\n", row.summary.c_str());
  }
  std::printf("default (curvenet demo): builtin:%s\n", defaultBuiltinName().c_str());
}

} // namespace

Command addListCommand(CLI::App &app) {
  CLI::App *sub = app.add_subcommand("list", "The built-in networks (use as builtin:NAME)");
  auto quiet = std::make_shared<bool>(false);
  auto json = std::make_shared<bool>(false);
  sub->add_flag("--json", *json, "print one JSON object instead of the table");
  addQuietFlag(sub, *quiet); // accepted everywhere; list shows no progress line
  return {sub, [quiet, json] {
            const std::vector<BuiltinRow> rows = builtinRows();
            if (*json) printJson(rows);
            else printTable(rows);
            return 0;
          }};
}

} // namespace curvenet::cli
