// Scheme names on the command line (DESIGN.md §6).
#include <cstdio>

#include "commands.hpp"
#include "curvenet/error.hpp"

namespace curvenet::cli {

Scheme parseScheme(const std::string &name) {
  if (auto scheme = schemeFromName(name)) return *scheme;
  std::string known;
  for (Scheme s : availableSchemes()) known += (known.empty() ? "" : ", ") + schemeName(s);
  throw InputError("", "--scheme", "unknown or not yet available scheme '" + name + "'; available: " + known);
}

void warnAboutFolds(const Surface &surface) {
  for (int face : surface.foldedFaces())
    std::fprintf(stderr,
                 "curvenet: warning: face %d: the %s patch folds over itself (its normal turns over inside the face); "
                 "split the face with an extra curve or try another scheme\n",
                 face, schemeName(surface.options().scheme).c_str());
}

} // namespace curvenet::cli
