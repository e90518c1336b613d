// The JSON report shared by `check` and `demo` (key names: DESIGN.md §6).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "curvenet/network.hpp"
#include "curvenet/surface.hpp"

namespace curvenet::cli {

/// The network part: patches, faces by side count, vertices[] with valence,
/// independent curves and kind.
nlohmann::json networkReport(const Network &network, const std::string &input);

/// Adds the surface figures of DESIGN.md §5 for one scheme: `scheme`,
/// `continuity.*` (sampled at `samplesPerSegment` points per segment) and,
/// when the network has a reference surface, `reference.*` (measured at the
/// vertices of a tessellation at `resolution`).
void addSurfaceReport(nlohmann::json &report, const Surface &surface, int samplesPerSegment, int resolution);

/// Prints the report as a readable table (vertices worst first once the
/// analysis fills residuals).
void printReportTable(const nlohmann::json &report);

} // namespace curvenet::cli
