// Control-net export and edge continuity of the Bézier schemes (curvenet/bezier.hpp).
#include "curvenet/bezier.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>

#include "bezier/bezier_surface.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"

namespace curvenet {
inline namespace v1 {

namespace {
const bezier::BezierSurfaceData &dataOf(const Surface &surface) {
  const bezier::BezierSurfaceData *data = SurfaceAccess::bezierData(surface);
  if (!data)
    throw InputError("", "scheme", schemeName(surface.options().scheme) + " has no Bézier control nets; use bezier-g1 or coons-c0");
  return *data;
}

/// Normal of a construction patch at (u, v); at a degenerate (straight-angle)
/// corner the limit from inside.
Vec3 patchNormal(const bezier::QuinticPatch &patch, double u, double v) {
  auto p = patch.evaluate(u, v);
  Vec3 n = cross(p.du, p.dv);
  if (squaredNorm(n) <= 1e-24 * squaredNorm(p.du) * squaredNorm(p.dv)) {
    p = patch.evaluate(0.5 + (u - 0.5) * (1 - 1e-7), 0.5 + (v - 0.5) * (1 - 1e-7));
    n = cross(p.du, p.dv);
  }
  return normalized(n);
}

/// Patch parameters of face side k at side parameter s.
Vec2 sideUV(int k, double s) {
  switch (k) {
  case 0: return {s, 0};
  case 1: return {1, s};
  case 2: return {1 - s, 1};
  default: return {0, 1 - s};
  }
}
} // namespace

std::vector<FaceControlNets> controlNets(const Surface &surface) {
  const bezier::BezierSurfaceData &data = dataOf(surface);
  std::vector<FaceControlNets> out;
  for (size_t f = 0; f < data.faces.size(); ++f) {
    FaceControlNets face;
    face.name = surface.network().faces()[f].name;
    const bezier::BezierFace &bf = data.faces[f];
    for (size_t q = 0; q < bf.constructionFaces.size(); ++q) {
      QuinticControlNet net;
      const auto &patch = data.patches[bf.constructionFaces[q]];
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) net.points[6 * j + i] = patch.net[i][j];
      // Quads are stored in the subdivision frame; turn them back to the face's (u, v).
      for (int c = 0; c < 4; ++c) {
        Vec2 p = bf.quads[q][c];
        for (int r = 0; r < bf.rotation; ++r) p = {1 - p.y, p.x};
        net.faceCorners[c] = p;
      }
      face.patches.push_back(net);
    }
    out.push_back(std::move(face));
  }
  return out;
}

std::string controlNetsJson(const Surface &surface) {
  using nlohmann::json;
  json doc = {{"format", "curvenet-quintic-nets"},
              {"version", 1},
              {"scheme", schemeName(surface.options().scheme)},
              {"degree", {5, 5}},
              {"layout", "row-major: point index 6*j + i, i along u, j along v"}};
  json faces = json::array();
  const auto nets = controlNets(surface);
  for (size_t f = 0; f < nets.size(); ++f) {
    json face = {{"face", f}, {"name", nets[f].name}, {"side_order", {0, 1, 2, 3}}};
    json patches = json::array();
    for (const QuinticControlNet &n : nets[f].patches) {
      json corners = json::array(), points = json::array();
      for (const Vec2 &c : n.faceCorners) corners.push_back({c.x, c.y});
      for (const Vec3 &p : n.points) points.push_back({p.x, p.y, p.z});
      patches.push_back({{"face_corners", corners}, {"points", points}});
    }
    face["patches"] = patches;
    faces.push_back(face);
  }
  doc["faces"] = faces;
  return doc.dump(1);
}

void writeControlNets(const Surface &surface, const std::string &path) {
  const std::string text = controlNetsJson(surface);
  writeFileAtomically(path, [&](std::ostream &s) { s << text << "\n"; });
}

EdgeContinuity bezierEdgeContinuity(const Surface &surface, int samplesPerEdge) {
  if (samplesPerEdge < 1) throw InputError("", "samples", "must be at least 1");
  const bezier::BezierSurfaceData &data = dataOf(surface);
  const Network &net = data.construction;
  EdgeContinuity result;
  double sum = 0;
  for (size_t e = 0; e < net.segments().size(); ++e) {
    const Segment &seg = net.segments()[e];
    if (seg.isBoundary()) continue;
    ++result.edges;
    // Where each face shows the segment: side k, side-parameter range, direction.
    struct View {
      int face, side;
      double b0, b1;
      bool reversed;
    };
    std::array<View, 2> views;
    for (int s = 0; s < 2; ++s) {
      const Face &face = net.faces()[seg.faces[s]];
      for (int k = 0; k < face.sideCount(); ++k)
        for (size_t j = 0; j < face.sides[k].segments.size(); ++j)
          if (face.sides[k].segments[j] == static_cast<int>(e)) {
            const auto &br = face.sides[k].breaks;
            views[s] = {seg.faces[s], k, j == 0 ? 0.0 : br[j - 1], j + 1 == face.sides[k].segments.size() ? 1.0 : br[j],
                        face.sides[k].segmentReversed[j]};
          }
    }
    for (int i = 0; i <= samplesPerEdge; ++i) {
      const double t = double(i) / samplesPerEdge; // segment parameter
      Vec3 normal[2], point[2];
      for (int s = 0; s < 2; ++s) {
        const View &v = views[s];
        const double local = v.reversed ? 1 - t : t;
        const Vec2 uv = sideUV(v.side, v.b0 + (v.b1 - v.b0) * local);
        const auto &patch = data.patches[v.face];
        point[s] = patch.evaluate(uv.x, uv.y).point;
        normal[s] = patchNormal(patch, uv.x, uv.y);
      }
      const double angle = angleBetween(normal[0], normal[1]) * 180 / std::numbers::pi;
      result.maxNormalAngleDeg = std::max(result.maxNormalAngleDeg, angle);
      result.maxPositionGap = std::max(result.maxPositionGap, norm(point[0] - point[1]));
      sum += angle;
      ++result.samples;
    }
  }
  result.meanNormalAngleDeg = result.samples ? sum / result.samples : 0.0;
  return result;
}

} // namespace v1
} // namespace curvenet
