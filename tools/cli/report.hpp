// The JSON report shared by `check` and `demo` (key names: DESIGN.md §6).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "curvenet/analysis.hpp"
#include "curvenet/network.hpp"
#include "curvenet/shape.hpp"
#include "curvenet/surface.hpp"

namespace curvenet::cli {

/// The network part: patches, faces by side count, vertices[] with valence,
/// independent curves and kind.
nlohmann::json networkReport(const Network &network, const std::string &input);

/// Adds the surface figures of DESIGN.md §5 for one scheme: `scheme`,
/// `continuity.*` (sampled at `samplesPerSegment` points per segment) and,
/// when the network has a reference surface, `reference.*` (measured at the
/// vertices of a tessellation at `resolution`); when edges name a master
/// face, `masters[]` with per master edge `edge` (segment), `curve`,
/// `master_face`, `master_name`, `slave_face`, `max_curvature_jump`,
/// `mean_curvature_jump` and `samples`.
///
/// Also `repair` (SurfaceOptions::curves and every move of the vertex
/// repair: vertex, curve, kind, size, size_relative, angle_deg) and `shape`
/// (curvenet/shape.hpp: folded faces, excursion and fairness per face and
/// overall, the faces rejected by --strict).
void addSurfaceReport(nlohmann::json &report, const Surface &surface, int samplesPerSegment, int resolution);
/// The same with the shape already measured.
void addSurfaceReport(nlohmann::json &report, const Surface &surface, const ShapeReport &shape, int samplesPerSegment,
                      int resolution);

/// Adds the vertex analysis (curvenet/analysis.hpp) to a networkReport: per
/// vertex `enclosure_residual`, `euler_residual` (both relative to the
/// vertex's curvature scale), `k1`, `k2`, `lambda`, `tangent_residual_deg`,
/// `forms_x`, `verdict` and more under `vertices[]`, and an `analysis` summary
/// with the network's verdict.
void addVertexAnalysis(nlohmann::json &report, const NetworkAnalysis &analysis);

/// Adds a `tweak` object: what tweakNetwork changed, where the result went and
/// the residuals of the repaired network.
void addTweakReport(nlohmann::json &report, const TweakResult &tweak, const NetworkAnalysis &repaired,
                    const std::string &output);

/// The vertex table of an analysed report, worst vertices first (at most
/// `maxRows` rows), then the one-line verdict and the tweak summary.
void printAnalysisTable(const nlohmann::json &report, int maxRows = 30);

/// Prints the report as a readable table (vertices worst first once the
/// analysis fills residuals).
void printReportTable(const nlohmann::json &report);

} // namespace curvenet::cli
