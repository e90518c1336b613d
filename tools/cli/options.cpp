// Option values shared by every subcommand: whole numbers and numbers within
// limits, the scheme list of the help, and `-` for standard input or output.
// The messages are one short line naming the word given and the limit.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <sstream>

#include "commands.hpp"
#include "curvenet/error.hpp"

namespace curvenet::cli {

namespace {

/// "[0, 1024]", or "at least 0" when the upper limit is the type's own.
template <class T> std::string describeRange(T min, T max, T unbounded) {
  std::ostringstream s;
  if (max == unbounded) s << "at least " << min;
  else s << "in [" << min << ", " << max << "]";
  return s.str();
}

} // namespace

CLI::Validator wholeNumberIn(long min, long max) {
  const std::string range = describeRange(min, max, kNoLimit);
  return CLI::Validator(
      [min, max, range](std::string &word) -> std::string {
        long value = 0;
        const char *end = word.data() + word.size();
        const auto [at, error] = std::from_chars(word.data(), end, value);
        if (word.empty() || at != end || (error != std::errc() && error != std::errc::result_out_of_range))
          return "'" + word + "' is not a whole number";
        if (error == std::errc::result_out_of_range || value < min || value > max)
          return word + " is not " + range;
        return {};
      },
      range);
}

CLI::Validator numberIn(double min, double max) {
  const std::string range = describeRange(min, max, double(kNoLimit));
  return CLI::Validator(
      [min, max, range](std::string &word) -> std::string {
        char *end = nullptr;
        const double value = std::strtod(word.c_str(), &end);
        if (word.empty() || end != word.c_str() + word.size() || !std::isfinite(value))
          return "'" + word + "' is not a number";
        if (value < min || value > max) return word + " is not " + range;
        return {};
      },
      range);
}

void addThreadsOption(CLI::App *sub, int &threads) {
  sub->add_option("--threads", threads, "worker threads (0 = all cores)")
      ->check(wholeNumberIn(0, kMaxThreads))
      ->capture_default_str();
}

std::string schemeChoices() {
  std::string choices;
  for (Scheme s : availableSchemes()) choices += (choices.empty() ? "" : " | ") + schemeName(s);
  return choices;
}

bool isStandardStream(const std::string &path) { return path == "-"; }

std::string fileFormat(const std::string &path, const std::string &format, const std::string &what) {
  if (!format.empty()) return "." + format;
  if (isStandardStream(path))
    throw InputError("", what, "'-' (standard " + std::string(what == "--output" ? "output" : "input") +
                                   ") needs --format to say the format");
  std::string ext = std::filesystem::path(path).extension().string();
  for (char &c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

const std::string &readStandardInput() {
  // Read once: a command may look at the text before choosing its reader.
  static const std::string text = [] {
    std::string all(std::istreambuf_iterator<char>(std::cin), {});
    if (std::cin.bad()) throw InputError("-", {}, "cannot read standard input");
    return all;
  }();
  return text;
}

} // namespace curvenet::cli
