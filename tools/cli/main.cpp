// curvenet — command-line front end of the engine. Exit codes: 0 success,
// 1 bad input or failed operation (message on stderr), 2 usage errors.
#include <cstdio>
#include <exception>
#include <map>

#include "commands.hpp"
#include "curvenet/error.hpp"

int main(int argc, char **argv) {
  using namespace curvenet::cli;
  CLI::App app{"curvenet: smooth transfinite surfaces over 3D curve networks, tessellated fast", "curvenet"};
  app.set_version_flag("--version", std::string("curvenet ") + CURVENET_VERSION);
  app.require_subcommand(1);

  std::map<CLI::App *, std::function<int()>> actions;
  auto track = [&](Command command) { actions[command.app] = std::move(command.run); };
  track(addDemoCommand(app));
  track(addTessellateCommand(app));
  track(addCheckCommand(app));
  track(addRenderCommand(app));
  track(addBenchCommand(app));
  track(addApproximateCommand(app));
  track(addFacesCommand(app));
  track(addListCommand(app));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError &e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    for (CLI::App *sub : app.get_subcommands())
      if (auto it = actions.find(sub); it != actions.end()) return it->second();
  } catch (const curvenet::InputError &e) {
    std::fprintf(stderr, "curvenet: error: %s\n", e.what());
    return 1;
  } catch (const std::exception &e) {
    std::fprintf(stderr, "curvenet: internal error: %s\n", e.what());
    return 1;
  }
  return 2;
}
