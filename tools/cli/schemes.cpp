// Scheme names on the command line (DESIGN.md §6).
#include "commands.hpp"
#include "curvenet/error.hpp"

namespace curvenet::cli {

Scheme parseScheme(const std::string &name) {
  if (auto scheme = schemeFromName(name)) return *scheme;
  std::string known;
  for (Scheme s : availableSchemes()) known += (known.empty() ? "" : ", ") + schemeName(s);
  throw InputError("", "--scheme", "unknown or not yet available scheme '" + name + "'; available: " + known);
}

} // namespace curvenet::cli
