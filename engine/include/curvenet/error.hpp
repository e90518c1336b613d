// curvenet/error.hpp — how curvenet reports bad input.
//
// Everything a user can get wrong (a file, a network, a parameter) is reported
// as an InputError naming where (the file, if any, and the element: "curve 3",
// "face 2 side 1", "line 17") and what is wrong. Engine invariants that cannot
// be broken by input are checked with CURVENET_CHECK, which reports the values
// involved and aborts the operation with InternalError.
#pragma once

#include <stdexcept>
#include <string>

namespace curvenet {
inline namespace v1 {

class InputError : public std::runtime_error {
public:
  InputError(std::string file, std::string element, std::string reason)
      : std::runtime_error(compose(file, element, reason)), file_(std::move(file)),
        element_(std::move(element)), reason_(std::move(reason)) {}

  const std::string &file() const { return file_; }       ///< may be empty (built-in or in-memory input)
  const std::string &element() const { return element_; } ///< e.g. "curve 3", "face 0 side 2", "line 7"
  const std::string &reason() const { return reason_; }

  /// A copy with the file name filled in (readers learn the name late).
  InputError inFile(const std::string &file) const { return {file, element_, reason_}; }

private:
  static std::string compose(const std::string &file, const std::string &element, const std::string &reason) {
    std::string m;
    if (!file.empty()) m += file + ": ";
    if (!element.empty()) m += element + ": ";
    return m + reason;
  }
  std::string file_, element_, reason_;
};

class InternalError : public std::logic_error {
  using std::logic_error::logic_error;
};

} // namespace v1
} // namespace curvenet

/// Always-on invariant check; the message carries the failed expression and location.
#define CURVENET_CHECK(cond, ...)                                                                  \
  do {                                                                                              \
    if (!(cond))                                                                                    \
      throw ::curvenet::InternalError(std::string("check failed: " #cond " at ") + __FILE__ + ":" + \
                                      std::to_string(__LINE__) + " " + std::string(__VA_ARGS__));   \
  } while (0)
