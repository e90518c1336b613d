// The subcommands of the curvenet program (docs/design.md §6). Each registers its
// options on the CLI11 app and returns the process exit code when run.
#pragma once

#include <CLI/CLI.hpp>

#include <climits>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>

#include "curvenet/error.hpp"
#include "curvenet/mesh.hpp"
#include "curvenet/network.hpp"
#include "curvenet/shape.hpp"
#include "curvenet/surface.hpp"
#include "render.hpp"

namespace curvenet::cli {

/// A mistake in how the program is called, found after parsing: an option
/// value it does not accept ("--scheme nope", "--size 0x0") or options that do
/// not go together. Exit 2 with one line, as CLI11's own usage errors.
class UsageError : public std::runtime_error {
public:
  UsageError(const std::string &option, const std::string &reason) : std::runtime_error(option + ": " + reason) {}
};

/// A registered subcommand and what it does after parsing (returns the exit code).
struct Command {
  CLI::App *app = nullptr;
  std::function<int()> run;
};

Command addListCommand(CLI::App &app);
Command addCheckCommand(CLI::App &app);
Command addTessellateCommand(CLI::App &app);
Command addDemoCommand(CLI::App &app);
Command addRenderCommand(CLI::App &app);
Command addBenchCommand(CLI::App &app);
Command addApproximateCommand(CLI::App &app);
Command addFacesCommand(CLI::App &app);

/// No upper limit, for wholeNumberIn.
inline constexpr long kNoLimit = LONG_MAX;
/// Most worker threads --threads accepts.
inline constexpr long kMaxThreads = 1024;
/// Accepts a whole number in [min, max]; otherwise one short line naming the
/// word ("'abc' is not a whole number", "-1 is not in [0, 1024]").
CLI::Validator wholeNumberIn(long min, long max);
/// Accepts a finite number in [min, max], with the same kind of message.
CLI::Validator numberIn(double min, double max);
/// `--threads T` (0 = all cores, at most kMaxThreads) on `sub`.
void addThreadsOption(CLI::App *sub, int &threads);
/// "gregory-g1 | gregory-g2 | ..." — every scheme this build has, for the help.
std::string schemeChoices();

/// Whether a file argument is `-` (standard input or output).
bool isStandardStream(const std::string &path);
/// The format of a file argument as a lowercase extension (".obj"): from
/// `format` (a --format value) when given, else from the path's extension;
/// InputError naming `what` for `-` without a --format.
std::string fileFormat(const std::string &path, const std::string &format, const std::string &what);
/// Everything on standard input (read on the first call, kept for later
/// ones); InputError naming "-" when it cannot be read.
const std::string &readStandardInput();
/// Whether standard input holds a network (a JSON object or a .lop loop,
/// which starts with its curve count) rather than a mesh.
bool standardInputIsNetwork();

/// A network argument: builtin:NAME, a file, or `-` = standard input (a
/// native JSON document or a .lop loop, told apart by the first character).
NetworkDescription loadNetworkArgument(const std::string &input);
/// A mesh argument: a file (.obj, .off, .ply, .stl) or `-` = standard input
/// (the format recognised from the content).
Mesh readMeshArgument(const std::string &input);
/// InputError naming `what` unless `path` with `format` (a --format value,
/// may be empty) is an OBJ or PLY mesh output; called before any work starts.
void checkMeshOutput(const std::string &path, const std::string &format, const std::string &what);
/// Writes the mesh to `path` (atomically) or, for `-`, to standard output, in
/// `format` when given, else by the path's extension.
void writeMeshArgument(const Mesh &mesh, const std::string &path, const std::string &format);
/// `step()`, whose InputErrors name `input` (the command's INPUT) when they
/// name no file: the engine's later stages (patches, vertex analysis) know
/// the face or vertex, not the file it came from.
template <class Step> auto namingInput(const std::string &input, Step &&step) -> decltype(step()) {
  try {
    return step();
  } catch (const InputError &e) {
    if (!e.file().empty()) throw;
    throw InputError(input, e.element(), e.reason());
  }
}
/// Surface::build through namingInput.
Surface buildSurface(const Network &network, const SurfaceOptions &options, const std::string &input);
/// Creates `folder` and its parents if missing; InputError naming it when
/// that fails or when it exists as something other than a folder.
void createOutputFolder(const std::string &folder);
/// Where a command's summary lines go: standard error when `output` is `-`
/// (standard output then carries the data), standard output otherwise.
std::FILE *summaryStream(const std::string &output);

/// The scheme for a --scheme value; UsageError listing the known ones otherwise.
Scheme parseScheme(const std::string &name);
/// `--masters rebuilt|kept-g1` (what gregory-g2 builds over master faces) on `sub`.
void addMastersOption(CLI::App *sub, std::string &masters);
/// `--curves repaired|kept` (SurfaceOptions::curves) on `sub`.
void addCurvesOption(CLI::App *sub, std::string &curves);
/// `--strict` on `sub`: a surface that folds or leaves its boundary's box
/// (curvenet/shape.hpp) fails the command before anything is written.
void addStrictFlag(CLI::App *sub, bool &strict);
/// The surface options for --scheme, --masters and --curves values;
/// UsageError for an unknown name, or kept-g1 with a scheme other than gregory-g2.
SurfaceOptions parseSurfaceOptions(const std::string &scheme, const std::string &masters,
                                   const std::string &curves = "repaired");

/// A picture with the mesh it shows and the render time (seconds).
struct RenderedPicture {
  Mesh mesh;
  render::Image image;
  double seconds = 0;
};
/// Tessellates at `resolution`, computes the patch curvature for mean/gauss
/// modes, and renders (shared by `render` and `demo`). `showProgress`: a
/// progress line on stderr for each of the two steps (see progress.hpp).
/// `framed`: the camera direction of `options` is replaced by render::framingView.
RenderedPicture renderPicture(const Surface &surface, const render::RenderOptions &options, int resolution,
                              bool showProgress = false, bool framed = false);
/// Renders a mesh as it is (reflection or isophote modes: it has no patches to
/// measure curvature on).
RenderedPicture renderMeshPicture(Mesh mesh, const render::RenderOptions &options, bool showProgress);

/// "wrote PATH (size, mode, range, triangles, time, rays/s)".
void printPictureLine(const std::string &path, const RenderedPicture &picture);
/// One stderr warning per face whose patch folds (Surface::foldedFaces).
void warnAboutFolds(const Surface &surface);
/// One stderr warning per face whose excursion exceeds kExcursionBound
/// (folds: warnAboutFolds); with `strict`, an InputError naming the rejected
/// faces instead, when there are any.
void enforceShape(const Surface &surface, const ShapeReport &shape, bool strict);
/// "curvenet: repaired the curves at N vertices (M control points, largest move X of the diagonal)" on stderr.
void noteRepair(const Surface &surface);

/// Memory a mesh of `vertices` needs while being built (and written as text).
double estimateMeshBytes(std::size_t vertices, bool writesText);
/// Memory the check report's tessellation-based figures need at `resolution`.
double estimateReportBytes(const Surface &surface, int resolution);
/// InputError naming `what` with the estimate when `bytes` exceeds 80% of
/// the memory available now (memoryShortfall); called before any work starts.
void refuseIfTooLarge(double bytes, const std::string &what);


} // namespace curvenet::cli
