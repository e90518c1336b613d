// The JSON report shared by `check` and `demo` (key names: docs/design.md §6).
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

/// Adds the surface figures of docs/design.md §5 for one scheme: `scheme`,
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

/// What `check` measures besides the network: the surface of `surface`'s
/// scheme, sampled at `samples` points per segment, and its reference
/// deviation at tessellation `resolution`.
struct CheckOptions {
  SurfaceOptions surface;
  int samples = 64;
  int resolution = 32;
  /// Refuse (InputError) when a face folds or leaves its boundary's box (`--strict`).
  bool strict = false;
};

/// The object `curvenet check --json` prints (without `tweak`): the
/// networkReport of `network` read from `input`, its vertex analysis, the
/// surface report for `options` (with its shape figures) and, for bezier-g1,
/// the coons-c0 `baseline`.
/// Throws InputError when the surface cannot be built.
nlohmann::json checkReport(const Network &network, const std::string &input, const CheckOptions &options);

/// What `bench` measures: the network `input` (file or builtin:NAME), face
/// interiors at `resolution`, `points` random domain points, and the
/// parallel figures on `threads` threads (0 = all cores).
struct BenchOptions {
  std::string input = "builtin:pentagon";
  int resolution = 256, points = 4000, threads = 0;
};

/// The object `curvenet bench --json` prints: per scheme (gregory-g1,
/// gregory-g2, composite-ribbon) build, pointwise, face-interior (cold, warm,
/// all threads) and tessellation timings, and the G²/G¹ ratios. Runs for
/// seconds at the default resolution.
nlohmann::json benchReport(const BenchOptions &options);

/// The vertex table of an analysed report, worst vertices first (at most
/// `maxRows` rows), then the one-line verdict and the tweak summary.
void printAnalysisTable(const nlohmann::json &report, int maxRows = 30);

/// Prints the report as a readable table (vertices worst first once the
/// analysis fills residuals).
void printReportTable(const nlohmann::json &report);

} // namespace curvenet::cli
