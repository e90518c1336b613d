// Embree primary-ray renderer and image writer (see render.hpp).
#include "render.hpp"

#include "curvenet/io.hpp"

#include <dlfcn.h>
#include <embree3/rtcore.h>
#include <tbb/blocked_range2d.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>

#include <unistd.h>

#include "curvenet/error.hpp"
#include "image_codec.h"
#include "parallel/fork_join.hpp"

namespace curvenet::render {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
const Vec3 kBackground{0.20, 0.22, 0.25};
const Vec3 kDark{0.03, 0.03, 0.035}, kLight{0.92, 0.92, 0.90};
const Vec3 kBoundary{1.0, 0.42, 0.05};

// Pixel-centre sample first (it alone gives phase and face), then a rotated
// 2×2 grid; equal weights.
constexpr double kSamples[5][2] = {{0.5, 0.5}, {0.375, 0.125}, {0.875, 0.375}, {0.625, 0.875}, {0.125, 0.625}};

double smoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

/// White band where fract(phase) ∈ [¼, ¾], soft edges 0.08 of a period wide.
double stripe(double phase) {
  const double b = phase - std::floor(phase);
  constexpr double e = 0.04;
  return smoothstep(0.25 - e, 0.25 + e, b) - smoothstep(0.75 - e, 0.75 + e, b);
}

Vec3 mix(const Vec3 &a, const Vec3 &b, double t) { return a * (1 - t) + b * t; }

/// Diverging map over t ∈ [−1, 1]: the cool–warm end colours (Moreland 2009)
/// through a light grey, interpolated in linear RGB.
Vec3 diverging(double t) {
  const Vec3 cold{0.085, 0.133, 0.525}, mid{0.80, 0.80, 0.80}, warm{0.47, 0.0, 0.02};
  return t < 0 ? mix(mid, cold, -t) : mix(mid, warm, t);
}

struct Camera {
  Vec3 eye, forward, right, up, back;
  double tanHalfH, tanHalfV;
};

Camera frame(const Mesh &mesh, const RenderOptions &o) {
  const BoundingBox box = mesh.bounds();
  const double az = o.azimuth * std::numbers::pi / 180, el = o.elevation * std::numbers::pi / 180;
  Camera c;
  c.back = {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
  c.forward = -c.back;
  // z is up unless the camera looks (almost) straight along it.
  const Vec3 worldUp = std::abs(c.back.z) > 0.999 ? Vec3{-std::cos(az), -std::sin(az), 0} : Vec3{0, 0, 1};
  c.right = normalized(cross(c.forward, worldUp));
  c.up = cross(c.right, c.forward);
  c.tanHalfV = std::tan(15.0 * std::numbers::pi / 180);
  c.tanHalfH = c.tanHalfV * o.width / o.height;
  // Fitted to the image: the eye sits on the view axis through the middle of
  // the model's projected extent, as close as lets every vertex in, with a
  // small margin (a bounding sphere would leave a long model small).
  const Vec3 centre = box.center();
  double minX = INFINITY, maxX = -INFINITY, minY = INFINITY, maxY = -INFINITY;
  for (const Vec3 &p : mesh.positions) {
    const double x = dot(p - centre, c.right), y = dot(p - centre, c.up);
    minX = std::min(minX, x), maxX = std::max(maxX, x), minY = std::min(minY, y), maxY = std::max(maxY, y);
  }
  const Vec3 aim = centre + c.right * ((minX + maxX) / 2) + c.up * ((minY + maxY) / 2);
  constexpr double margin = 0.94; // of the half-width and half-height
  double distance = 0, depth = 0;
  for (const Vec3 &p : mesh.positions) {
    const Vec3 d = p - aim;
    const double z = dot(d, c.back);
    depth = std::max(depth, std::abs(z));
    distance = std::max({distance, z + std::abs(dot(d, c.right)) / (margin * c.tanHalfH),
                         z + std::abs(dot(d, c.up)) / (margin * c.tanHalfV)});
  }
  // Never inside the model, and at a positive distance even for a single point.
  distance = std::max({distance, 1.05 * depth, 1e-12 + 0.1 * norm(box.max - box.min)});
  c.eye = aim + c.back * distance;
  return c;
}

struct EmbreeScene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<float> vertices; // x y z pad: 16-byte stride, safe for Embree's vector loads
  ~EmbreeScene() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

void checkDevice(RTCDevice device, const char *what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree: ") + what + " failed (error " + std::to_string(e) + ")");
}

std::unique_ptr<EmbreeScene> buildScene(const Mesh &mesh) {
  auto s = std::make_unique<EmbreeScene>();
  s->device = rtcNewDevice(nullptr);
  if (!s->device) throw std::runtime_error("Embree: cannot create a device");
  s->vertices.resize(4 * mesh.positions.size() + 4);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    s->vertices[4 * i + 0] = static_cast<float>(mesh.positions[i].x);
    s->vertices[4 * i + 1] = static_cast<float>(mesh.positions[i].y);
    s->vertices[4 * i + 2] = static_cast<float>(mesh.positions[i].z);
  }
  s->scene = rtcNewScene(s->device);
  // Robust traversal: no ray slips through a shared edge of the watertight mesh.
  rtcSetSceneFlags(s->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(s->scene, RTC_BUILD_QUALITY_MEDIUM);
  RTCGeometry g = rtcNewGeometry(s->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, s->vertices.data(), 0, 4 * sizeof(float),
                             mesh.positions.size());
  // Mesh::triangles is a packed array of three uint32 per triangle: shared as is.
  rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.triangles.data(), 0,
                             3 * sizeof(std::uint32_t), mesh.triangles.size());
  rtcCommitGeometry(g);
  rtcAttachGeometry(s->scene, g);
  rtcReleaseGeometry(g);
  // The BVH is built on one thread: a parallel build may lay the tree out
  // differently from run to run, and with it which of two triangles sharing
  // an edge a ray reports — the picture must not depend on the thread count.
  tbb::task_arena serial(1);
  serial.execute([&] { rtcCommitScene(s->scene); });
  checkDevice(s->device, "scene build");
  return s;
}

/// Per triangle, the face whose range of mesh.faceTriangleStart holds it;
/// `unassigned` for triangles in none.
std::vector<std::int32_t> triangleFaces(const Mesh &mesh, std::int32_t unassigned) {
  std::vector<std::int32_t> faceOf(mesh.triangles.size(), unassigned);
  for (std::size_t f = 0; f + 1 < mesh.faceTriangleStart.size(); ++f)
    for (std::uint32_t k = mesh.faceTriangleStart[f]; k < mesh.faceTriangleStart[f + 1] && k < faceOf.size(); ++k)
      faceOf[k] = static_cast<std::int32_t>(f);
  return faceOf;
}

/// Per triangle, bit k set when the edge opposite corner k is a patch
/// boundary (its two triangles belong to different faces) or a mesh border.
std::vector<std::uint8_t> boundaryEdges(const Mesh &mesh) {
  const std::size_t t = mesh.triangles.size();
  const std::vector<std::int32_t> faceOf = triangleFaces(mesh, 0);
  struct Edge {
    std::uint32_t a, b, triangle, corner;
  };
  std::vector<Edge> edges;
  edges.reserve(3 * t);
  for (std::uint32_t i = 0; i < t; ++i)
    for (std::uint32_t k = 0; k < 3; ++k) {
      std::uint32_t a = mesh.triangles[i][(k + 1) % 3], b = mesh.triangles[i][(k + 2) % 3];
      if (a > b) std::swap(a, b);
      edges.push_back({a, b, i, k});
    }
  std::sort(edges.begin(), edges.end(), [](const Edge &x, const Edge &y) {
    return x.a != y.a ? x.a < y.a : (x.b != y.b ? x.b < y.b : x.triangle < y.triangle);
  });
  std::vector<std::uint8_t> mask(t, 0);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].a == edges[i].a && edges[j].b == edges[i].b) ++j;
    bool mark = j - i == 1; // border
    for (std::size_t k = i + 1; k < j; ++k) mark |= faceOf[edges[k].triangle] != faceOf[edges[i].triangle];
    if (mark)
      for (std::size_t k = i; k < j; ++k) mask[edges[k].triangle] |= static_cast<std::uint8_t>(1u << edges[k].corner);
    i = j;
  }
  return mask;
}

