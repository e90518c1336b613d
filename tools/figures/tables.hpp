// The deterministic tables of README.md and docs/: continuity, deviation and
// counts, computed from the build with the same engine calls and defaults as
// the `curvenet` commands named beside each table in the documents.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace curvenet::figures {

/// One table of the documents: the lines between `<!-- figures:NAME -->` and
/// `<!-- /figures -->`. A keyed table owns only the rows whose first cell it
/// generates; the document may hold other rows beside them (speed figures,
/// which are measured, not computed, and keep their command in the row).
struct Table {
  std::string name;
  bool keyed = false;
  std::vector<std::string> lines;
};

/// The names of every table, in the order the documents first show them.
std::vector<std::string> tableNames();

/// Computes the table `name` (one of tableNames()). `repository` is the
/// source tree: docs/network-format.md's example is measured as it stands there.
Table computeTable(const std::string &name, const std::filesystem::path &repository);

} // namespace curvenet::figures
