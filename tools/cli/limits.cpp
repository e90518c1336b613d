// Refusing work whose memory would exceed what the machine has, before any
// of it starts (issue: safe outputs and limits).
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "commands.hpp"
#include "curvenet/error.hpp"

namespace curvenet::cli {

namespace {

/// MemAvailable from /proc/meminfo (bytes), else physical memory, else 0 (unknown).
std::size_t availableMemory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::size_t kilobytes = 0;
  std::string unit;
  while (meminfo >> key >> kilobytes >> unit)
    if (key == "MemAvailable:") return kilobytes * 1024;
  const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && pageSize > 0 ? static_cast<std::size_t>(pages) * static_cast<std::size_t>(pageSize) : 0;
}

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
  return vertices * (48 + 24 + 32 + (writesText ? 150 : 0));
}

void refuseIfTooLarge(std::size_t bytes, const std::string &what) {
  const std::size_t available = availableMemory();
  if (available == 0 || bytes <= available * 8 / 10) return;
  throw InputError("", what,
                   "needs about " + gigabytes(double(bytes)) + " of memory but only " + gigabytes(double(available)) +
                       " is available; lower the resolution or the image size");
}

} // namespace curvenet::cli