double automaticRange(std::span<const double> values) {
  std::vector<double> a;
  a.reserve(values.size());
  for (double v : values)
    if (std::isfinite(v)) a.push_back(std::abs(v));
  if (a.empty()) return 1;
  const std::size_t k = std::min(a.size() - 1, static_cast<std::size_t>(0.98 * static_cast<double>(a.size())));
  std::nth_element(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(k), a.end());
  return a[k] > 0 ? a[k] : 1;
}

struct Shaded {
  Vec3 color;
  double phase = std::numeric_limits<double>::quiet_NaN();
  std::int32_t face = -1;
  bool hit = false;
};

/// Throws InputError naming what a render request gets wrong.
void checkRenderInput(const Mesh &mesh, const RenderOptions &o, std::span<const double> vertexValues) {
  if (o.width < 1 || o.width > 16384 || o.height < 1 || o.height > 16384)
    throw InputError("", "image size", "width and height must lie in [1, 16384]");
  if (!(o.stripes > 0) || !std::isfinite(o.stripes)) throw InputError("", "stripes", "must be a positive number");
  if (!std::isfinite(o.azimuth) || !std::isfinite(o.elevation)) throw InputError("", "view", "angles must be finite");
  if (!(o.valueRange >= 0) || !std::isfinite(o.valueRange)) throw InputError("", "value range", "must be ≥ 0");
  if (mesh.triangles.empty() || mesh.positions.empty()) throw InputError("", "mesh", "has no triangles");
  if (mesh.normals.size() != mesh.positions.size()) throw InputError("", "mesh", "needs one normal per vertex");
  const bool valueMode = o.mode == Mode::Mean || o.mode == Mode::Gauss;
  if (valueMode && vertexValues.size() != mesh.positions.size())
    throw InputError("", "mesh", "curvature maps need one value per vertex");
  for (const auto &t : mesh.triangles)
    for (std::uint32_t v : t)
      if (v >= mesh.positions.size()) throw InputError("", "mesh", "triangle index out of range");
}

