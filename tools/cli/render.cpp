// curvenet render INPUT -o FILE.{png,exr} [--scheme S] [--masters M] [--mode M] [--size WxH]
// [--view AZ,EL] [--stripes K] [--boundaries] [--resolution R] [--threads T]
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <algorithm>
#include <cctype>
#include <numbers>
#include <regex>

#include "commands.hpp"
#include "curvenet/curvature.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "curvenet/sketch.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"
#include "progress.hpp"
#include "render.hpp"

namespace curvenet::cli {

namespace {

/// Whether a render INPUT names a mesh file (rendered as it is) rather than a
/// network. An OBJ of polylines and no faces is a curve graph: a network.
bool isMeshFile(const std::string &input) {
  std::string ext = std::filesystem::path(input).extension().string();
  for (char &c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".obj") {
    std::ifstream in(input, std::ios::binary);
    if (!in) return true; // the mesh reader names the file that cannot be read
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return !objIsCurveGraph(text);
  }
  return ext == ".ply" || ext == ".off" || ext == ".stl";
}

/// Unit vertex normals weighted by the triangles' areas (a mesh file carries
/// none the readers keep); InputError naming `file` when a vertex has none.
void addAreaWeightedNormals(Mesh &mesh, const std::string &file) {
  mesh.normals.assign(mesh.positions.size(), Vec3{});
  for (const auto &t : mesh.triangles) {
    const Vec3 n = cross(mesh.positions[t[1]] - mesh.positions[t[0]], mesh.positions[t[2]] - mesh.positions[t[0]]);
    for (std::uint32_t v : t) mesh.normals[v] += n;
  }
  for (std::size_t v = 0; v < mesh.normals.size(); ++v) {
    const double length = norm(mesh.normals[v]);
    // An unused or degenerate vertex is never hit by a ray: any unit normal will do.
    mesh.normals[v] = length > 0 ? mesh.normals[v] / length : Vec3{0, 0, 1};
  }
  if (mesh.triangles.empty()) throw InputError(file, {}, "the mesh has no triangles");
}

} // namespace

RenderedPicture renderMeshPicture(Mesh mesh, const render::RenderOptions &options, bool showProgress) {
  const auto start = std::chrono::steady_clock::now();
  ProgressLine progress("render", showProgress);
  render::RenderOptions withProgress = options;
  withProgress.progress = progress.callback();
  RenderedPicture out;
  out.image = render::renderMesh(mesh, withProgress);
  progress.clear();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.mesh = std::move(mesh);
  return out;
}

RenderedPicture renderPicture(const Surface &surface, const render::RenderOptions &options, int resolution,
                              bool showProgress, bool framed) {
  const bool curvatureMode = options.mode == render::Mode::Mean || options.mode == render::Mode::Gauss;
  TessellationOptions t;
  t.resolution = resolution;
  t.threads = options.threads;
  t.recordDomainPoints = curvatureMode;
  // Mesh + Embree's BVH (~ the mesh again) + image planes (color, phase,
  // coverage, face: 24 B per pixel) before any work starts.
  const double pixels = double(options.width) * double(options.height);
  refuseIfTooLarge(2 * estimateMeshBytes(estimateMeshVertices(surface, resolution), false) + 24 * pixels,
                   "--resolution " + std::to_string(resolution) + " at " + std::to_string(options.width) + "x" +
                       std::to_string(options.height));
  RenderedPicture out;
  out.mesh = tessellateShowingProgress(surface, t, "tessellate", showProgress);
  render::RenderOptions withProgress = options;
  if (framed) {
    const render::View view = render::framingView(out.mesh);
    withProgress.azimuth = view.azimuth, withProgress.elevation = view.elevation;
  }
  std::vector<double> values;
  if (curvatureMode) {
    CurvatureOptions c;
    c.threads = options.threads;
    for (const CurvatureSample &s : meshCurvature(surface, out.mesh, c))
      values.push_back(options.mode == render::Mode::Mean ? s.mean : s.gauss);
  }
  const auto start = std::chrono::steady_clock::now();
  ProgressLine progress("render", showProgress);
  withProgress.progress = progress.callback();
  out.image = render::renderMesh(out.mesh, withProgress, values);
  progress.clear();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

void printPictureLine(const std::string &path, const RenderedPicture &p) {
  std::printf("wrote %s (%dx%d, %s", path.c_str(), p.image.width, p.image.height,
              render::modeName(p.image.mode).c_str());
  if (p.image.mode == render::Mode::Mean || p.image.mode == render::Mode::Gauss)
    std::printf(", colour range [%.6g, %.6g]", -p.image.valueRange, p.image.valueRange);
  std::printf(", %zu triangles, %.3g s, %.3g Mrays/s)\n", p.mesh.triangles.size(), p.seconds,
              p.image.rays / p.seconds * 1e-6);
}

Command addRenderCommand(CLI::App &app) {
  struct Options {
    std::string input, output, scheme = "gregory-g1", masters = "rebuilt", curves = "repaired", mode = "reflection", size = "800x600", view;
    double stripes = 8;
    bool boundaries = false, quiet = false, strict = false;
    int resolution = 32, threads = 0;
  };
  auto o = std::make_shared<Options>();
  CLI::App *sub = app.add_subcommand("render", "Ray-traced reflection lines, isophotes and curvature maps");
  sub->add_option("INPUT", o->input,
                  "network file (.json, .lop) or builtin:NAME; or a mesh file (.obj, .ply, .off, .stl), shown as it "
                  "is; - = either on standard input")
      ->required();
  sub->add_option("-o,--output", o->output, "output image (.png 8-bit sRGB, .exr float with a phase channel)")
      ->required();
  sub->add_option("--scheme", o->scheme, schemeChoices())->capture_default_str();
  addMastersOption(sub, o->masters);
  addCurvesOption(sub, o->curves);
  addStrictFlag(sub, o->strict);
  sub->add_option("--mode", o->mode, "reflection | isophote | mean | gauss (mean, gauss: networks only)")
      ->capture_default_str();
  sub->add_option("--size", o->size, "image size WxH, each at most 16384")->capture_default_str();
  sub->add_option("--view", o->view,
                  "camera azimuth,elevation in degrees (default: framed, from the model's mean normal or across its "
                  "thinnest axis, tilted 30 degrees)");
  sub->add_option("--stripes", o->stripes, "light lines per half turn / isophote stripes")
      ->check(numberIn(1e-6, 1e6))
      ->capture_default_str();
  sub->add_flag("--boundaries", o->boundaries, "overlay the patch boundaries");
  sub->add_option("--resolution", o->resolution, "tessellation intervals per segment")
      ->check(wholeNumberIn(1, 4096))
      ->capture_default_str();
  addThreadsOption(sub, o->threads);
  addQuietFlag(sub, o->quiet);
  return {sub, [o] {
            // Every option is checked before any work, so a mistake costs nothing and writes nothing.
            const std::string ext = std::filesystem::path(o->output).extension().string();
            if (ext != ".png" && ext != ".exr" && ext != ".PNG" && ext != ".EXR")
              throw InputError(o->output, {}, "unknown image extension \"" + ext + "\" (expected .png or .exr)");
            const SurfaceOptions surfaceOptions = parseSurfaceOptions(o->scheme, o->masters, o->curves);
            render::RenderOptions r;
            if (auto m = render::modeFromName(o->mode)) r.mode = *m;
            else throw UsageError("--mode", "unknown mode '" + o->mode + "'; available: reflection, isophote, mean, gauss");
            std::smatch match;
            static const std::regex sizePattern(R"(^([0-9]{1,9})[xX]([0-9]{1,9})$)");
            if (!std::regex_match(o->size, match, sizePattern))
              throw UsageError("--size", "expected WxH, e.g. 800x600, got '" + o->size + "'");
            r.width = std::stoi(match[1]);
            r.height = std::stoi(match[2]);
            if (r.width < 1 || r.height < 1 || r.width > 16384 || r.height > 16384)
              throw UsageError("--size", o->size + ": width and height must lie in [1, 16384]");
            static const std::regex viewPattern(R"(^\s*([-+]?[0-9]*\.?[0-9]+)\s*,\s*([-+]?[0-9]*\.?[0-9]+)\s*$)");
            const bool framed = o->view.empty();
            if (!framed) {
              if (!std::regex_match(o->view, match, viewPattern))
                throw UsageError("--view", "expected AZ,EL in degrees, e.g. 30,30, got '" + o->view + "'");
              r.azimuth = std::stod(match[1]);
              r.elevation = std::stod(match[2]);
            }
            r.stripes = o->stripes;
            r.boundaries = o->boundaries;
            r.threads = o->threads;

            if (isMeshFile(o->input) || (isStandardStream(o->input) && !standardInputIsNetwork())) {
              if (r.mode == render::Mode::Mean || r.mode == render::Mode::Gauss)
                throw InputError(o->input, "--mode", o->mode + " needs a network (a mesh file has no patches to measure "
                                                               "curvature on); use reflection or isophote");
              Mesh mesh = readMeshArgument(o->input);
              addAreaWeightedNormals(mesh, o->input);
              refuseIfTooLarge(2 * estimateMeshBytes(mesh.positions.size(), false) + 24 * double(r.width) * r.height,
                               o->input + " at " + o->size);
              if (framed) {
                const render::View view = render::framingView(mesh);
                r.azimuth = view.azimuth, r.elevation = view.elevation;
              }
              const RenderedPicture picture = renderMeshPicture(std::move(mesh), r, progressWanted(o->quiet));
              render::writeImage(picture.image, o->output);
              printPictureLine(o->output, picture);
              return 0;
            }
            const Network network = Network::build(loadNetworkArgument(o->input), o->input);
            const Surface surface = buildSurface(network, surfaceOptions, o->input);
            warnAboutFolds(surface);
            noteRepair(surface);
            enforceShape(surface, measureShape(surface), o->strict);
            const RenderedPicture picture = renderPicture(surface, r, o->resolution, progressWanted(o->quiet), framed);
            render::writeImage(picture.image, o->output);
            printPictureLine(o->output, picture);
            return 0;
          }};
}

} // namespace curvenet::cli
