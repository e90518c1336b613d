// Patches against their master surfaces (curvenet/master_contact.hpp).
#include "curvenet/master_contact.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "curvenet/bspline_surface.hpp"
#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

/// Normal angle and distance at u = j / n, ends included.
void measureTangency(const Surface &surface, const BSplineSurface &master, int segment, int face, int intervals,
                     MasterSurfaceContact &contact) {
  const double diagonal = surface.network().diagonal();
  for (int j = 0; j <= intervals; ++j) {
    const double u = double(j) / intervals;
    const SurfacePoint p = surface.evaluate(face, surface.domainPointOnSegment(face, segment, u));
    const SurfaceProjection foot = master.closestPoint(p.point); // world coordinates
    const Vec3 n = master.normal(foot.u, foot.v);
    const double angle = angleBetween(p.normal, dot(p.normal, n) < 0 ? -n : n) * 180 / std::numbers::pi;
    contact.maxNormalAngleDeg = std::max(contact.maxNormalAngleDeg, angle);
    contact.maxDistance = std::max(contact.maxDistance, foot.distance / diagonal);
  }
}

/// Curvature jump at the curvature-jump samples away from the ends.
void measureCurvature(const Surface &surface, const BSplineSurface &master, int segment, int face,
                      const CurvatureJumpOptions &options, MasterSurfaceContact &contact) {
  const Network &network = surface.network();
  const Segment &seg = network.segments()[size_t(segment)];
  const double floor = 1.0 / network.diagonal();
  double sum = 0;
  for (int j = 0; j < options.samplesPerSegment; ++j) {
    const double u =
        options.endExclusion + (1 - 2 * options.endExclusion) * double(j) / (options.samplesPerSegment - 1);
    const SurfacePoint2 p =
        surface.evaluateSecondOrder(face, surface.domainPointOnSegment(face, segment, u), options.step);
    const SurfaceProjection foot = master.closestPoint(p.point);
    const SurfaceFrame frame = master.frame(foot.u, foot.v);
    const Vec3 direction = cross(frame.normal, seg.curve.derivatives(u)[1]);
    const double kappaMaster = frame.normalCurvature(direction);
    const double kappaFace = (dot(p.normal, frame.normal) < 0 ? -1.0 : 1.0) * p.normalCurvature(direction);
    const double jump = std::abs(kappaFace - kappaMaster) / std::max({std::abs(kappaFace), std::abs(kappaMaster), floor});
    contact.maxCurvatureJump = std::max(contact.maxCurvatureJump, jump);
    sum += jump;
    ++contact.samples;
  }
  if (contact.samples > 0) contact.meanCurvatureJump = sum / contact.samples;
}

} // namespace

std::vector<MasterSurfaceContact> measureMasterSurfaceContact(const Surface &surface,
                                                              const CurvatureJumpOptions &options) {
  if (options.samplesPerSegment < 2) throw InputError("", "samplesPerSegment", "must be at least 2");
  if (!(options.endExclusion >= 0 && options.endExclusion < 0.5))
    throw InputError("", "endExclusion", "must lie in [0, 0.5)");
  const Network &network = surface.network();
  std::vector<MasterSurfaceContact> contacts;
  for (size_t e = 0; e < network.segments().size(); ++e) {
    const Segment &seg = network.segments()[e];
    if (seg.masterSurface < 0) continue;
    const BSplineSurface &master = network.description().surfaces[size_t(seg.masterSurface)];
    for (int face : seg.faces) {
      if (face < 0) continue;
      MasterSurfaceContact contact;
      contact.segment = int(e);
      contact.curve = seg.sourceCurve;
      contact.masterSurface = seg.masterSurface;
      contact.face = face;
      measureTangency(surface, master, int(e), face, options.samplesPerSegment - 1, contact);
      measureCurvature(surface, master, int(e), face, options, contact);
      contacts.push_back(contact);
    }
  }
  return contacts;
}

} // namespace v1
} // namespace curvenet
