// Writing output files so that a reader never sees a half-written file.
//
// Output goes to "<path>.tmp-<pid>" and is renamed over <path> only on Commit(). If the writer
// is destroyed without Commit() (an exception, an error return), the temporary file is removed.
#pragma once

#include <fstream>
#include <string>

namespace spallkit {

// Throws InputError naming `path` when something other than a regular file is there (a folder, a
// device such as /dev/null, a pipe, a socket or a symbolic link): the rename would replace it.
void CheckReplaceableOutput(const std::string& path);

class AtomicFile {
 public:
  // Throws InputError (CheckReplaceableOutput) when final_path is not a regular file or absent.
  explicit AtomicFile(std::string final_path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // The temporary path to write to (for libraries that open files themselves, e.g. HDF5, OpenCV).
  const std::string& temp_path() const { return temp_path_; }
  const std::string& final_path() const { return final_path_; }

  // Renames the temporary file over the final path. Throws InputError if that fails.
  void Commit();

 private:
  std::string final_path_;
  std::string temp_path_;
  bool committed_ = false;
};

// Writes `contents` to `path` atomically. Throws InputError naming the path on failure.
void WriteFileAtomically(const std::string& path, const std::string& contents);

}  // namespace spallkit
