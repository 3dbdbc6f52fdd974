#include "core/input_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <system_error>

#include "core/error.h"

namespace spallkit {

std::string ReadInputFile(const std::string& path, const std::string& what) {
  std::error_code ec;
  const std::filesystem::file_status s = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(s))
    throw InputError(path + ": is a directory, expected " + what);
  const bool regular = std::filesystem::is_regular_file(s);
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!file) throw InputError(path + ": cannot open (" + std::strerror(errno) + ")");
  std::string text;
  char buffer[1 << 16];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) {
    text.append(buffer, n);
    if (!regular && text.size() > kMaxStreamedInputBytes)
      throw InputError(path + ": not a regular file and more than " +
                       std::to_string(kMaxStreamedInputBytes >> 20) + " MB read; expected " + what);
  }
  if (std::ferror(file.get()))
    throw InputError(path + ": read error (" + std::strerror(errno) + "); expected " + what);
  return text;
}

}  // namespace spallkit
