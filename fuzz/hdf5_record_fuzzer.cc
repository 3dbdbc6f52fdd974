// libFuzzer target: the HDF5 record reader (core/record_io.h ReadHdf5Record).
//
// Two modes, by the first byte:
//  - even: structured. The bytes describe up to three datasets (path, shape, float64 values of
//    any bit pattern, an optional sample_rate_hz attribute of any value, a units string) that are
//    written with core/hdf5.h and read back with a channel and sample rate also taken from the
//    bytes: this exercises the reader's own checks (channel choice, shapes, non-finite values,
//    rates).
//  - odd: raw. The remaining bytes are the file itself (start from the seed corpus's valid files):
//    this exercises the wrapper's handling of every error libhdf5 reports for a damaged file.
// Bad input must be an InputError.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/hdf5.h"
#include "core/record_io.h"

namespace {

class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t Byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  double Double() {
    std::uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits |= static_cast<std::uint64_t>(Byte()) << (8 * i);
    double v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }
  bool Empty() const { return pos_ >= size_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_, pos_ = 0;
};

const char* const kPaths[] = {"/signals/accel_y", "/signals/accel_z", "/a", "/g/b"};

void WriteStructured(Bytes& in, const std::string& path, spallkit::RecordOptions* options) {
  spallkit::h5::File f = spallkit::h5::File::Create(path);
  const int datasets = 1 + in.Byte() % 3;
  for (int k = 0; k < datasets; ++k) {
    const std::string name = kPaths[in.Byte() % 4];
    if (f.IsDataset(name)) continue;
    const int rows = in.Byte() % 3 == 0 ? 1 + in.Byte() % 3 : 1;
    const int cols = in.Byte() % 40;
    std::vector<double> values(static_cast<std::size_t>(rows) * cols);
    for (double& v : values) v = in.Byte() % 4 == 0 ? in.Double() : 0.01 * in.Byte();
    if (rows == 1)
      f.WriteDataset(name, values);
    else
      f.WriteDataset2D(name, values, rows, cols);
    if (in.Byte() % 2)
      f.SetAttribute(name, "sample_rate_hz", in.Byte() % 4 ? 1000.0 * in.Byte() : in.Double());
    if (in.Byte() % 2) f.SetAttribute(name, "units", "m/s^2");
  }
  f.Close();
  const std::uint8_t opt = in.Byte();
  if (opt & 1) options->channel = kPaths[(opt >> 1) % 4];
  if (opt & 8) options->channel = "nosuch";
  if (opt & 16) options->sample_rate_hz = opt & 32 ? in.Double() : 20000.0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const std::string path = "/tmp/spall_fuzz_hdf5_" + std::to_string(::getpid()) + ".h5";
  spallkit::RecordOptions options;
  try {
    if (data[0] % 2 == 0) {
      Bytes in(data + 1, size - 1);
      WriteStructured(in, path, &options);
    } else {
      if (data[0] & 2) options.sample_rate_hz = 20000.0;  // the seed files have no attribute
      FILE* f = std::fopen(path.c_str(), "wb");
      if (!f) return 0;
      std::fwrite(data + 1, 1, size - 1, f);
      std::fclose(f);
    }
    const spallkit::Record r = spallkit::ReadHdf5Record(path, options);
    if (!(r.sample_rate_hz > 0) || r.samples.size() < 2) __builtin_trap();
  } catch (const spallkit::InputError&) {
  }
  std::remove(path.c_str());
  return 0;
}
