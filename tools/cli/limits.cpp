// Refusing work whose memory would exceed what the machine has, before any
// of it starts (issue: safe outputs and limits).
#include <string>

#include "commands.hpp"
#include "curvenet/error.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"

namespace curvenet::cli {

double estimateMeshBytes(std::size_t vertices, bool writesText) {
  // Positions and normals (48 B), about two triangles per vertex (24 B), the
  // per-face staging of the tessellator (~32 B), and for OBJ/PLY output the
  // formatted text held before writing (~150 B per vertex with its triangles).
  return static_cast<double>(vertices) * (48 + 24 + 32 + (writesText ? 150 : 0));
}

double estimateReportBytes(const Surface &surface, int resolution) {
  // The reference deviation tessellates at `resolution` recording each
  // vertex's domain point (24 B) and measures every vertex (~16 B); the
  // continuity figures' samples are few beside it.
  const double vertices = static_cast<double>(estimateMeshVertices(surface, resolution));
  return estimateMeshBytes(static_cast<std::size_t>(vertices), false) + 40 * vertices;
}

void refuseIfTooLarge(double bytes, const std::string &what) {
  if (const std::string shortfall = memoryShortfall(bytes); !shortfall.empty())
    throw InputError("", what, shortfall + "; lower the resolution or the image size");
}

} // namespace curvenet::cli
