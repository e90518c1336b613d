// Refusing work whose memory would exceed what the machine has, before any
// of it starts (issue: safe outputs and limits).
#include <limits>
#include <sstream>
#include <string>

#include "commands.hpp"
#include "curvenet/error.hpp"
#include "curvenet/tessellate.hpp"

namespace curvenet::cli {

namespace {

std::string gigabytes(double bytes) {
  std::ostringstream s;
  s.precision(3);
  s << bytes / (1024.0 * 1024.0 * 1024.0) << " GiB";
  return s.str();
}

} // namespace

std::size_t estimateMeshBytes(std::size_t vertices, bool writesText) {
  // Positions and normals (48 B), about two triangles per vertex (24 B), the
  // per-face staging of the tessellator (~32 B), and for OBJ/PLY output the
  // formatted text held before writing (~150 B per vertex with its triangles).
  const std::size_t perVertex = 48 + 24 + 32 + (writesText ? 150 : 0);
  return vertices < std::numeric_limits<std::size_t>::max() / perVertex ? vertices * perVertex
                                                                         : std::numeric_limits<std::size_t>::max();
}

void refuseIfTooLarge(std::size_t bytes, const std::string &what) {
  const std::size_t available = availableMemory();
  if (available == 0 || bytes <= available * 8 / 10) return;
  throw InputError("", what,
                   "needs about " + gigabytes(double(bytes)) + " of memory but only " + gigabytes(double(available)) +
                       " is available; lower the resolution or the image size");
}

} // namespace curvenet::cli
