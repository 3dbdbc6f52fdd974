#include "core/checkpoint_io.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"

namespace {

struct Pod {
  int a;
  double b;
};

std::string Sample() {
  spallkit::CheckpointWriter out;
  out.Put(42);
  out.Put(true);
  out.Put(Pod{7, -2.5});
  out.PutVector(std::vector<double>{1.0, 2.0, 3.0});
  out.PutVector(std::vector<double>{});
  out.PutBytes("name");
  return out.Take();
}

// Catches the InputError of `f` and returns its message ("" if none was thrown).
template <typename F>
std::string ErrorOf(F f) {
  try {
    f();
  } catch (const spallkit::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(CheckpointIo, RoundTripsValuesVectorsAndBlobsInOrder) {
  const std::string bytes = Sample();
  // Layout: values as they are, lengths as uint64 before vectors and blobs.
  EXPECT_EQ(bytes.size(),
            sizeof(int) + sizeof(bool) + sizeof(Pod) + 8 + 3 * sizeof(double) + 8 + 8 + 4);
  spallkit::CheckpointReader in(bytes, "test state");
  EXPECT_EQ(in.Get<int>(), 42);
  EXPECT_TRUE(in.Get<bool>());
  const Pod p = in.Get<Pod>();
  EXPECT_EQ(p.a, 7);
  EXPECT_EQ(p.b, -2.5);
  std::vector<double> v(3);
  in.GetVectorInto(&v, "v");
  EXPECT_EQ(v, (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_TRUE(in.GetVector<double>().empty());
  EXPECT_EQ(in.GetBytes(), "name");
  EXPECT_TRUE(in.AtEnd());
}

TEST(CheckpointIo, TruncatedDataIsAnInputErrorNamingTheState) {
  const std::string bytes = Sample();
  for (size_t cut : {size_t{0}, size_t{3}, bytes.size() / 2, bytes.size() - 1}) {
    const std::string message = ErrorOf([&] {
      spallkit::CheckpointReader in(std::string_view(bytes).substr(0, cut), "contact pair 'a/b'");
      in.Get<int>();
      in.Get<bool>();
      in.Get<Pod>();
      in.GetVector<double>();
      in.GetVector<double>();
      in.GetBytes();
    });
    EXPECT_EQ(message, "contact pair 'a/b' is truncated") << "cut at " << cut;
  }
}

TEST(CheckpointIo, StoredSizeMustMatchTheModel) {
  spallkit::CheckpointWriter out;
  out.PutVector(std::vector<double>{1.0, 2.0});
  const std::string bytes = out.Take();
  spallkit::CheckpointReader in(bytes, "checkpoint");
  std::vector<double> v(3);
  EXPECT_EQ(ErrorOf([&] { in.GetVectorInto(&v, "x"); }), "checkpoint: 'x' has the wrong size");
  // A corrupt length larger than the data is caught before allocating it.
  spallkit::CheckpointWriter huge;
  huge.Put<std::uint64_t>(1ull << 60);
  const std::string huge_bytes = huge.Take();
  spallkit::CheckpointReader in2(huge_bytes, "checkpoint");
  EXPECT_EQ(ErrorOf([&] { in2.GetVector<double>(); }), "checkpoint is truncated");
}
