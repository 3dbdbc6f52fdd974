#include "core/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace spallkit {

void CheckReplaceableOutput(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status s = std::filesystem::symlink_status(path, ec);
  if (ec || !std::filesystem::exists(s) || std::filesystem::is_regular_file(s)) return;
  const char* what = std::filesystem::is_directory(s) ? "a folder"
                     : std::filesystem::is_symlink(s) ? "a symbolic link"
                     : std::filesystem::is_fifo(s)    ? "a pipe"
                     : std::filesystem::is_socket(s)  ? "a socket"
                                                      : "a device";
  throw InputError(path + ": is " + std::string(what) +
                   ", not a regular file (outputs are written to a new file and renamed over the "
                   "path, which would replace it)");
}

AtomicFile::AtomicFile(std::string final_path)
    : final_path_(std::move(final_path)),
      temp_path_(final_path_ + ".tmp-" + std::to_string(::getpid())) {
  CheckReplaceableOutput(final_path_);
}

AtomicFile::~AtomicFile() {
  if (!committed_) std::remove(temp_path_.c_str());
}

void AtomicFile::Commit() {
  if (std::rename(temp_path_.c_str(), final_path_.c_str()) != 0) {
    throw InputError(final_path_ + ": cannot write (" + std::strerror(errno) + ")");
  }
  committed_ = true;
}

void WriteFileAtomically(const std::string& path, const std::string& contents) {
  AtomicFile file(path);
  {
    std::ofstream out(file.temp_path(), std::ios::binary);
    if (!out) throw InputError(path + ": cannot open for writing (" + std::strerror(errno) + ")");
    out << contents;
    out.flush();
    if (!out) throw InputError(path + ": write failed");
  }
  file.Commit();
}

}  // namespace spallkit
