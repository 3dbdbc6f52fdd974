// The bad-input contract of `spall` at the command line (docs/RELIABILITY.md): every error is one
// line on stderr, prefixed "spall:", naming the option or subcommand and what was expected, with
// exit code 2.
//
//   GuardOptions(app)            after all subcommands are declared: every option that takes a
//                                value rejects an empty one, every floating-point option rejects
//                                inf and nan (each command still checks its own ranges);
//   UnknownSubcommand(app, ...)  names a word that is no subcommand ("spall simulte"), before
//                                CLI11's generic "a subcommand is required";
//   ParseErrorLine(e)            CLI11's parse error as one line;
//   OneLine(message)             any message as one line of bounded length.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace spallkit::apps {

void GuardOptions(CLI::App& app);

// The one-line message when argv names a subcommand that does not exist; nullopt otherwise.
std::optional<std::string> UnknownSubcommand(const CLI::App& app,
                                             int argc,
                                             const char* const* argv);

// "spall: error: <command path>: <CLI11 message>" (the path of the deepest parsed subcommand).
std::string ParseErrorLine(const CLI::App& app, const CLI::ParseError& e);

// Newlines become "; ", and a message longer than `max_chars` is cut with its length noted (a
// whole 1 MB input line is never echoed).
std::string OneLine(const std::string& message, std::size_t max_chars = 400);

// A value for a message: "%.6g" ("1e-07", not std::to_string's "0.000000").
std::string Number(double value);

// For an unsigned 64-bit option (a seed): decimal digits only, within 0..2^64-1 (CLI11 takes
// "-3" as 2^64 - 3 and lets a too large number through).
CLI::Validator Uint64Digits();

}  // namespace spallkit::apps
