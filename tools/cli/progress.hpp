// Progress display of the curvenet program: one self-overwriting stderr line
// ("tessellate  42%") while a long step runs, shown only when stderr is a
// terminal and --quiet was not given, so pipes, logs and scripts see nothing.
#pragma once

#include <chrono>
#include <string>

#include "curvenet/progress.hpp"
#include "curvenet/tessellate.hpp"

namespace CLI {
class App;
}

namespace curvenet::cli {

/// Registers the `-q,--quiet` flag (progress display off; warnings, errors
/// and the result lines still print) on a subcommand.
void addQuietFlag(CLI::App *sub, bool &quiet);

/// Whether progress should be displayed: stderr is a terminal and not `quiet`.
bool progressWanted(bool quiet);

/// One progress line for one step. Not thread-safe: fed from the engine's
/// ProgressCallback, which runs on the calling thread only.
class ProgressLine {
public:
  /// `label` names the step ("tessellate", "render"); nothing is ever written when `enabled` is false.
  ProgressLine(std::string label, bool enabled);
  ~ProgressLine(); ///< clears the line if it is still shown (also when the step threw)
  ProgressLine(const ProgressLine &) = delete;
  ProgressLine &operator=(const ProgressLine &) = delete;

  /// The callback to pass to the engine (empty when disabled, so the engine skips the counting).
  ProgressCallback callback();
  /// Shows `fraction` (rewritten when the whole percentage changes, at most every 100 ms, and at 100%).
  void update(double fraction);
  /// Clears the line, leaving the cursor where the step started.
  void clear();

private:
  std::string label_;
  bool enabled_, shown_ = false;
  int lastPercent_ = -1;
  std::chrono::steady_clock::time_point lastWrite_{};
};

/// tessellate(surface, options) showing a progress line labelled `label` when
/// `show` (options.progress is replaced); the line is cleared when it ends.
Mesh tessellateShowingProgress(const Surface &surface, TessellationOptions options, const std::string &label, bool show);

} // namespace curvenet::cli
