// The names of the surface options (schemes, edge-curvature sources, master
// faces) as the command line, the native format and the reports spell them.
#include <optional>
#include <string>
#include <vector>

#include "curvenet/surface.hpp"

namespace curvenet {
inline namespace v1 {

std::string schemeName(Scheme scheme) {
  switch (scheme) {
  case Scheme::GregoryG1: return "gregory-g1";
  case Scheme::CompositeRibbon: return "composite-ribbon";
  case Scheme::GregoryG2: return "gregory-g2";
  case Scheme::BezierG1: return "bezier-g1";
  case Scheme::CoonsC0: return "coons-c0";
  }
  return "?";
}

std::vector<Scheme> availableSchemes() {
  return {Scheme::GregoryG1, Scheme::CompositeRibbon, Scheme::GregoryG2, Scheme::BezierG1, Scheme::CoonsC0};
}

bool acceptsAnyLoop(Scheme scheme) { return scheme != Scheme::BezierG1 && scheme != Scheme::CoonsC0; }

std::optional<Scheme> schemeFromName(const std::string &name) {
  for (Scheme s : availableSchemes())
    if (schemeName(s) == name) return s;
  return std::nullopt;
}

std::string edgeCurvatureName(EdgeCurvature source) {
  switch (source) {
  case EdgeCurvature::MasterSlave: return "master-slave";
  case EdgeCurvature::Averaging: return "averaging";
  case EdgeCurvature::Direct: return "direct";
  case EdgeCurvature::Reference: return "reference";
  }
  return "?";
}

std::optional<EdgeCurvature> edgeCurvatureFromName(const std::string &name) {
  for (EdgeCurvature s :
       {EdgeCurvature::MasterSlave, EdgeCurvature::Averaging, EdgeCurvature::Direct, EdgeCurvature::Reference})
    if (edgeCurvatureName(s) == name) return s;
  return std::nullopt;
}

std::string masterFacesName(MasterFaces masters) {
  switch (masters) {
  case MasterFaces::Rebuilt: return "rebuilt";
  case MasterFaces::KeptG1: return "kept-g1";
  }
  return "?";
}

std::optional<MasterFaces> masterFacesFromName(const std::string &name) {
  for (MasterFaces m : {MasterFaces::Rebuilt, MasterFaces::KeptG1})
    if (masterFacesName(m) == name) return m;
  return std::nullopt;
}

} // namespace v1
} // namespace curvenet
