// Subcommand registry for the `spall` program.
//
// Each subcommand lives in apps/cmd_<name>.cc: it declares its options on a CLI11 subcommand and
// returns a function that runs it. Registration is static, so adding a subcommand touches no
// other file:
//
//   static spallkit::apps::Register reg("frequencies", "Kinematic fault frequencies",
//       [](CLI::App& sub) { auto opts = std::make_shared<Opts>(); sub.add_option(...);
//                           return [opts] { ...; return 0; }; });
//
// A runner returns the exit code. Library exceptions (InputError, NumericalError) are caught in
// main and printed as one line on stderr with exit code 2.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace spallkit::apps {

using Runner = std::function<int()>;
using Setup = std::function<Runner(CLI::App& sub)>;

struct CommandSpec {
  std::string name;
  std::string description;
  Setup setup;
};

std::vector<CommandSpec>& Commands();

struct Register {
  Register(std::string name, std::string description, Setup setup) {
    Commands().push_back({std::move(name), std::move(description), std::move(setup)});
  }
};

}  // namespace spallkit::apps
