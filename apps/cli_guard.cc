#include "apps/cli_guard.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "core/format.h"

namespace spallkit::apps {
namespace {

// Every subcommand below `app`, parents first.
void Collect(CLI::App* app, std::vector<CLI::App*>* out) {
  out->push_back(app);
  for (CLI::App* sub : app->get_subcommands([](CLI::App*) { return true; })) Collect(sub, out);
}

std::string NonEmpty(std::string& value) {
  return value.empty() ? "empty value (expected a value after the option)" : std::string();
}

// CLI11 reads "inf", "nan" and overflowing numbers such as 1e999 as valid doubles.
std::string FiniteNumber(std::string& value) {
  if (value.empty()) return NonEmpty(value);
  const char* begin = value.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (end == begin) return {};  // not a number: CLI11's conversion reports it
  if (!std::isfinite(v)) return "expected a finite number (got '" + value + "')";
  return {};
}

std::string Names(const std::vector<const CLI::App*>& apps) {
  std::string s;
  for (const CLI::App* a : apps) s += (s.empty() ? "" : ", ") + a->get_name();
  return s;
}

// "simulate", "bench fe": the deepest parsed subcommand's path (empty at the top).
std::string ParsedPath(const CLI::App& app) {
  std::string path;
  const CLI::App* cur = &app;
  for (;;) {
    const auto subs = cur->get_subcommands([](const CLI::App* a) { return a->parsed(); });
    if (subs.empty()) break;
    cur = subs.front();
    path += (path.empty() ? "" : " ") + cur->get_name();
  }
  return path;
}

}  // namespace

void GuardOptions(CLI::App& app) {
  std::vector<CLI::App*> apps;
  Collect(&app, &apps);
  for (CLI::App* a : apps) {
    for (CLI::Option* opt : a->get_options()) {
      if (opt->get_items_expected_max() == 0) continue;  // a flag
      const std::string type = opt->get_type_name();
      if (type.rfind("FLOAT", 0) == 0)
        opt->check(CLI::Validator(FiniteNumber, ""));
      else
        opt->check(CLI::Validator(NonEmpty, ""));
    }
  }
}

std::optional<std::string> UnknownSubcommand(const CLI::App& app,
                                             int argc,
                                             const char* const* argv) {
  const CLI::App* cur = &app;
  std::string path;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    const auto subs = cur->get_subcommands([](const CLI::App*) { return true; });
    if (subs.empty()) return std::nullopt;  // a leaf: the rest is its options and positionals
    if (word.empty() || word[0] == '-') return std::nullopt;  // an option: CLI11 handles it
    const CLI::App* next = nullptr;
    for (const CLI::App* s : subs)
      if (s->get_name() == word) next = s;
    // A command taking positionals besides subcommands ("plot FILE" and "plot study DIR").
    const bool takes_positionals =
        !cur->get_options([](const CLI::Option* o) { return o->get_positional(); }).empty();
    if (!next && takes_positionals) return std::nullopt;
    if (!next)
      return "spall: error: unknown subcommand '" + OneLine(word, 80) + "'" +
             (path.empty() ? "" : " of '" + path + "'") + " (known: " + Names(subs) + ")";
    path += (path.empty() ? "" : " ") + word;
    cur = next;
  }
  return std::nullopt;
}

std::string ParseErrorLine(const CLI::App& app, const CLI::ParseError& e) {
  const std::string path = ParsedPath(app);
  std::string line = "spall: error: " + (path.empty() ? std::string() : path + ": ") + e.what();
  line += " (see 'spall " + (path.empty() ? std::string() : path + " ") + "--help')";
  return OneLine(line);
}

std::string OneLine(const std::string& message, std::size_t max_chars) {
  std::string s;
  s.reserve(std::min(message.size(), max_chars) + 32);
  for (std::size_t i = 0; i < message.size() && s.size() < max_chars; ++i) {
    const char c = message[i];
    if (c == '\n') {
      if (i + 1 < message.size()) s += "; ";
    } else if (c == '\r' || c == '\t') {
      s += ' ';
    } else {
      s += c;
    }
  }
  if (s.size() >= max_chars && message.size() > max_chars)
    s += "... (" + std::to_string(message.size()) + " characters)";
  return s;
}

std::string Number(double value) { return FormatNumber("%.6g", value); }

CLI::Validator Uint64Digits() {
  return CLI::Validator(
      [](std::string& v) -> std::string {
        std::uint64_t parsed = 0;
        const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), parsed);
        if (v.empty() || ec != std::errc() || end != v.data() + v.size())
          return "must be an integer in 0..18446744073709551615";
        return {};
      },
      "");
}

}  // namespace spallkit::apps
