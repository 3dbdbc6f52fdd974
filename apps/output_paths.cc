#include "apps/output_paths.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/atomic_file.h"
#include "core/error.h"

namespace spallkit::apps {
namespace fs = std::filesystem;
namespace {

// The same file for two spellings ("out.h5", "./out.h5"), whether or not it exists yet.
bool SameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(fs::absolute(a, ec), ec) ==
         fs::weakly_canonical(fs::absolute(b, ec), ec);
}

void CheckWritable(const std::string& option, const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw InputError(option + " " + path + ": is a directory, expected a file name");
  try {
    CheckReplaceableOutput(path);
  } catch (const InputError& e) {
    throw InputError(option + " " + e.what());
  }
  fs::path folder = fs::path(path).parent_path();
  if (folder.empty()) folder = ".";
  if (!fs::exists(folder, ec))
    throw InputError(option + " " + path + ": folder '" + folder.string() + "' does not exist");
  if (!fs::is_directory(folder, ec))
    throw InputError(option + " " + path + ": '" + folder.string() + "' is not a folder");
  // The result is written as a temporary file in the same folder and renamed (core/atomic_file):
  // create and remove one such file now (permission bits alone say nothing for root, or on a
  // read-only or virtual file system).
  std::string probe = (folder / ".spall-write-test-XXXXXX").string();
  const int fd = ::mkstemp(probe.data());
  if (fd < 0)
    throw InputError(option + " " + path + ": folder '" + folder.string() + "' is not writable (" +
                     std::strerror(errno) + ")");
  ::close(fd);
  ::unlink(probe.c_str());
}

}  // namespace

void OutputPaths::Add(const std::string& option, const std::string& path, bool required) {
  outputs_.push_back({option, path, required});
}

void OutputPaths::MustDifferFrom(const std::string& what, const std::string& input_path) {
  if (!input_path.empty()) inputs_.emplace_back(what, input_path);
}

void OutputPaths::Check() const {
  for (std::size_t i = 0; i < outputs_.size(); ++i) {
    const Entry& e = outputs_[i];
    if (e.path.empty()) {
      if (e.required) throw InputError(e.option + ": empty file name");
      continue;
    }
    CheckWritable(e.option, e.path);
    for (const auto& [what, input] : inputs_)
      if (SameFile(e.path, input))
        throw InputError(e.option + " " + e.path + ": is the " + what +
                         " (an output would overwrite an input)");
    for (std::size_t j = 0; j < i; ++j)
      if (!outputs_[j].path.empty() && SameFile(e.path, outputs_[j].path))
        throw InputError(e.option + " " + e.path + ": same file as " + outputs_[j].option +
                         " (each output needs its own file)");
  }
}

}  // namespace spallkit::apps
