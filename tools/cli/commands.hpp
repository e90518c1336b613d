// The subcommands of the curvenet program (DESIGN.md §6). Each registers its
// options on the CLI11 app and returns the process exit code when run.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

#include "curvenet/mesh.hpp"
#include "curvenet/surface.hpp"
#include "render.hpp"

namespace curvenet::cli {

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

/// The scheme for a --scheme value; InputError listing the known ones otherwise.
Scheme parseScheme(const std::string &name);
/// `--masters rebuilt|kept-g1` (what gregory-g2 builds over master faces) on `sub`.
void addMastersOption(CLI::App *sub, std::string &masters);
/// The surface options for --scheme and --masters values; InputError for an
/// unknown name, or kept-g1 with a scheme other than gregory-g2.
SurfaceOptions parseSurfaceOptions(const std::string &scheme, const std::string &masters);

/// A picture with the mesh it shows and the render time (seconds).
struct RenderedPicture {
  Mesh mesh;
  render::Image image;
  double seconds = 0;
};
/// Tessellates at `resolution`, computes the patch curvature for mean/gauss
/// modes, and renders (shared by `render` and `demo`). `showProgress`: a
/// progress line on stderr for each of the two steps (see progress.hpp).
RenderedPicture renderPicture(const Surface &surface, const render::RenderOptions &options, int resolution,
                              bool showProgress = false);
/// "wrote PATH (size, mode, range, triangles, time, rays/s)".
void printPictureLine(const std::string &path, const RenderedPicture &picture);
/// One stderr warning per face whose patch folds (Surface::foldedFaces).
void warnAboutFolds(const Surface &surface);

/// Memory a mesh of `vertices` needs while being built (and written as text).
double estimateMeshBytes(std::size_t vertices, bool writesText);
/// InputError naming `what` with the estimate when `bytes` exceeds 80% of
/// the memory available now (memoryShortfall); called before any work starts.
void refuseIfTooLarge(double bytes, const std::string &what);


} // namespace curvenet::cli