/// What a ray shows: the background, or at its hit on the mesh the mode's
/// colour (reflection lines, isophotes or the curvature map, two-sided)
/// with the patch boundaries drawn over it.
class Shader {
public:
  Shader(const Mesh &mesh, const RenderOptions &o, std::span<const double> vertexValues, const Camera &cam,
         double valueRange)
      : mesh_(mesh), o_(o), values_(vertexValues), cam_(cam), valueRange_(valueRange),
        light_(normalized(cam.back + cam.up * 0.6 - cam.right * 0.4)),
        pixelAngle_(2 * cam.tanHalfV / o.height), // world size of a pixel per unit distance
        edgeMask_(o.boundaries ? boundaryEdges(mesh) : std::vector<std::uint8_t>{}),
        faceOf_(triangleFaces(mesh, -1)) {}

  Shaded operator()(const Vec3 &dir, const RTCRayHit &rh) const {
    Shaded s;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
      s.color = kBackground;
      return s;
    }
    s.hit = true;
    const std::uint32_t prim = rh.hit.primID;
    const auto &tri = mesh_.triangles[prim];
    const double b1 = rh.hit.u, b2 = rh.hit.v, bary[3] = {1 - b1 - b2, b1, b2};
    s.face = faceOf_[prim];
    Vec3 n = normalized(mesh_.normals[tri[0]] * bary[0] + mesh_.normals[tri[1]] * bary[1] +
                        mesh_.normals[tri[2]] * bary[2]);
    const bool backFacing = dot(n, dir) > 0;
    if (backFacing) n = -n; // two-sided: the inside of an open surface is shown too
    shadeByMode(dir, n, tri, bary, s);
    if (backFacing) s.color = Vec3{s.color.x * 1.0, s.color.y * 0.8, s.color.z * 0.65};
    if (!edgeMask_.empty() && edgeMask_[prim]) s.color = withBoundary(s.color, prim, bary, rh.ray.tfar);
    return s;
  }

