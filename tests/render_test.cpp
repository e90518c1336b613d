// Verification pictures that are checked, not only looked at. Two-patch
// height fields z = f(x) joined at x = 0 with known smoothness are rendered
// in memory; along the pixel row through the middle, the stripe phase must
// be C¹ across a C² join, kinked across a G¹ join with a curvature break and
// broken across a C⁰ join. Rendering is deterministic across thread counts,
// and the CLI writes readable pictures or, on bad input, nothing.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <numbers>

#include "curvenet/builtins.hpp"
#include "curvenet/curvature.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "curvenet/network.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"
#include "render.hpp"
#include "scratch.hpp"

using namespace curvenet;
namespace fs = std::filesystem;

namespace {

/// One piece of the height field: f and f'.
struct Piece {
  std::function<double(double)> f, df;
};

/// Face 0 covers x ∈ [−1, 0], face 1 x ∈ [0, 1], y ∈ [−0.6, 0.6], `columns`
/// grid columns per face. With `splitSeam` the seam vertices are doubled so
/// each face keeps its own normals there (a C⁰ join); otherwise they are
/// shared, with the left piece's normal (equal to the right one's for G¹).
Mesh twoPatchMesh(const Piece &left, const Piece &right, bool splitSeam, int columns = 200, int rows = 60) {
  Mesh mesh;
  auto vertexGrid = [&](const Piece &piece, double x0, double x1) {
    std::vector<std::uint32_t> ids;
    for (int j = 0; j <= rows; ++j)
      for (int i = 0; i <= columns; ++i) {
        const double x = x0 + (x1 - x0) * i / columns, y = -0.6 + 1.2 * j / rows;
        ids.push_back(static_cast<std::uint32_t>(mesh.positions.size()));
        mesh.positions.push_back({x, y, piece.f(x)});
        mesh.normals.push_back(normalized(Vec3{-piece.df(x), 0, 1}));
      }
    return ids;
  };
  std::vector<std::uint32_t> a = vertexGrid(left, -1, 0), b = vertexGrid(right, 0, 1);
  if (!splitSeam) // weld: the right grid's first column is the left grid's last
    for (int j = 0; j <= rows; ++j) b[j * (columns + 1)] = a[j * (columns + 1) + columns];
  mesh.faceTriangleStart.push_back(0);
  for (const auto *grid : {&a, &b}) {
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < columns; ++i) {
        auto at = [&](int ii, int jj) { return (*grid)[jj * (columns + 1) + ii]; };
        mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    mesh.faceTriangleStart.push_back(static_cast<std::uint32_t>(mesh.triangles.size()));
  }
  return mesh;
}

render::RenderOptions rowOptions(render::Mode mode) {
  render::RenderOptions o;
  o.width = 320;
  o.height = 240;
  o.azimuth = -90; // camera on the −y side: image rows run along +x
  o.elevation = 60;
  o.mode = mode;
  o.stripes = 4;
  o.threads = 2;
  return o;
}

/// Jumps where the middle row crosses from face 0 to face 1: quadratics are
/// fitted to 30 pixels of phase on each side (leaving 2 pixels at the join)
/// and compared at the join. `phase` is the jump of the phase in units of the
/// typical phase change per pixel; `slope` the jump of its derivative
/// relative to the larger of the two one-sided derivatives.
struct Jumps {
  double phase, slope;
};

double fitAt(const std::vector<double> &xs, const std::vector<double> &ys, double at, bool derivative) {
  // Least-squares quadratic in t = x − at: the value is c0, the slope c1.
  double s[5] = {0, 0, 0, 0, 0}, r[3] = {0, 0, 0};
  for (size_t i = 0; i < xs.size(); ++i) {
    const double t = xs[i] - at;
    double p = 1;
    for (int k = 0; k < 5; ++k, p *= t) s[k] += p;
    r[0] += ys[i], r[1] += ys[i] * t, r[2] += ys[i] * t * t;
  }
  // Solve the 3×3 normal equations by Cramer's rule.
  const double m[3][3] = {{s[0], s[1], s[2]}, {s[1], s[2], s[3]}, {s[2], s[3], s[4]}};
  auto det3 = [](const double a[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const int column = derivative ? 1 : 0;
  double mc[3][3];
  std::memcpy(mc, m, sizeof m);
  for (int i = 0; i < 3; ++i) mc[i][column] = r[i];
  return det3(mc) / det3(m);
}

Jumps jumpsAcrossJoin(const render::Image &img) {
  const int y = img.height / 2;
  auto at = [&](int x) { return static_cast<std::size_t>(y) * img.width + x; };
  int join = -1;
  for (int x = 0; x + 1 < img.width; ++x)
    if (img.face[at(x)] == 0 && img.face[at(x + 1)] == 1) join = x;
  EXPECT_GT(join, 40);
  EXPECT_LT(join, img.width - 40);
  std::vector<double> lx, ly, rx, ry, diffs;
  for (int x = join - 31; x <= join - 2; ++x) lx.push_back(x), ly.push_back(img.phase[at(x)]);
  for (int x = join + 3; x <= join + 32; ++x) rx.push_back(x), ry.push_back(img.phase[at(x)]);
  for (int x = join - 31; x < join + 32; ++x) {
    EXPECT_TRUE(std::isfinite(img.phase[at(x)])) << "pixel " << x << " misses the surface";
    if (x < join - 2 || x > join + 2) diffs.push_back(std::abs(img.phase[at(x + 1)] - img.phase[at(x)]));
  }
  std::nth_element(diffs.begin(), diffs.begin() + diffs.size() / 2, diffs.end());
  const double typical = diffs[diffs.size() / 2];
  const double mid = join + 0.5;
  Jumps j;
  j.phase = std::abs(fitAt(rx, ry, mid, false) - fitAt(lx, ly, mid, false)) / typical;
  const double slopeLeft = fitAt(lx, ly, mid, true), slopeRight = fitAt(rx, ry, mid, true);
  j.slope = std::abs(slopeRight - slopeLeft) / std::max(std::abs(slopeLeft), std::abs(slopeRight));
  return j;
}

const Piece c2Left{[](double x) { return 0.25 * x * x + 0.15 * x * x * x; },
                   [](double x) { return 0.5 * x + 0.45 * x * x; }};
const Piece c2Right{[](double x) { return 0.25 * x * x - 0.15 * x * x * x; },
                    [](double x) { return 0.5 * x - 0.45 * x * x; }};
const Piece g1Right{[](double x) { return 0.6 * x * x; }, [](double x) { return 1.2 * x; }};
const Piece c0Left{[](double x) { return 0.25 * x * x - 0.15 * x; }, [](double x) { return 0.5 * x - 0.15; }};
const Piece c0Right{[](double x) { return 0.25 * x * x + 0.15 * x; }, [](double x) { return 0.5 * x + 0.15; }};

// Reflection lines: the phase is a smooth function of the normal, so it has
// the smoothness of the normal field. Measured on this set-up: C² join phase
// 0.07, slope 5e-7; G¹ join phase 0.4, slope 0.67; C⁰ join phase 91.
TEST(RenderJoins, C2JoinKeepsThePhaseSmooth) {
  const Jumps j = jumpsAcrossJoin(
      render::renderMesh(twoPatchMesh(c2Left, c2Right, false), rowOptions(render::Mode::Reflection)));
  EXPECT_LT(j.phase, 1.0);
  EXPECT_LT(j.slope, 0.02);
}

TEST(RenderJoins, G1JoinWithCurvatureBreakKinksThePhase) {
  const Jumps j = jumpsAcrossJoin(
      render::renderMesh(twoPatchMesh(c2Left, g1Right, false), rowOptions(render::Mode::Reflection)));
  EXPECT_LT(j.phase, 1.0); // still continuous …
  EXPECT_GT(j.slope, 0.3); // … but its first difference jumps
}

class C0Join : public ::testing::TestWithParam<render::Mode> {};

TEST_P(C0Join, BreaksThePhase) {
  const Jumps j = jumpsAcrossJoin(render::renderMesh(twoPatchMesh(c0Left, c0Right, true), rowOptions(GetParam())));
  EXPECT_GT(j.phase, 10.0);
}

INSTANTIATE_TEST_SUITE_P(Render, C0Join, ::testing::Values(render::Mode::Reflection, render::Mode::Isophote),
                         [](const ::testing::TestParamInfo<render::Mode> &p) { return render::modeName(p.param); });

using test::readFile;
using test::ScratchDir;

template <typename T> bool sameBytes(const std::vector<T> &a, const std::vector<T> &b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(Render, OneAndTwoThreadsGiveTheSameBytes) {
  const Surface s = Surface::build(Network::build(builtinNetwork("pentagon")), {});
  TessellationOptions t;
  t.resolution = 24;
  t.recordDomainPoints = true;
  const Mesh mesh = tessellate(s, t);
  std::vector<double> mean;
  for (const CurvatureSample &c : meshCurvature(s, mesh)) mean.push_back(c.mean);
  ScratchDir dir;
  for (render::Mode mode : {render::Mode::Reflection, render::Mode::Mean}) {
    render::RenderOptions o;
    o.width = 200;
    o.height = 150;
    o.mode = mode;
    o.boundaries = true;
    o.threads = 1;
    const render::Image one = render::renderMesh(mesh, o, mean);
    o.threads = 2;
    const render::Image two = render::renderMesh(mesh, o, mean);
    EXPECT_TRUE(sameBytes(one.color, two.color));
    EXPECT_TRUE(sameBytes(one.phase, two.phase));
    EXPECT_TRUE(sameBytes(one.coverage, two.coverage));
    EXPECT_TRUE(sameBytes(one.face, two.face));
    for (const char *ext : {".png", ".exr"}) {
      const fs::path a = dir.path() / (std::string("one") + ext), b = dir.path() / (std::string("two") + ext);
      render::writeImage(one, a.string());
      render::writeImage(two, b.string());
      EXPECT_EQ(readFile(a), readFile(b)) << ext;
    }
  }
}

TEST(Render, ExrCarriesPhaseCoverageAndRange) {
  ScratchDir dir;
  const Mesh mesh = twoPatchMesh(c2Left, g1Right, false, 40, 12);
  std::vector<double> values(mesh.positions.size());
  for (std::size_t v = 0; v < values.size(); ++v) values[v] = mesh.positions[v].x; // −1 … 1
  render::RenderOptions o = rowOptions(render::Mode::Mean);
  o.valueRange = 2;
  const render::Image img = render::renderMesh(mesh, o, values);
  const fs::path path = dir.path() / "map.exr";
  render::writeImage(img, path.string());
  auto in = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec &spec = in->spec();
  ASSERT_EQ(spec.width, o.width);
  ASSERT_EQ(spec.nchannels, 6);
  // OpenEXR orders channels by name: look them up.
  const int phase = spec.channelindex("phase"), alpha = spec.channelindex("A");
  ASSERT_GE(phase, 0);
  ASSERT_GE(alpha, 0);
  ASSERT_GE(spec.channelindex("face"), 0);
  EXPECT_FLOAT_EQ(spec.get_float_attribute("curvenet:range"), 2.f);
  std::vector<float> pixels(static_cast<std::size_t>(spec.width) * spec.height * 6);
  ASSERT_TRUE(in->read_image(0, 0, 0, 6, OIIO::TypeDesc::FLOAT, pixels.data()));
  for (std::size_t i = 0; i < img.phase.size(); ++i) {
    EXPECT_EQ(pixels[6 * i + alpha], img.coverage[i]);
    if (img.coverage[i] == 0) {
      EXPECT_TRUE(std::isnan(pixels[6 * i + phase]));
    } else if (!std::isnan(img.phase[i])) {
      EXPECT_EQ(pixels[6 * i + phase], img.phase[i]);
    }
  }
}

TEST(Render, BadOptionsAreInputErrors) {
  const Mesh mesh = twoPatchMesh(c2Left, c2Right, false, 4, 2);
  render::RenderOptions o;
  o.width = 0;
  EXPECT_THROW(render::renderMesh(mesh, o), InputError);
  o = {};
  o.stripes = -1;
  EXPECT_THROW(render::renderMesh(mesh, o), InputError);
  o = {};
  o.mode = render::Mode::Gauss; // no values
  EXPECT_THROW(render::renderMesh(mesh, o), InputError);
  ScratchDir dir;
  render::Image img = render::renderMesh(mesh, render::RenderOptions{.width = 8, .height = 8});
  EXPECT_THROW(render::writeImage(img, (dir.path() / "x.jpg").string()), InputError);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

int runCli(const std::string &args) {
  const std::string command = std::string(CURVENET_CLI) + " " + args + " > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(RenderCli, WritesAReadablePng) {
  ScratchDir dir;
  const fs::path out = dir.path() / "pentagon.png";
  ASSERT_EQ(0, runCli("render builtin:pentagon -o " + out.string() +
                      " --scheme gregory-g1 --mode reflection --size 160x120 --resolution 12 --boundaries"));
  auto in = OIIO::ImageInput::open(out.string());
  ASSERT_TRUE(in);
  ASSERT_EQ(in->spec().width, 160);
  ASSERT_EQ(in->spec().height, 120);
  ASSERT_EQ(in->spec().nchannels, 3);
  std::vector<unsigned char> pixels(160 * 120 * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, pixels.data()));
  // The corner pixel is background; a good share of the picture must differ from it.
  int covered = 0;
  for (int i = 0; i < 160 * 120; ++i)
    covered += std::memcmp(&pixels[3 * i], pixels.data(), 3) != 0;
  EXPECT_GT(covered, 160 * 120 / 10);
  EXPECT_EQ(fs::directory_iterator(dir.path())->path(), out); // no temporary left behind
}

TEST(RenderCli, BadInputExitsNonZeroAndWritesNothing) {
  ScratchDir dir;
  const std::string out = (dir.path() / "x.png").string();
  EXPECT_NE(0, runCli("render builtin:pentagon -o " + out + " --mode bogus"));
  EXPECT_NE(0, runCli("render builtin:pentagon -o " + out + " --scheme bogus"));
  EXPECT_NE(0, runCli("render builtin:pentagon -o " + out + " --size 12by5"));
  EXPECT_NE(0, runCli("render builtin:pentagon -o " + (dir.path() / "x.tif").string()));
  EXPECT_NE(0, runCli("render builtin:nosuch -o " + out));
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

} // namespace

// OpenImageIO is opened with the first image (tools/render/image_codec.h):
// the program itself must not need it, or every command would again pay
// for its ~250 shared libraries at start-up.
TEST(RenderCli, TheProgramStartsWithoutOpenImageIO) {
  const std::string command = "ldd '" + std::string(CURVENET_CLI) + "' 2>&1";
  FILE *pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string libraries;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) libraries.append(buffer, n);
  ASSERT_EQ(::pclose(pipe), 0) << libraries;
  EXPECT_NE(libraries.find("libembree3"), std::string::npos) << libraries; // ldd listed the program's libraries
  EXPECT_EQ(libraries.find("OpenImageIO"), std::string::npos) << libraries;
}

// ------------------------------------------------------------ shading and framing

namespace {

/// A coarse sphere: the octahedron's faces split in four, vertices pushed to
/// the unit sphere with their exact normals. Its triangles span many pixels.
Mesh coarseSphere() {
  Mesh mesh;
  const Vec3 corners[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  auto add = [&](const Vec3 &p) {
    mesh.positions.push_back(normalized(p));
    mesh.normals.push_back(normalized(p));
    return static_cast<std::uint32_t>(mesh.positions.size() - 1);
  };
  for (const auto &f : faces) {
    const Vec3 a = corners[f[0]], b = corners[f[1]], c = corners[f[2]];
    const std::uint32_t ia = add(a), ib = add(b), ic = add(c), ab = add(a + b), bc = add(b + c), ca = add(c + a);
    for (const std::array<std::uint32_t, 3> &t : {std::array{ia, ab, ca}, std::array{ab, ib, bc},
                                                  std::array{ca, bc, ic}, std::array{ab, bc, ca}})
      mesh.triangles.push_back(t);
  }
  return mesh;
}

} // namespace

// Shading from the interpolated normal makes the reflection phase continuous
// across the triangles' edges; from the flat triangle normal it is nearly
// constant inside each triangle and jumps at its edges. On triangles tens of
// pixels wide, a jump shows as a step between neighbouring pixels far larger
// than the steps on either side of it (near the silhouette the phase changes
// fast too, but smoothly: its neighbouring steps are as large).
TEST(RenderShading, ReflectionPhaseFollowsTheInterpolatedNormalOnACoarseMesh) {
  render::RenderOptions options;
  options.width = 240, options.height = 180, options.threads = 1;
  const render::Image image = render::renderMesh(coarseSphere(), options);
  std::size_t steps = 0, jumps = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 1; x + 2 < image.width; ++x) {
      const std::size_t i = std::size_t(y) * image.width + x;
      bool inside = true; // four neighbours on the model, no silhouette pixel mixing in background
      for (std::size_t k = i - 1; k <= i + 2; ++k) inside = inside && image.coverage[k] >= 1;
      if (!inside) continue;
      auto step = [&](std::size_t k) { return std::abs(double(image.phase[k + 1]) - image.phase[k]); };
      const double before = step(i - 1), here = step(i), after = step(i + 1);
      if (here > options.stripes) continue; // atan2's branch cut: a jump by 2K
      ++steps;
      jumps += here > 0.05 && here > 4 * std::max(before, after);
    }
  ASSERT_GT(steps, 5000u);
  EXPECT_LT(double(jumps), 0.002 * double(steps))
      << jumps << " of " << steps << " steps jump: the phase breaks at triangle edges (flat-normal shading?)";
}

namespace {

/// Coverage of the framed default view of `mesh`: the fraction of the image
/// the model covers and the share of width and height its pixels span.
struct Framing {
  double covered = 0, spanX = 0, spanY = 0;
  bool touchesBorder = false;
};

Framing framedView(const Mesh &mesh) {
  render::RenderOptions options;
  options.width = 160, options.height = 120, options.threads = 1;
  const render::View view = render::framingView(mesh);
  options.azimuth = view.azimuth, options.elevation = view.elevation;
  const render::Image image = render::renderMesh(mesh, options);
  Framing f;
  int minX = image.width, maxX = -1, minY = image.height, maxY = -1;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double c = image.coverage[std::size_t(y) * image.width + x];
      if (c <= 0) continue;
      f.covered += c;
      minX = std::min(minX, x), maxX = std::max(maxX, x), minY = std::min(minY, y), maxY = std::max(maxY, y);
    }
  f.covered /= double(image.width) * image.height;
  f.spanX = double(maxX - minX + 1) / image.width, f.spanY = double(maxY - minY + 1) / image.height;
  f.touchesBorder = minX == 0 || minY == 0 || maxX == image.width - 1 || maxY == image.height - 1;
  return f;
}

void expectFramed(const Mesh &mesh, const std::string &name) {
  const Framing f = framedView(mesh);
  // Fitted: the model spans most of the width or the height, inside a margin.
  EXPECT_GT(std::max(f.spanX, f.spanY), 0.8) << name;
  EXPECT_FALSE(f.touchesBorder) << name;
  // Not edge-on: the model covers a fair part of its own extent.
  EXPECT_GT(f.covered / (f.spanX * f.spanY), 0.3) << name << " covers " << f.covered << " of the image";
}

} // namespace

TEST(RenderFraming, DefaultViewFramesEveryBuiltin) {
  for (const BuiltinInfo &info : builtinNetworks()) {
    const Surface surface = Surface::build(Network::build(builtinNetwork(info.name)), {});
    expectFramed(tessellate(surface, {4, 1}), info.name);
  }
}

TEST(RenderFraming, DefaultViewFramesTheSharedModels) {
  const std::filesystem::path models = std::filesystem::path(CURVENET_SHARED_DATA_DIR) / "transfinite-models";
  if (!std::filesystem::is_directory(models)) GTEST_SKIP() << models << " is not there (shared data absent)";
  int seen = 0;
  for (const auto &entry : std::filesystem::directory_iterator(models)) {
    if (entry.path().extension() != ".lop") continue;
    const std::string file = entry.path().string();
    const Surface surface = Surface::build(Network::build(readNetworkFile(file), file), {});
    expectFramed(tessellate(surface, {8, 1}), entry.path().filename().string());
    ++seen;
  }
  EXPECT_GT(seen, 0);
}

// An open model seen edge-on by a fixed default would cover a sliver; the
// framing view looks at it from its mean normal.
TEST(RenderFraming, AFlatModelIsSeenFaceOn) {
  Mesh strip;
  for (int i = 0; i <= 10; ++i)
    for (double y : {0.0, 0.2}) {
      strip.positions.push_back({0.0, y, 0.1 * i}); // a strip in the x = 0 plane
      strip.normals.push_back({1, 0, 0});
    }
  for (std::uint32_t i = 0; i < 10; ++i)
    strip.triangles.push_back({2 * i, 2 * i + 2, 2 * i + 1}), strip.triangles.push_back({2 * i + 1, 2 * i + 2, 2 * i + 3});
  const render::View view = render::framingView(strip);
  const double az = view.azimuth * std::numbers::pi / 180, el = view.elevation * std::numbers::pi / 180;
  const Vec3 back{std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
  EXPECT_GT(std::abs(back.x), std::cos(31 * std::numbers::pi / 180)); // within the 30 degrees of tilt
  expectFramed(strip, "strip");
}
