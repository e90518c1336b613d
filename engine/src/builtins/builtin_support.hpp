// Shared construction helpers for the built-in networks (engine-private).
//
// Each built-in is generated as a BuiltinData: the NetworkDescription plus the
// vertex facts its combinatorial construction knows (position, valence,
// independent curves), so tests can check the network builder against it.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "curvenet/builtins.hpp"

namespace curvenet {
inline namespace v1 {
namespace builtin_detail {

struct BuiltinData {
  NetworkDescription network;
  std::vector<BuiltinVertexFact> facts;
};

/// Degree of every built-in curve fit.
inline constexpr int kFitDegree = 5;

/// B-spline interpolation (degree kFitDegree) of the exact surface curve `exact`
/// sampled uniformly at `intervals` + 1 parameters over [t0, t1]; the first and
/// last data points are replaced by `start` and `end` so that the curve ends are
/// bit-identical to the vertex points the construction computed.
BSplineCurve fitSurfaceCurve(const std::function<Vec3(double)> &exact, double t0, double t1, int intervals,
                             const Vec3 &start, const Vec3 &end);

/// A convex polyhedron projected on the unit sphere: vertices (unit vectors)
/// and faces as vertex loops (any cyclic order; oriented by the builder).
struct SpherePolyhedron {
  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> faces;
};

/// Network on the ellipsoid diag(radii)·S²: edges are great arcs of the unit
/// sphere mapped by diag(radii) (planar sections through the centre, exact
/// curves on the ellipsoid); faces counter-clockwise seen from outside; every
/// vertex is independent (no curve passes straight through).
BuiltinData ellipsoidNetworkFromSphere(const std::string &name, const SpherePolyhedron &polyhedron,
                                       const Vec3 &radii);

SpherePolyhedron dodecahedronOnSphere();
SpherePolyhedron truncatedIcosahedronOnSphere();
/// One pentagonal loop around the north pole (polar angle ~35°).
SpherePolyhedron pentagonCapOnSphere();

BuiltinData torusMixed();
BuiltinData saddleNodes();

// Loops that need connection curves ([SV14] Sec. 5.2), see composite.cpp.
BuiltinData concaveL();
/// `holeSides` arcs make the hole (the built-in `ring`: 4, each facing an
/// outer corner).
BuiltinData ring(int holeSides = 4);
/// A loop of `sides` sides with all corners but two crowded on 100° of its
/// turn (the built-in `uneven-loop`: 10; [SV14] Fig. 9), split by
/// connection curves.
BuiltinData unevenLoop(int sides = 10);
/// A loop of `sides` sides inscribed in an ellipse (the built-in
/// `many-sided`: 12), split by connection curves into parts of at most 8.
BuiltinData manySidedLoop(int sides);

// Master–slave vertex blend ([SV14] Sec. 5.1, Fig. 8), see setback.cpp.
BuiltinData setbackVertexBlend();
// The same blend with the fillets given as external NURBS master surfaces.
BuiltinData setbackExternalMasters();

// Cubic Bézier networks with T-junctions ([OSK11]), see tjunctions.cpp.
BuiltinData hemisphereTJunction();
BuiltinData tjunctionSurrounded();
BuiltinData tjunctionVertex();
BuiltinData hullLike();

} // namespace builtin_detail
} // namespace v1
} // namespace curvenet