private:
  /// The mode's phase and colour at a hit with normal n (facing the eye).
  void shadeByMode(const Vec3 &dir, const Vec3 &n, const std::array<std::uint32_t, 3> &tri, const double (&bary)[3],
                   Shaded &s) const {
    switch (o_.mode) {
    case Mode::Reflection: {
      const Vec3 r = dir - n * (2 * dot(dir, n));
      s.phase = o_.stripes * std::atan2(dot(r, cam_.right), dot(r, cam_.back)) / std::numbers::pi;
      s.color = mix(kDark, kLight, stripe(s.phase));
      break;
    }
    case Mode::Isophote:
      s.phase = o_.stripes * dot(n, light_);
      s.color = mix(kDark, kLight, stripe(s.phase));
      break;
    case Mode::Mean:
    case Mode::Gauss: {
      s.phase = values_[tri[0]] * bary[0] + values_[tri[1]] * bary[1] + values_[tri[2]] * bary[2];
      // A little diffuse light keeps the shape readable under the colours.
      const double lit = 0.72 + 0.28 * std::abs(dot(n, light_));
      s.color = (std::isfinite(s.phase) ? diverging(std::clamp(s.phase / valueRange_, -1.0, 1.0))
                                        : Vec3{0.5, 0.5, 0.5}) * lit;
      break;
    }
    }
  }

  /// `color` with the marked edges of triangle prim drawn over it, about
  /// one and a half pixels wide at the hit's distance.
  Vec3 withBoundary(const Vec3 &color, std::uint32_t prim, const double (&bary)[3], float distance) const {
    // Distance from the hit to a marked edge: barycentric k times the
    // triangle's height over the edge opposite corner k.
    const auto &tri = mesh_.triangles[prim];
    const Vec3 p[3] = {mesh_.positions[tri[0]], mesh_.positions[tri[1]], mesh_.positions[tri[2]]};
    const double area2 = norm(cross(p[1] - p[0], p[2] - p[0]));
    double nearest = INFINITY;
    for (int k = 0; k < 3; ++k)
      if (edgeMask_[prim] & (1u << k)) {
        const double len = norm(p[(k + 2) % 3] - p[(k + 1) % 3]);
        if (len > 0) nearest = std::min(nearest, bary[k] * area2 / len);
      }
    const double halfWidth = 0.75 * pixelAngle_ * distance;
    return mix(color, kBoundary, 1 - smoothstep(0.6 * halfWidth, halfWidth, nearest));
  }

  const Mesh &mesh_;
  const RenderOptions &o_;
  std::span<const double> values_;
  const Camera &cam_;
  double valueRange_;
  Vec3 light_;
  double pixelAngle_;
  std::vector<std::uint8_t> edgeMask_;
  std::vector<std::int32_t> faceOf_;
};

/// The ray from the eye along dir, as Embree takes it.
RTCRayHit primaryRay(const Vec3 &eye, const Vec3 &dir) {
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(eye.x);
  rh.ray.org_y = static_cast<float>(eye.y);
  rh.ray.org_z = static_cast<float>(eye.z);
  rh.ray.dir_x = static_cast<float>(dir.x);
  rh.ray.dir_y = static_cast<float>(dir.y);
  rh.ray.dir_z = static_cast<float>(dir.z);
  rh.ray.tnear = 0.f;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

/// An image of the options' size with every buffer cleared.
Image blankImage(const RenderOptions &o, double valueRange) {
  Image img;
  img.width = o.width;
  img.height = o.height;
  img.mode = o.mode;
  img.stripes = o.stripes;
  img.valueRange = valueRange;
  const std::size_t pixels = static_cast<std::size_t>(o.width) * o.height;
  img.color.assign(3 * pixels, 0.f);
  img.phase.assign(pixels, kNaN);
  img.coverage.assign(pixels, 0.f);
  img.face.assign(pixels, -1);
  img.rays = 5 * pixels;
  return img;
}

} // namespace

