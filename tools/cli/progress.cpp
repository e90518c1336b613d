#include "progress.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <unistd.h>

namespace curvenet::cli {

void addQuietFlag(CLI::App *sub, bool &quiet) {
  sub->add_flag("-q,--quiet", quiet, "no progress display on a terminal (warnings, errors and results still print)");
}

bool progressWanted(bool quiet) { return !quiet && ::isatty(STDERR_FILENO) == 1; }

ProgressLine::ProgressLine(std::string label, bool enabled) : label_(std::move(label)), enabled_(enabled) {}

ProgressLine::~ProgressLine() { clear(); }

ProgressCallback ProgressLine::callback() {
  if (!enabled_) return {};
  return [this](double fraction) { update(fraction); };
}

void ProgressLine::update(double fraction) {
  if (!enabled_) return;
  const int percent = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 100.0);
  const auto now = std::chrono::steady_clock::now();
  // A terminal repaints quickly, but a line per report would flood a slow
  // remote session: only new whole percentages, at most ten per second,
  // except the first and the last, which always show.
  if (percent == lastPercent_) return;
  if (shown_ && percent < 100 && now - lastWrite_ < std::chrono::milliseconds(100)) return;
  std::fprintf(stderr, "\r%s %3d%%", label_.c_str(), percent);
  std::fflush(stderr);
  shown_ = true;
  lastPercent_ = percent;
  lastWrite_ = now;
}

void ProgressLine::clear() {
  if (!shown_) return;
  // Carriage return + erase to the end of the line: the next output starts on a clean line.
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
  shown_ = false;
  lastPercent_ = -1;
}

Mesh tessellateShowingProgress(const Surface &surface, TessellationOptions options, const std::string &label,
                               bool show) {
  ProgressLine progress(label, show);
  options.progress = progress.callback();
  Mesh mesh = tessellate(surface, options);
  progress.clear();
  return mesh;
}

} // namespace curvenet::cli
