// The JSON report shared by `check` and `demo` (key names: DESIGN.md §6).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "curvenet/network.hpp"

namespace curvenet::cli {

/// The network part: patches, faces by side count, vertices[] with valence,
/// independent curves and kind.
nlohmann::json networkReport(const Network &network, const std::string &input);

/// Prints the report as a readable table (vertices worst first once the
/// analysis fills residuals).
void printReportTable(const nlohmann::json &report);

} // namespace curvenet::cli
