// spall verify [--json] [--filter S]: runs the verification cases (sim/verify) and prints a table
// (case, reference, computed, relative error, tolerance, pass) or JSON. Exit code 1 if any fails.
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "apps/command.h"
#include "core/error.h"
#include "sim/verify/verification.h"

namespace {

struct Opts {
  bool json = false;
  std::string filter;
};

spallkit::apps::Register reg(
    "verify", "Run the verification cases against analytic references", [](CLI::App& sub) {
      auto opts = std::make_shared<Opts>();
      sub.add_flag("--json", opts->json, "Print JSON instead of a table");
      sub.add_option("--filter", opts->filter, "Only cases whose name contains this string");
      return [opts] {
        const auto results = spallkit::sim::verify::RunVerification(opts->filter);
        if (results.empty())
          throw spallkit::InputError("--filter '" + opts->filter +
                                     "' matches no verification case ('spall verify' runs all)");
        bool all = true;
        for (const auto& r : results) all = all && r.pass;
        if (opts->json) {
          nlohmann::json cases = nlohmann::json::array();
          for (const auto& r : results)
            cases.push_back({{"name", r.name},
                             {"quantity", r.quantity},
                             {"reference", r.reference},
                             {"computed", r.computed},
                             {"error", r.error},
                             {"tolerance", r.tolerance},
                             {"pass", r.pass},
                             {"note", r.note}});
          std::printf("%s\n", nlohmann::json({{"cases", cases}}).dump(2).c_str());
        } else {
          std::printf("%-58s %14s %14s %11s %10s  %s\n",
                      "case",
                      "reference",
                      "computed",
                      "error",
                      "tolerance",
                      "pass");
          for (const auto& r : results)
            std::printf("%-58s %14.6g %14.6g %11.3e %10.3g  %s\n",
                        r.name.c_str(),
                        r.reference,
                        r.computed,
                        r.error,
                        r.tolerance,
                        r.pass ? "PASS" : "FAIL");
          std::printf("%zu case(s), %s\n", results.size(), all ? "all passed" : "FAILURES");
        }
        return all ? 0 : 1;
      };
    });

}  // namespace
