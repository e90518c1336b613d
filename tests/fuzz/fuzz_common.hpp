// What every harness does with what it reads (refusedOrSound), and with a
// description that parsed: build the topology, the surface of every scheme,
// and a coarse tessellation.
// Bad input must surface as InputError only; anything else (a crash, a
// sanitizer report, an InternalError, a hang) is a finding.
#pragma once

#include <cstdio>
#include <cstdlib>

#include "curvenet/error.hpp"
#include "curvenet/network.hpp"
#include "curvenet/surface.hpp"
#include "curvenet/tessellate.hpp"

namespace curvenet::fuzz {

/// Runs `body`, for which an InputError is bad input refused with a
/// message (the expected outcome) and an InternalError a finding (abort).
template <class Body> void refusedOrSound(const Body &body) {
  try {
    body();
  } catch (const InputError &) {
    // refused with a message: the expected outcome for bad input
  } catch (const InternalError &e) {
    std::fprintf(stderr, "internal error: %s\n", e.what());
    std::abort();
  }
}

inline void exercise(const NetworkDescription &description) {
  refusedOrSound([&] {
    // Keep single inputs cheap so that the fuzzer explores breadth, not size.
    std::size_t controlPoints = 0;
    for (const BSplineCurve &c : description.curves) controlPoints += c.controlPoints().size();
    if (controlPoints > 2000 || description.faces.size() > 64) return;
    const Network network = Network::build(description, "fuzz");
    for (Scheme scheme : {Scheme::GregoryG1, Scheme::CompositeRibbon, Scheme::GregoryG2, Scheme::BezierG1}) {
      const Surface surface = Surface::build(network, {scheme});
      const Mesh mesh = tessellate(surface, {2, 1});
      if (mesh.positions.size() != mesh.normals.size()) std::abort();
    }
  });
}

} // namespace curvenet::fuzz