std::string modeName(Mode mode) {
  switch (mode) {
  case Mode::Reflection: return "reflection";
  case Mode::Isophote: return "isophote";
  case Mode::Mean: return "mean";
  case Mode::Gauss: return "gauss";
  }
  return "?";
}

std::optional<Mode> modeFromName(const std::string &name) {
  for (Mode m : {Mode::Reflection, Mode::Isophote, Mode::Mean, Mode::Gauss})
    if (modeName(m) == name) return m;
  return std::nullopt;
}

Image renderMesh(const Mesh &mesh, const RenderOptions &o, std::span<const double> vertexValues) {
  checkRenderInput(mesh, o, vertexValues);
  std::optional<tbb::global_control> limit;
  if (o.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, o.threads);

  const auto scene = buildScene(mesh);
  const Camera cam = frame(mesh, o);
  const bool valueMode = o.mode == Mode::Mean || o.mode == Mode::Gauss;
  Image img = blankImage(o, valueMode ? (o.valueRange > 0 ? o.valueRange : automaticRange(vertexValues)) : 0);
  const Shader shade(mesh, o, vertexValues, cam, img.valueRange);

  // Five rays a pixel (kSamples); the first gives the pixel's phase and face.
  RTCScene rtcScene = scene->scene;
  ProgressCounter progress(o.progress, static_cast<std::uint64_t>(o.width) * static_cast<std::uint64_t>(o.height));
  parallel::parallelFor(tbb::blocked_range2d<int>(0, o.height, 16, 0, o.width, 16), [&](const auto &tile) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (int y = tile.rows().begin(); y != tile.rows().end(); ++y)
      for (int x = tile.cols().begin(); x != tile.cols().end(); ++x) {
        const std::size_t pixel = static_cast<std::size_t>(y) * o.width + x;
        Vec3 sum;
        int hits = 0;
        for (int k = 0; k < 5; ++k) {
          const double sx = (2 * (x + kSamples[k][0]) / o.width - 1) * cam.tanHalfH;
          const double sy = (1 - 2 * (y + kSamples[k][1]) / o.height) * cam.tanHalfV;
          const Vec3 dir = normalized(cam.forward + cam.right * sx + cam.up * sy);
          RTCRayHit rh = primaryRay(cam.eye, dir);
          rtcIntersect1(rtcScene, &context, &rh);
          const Shaded s = shade(dir, rh);
          sum += s.color;
          hits += s.hit;
          if (k == 0) {
            img.phase[pixel] = static_cast<float>(s.phase);
            img.face[pixel] = s.face;
          }
        }
        sum /= 5.0;
        img.color[3 * pixel + 0] = static_cast<float>(sum.x);
        img.color[3 * pixel + 1] = static_cast<float>(sum.y);
        img.color[3 * pixel + 2] = static_cast<float>(sum.z);
        img.coverage[pixel] = static_cast<float>(hits / 5.0);
      }
    progress.advance(static_cast<std::uint64_t>(tile.rows().size()) * static_cast<std::uint64_t>(tile.cols().size()));
  });
  checkDevice(scene->device, "ray casting");
  progress.finish();
  return img;
}

