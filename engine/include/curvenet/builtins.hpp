// curvenet/builtins.hpp — built-in networks cut from analytic surfaces.
//
// Every built-in is generated from an analytic surface so that exact points,
// normals and principal curvatures are known everywhere along and between the
// curves: each carries its ReferenceSurface. Curves are B-spline fits of curves
// lying on the surface, accurate to 1e-8 of the bounding-box diagonal in
// position and 1e-5 relative in normal curvature — except the cubic Bézier
// networks of [OSK11] (hemisphere-tjunction, tjunction-surrounded,
// tjunction-vertex, hull-like), whose curves are cubic arcs on the sphere or
// ellipsoid (ends and end tangents exact, ~1e-4 of the radius between) and
// whose vertex facts are not listed — and except `setback-vertex-blend`
// ([SV14] Sec. 5.1, Fig. 8), a box corner rounded by three cylindrical
// fillets (faces 0–2, exact rational arcs and straight lines) that a 6-sided
// vertex blend (face 3) joins: the blend is what the network defines, so
// this built-in carries no reference surface. Its three fillet end arcs name
// their fillet as master face (EdgeDescription::masterFace).
#pragma once

#include <string>
#include <vector>

#include "curvenet/network.hpp"

namespace curvenet {
inline namespace v1 {

struct BuiltinInfo {
  std::string name;
  std::string summary; ///< one line: surface and layout
};

/// All built-ins, in a stable order.
const std::vector<BuiltinInfo> &builtinNetworks();

/// The network the demo uses when no input is given.
std::string defaultBuiltinName();

/// Generates a built-in; throws InputError for an unknown name (listing the known ones).
NetworkDescription builtinNetwork(const std::string &name);

/// What the construction of a built-in knows about each vertex, independent
/// of the network builder: used by tests to check vertex classification.
struct BuiltinVertexFact {
  Vec3 position;
  int valence = 0;
  int independentCurves = 0;
};
std::vector<BuiltinVertexFact> builtinVertexFacts(const std::string &name);

} // namespace v1
} // namespace curvenet
