// spall: the spallkit command-line program. Subcommands register themselves (see command.h).
#include <algorithm>
#include <cstdio>
#include <map>

#include "apps/cli_guard.h"
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

  // Parents before children: sorting by path puts "bench" before "bench fe".
  auto& commands = Commands();
  std::sort(commands.begin(), commands.end(), [](const CommandSpec& a, const CommandSpec& b) {
    return a.name < b.name;
  });
  std::map<std::string, CLI::App*> apps_by_path;
  std::map<CLI::App*, Runner> runners;
  for (const auto& spec : commands) {
    CLI::App* parent = &app;
    std::string leaf = spec.name;
    if (const auto space = spec.name.rfind(' '); space != std::string::npos) {
      const std::string parent_path = spec.name.substr(0, space);
      leaf = spec.name.substr(space + 1);
      auto it = apps_by_path.find(parent_path);
      if (it == apps_by_path.end()) {
        it = apps_by_path.emplace(parent_path, app.add_subcommand(parent_path, "")).first;
        it->second->require_subcommand(1);
      }
      parent = it->second;
    }
    CLI::App* sub = parent->add_subcommand(leaf, spec.description);
    apps_by_path[spec.name] = sub;
    if (spec.setup) {
      runners[sub] = spec.setup(*sub);
    } else {
      sub->require_subcommand(1);  // a group
    }
  }

  GuardOptions(app);
  if (const auto unknown = UnknownSubcommand(app, argc, argv)) {
    std::fprintf(stderr, "%s\n", unknown->c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version print and exit 0; usage errors are one line and exit code 2.
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "%s\n", ParseErrorLine(app, e).c_str());
    return 2;
  }

  try {
    // The deepest parsed command runs (a group's child, not the group).
    for (auto& [sub, run] : runners) {
      if (sub->parsed()) return run();
    }
  } catch (const spallkit::InputError& e) {
    std::fprintf(stderr, "spall: error: %s\n", OneLine(e.what()).c_str());
    return 2;
  } catch (const spallkit::NumericalError& e) {
    // A run that went wrong, not the input's form: exit code 1 (docs/RELIABILITY.md).
    std::fprintf(stderr, "spall: numerical error: %s\n", OneLine(e.what()).c_str());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr,
                 "spall: error: out of memory (the input asks for more memory than this machine "
                 "has; reduce the run's size)\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "spall: error: %s\n", OneLine(e.what()).c_str());
    return 1;
  }
  return 2;
}
