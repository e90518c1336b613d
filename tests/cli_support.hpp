// Running the `curvenet` program from a test: one helper for every suite
// that checks the command line end to end.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <pty.h>
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

/// Runs CURVENET_CLI with `arguments` on a fresh pseudo-terminal (stdin,
/// stdout and stderr all on it, as in an interactive shell) and waits for it.
/// Everything the program wrote is in `out`, as the terminal received it.
inline CliRun runCliOnTerminal(const std::string &arguments) {
  const std::string command = std::string("'") + CURVENET_CLI + "' " + arguments;
  CliRun run;
  int terminal = -1;
  const pid_t pid = ::forkpty(&terminal, nullptr, nullptr, nullptr);
  if (pid < 0) return run;
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char *>(nullptr));
    ::_exit(127);
  }
  // Read until the program's side closes (EIO once no process holds the terminal).
  std::array<char, 4096> buffer{};
  for (;;) {
    const ssize_t n = ::read(terminal, buffer.data(), buffer.size());
    if (n > 0) run.out.append(buffer.data(), static_cast<std::size_t>(n));
    else if (n < 0 && errno == EINTR) continue;
    else break;
  }
  ::close(terminal);
  int status = 0;
  ::waitpid(pid, &status, 0);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

} // namespace curvenet::test
