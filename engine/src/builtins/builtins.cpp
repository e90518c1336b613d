// The registry of built-in networks (curvenet/builtins.hpp).
#include "curvenet/builtins.hpp"

#include <functional>

#include "builtins/builtin_support.hpp"
#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

using builtin_detail::BuiltinData;

struct Entry {
  BuiltinInfo info;
  std::function<BuiltinData()> make;
};

const std::vector<Entry> &entries() {
  using namespace builtin_detail;
  static const std::vector<Entry> list = {
      {{"pentagon", "one 5-sided loop of planar sections around the top of the ellipsoid (1.2, 1.0, 0.8)"},
       [] { return ellipsoidNetworkFromSphere("pentagon", pentagonCapOnSphere(), {1.2, 1.0, 0.8}); }},
      {{"sphere-dodecahedron", "12 pentagons on the unit sphere, dodecahedron edges as great-circle arcs"},
       [] { return ellipsoidNetworkFromSphere("sphere-dodecahedron", dodecahedronOnSphere(), {1, 1, 1}); }},
      {{"ellipsoid-truncated-icosahedron",
        "12 pentagons + 20 hexagons, truncated icosahedron on the ellipsoid (1.3, 1.0, 0.75), planar-section edges"},
       [] {
         return ellipsoidNetworkFromSphere("ellipsoid-truncated-icosahedron", truncatedIcosahedronOnSphere(),
                                           {1.3, 1.0, 0.75});
       }},
      {{"torus-mixed", "closed torus (R 1, r 0.45): 3-, 4-, 5-, 6-sided faces, valence 3/4/5, inner hyperbolic band"},
       [] { return torusMixed(); }},
      {{"saddle-nodes", "open network on z = x^2 - y^2 with an X-node, a T-node and a 2-sided lens"},
       [] { return saddleNodes(); }},
      {{"hemisphere-tjunction",
        "3 cubic Bezier patches on the unit sphere, a T-junction on the boundary curve of the third ([OSK11])"},
       [] { return hemisphereTJunction(); }},
      {{"tjunction-surrounded", "hemisphere x >= 0 in 6 cubic Bezier patches, the T-junction surrounded by patches"},
       [] { return tjunctionSurrounded(); }},
      {{"tjunction-vertex", "3 cubic Bezier patches, one running straight through its corner at a T-junction"},
       [] { return tjunctionVertex(); }},
      {{"hull-like", "ship-hull-like side of the ellipsoid (3, 1, 0.8): 10 cubic Bezier patches, 4 T-junctions"},
       [] { return hullLike(); }},
      {{"concave-L", "one L-shaped 6-sided loop with a concave corner on the bowl z = 0.25x^2 + 0.15y^2; "
                     "a connection curve splits it (hidden)"},
       [] { return concaveL(); }},
      {{"ring", "a square face with a circular hole on the bowl z = 0.25x^2 + 0.15y^2; four connection curves "
                "make it four quads (hidden)"},
       [] { return ring(); }},
      {{"uneven-loop", "a 10-sided loop on the bowl z = 0.25x^2 + 0.15y^2, eight corners crowded on 100 degrees of "
                       "its turn (Fig. 9); connection curves split it into even parts (hidden)"},
       [] { return unevenLoop(); }},
      {{"many-sided", "a 12-sided loop inscribed in an ellipse on the bowl z = 0.25x^2 + 0.15y^2; connection curves "
                      "split it into parts of at most 8 sides (hidden)"},
       [] { return manySidedLoop(12); }},
      {{"setback-vertex-blend", "box corner with cylindrical fillets of radii 0.30, 0.22, 0.38 (the masters) and a "
                                "6-sided setback vertex blend G2 to all three (the slave); no reference surface"},
       [] { return setbackVertexBlend(); }},
      {{"setback-external-masters", "the setback vertex blend alone, its three fillets (obliquely trimmed) given as "
                                    "external NURBS cylinders that its arc edges name as master surfaces"},
       [] { return setbackExternalMasters(); }},
  };
  return list;
}

BuiltinData generate(const std::string &name) {
  for (const Entry &e : entries())
    if (e.info.name == name) return e.make();
  std::string known;
  for (const Entry &e : entries()) known += (known.empty() ? "" : ", ") + e.info.name;
  throw InputError("", "builtin:" + name, "unknown built-in network; known: " + known);
}

} // namespace

const std::vector<BuiltinInfo> &builtinNetworks() {
  static const std::vector<BuiltinInfo> infos = [] {
    std::vector<BuiltinInfo> v;
    for (const Entry &e : entries()) v.push_back(e.info);
    return v;
  }();
  return infos;
}

std::string defaultBuiltinName() { return "ellipsoid-truncated-icosahedron"; }

NetworkDescription builtinNetwork(const std::string &name) { return generate(name).network; }

std::vector<BuiltinVertexFact> builtinVertexFacts(const std::string &name) { return generate(name).facts; }

} // namespace v1
} // namespace curvenet
