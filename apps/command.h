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
// A nested subcommand is registered under its path, e.g. "bench fe" (apps/cmd_bench_fe.cc): the
// parent ("bench") is created once, with the description given by RegisterGroup, and requires
// one of its children. Each child still lives in its own file.
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
  std::string name;  // "simulate", or a path "bench fe" for a nested subcommand
  std::string description;
  Setup setup;  // empty for a group (a parent that only holds subcommands)
};

std::vector<CommandSpec>& Commands();

struct Register {
  Register(std::string name, std::string description, Setup setup) {
    Commands().push_back({std::move(name), std::move(description), std::move(setup)});
  }
};

// A parent command that only groups subcommands ("bench": "bench fe", "bench diagnose", ...).
struct RegisterGroup {
  RegisterGroup(std::string name, std::string description) {
    Commands().push_back({std::move(name), std::move(description), Setup{}});
  }
};

}  // namespace spallkit::apps
