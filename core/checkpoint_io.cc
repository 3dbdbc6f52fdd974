#include "core/checkpoint_io.h"

#include "core/error.h"

namespace spallkit {

void CheckpointWriter::PutBytes(std::string_view bytes) {
  Put<std::uint64_t>(bytes.size());
  bytes_.append(bytes);
}

CheckpointReader::CheckpointReader(std::string_view bytes, std::string what)
    : bytes_(bytes), what_(std::move(what)) {}

const char* CheckpointReader::Take(size_t n) {
  if (n > Remaining()) Truncated();
  const char* p = bytes_.data() + pos_;
  pos_ += n;
  return p;
}

std::string CheckpointReader::GetBytes() {
  const std::uint64_t n = Get<std::uint64_t>();
  if (n > Remaining()) Truncated();
  return std::string(Take(n), n);
}

void CheckpointReader::Truncated() const { throw InputError(what_ + " is truncated"); }

void CheckpointReader::WrongSize(std::string_view name) const {
  throw InputError(what_ + ": '" + std::string(name) + "' has the wrong size");
}

}  // namespace spallkit