namespace {

float srgbFromLinear(float c) {
  c = std::clamp(c, 0.f, 1.f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1 / 2.4f) - 0.055f;
}

std::string description(const Image &img) {
  std::string d = "curvenet render: mode " + modeName(img.mode);
  if (img.mode == Mode::Mean || img.mode == Mode::Gauss) d += ", colour range +-" + std::to_string(img.valueRange);
  else d += ", stripes " + std::to_string(img.stripes);
  return d;
}

/// The encoder of image_codec.h, loaded once per process: from the install
/// layout next to the running program (bin/ → lib/curvenet/), else from the
/// build tree. A program without the module fails here, at its first image,
/// with the places it looked; everything else it does is unaffected.
curvenet_image_encode_fn imageEncoder(const std::string &path) {
  struct Loaded {
    curvenet_image_encode_fn encode = nullptr;
    std::string error;
  };
  static const Loaded loaded = [] {
    Loaded result;
    auto failed = [&](const std::string &why) { result.error += (result.error.empty() ? "" : "; ") + why; };
    std::vector<std::filesystem::path> candidates;
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) candidates.push_back(self.parent_path() / CURVENET_IMAGE_MODULE_FROM_BINDIR);
    candidates.push_back(CURVENET_IMAGE_MODULE_BUILT);
    for (const std::filesystem::path &candidate : candidates) {
      if (!std::filesystem::exists(candidate, ec)) {
        failed(candidate.lexically_normal().string() + ": no such file");
        continue;
      }
      void *module = ::dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!module) {
        const char *why = ::dlerror();
        failed(why ? why : candidate.string());
        continue;
      }
      // The module stays loaded for the rest of the process (never dlclose).
      if (void *symbol = ::dlsym(module, CURVENET_IMAGE_ENCODE_SYMBOL)) {
        result.encode = reinterpret_cast<curvenet_image_encode_fn>(symbol);
        return result;
      }
      failed(candidate.string() + " has no " CURVENET_IMAGE_ENCODE_SYMBOL);
    }
    return result;
  }();
  if (!loaded.encode) throw InputError(path, {}, "cannot load the image writer module (" + loaded.error + ")");
  return loaded.encode;
}

} // namespace

std::vector<std::uint8_t> srgbBytes(const Image &img) {
  std::vector<std::uint8_t> bytes(img.color.size());
  for (std::size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = static_cast<std::uint8_t>(std::lround(255.f * srgbFromLinear(img.color[i])));
  return bytes;
}

void writeImage(const Image &img, const std::string &path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char &c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".png" && ext != ".exr")
    throw InputError(path, {}, "unknown image extension \"" + ext + "\" (expected .png or .exr)");
  const bool exr = ext == ".exr";
  const std::size_t pixels = static_cast<std::size_t>(img.width) * img.height;
  CURVENET_CHECK(img.color.size() == 3 * pixels && img.phase.size() == pixels, "image arrays do not match its size");

  std::vector<float> floats;
  std::vector<std::uint8_t> bytes;
  const std::string mode(modeName(img.mode)), text = description(img);
  std::vector<curvenet_image_attribute> attributes;
  const char *const channelNames[] = {"R", "G", "B", "A", "phase", "face"};
  curvenet_image_request request{};
  request.abi = CURVENET_IMAGE_ABI;
  request.name = path.c_str();
  request.width = img.width, request.height = img.height;
  request.alpha_channel = -1;
  if (exr) {
    request.format = "openexr", request.channels = 6, request.float_pixels = 1;
    request.channel_names = channelNames, request.alpha_channel = 3;
    attributes = {{"compression", "zip", 0},
                  {"curvenet:mode", mode.c_str(), 0},
                  {"curvenet:stripes", nullptr, static_cast<float>(img.stripes)},
                  {"curvenet:range", nullptr, static_cast<float>(img.valueRange)}};
    floats.resize(6 * pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
      for (int c = 0; c < 3; ++c) floats[6 * i + c] = img.color[3 * i + c];
      floats[6 * i + 3] = img.coverage[i];
      floats[6 * i + 4] = img.phase[i];
      floats[6 * i + 5] = static_cast<float>(img.face[i]);
    }
    request.pixels = floats.data();
  } else {
    request.format = "png", request.channels = 3, request.float_pixels = 0;
    bytes = srgbBytes(img);
    request.pixels = bytes.data();
    attributes.push_back({"oiio:ColorSpace", "sRGB", 0});
  }
  attributes.push_back({"ImageDescription", text.c_str(), 0});
  attributes.push_back({"Software", "curvenet", 0});
  // The OpenEXR writer stamps the current time as capDate unless the spec
  // names one: an empty date keeps the bytes the same on every run.
  attributes.push_back({"DateTime", "", 0});
  request.attribute_count = static_cast<int>(attributes.size());
  request.attributes = attributes.data();

  // The image is encoded into memory and handed to writeFileAtomically: it
  // reaches the disk in one unnamed file that gets its name only when
  // complete, exactly like the meshes.
  std::vector<unsigned char> encoded;
  auto append = [](void *context, const void *data, std::size_t size) {
    auto &to = *static_cast<std::vector<unsigned char> *>(context);
    to.insert(to.end(), static_cast<const unsigned char *>(data), static_cast<const unsigned char *>(data) + size);
  };
  char error[512] = "";
  if (imageEncoder(path)(&request, append, &encoded, error, sizeof error) != 0) throw InputError(path, {}, error);
  writeFileAtomically(path, [&](std::ostream &file) {
    file.write(reinterpret_cast<const char *>(encoded.data()), static_cast<std::streamsize>(encoded.size()));
  });
}

