#include "core/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/error.h"

namespace spallkit {

AtomicFile::AtomicFile(std::string final_path)
    : final_path_(std::move(final_path)),
      temp_path_(final_path_ + ".tmp-" + std::to_string(::getpid())) {}

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
