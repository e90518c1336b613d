// Running the `curvenet` program from a test: one helper for every suite
// that checks the command line end to end.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace curvenet::test {

struct CliRun {
  int exitCode = -1;
  std::string out; ///< standard output
  std::string err; ///< standard error
};

/// Runs CURVENET_CLI with `arguments` (already shell-quoted) and waits for it.
inline CliRun runCli(const std::string &arguments) {
  static int serial = 0;
  const std::filesystem::path errFile =
      std::filesystem::temp_directory_path() /
      ("curvenet-cli-" + std::to_string(::getpid()) + "-" + std::to_string(serial++) + ".err");
  const std::string command = std::string("'") + CURVENET_CLI + "' " + arguments + " 2>'" + errFile.string() + "'";
  CliRun run;
  FILE *pipe = ::popen(command.c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buffer{};
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) run.out.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(errFile);
  run.err.assign(std::istreambuf_iterator<char>(err), {});
  std::filesystem::remove(errFile);
  return run;
}

} // namespace curvenet::test