View framingView(const Mesh &mesh) {
  // The area-weighted mean normal says where an open model faces; a closed
  // one (mean normal ~0) is seen across its thinnest principal axis.
  Vec3 meanNormal{}, centroid{};
  double area = 0;
  for (const auto &t : mesh.triangles) {
    const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    const Vec3 n = cross(b - a, c - a);
    meanNormal += n / 2;
    area += norm(n) / 2;
    centroid += (a + b + c) * (norm(n) / 6);
  }
  Vec3 direction;
  if (area > 0 && norm(meanNormal) > 0.25 * area) {
    direction = meanNormal / norm(meanNormal);
  } else {
    centroid = area > 0 ? centroid / area : mesh.bounds().center();
    double covariance[3][3] = {};
    for (const Vec3 &p : mesh.positions) {
      const double d[3] = {p.x - centroid.x, p.y - centroid.y, p.z - centroid.z};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) covariance[i][j] += d[i] * d[j];
    }
    // The thinnest axis: the dominant eigenvector of trace·I − C (power iteration).
    const double trace = covariance[0][0] + covariance[1][1] + covariance[2][2];
    direction = normalized(Vec3{0.2, 0.3, 1});
    for (int iteration = 0; iteration < 200; ++iteration) {
      const double v[3] = {direction.x, direction.y, direction.z};
      double w[3];
      for (int i = 0; i < 3; ++i)
        w[i] = trace * v[i] - (covariance[i][0] * v[0] + covariance[i][1] * v[1] + covariance[i][2] * v[2]);
      const Vec3 next{w[0], w[1], w[2]};
      if (!(norm(next) > 0)) break;
      direction = normalized(next);
    }
    if (direction.z < 0) direction = -direction; // from above rather than below
  }
  // Tilted 30 degrees towards the usual view from the +x+y+z octant, so that
  // relief along the direction shows (a face-on view flattens it).
  const Vec3 usual = normalized(Vec3{1, 1, 1});
  Vec3 side = usual - direction * dot(usual, direction);
  if (norm(side) < 1e-6) side = std::abs(direction.z) < 0.9 ? Vec3{0, 0, 1} - direction * direction.z : Vec3{1, 0, 0};
  side = normalized(side);
  const double tilt = 30 * std::numbers::pi / 180;
  const Vec3 back = direction * std::cos(tilt) + side * std::sin(tilt);
  constexpr double degrees = 180 / std::numbers::pi;
  return {std::atan2(back.y, back.x) * degrees, std::asin(std::clamp(back.z, -1.0, 1.0)) * degrees};
}

} // namespace curvenet::render
