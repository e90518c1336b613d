// Tokens of line-based text formats (OBJ, OFF, .lop-like files): the
// whitespace split and the number parses the readers share, each error
// naming the file and the element it was reading.
#pragma once

#include <charconv>
#include <cctype>
#include <cmath>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {
namespace text {

/// Lines without comments (`#` to the end) and without trailing '\r'.
inline std::vector<std::string_view> lines(const std::string &text) {
  std::vector<std::string_view> out;
  std::string_view all(text);
  std::size_t start = 0;
  while (start <= all.size()) {
    std::size_t end = all.find('\n', start);
    if (end == std::string_view::npos) end = all.size();
    std::string_view line = all.substr(start, end - start);
    if (auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    out.push_back(line);
    start = end + 1;
  }
  return out;
}

/// Splits into whitespace-separated tokens.
inline std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    std::size_t j = i;
    while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

/// The whole token as a finite number, else InputError(file, where).
inline double number(std::string_view token, const std::string &file, const std::string &where) {
  double value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(value))
    throw InputError(file, where, "not a finite number: \"" + std::string(token) + "\"");
  return value;
}

/// The whole token as an integer, else InputError(file, where).
inline long long integer(std::string_view token, const std::string &file, const std::string &where) {
  long long value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size())
    throw InputError(file, where, "not an integer: \"" + std::string(token) + "\"");
  return value;
}

} // namespace text
} // namespace v1
} // namespace curvenet
