// curvenet — command-line front end of the engine. Exit codes: 0 success,
// 1 bad input or failed operation (message on stderr), 2 usage errors (an
// unknown subcommand or option, a bad option value: one line on stderr).
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "commands.hpp"
#include "curvenet/error.hpp"

int main(int argc, char **argv) {
  using namespace curvenet::cli;
  CLI::App app{"curvenet: smooth transfinite surfaces over 3D curve networks, tessellated fast", "curvenet"};
  app.set_version_flag("--version", std::string("curvenet ") + CURVENET_VERSION);
  app.require_subcommand(1);

  std::map<CLI::App *, std::function<int()>> actions;
  std::vector<std::string> names;
  auto track = [&](Command command) {
    names.push_back(command.app->get_name());
    actions[command.app] = std::move(command.run);
  };
  track(addDemoCommand(app));
  track(addTessellateCommand(app));
  track(addCheckCommand(app));
  track(addRenderCommand(app));
  track(addBenchCommand(app));
  track(addApproximateCommand(app));
  track(addFacesCommand(app));
  track(addListCommand(app));

  // CLI11 takes an unknown first word for a stray argument ("A subcommand is
  // required"); name it instead.
  if (argc > 1 && argv[1][0] != '-' && std::find(names.begin(), names.end(), argv[1]) == names.end()) {
    std::string known;
    for (const std::string &name : names) known += (known.empty() ? "" : ", ") + name;
    std::fprintf(stderr, "curvenet: unknown subcommand '%s'; available: %s\n", argv[1], known.c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp &e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp &e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion &e) {
    return app.exit(e);
  } catch (const CLI::ParseError &e) {
    std::fprintf(stderr, "curvenet: usage error: %s (see --help)\n", e.what());
    return 2;
  }
  try {
    for (CLI::App *sub : app.get_subcommands())
      if (auto it = actions.find(sub); it != actions.end()) return it->second();
  } catch (const UsageError &e) {
    std::fprintf(stderr, "curvenet: usage error: %s (see --help)\n", e.what());
    return 2;
  } catch (const curvenet::InputError &e) {
    std::fprintf(stderr, "curvenet: error: %s\n", e.what());
    return 1;
  } catch (const std::filesystem::filesystem_error &e) {
    // A file or folder the user named could not be used: bad input, not a defect.
    std::fprintf(stderr, "curvenet: error: %s: %s\n", e.path1().string().c_str(), e.code().message().c_str());
    return 1;
  } catch (const std::exception &e) {
    std::fprintf(stderr, "curvenet: internal error: %s\n", e.what());
    return 1;
  }
  return 2;
}
