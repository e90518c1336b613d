// Engine errors raised while one face is evaluated name that face.
#pragma once

#include <string>
#include <utility>

#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

/// step(), its InternalErrors prefixed "face F: ". A patch knows its sides (a
/// ribbon table that cannot be built says "side 2: ribbon table: …"), not its
/// face; the loops over faces' samples add which face it is.
template <class Step> decltype(auto) namingFace(int face, Step &&step) {
  try {
    return std::forward<Step>(step)();
  } catch (const InternalError &e) {
    throw InternalError("face " + std::to_string(face) + ": " + e.what());
  }
}

} // namespace v1
} // namespace curvenet
