// Engine errors raised while one face is evaluated name that face.
#pragma once

#include <string>
#include <utility>

#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

/// step(), its InternalErrors prefixed "face F: " and its InputErrors about a
/// side ("side 2", a ribbon table the input's curves do not let reach its
/// tolerances) given the element "face F side 2". A patch knows its sides,
/// not its face; the loops over faces' samples, and Surface's batch
/// evaluations, add which face it is. Nested (a tessellation tile evaluating
/// a face's batch), the face is named once.
template <class Step> decltype(auto) namingFace(int face, Step &&step) {
  try {
    return std::forward<Step>(step)();
  } catch (const InternalError &e) {
    const std::string prefix = "face " + std::to_string(face) + ": ", message = e.what();
    if (message.rfind(prefix, 0) == 0) throw;
    throw InternalError(prefix + message);
  } catch (const InputError &e) {
    if (e.element().rfind("side ", 0) != 0) throw;
    throw InputError(e.file(), "face " + std::to_string(face) + " " + e.element(), e.reason());
  }
}

} // namespace v1
} // namespace curvenet
