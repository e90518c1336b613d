// Surface::build — edge data shared by faces, then one patch per face.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "analysis/vertex_frames.hpp"
#include "bezier/bezier_surface.hpp"
#include "curvenet/error.hpp"
#include "curvenet/surface.hpp"
#include "patches/patch.hpp"

namespace curvenet {
inline namespace v1 {

std::string schemeName(Scheme scheme) {
  switch (scheme) {
  case Scheme::GregoryG1: return "gregory-g1";
  case Scheme::CompositeRibbon: return "composite-ribbon";
  case Scheme::BezierG1: return "bezier-g1";
  case Scheme::CoonsC0: return "coons-c0";
  }
  return "?";
}

std::vector<Scheme> availableSchemes() {
  return {Scheme::GregoryG1, Scheme::CompositeRibbon, Scheme::BezierG1, Scheme::CoonsC0};
}

bool acceptsAnyLoop(Scheme scheme) { return scheme == Scheme::GregoryG1 || scheme == Scheme::CompositeRibbon; }

std::optional<Scheme> schemeFromName(const std::string &name) {
  for (Scheme s : availableSchemes())
    if (schemeName(s) == name) return s;
  return std::nullopt;
}

namespace {
// A loop corner whose two tangents are closer than this to a straight line
// carries no cross direction (the ribbon follows the fence there); closer
// than this to folding back it is a cusp, which no patch can span.
constexpr double kStraightAngle = 1e-2; // radians
constexpr double kCuspAngle = 1e-3;     // radians
} // namespace

struct Surface::Impl {
  Network network;
  SurfaceOptions options;
  std::vector<VertexFrame> frames;
  std::vector<std::unique_ptr<NormalFence>> fences;
  std::vector<Patch> patches;
  using DomainSide = DomainSideRange;
  /// Per face: the face side and side-parameter range of each domain side.
  std::vector<std::vector<DomainSide>> domainSides;
  /// bezier-g1 / coons-c0: the quintic patches (the transfinite members stay empty).
  std::shared_ptr<const bezier::BezierSurfaceData> bezier;
};

const bezier::BezierSurfaceData *SurfaceAccess::bezierData(const Surface &surface) {
  return surface.impl_->bezier.get();
}

namespace {
const RegularDomain &squareDomain() {
  static const RegularDomain domain(4);
  return domain;
}
} // namespace

Surface Surface::build(const Network &network, const SurfaceOptions &options) {
  auto impl = std::make_shared<Impl>();
  impl->network = network;
  impl->options = options;
  impl->frames = computeVertexFrames(network);
  if (options.scheme == Scheme::BezierG1 || options.scheme == Scheme::CoonsC0) {
    impl->bezier = std::make_shared<const bezier::BezierSurfaceData>(
        bezier::buildBezierSurface(network, options.scheme == Scheme::BezierG1));
    for (size_t f = 0; f < network.faces().size(); ++f)
      impl->domainSides.push_back({{0, 0.0, 1.0}, {1, 0.0, 1.0}, {2, 0.0, 1.0}, {3, 0.0, 1.0}});
    Surface surface;
    surface.impl_ = std::move(impl);
    return surface;
  }
  for (const Segment &seg : network.segments())
    impl->fences.push_back(std::make_unique<NormalFence>(seg.curve, impl->frames[seg.start].normal,
                                                         impl->frames[seg.end].normal));

  for (size_t f = 0; f < network.faces().size(); ++f) {
    const Face &face = network.faces()[f];
    std::vector<Impl::DomainSide> sides;
    for (int k = 0; k < face.sideCount(); ++k) {
      if (face.sideCount() == 2) {
        // Split at the segment break nearest the middle, so that the new
        // corner is a vertex both neighbours already share; else the middle.
        double split = 0.5;
        for (double b : face.sides[k].breaks)
          if (std::abs(b - 0.5) < std::abs(split - 0.5) || split == 0.5) split = b;
        sides.push_back({k, 0.0, split});
        sides.push_back({k, split, 1.0});
      } else {
        sides.push_back({k, 0.0, 1.0});
      }
    }
    std::vector<LinearRibbon> ribbons;
    for (const Impl::DomainSide &ds : sides) {
      const FaceSide &side = face.sides[ds.faceSide];
      const double width = ds.sTo - ds.sFrom;
      BSplineCurve curve = width == 1.0 ? side.curve : side.curve.restricted(ds.sFrom, ds.sTo).reparameterized(0, 1);
      // Segments of this side, as ranges of the ribbon's own parameter.
      std::vector<LinearRibbon::Piece> pieces;
      for (size_t j = 0; j < side.segments.size(); ++j) {
        const double b0 = j == 0 ? 0.0 : side.breaks[j - 1];
        const double b1 = j + 1 == side.segments.size() ? 1.0 : side.breaks[j];
        if (b1 <= ds.sFrom || b0 >= ds.sTo) continue;
        pieces.push_back({impl->fences[side.segments[j]].get(), (b0 - ds.sFrom) / width, (b1 - ds.sFrom) / width,
                          side.segmentReversed[j]});
      }
      ribbons.emplace_back(std::move(curve), std::move(pieces));
    }
    // End conditions need the neighbouring sides' tangents (DESIGN.md §3).
    const int n = static_cast<int>(ribbons.size());
    for (int i = 0; i < n; ++i) {
      const LinearRibbon &prev = ribbons[(i + n - 1) % n], &next = ribbons[(i + 1) % n];
      LinearRibbon &ribbon = ribbons[i];
      const Vec3 startTangent = ribbon.curve().derivatives(0.0)[1], endTangent = ribbon.curve().derivatives(1.0)[1];
      const Vec3 prevTangent = prev.curve().derivatives(1.0)[1], nextTangent = next.curve().derivatives(0.0)[1];
      const double startTurn = angleBetween(startTangent, prevTangent);
      const double endTurn = angleBetween(endTangent, nextTangent);
      if (std::numbers::pi - startTurn < kCuspAngle)
        throw InputError("", "face " + std::to_string(f),
                         "cusp at the start of side " + std::to_string(sides[i].faceSide) +
                             ": the two curves leave the corner in the same direction");
      const Vec3 startTarget = startTurn < kStraightAngle ? ribbon.fenceDirection(0.0) : -prevTangent;
      const Vec3 endTarget = endTurn < kStraightAngle ? ribbon.fenceDirection(1.0) : nextTangent;
      ribbon.setEndConditions(startTarget, endTarget);
    }
    impl->patches.emplace_back(std::move(ribbons), options);
    impl->domainSides.push_back(std::move(sides));
  }
  Surface surface;
  surface.impl_ = std::move(impl);
  return surface;
}

const Network &Surface::network() const { return impl_->network; }
const SurfaceOptions &Surface::options() const { return impl_->options; }
int Surface::faceCount() const {
  return static_cast<int>(impl_->bezier ? impl_->bezier->faces.size() : impl_->patches.size());
}
int Surface::domainSides(int face) const {
  return impl_->bezier ? 4 : impl_->patches.at(face).domain().sides();
}
Vec2 Surface::domainCorner(int face, int corner) const {
  return impl_->bezier ? squareDomain().corner(corner) : impl_->patches.at(face).domain().corner(corner);
}

Surface::DomainSideRange Surface::domainSideRange(int face, int domainSide) const {
  return impl_->domainSides.at(face).at(domainSide);
}

Vec2 Surface::domainPointOnFaceSide(int face, int side, double s) const {
  const auto &sides = impl_->domainSides.at(face);
  for (size_t i = 0; i < sides.size(); ++i) {
    const auto &ds = sides[i];
    if (ds.faceSide == side && s <= ds.sTo)
      return (impl_->bezier ? squareDomain() : impl_->patches[face].domain()).pointOnSide(static_cast<int>(i), (s - ds.sFrom) / (ds.sTo - ds.sFrom));
  }
  throw InputError("", "face " + std::to_string(face), "no side " + std::to_string(side));
}

SurfacePoint Surface::evaluate(int face, const Vec2 &uv) const {
  if (impl_->bezier) {
    // Square domain → (u, v) ∈ [0, 1]² (see the header); d(u,v)/d(x,y) = 1/width.
    const Vec2 c0 = squareDomain().corner(0);
    const double width = squareDomain().corner(1).x - c0.x;
    const double u = std::clamp((uv.x - c0.x) / width, 0.0, 1.0), v = std::clamp((uv.y - c0.y) / width, 0.0, 1.0);
    const bezier::QuinticPatch::Point p = bezier::evaluateBezierFace(*impl_->bezier, face, u, v);
    Vec3 normal = cross(p.du, p.dv);
    // Degenerate only at a straight-angle corner of a Coons patch: the limit from inside.
    if (squaredNorm(normal) <= 1e-24 * squaredNorm(p.du) * squaredNorm(p.dv) || squaredNorm(normal) == 0) {
      const auto inside = bezier::evaluateBezierFace(*impl_->bezier, face, 0.5 + (u - 0.5) * (1 - 1e-7),
                                                     0.5 + (v - 0.5) * (1 - 1e-7));
      normal = cross(inside.du, inside.dv);
    }
    return {p.point, p.du / width, p.dv / width, normalized(normal)};
  }
  const Patch &patch = impl_->patches.at(face);
  const DualVec3 r = patch.evaluate(uv.x, uv.y);
  Vec3 normal = cross(r.du, r.dv);
  // Parallel derivatives happen only at straight-angle corners; the normal
  // there is the limit from inside the domain.
  if (squaredNorm(normal) <= 1e-24 * squaredNorm(r.du) * squaredNorm(r.dv)) {
    const DualVec3 inside = patch.evaluate(uv.x * (1 - 1e-7), uv.y * (1 - 1e-7));
    normal = cross(inside.du, inside.dv);
  }
  return {r.v, r.du, r.dv, normalized(normal)};
}

Vec3 Surface::vertexNormal(int vertex) const { return impl_->frames.at(vertex).normal; }
double Surface::vertexResidualAngle(int vertex) const { return impl_->frames.at(vertex).residualAngle; }

} // namespace v1
} // namespace curvenet
