// Where `spall diagnose` and `spall identify` put their result: the text report or, with --json,
// one JSON object on stdout; --json-out FILE also writes the JSON object to FILE (atomically), so
// one run gives both forms (scripts/main-job.sh).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "apps/output_paths.h"
#include "core/atomic_file.h"

namespace spallkit::apps {

struct ReportOutputOptions {
  bool json = false;
  std::string json_out;

  void Add(CLI::App& sub, const std::string& what) {
    sub.add_flag("--json", json, "print one JSON object instead of the " + what);
    sub.add_option(
        "--json-out",
        json_out,
        "also write the JSON object to this file (the " + what + " still goes to stdout)");
  }

  // Before the work: the output path is writable and is not the record.
  void Check(const std::string& record) const {
    OutputPaths paths;
    paths.Add("--json-out", json_out);
    paths.MustDifferFrom("record", record);
    paths.Check();
  }

  // The JSON file first: a failure to write it is an error before anything is printed.
  void Emit(const std::string& text, const std::string& json_text) const {
    if (!json_out.empty()) WriteFileAtomically(json_out, json_text + "\n");
    if (json)
      std::printf("%s\n", json_text.c_str());
    else
      std::printf("%s", text.c_str());
  }
};

}  // namespace spallkit::apps
