// Test helpers for readers that must refuse bad input with an InputError.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "curvenet/error.hpp"

namespace curvenet::test {

/// The InputError f() throws; a test failure (and a placeholder) if it throws none.
template <typename F> InputError catchInputError(F &&f) {
  try {
    f();
  } catch (const InputError &e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError("<none>", "<none>", "<none>");
}

inline bool contains(const std::string &haystack, const std::string &needle) {
  return haystack.find(needle) != std::string::npos;
}

} // namespace curvenet::test
