// spall: the spallkit command-line program. Subcommands register themselves (see command.h).
#include <algorithm>
#include <cstdio>
#include <map>

#include "apps/command.h"
#include "core/error.h"

namespace spallkit::apps {
std::vector<CommandSpec>& Commands() {
  static std::vector<CommandSpec> commands;
  return commands;
}
}  // namespace spallkit::apps

int main(int argc, char** argv) {
  using namespace spallkit::apps;
  CLI::App app{"spall: rolling-bearing spall simulation and diagnosis (spallkit " SPALLKIT_VERSION
               ")"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("spallkit ") + SPALLKIT_VERSION);

  auto& commands = Commands();
  std::sort(commands.begin(), commands.end(), [](const CommandSpec& a, const CommandSpec& b) {
    return a.name < b.name;
  });
  std::map<CLI::App*, Runner> runners;
  for (const auto& spec : commands) {
    CLI::App* sub = app.add_subcommand(spec.name, spec.description);
    runners[sub] = spec.setup(*sub);
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Usage errors: CLI11 prints help or the message; keep exit code 2 for errors, 0 for --help.
    int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }

  try {
    for (auto& [sub, run] : runners) {
      if (sub->parsed()) return run();
    }
  } catch (const spallkit::InputError& e) {
    std::fprintf(stderr, "spall: error: %s\n", e.what());
    return 2;
  } catch (const spallkit::NumericalError& e) {
    std::fprintf(stderr, "spall: numerical error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "spall: error: %s\n", e.what());
    return 2;
  }
  return 2;
}
