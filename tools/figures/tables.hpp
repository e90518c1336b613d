// The deterministic tables of README.md and docs/: continuity, deviation and
// counts, computed from the build with the same engine calls and defaults as
// the `curvenet` commands named beside each table in the documents.
#pragma once

#include <filesystem>
#include <memory>
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

/// Computes tables; surfaces measured for one table are kept for the next
/// (the continuity table and the headline share them).
class TableMaker {
public:
  /// `repository` is the source tree: docs/network-format.md's example is
  /// measured as it stands there.
  explicit TableMaker(std::filesystem::path repository);
  ~TableMaker();
  /// The table `name` (one of tableNames()).
  Table compute(const std::string &name);

private:
  struct Measured;
  std::filesystem::path repository_;
  std::unique_ptr<Measured> measured_;
};

} // namespace curvenet::figures
