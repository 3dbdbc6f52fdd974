// Binary checkpoint serialisation: one writer and one reader for every part of a simulation that
// saves state (solver, elements, contact pairs, constraints, rigid rollers, recorder).
//
// Format: values in native byte order and layout (a checkpoint is read back by the same build on
// the same machine). Put<T> writes a trivially copyable value as is; PutVector and PutBytes write a
// uint64 length followed by the data. The reader throws InputError naming what it was reading
// (`what`) when the data end early or a stored size does not match.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace spallkit {

class CheckpointWriter {
 public:
  template <typename T>
  void Put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "Put needs a trivially copyable value");
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  // Length (uint64) and elements.
  template <typename T>
  void PutVector(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>, "PutVector needs trivially copyable values");
    Put<std::uint64_t>(values.size());
    bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  // Length (uint64) and bytes: a nested blob or a name.
  void PutBytes(std::string_view bytes);

  const std::string& bytes() const { return bytes_; }
  std::string Take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class CheckpointReader {
 public:
  // `bytes` must outlive the reader; `what` names the state in error messages (e.g. "checkpoint:
  // contact pair 'roller0/outer'").
  CheckpointReader(std::string_view bytes, std::string what);

  template <typename T>
  T Get() {
    static_assert(std::is_trivially_copyable_v<T>, "Get needs a trivially copyable value");
    T value;
    std::memcpy(&value, Take(sizeof value), sizeof value);
    return value;
  }
  // A vector of any stored length.
  template <typename T>
  std::vector<T> GetVector() {
    const std::uint64_t n = Get<std::uint64_t>();
    if (n > Remaining() / sizeof(T)) Truncated();
    std::vector<T> values(n);
    if (n > 0) std::memcpy(values.data(), Take(n * sizeof(T)), n * sizeof(T));
    return values;
  }
  // Into a vector whose size is known: the stored length must equal values->size().
  template <typename T>
  void GetVectorInto(std::vector<T>* values, std::string_view name) {
    if (Get<std::uint64_t>() != values->size()) WrongSize(name);
    if (!values->empty())
      std::memcpy(values->data(), Take(values->size() * sizeof(T)), values->size() * sizeof(T));
  }
  std::string GetBytes();

  size_t Remaining() const { return bytes_.size() - pos_; }
  bool AtEnd() const { return pos_ == bytes_.size(); }
  const std::string& what() const { return what_; }

 private:
  const char* Take(size_t n);
  [[noreturn]] void Truncated() const;
  [[noreturn]] void WrongSize(std::string_view name) const;

  std::string_view bytes_;
  size_t pos_ = 0;
  std::string what_;
};

}  // namespace spallkit
