// Output-path checks a subcommand runs BEFORE its work, so a bad path fails in a second, not after
// an hour of simulation (docs/RELIABILITY.md). Each throws InputError naming the option:
//
//   OutputPaths paths;
//   paths.Add("-o", o.output);       // the folder exists and is writable, the path is no folder
//   paths.Add("--csv", o.csv);       // empty: not requested, skipped
//   paths.MustDifferFrom("scene file", o.scene);   // never overwrite an input
//   paths.Check();                   // also: no two outputs name the same file
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace spallkit::apps {

class OutputPaths {
 public:
  // An output named by `option`; an empty path means "not requested" unless `required`.
  void Add(const std::string& option, const std::string& path, bool required = false);
  // An input file that no output may overwrite.
  void MustDifferFrom(const std::string& what, const std::string& input_path);
  void Check() const;

 private:
  struct Entry {
    std::string option, path;
    bool required;
  };
  std::vector<Entry> outputs_;
  std::vector<std::pair<std::string, std::string>> inputs_;
};

}  // namespace spallkit::apps
