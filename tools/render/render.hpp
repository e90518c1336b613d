// render.hpp — verification pictures of a tessellated surface (docs/design.md §5).
//
// renderMesh casts one primary ray per sample through an Embree 3 scene built
// on the mesh (one shared vertex buffer, the mesh's own index array), over
// image tiles in parallel, and shades each hit from the barycentric
// interpolation of the mesh's exact vertex normals (or per-vertex values):
//
//  * reflection — the view ray d is mirrored about the normal n,
//    r = d − 2 (d·n) n, and looks into an environment at infinity made of
//    light lines parallel to the camera's up vector: a cylinder of stripes
//    around the model. The stripe phase is
//        phase = K · atan2(r · right, r · back) / π,
//    with right/back the camera's axes (back points from the model to the
//    camera): phase 0 reflects straight back to the camera, the branch cut
//    (±K) lies at grazing reflection. K = RenderOptions::stripes light lines
//    per half turn. The phase is a smooth function of n, so it is as smooth
//    as the normal field: C¹ across a G² join, a kink (first difference
//    jump) across a G¹ join with a curvature break, a jump across a kink.
//  * isophote — stripes of n · L for a fixed light L (camera-relative, from
//    the upper left behind the camera): phase = K · (n · L).
//  * mean / gauss — the caller's per-vertex values (curvenet/curvature.hpp),
//    interpolated and mapped by a diverging blue–white–red map over the
//    symmetric range [−R, R]; phase holds the raw interpolated value.
//
// Stripes are black and white bands (white where fract(phase) ∈ [¼, ¾]) with
// soft edges; each pixel averages five fixed samples (centre + rotated 2×2
// grid), so edges are anti-aliased and the result is deterministic. The
// phase channel is the unfiltered phase of the pixel-centre sample.
// Camera: perspective, 30° vertical field of view, looking at the centre of
// the mesh bounds from azimuth/elevation (degrees; z up, azimuth from +x
// towards +y), at the distance where the bounding sphere fills the frame.
// Background and light are fixed, so pictures compare across runs.
//
// Thread-safety: renderMesh reads the mesh only; concurrent calls are fine.
// Output is bit-identical for any thread count. Cost: BVH build O(T log T)
// for T triangles plus 5 · width · height rays.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "curvenet/mesh.hpp"
#include "curvenet/progress.hpp"

namespace curvenet::render {

enum class Mode { Reflection, Isophote, Mean, Gauss };

/// "reflection", "isophote", "mean", "gauss"; and back (nullopt when unknown).
std::string modeName(Mode mode);
std::optional<Mode> modeFromName(const std::string &name);

struct RenderOptions {
  int width = 800, height = 600; ///< pixels, each in [1, 16384]
  /// Camera direction in degrees (any finite value); the camera is placed so
  /// that the model's projection fills the image up to a 6% margin.
  double azimuth = 30, elevation = 30;
  Mode mode = Mode::Reflection;
  double stripes = 8;      ///< K > 0: light lines per half turn / isophote stripes per unit of n·L
  bool boundaries = false; ///< overlay the patch-boundary and border edges (about 1.5 px wide)
  int threads = 0;         ///< 0 = all cores, 1 = serial
  /// mean/gauss colour range R (> 0); 0 = automatic: the 98th percentile of
  /// |value| over the mesh vertices, so a few extreme corners do not wash the map out.
  double valueRange = 0;
  /// Optional: the fraction of pixels shaded so far, on the calling thread,
  /// at most every 50 ms, ending with 1 (curvenet/progress.hpp).
  ProgressCallback progress;
};

/// A rendered picture, rows top to bottom, all arrays width · height long
/// (color 3×). Background pixels: color = the fixed background, phase = NaN,
/// coverage = 0, face = −1.
struct Image {
  int width = 0, height = 0;
  Mode mode = Mode::Reflection;
  std::vector<float> color;    ///< linear RGB
  std::vector<float> phase;    ///< stripe phase or curvature value at the pixel centre
  std::vector<float> coverage; ///< fraction of the pixel's samples that hit the surface
  std::vector<std::int32_t> face; ///< network face at the pixel centre (per faceTriangleStart), −1 if none
  double valueRange = 0;       ///< mean/gauss: the symmetric colour range R used
  double stripes = 0;
  std::uint64_t rays = 0;      ///< primary rays cast
};

/// Renders `mesh` (positions, unit normals of the same count, triangles;
/// faceTriangleStart optional). `vertexValues` (one per vertex) is required
/// for mean/gauss and ignored otherwise; NaN values are shown grey.
/// Throws InputError for bad options or a mesh without normals or triangles.
Image renderMesh(const Mesh &mesh, const RenderOptions &options, std::span<const double> vertexValues = {});

/// The picture as 8-bit sRGB, 3 bytes per pixel, rows top to bottom: the
/// pixels of the PNG that writeImage writes.
std::vector<std::uint8_t> srgbBytes(const Image &image);

/// A camera direction (RenderOptions::azimuth, elevation), degrees.
struct View {
  double azimuth = 30, elevation = 30;
};
/// The direction that shows `mesh` best: from its area-weighted mean normal
/// when it is open and faces one way, else across its thinnest principal axis
/// (from above), tilted 30 degrees towards the +x+y+z octant so relief shows.
/// renderMesh then fits the model's projection to the image.
View framingView(const Mesh &mesh);

/// Writes `image` by the extension of `path`: .png (8-bit sRGB RGB, a text
/// description with mode and range) or .exr (32-bit float channels R, G, B
/// (linear), A = coverage, phase, face; attributes curvenet:mode,
/// curvenet:stripes, curvenet:range). Atomic: written to a temporary file
/// in the same folder and renamed into place; on any error no file is left.
/// Throws InputError for another extension or a failed write.
void writeImage(const Image &image, const std::string &path);

} // namespace curvenet::render
