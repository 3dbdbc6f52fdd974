// Tests for the HDF5 wrapper: round trips, attributes, listing, and one-line errors.
#include "core/hdf5.h"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"

namespace spallkit::h5 {
namespace {

namespace fs = std::filesystem;

class Hdf5Test : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("spallkit_hdf5_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

// Runs `command` and returns its stdout.
std::string Capture(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::string out;
  if (!pipe) return out;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe.get())) > 0) out.append(buffer, n);
  return out;
}

TEST_F(Hdf5Test, RoundTripsOneDimensionalDatasetWithAttributes) {
  const std::string path = Path("run.h5");
  std::vector<double> accel(1000);
  for (size_t i = 0; i < accel.size(); ++i) accel[i] = std::sin(0.01 * i) * 1e3 + 1.0 / 3.0;
  {
    File file = File::Create(path);
    file.WriteDataset("/signals/accel_y", accel);  // creates /signals
    file.SetAttribute("/signals/accel_y", "sample_rate_hz", 20000.0);
    file.SetAttribute("/signals/accel_y", "units", "m/s^2");
    file.SetAttribute("/", "spallkit_version", std::string("0.1.0"));
    file.SetAttribute("/", "scene", "[bearing]\nname = \"N205EM\"  # µ-ok UTF-8\n");
    file.Close();
    EXPECT_FALSE(file.is_open());
  }
  const File file = File::OpenReadOnly(path);
  std::vector<size_t> dims;
  const std::vector<double> back = file.ReadDataset("/signals/accel_y", &dims);
  ASSERT_EQ(dims, std::vector<size_t>{1000});
  ASSERT_EQ(back.size(), accel.size());
  for (size_t i = 0; i < accel.size(); ++i) ASSERT_EQ(back[i], accel[i]) << i;  // bit-exact
  EXPECT_EQ(file.ReadDoubleAttribute("/signals/accel_y", "sample_rate_hz"), 20000.0);
  EXPECT_EQ(file.ReadStringAttribute("signals/accel_y", "units"), "m/s^2");
  EXPECT_EQ(file.ReadStringAttribute("/", "spallkit_version"), "0.1.0");
  EXPECT_EQ(file.ReadStringAttribute("/", "scene"), "[bearing]\nname = \"N205EM\"  # µ-ok UTF-8\n");
  EXPECT_FALSE(file.ReadDoubleAttribute("/signals/accel_y", "no_such").has_value());
  EXPECT_FALSE(file.ReadStringAttribute("/", "no_such").has_value());
  const std::vector<std::string> attrs = file.ListAttributes("/signals/accel_y");
  EXPECT_EQ(attrs, (std::vector<std::string>{"sample_rate_hz", "units"}));
}

TEST_F(Hdf5Test, TwoDimensionalDatasetKeepsRowMajorOrderAndShape) {
  const std::string path = Path("contact.h5");
  const size_t rows = 4, cols = 3;
  std::vector<double> values(rows * cols);
  for (size_t i = 0; i < values.size(); ++i) values[i] = static_cast<double>(i);
  {
    File file = File::Create(path);
    file.WriteDataset2D("/contact/roller_outer", values, rows, cols);
    EXPECT_THROW(file.WriteDataset2D("/contact/bad", values, 5, 3), InputError);
  }
  const File file = File::OpenReadOnly(path);
  EXPECT_EQ(file.DatasetDims("/contact/roller_outer"), (std::vector<size_t>{rows, cols}));
  std::vector<size_t> dims;
  EXPECT_EQ(file.ReadDataset("/contact/roller_outer", &dims), values);
  EXPECT_EQ(dims, (std::vector<size_t>{4, 3}));

  // h5dump (Debian hdf5-tools) is the independent check of the C order: element (1, 2) is 5.
  if (std::system("command -v h5dump > /dev/null 2>&1") != 0) GTEST_SKIP() << "h5dump absent";
  const std::string dump = Capture("h5dump -d /contact/roller_outer -A 0 '" + path + "'");
  EXPECT_NE(dump.find("DATASPACE  SIMPLE { ( 4, 3 ) / ( 4, 3 ) }"), std::string::npos) << dump;
  EXPECT_NE(dump.find("(1,0): 3, 4, 5,"), std::string::npos) << dump;
}

TEST_F(Hdf5Test, StringAttributesAreVariableLengthUtf8) {
  const std::string path = Path("attrs.h5");
  {
    File file = File::Create(path);
    file.WriteDataset("/time", std::vector<double>{0.0, 1.0});
    file.SetAttribute("/time", "units", "s");
  }
  if (std::system("command -v h5dump > /dev/null 2>&1") != 0) GTEST_SKIP() << "h5dump absent";
  const std::string dump = Capture("h5dump -a /time/units '" + path + "'");
  // What h5py needs to return `str`: a variable-length string with UTF-8 character set.
  EXPECT_NE(dump.find("STRSIZE H5T_VARIABLE"), std::string::npos) << dump;
  EXPECT_NE(dump.find("CSET H5T_CSET_UTF8"), std::string::npos) << dump;
  EXPECT_NE(dump.find("\"s\""), std::string::npos) << dump;
}

TEST_F(Hdf5Test, ReadsFixedLengthStringAndIntegerAttributesWrittenByOtherTools) {
  const std::string path = Path("foreign.h5");
  {
    // Written with the raw C API the way MATLAB's h5writeatt or older tools do.
    const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, 8);
    H5Tset_strpad(type, H5T_STR_NULLPAD);
    const hid_t a = H5Acreate2(f, "units", type, space, H5P_DEFAULT, H5P_DEFAULT);
    const char text[8] = {'g', 0, 0, 0, 0, 0, 0, 0};
    H5Awrite(a, type, text);
    H5Aclose(a);
    const hid_t b = H5Acreate2(f, "fs", H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT);
    const int fs = 12000;
    H5Awrite(b, H5T_NATIVE_INT, &fs);
    H5Aclose(b);
    // A float32 dataset: read back converted to double.
    const hsize_t n = 3;
    const hid_t dspace = H5Screate_simple(1, &n, nullptr);
    const hid_t d =
        H5Dcreate2(f, "x32", H5T_IEEE_F32LE, dspace, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const float x[3] = {0.5f, -1.25f, 3.0f};
    H5Dwrite(d, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, x);
    H5Dclose(d);
    H5Sclose(dspace);
    H5Tclose(type);
    H5Sclose(space);
    H5Fclose(f);
  }
  const File file = File::OpenReadOnly(path);
  EXPECT_EQ(file.ReadStringAttribute("/", "units"), "g");
  EXPECT_EQ(file.ReadDoubleAttribute("/", "fs"), 12000.0);
  EXPECT_EQ(file.ReadDataset("x32"), (std::vector<double>{0.5, -1.25, 3.0}));
  // Type mismatches are errors, not garbage.
  EXPECT_THROW(file.ReadDoubleAttribute("/", "units"), InputError);
  EXPECT_THROW(file.ReadStringAttribute("/", "fs"), InputError);
}

TEST_F(Hdf5Test, ExistsListAndReplace) {
  const std::string path = Path("tree.h5");
  File file = File::Create(path);
  file.WriteDataset("/time", std::vector<double>{0, 1, 2});
  file.WriteDataset("/signals/accel_y", std::vector<double>{1, 2, 3});
  file.WriteDataset("/signals/accel_z", std::vector<double>{4, 5, 6});
  file.WriteDataset("/energy/kinetic", std::vector<double>{7});
  file.CreateGroup("/empty/group");
  file.WriteDataset("/signals/accel_z", std::vector<double>{9, 9});  // replaced
  EXPECT_TRUE(file.Exists("/"));
  EXPECT_TRUE(file.Exists("/signals"));
  EXPECT_TRUE(file.Exists("signals/accel_y"));
  EXPECT_TRUE(file.Exists("/empty/group"));
  EXPECT_FALSE(file.Exists("/signals/accel_x"));
  EXPECT_FALSE(file.Exists("/nope/deeper/still"));
  EXPECT_FALSE(file.Exists("/time/below_a_dataset"));
  EXPECT_TRUE(file.IsDataset("/time"));
  EXPECT_FALSE(file.IsDataset("/signals"));
  EXPECT_EQ(file.ListDatasets(),
            (std::vector<std::string>{
                "/energy/kinetic", "/signals/accel_y", "/signals/accel_z", "/time"}));
  EXPECT_EQ(file.ReadDataset("/signals/accel_z"), (std::vector<double>{9, 9}));
  EXPECT_THROW(file.CreateGroup("/time"), InputError);
}

TEST_F(Hdf5Test, ErrorsAreOneLineNamingFileAndObject) {
  auto message_of = [](auto&& f) -> std::string {
    try {
      f();
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no exception)";
  };
  const std::string missing = Path("missing.h5");
  std::string msg = message_of([&] { File::OpenReadOnly(missing); });
  EXPECT_NE(msg.find(missing), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;

  const std::string text = Path("not_hdf5.h5");
  std::ofstream(text) << "time_s,accel\n0,1\n";
  msg = message_of([&] { File::OpenReadOnly(text); });
  EXPECT_NE(msg.find("not an HDF5 file"), std::string::npos) << msg;

  msg = message_of([&] { File::Create(Path("no/such/dir/x.h5")); });
  EXPECT_NE(msg.find("no/such/dir/x.h5"), std::string::npos) << msg;

  const std::string path = Path("ok.h5");
  { File::Create(path).WriteDataset("/signals/accel_y", std::vector<double>{1, 2}); }
  const File file = File::OpenReadOnly(path);
  msg = message_of([&] { file.ReadDataset("/signals/accel_q"); });
  EXPECT_EQ(msg, path + ": dataset /signals/accel_q not found");
  msg = message_of([&] { file.ReadDoubleAttribute("/nope", "x"); });
  EXPECT_NE(msg.find("/nope: no such group or dataset"), std::string::npos) << msg;

  File closed = File::Create(Path("closed.h5"));
  closed.Close();
  EXPECT_THROW(closed.WriteDataset("/x", std::vector<double>{1}), InputError);
  EXPECT_THROW(closed.Close(), InputError);
}

TEST_F(Hdf5Test, MovedFromFileIsClosedAndTargetKeepsWorking) {
  File a = File::Create(Path("move.h5"));
  File b = std::move(a);
  EXPECT_FALSE(a.is_open());  // NOLINT(bugprone-use-after-move): documented state
  b.WriteDataset("/x", std::vector<double>{1.5});
  EXPECT_EQ(b.ReadDataset("/x"), std::vector<double>{1.5});
}

}  // namespace
}  // namespace spallkit::h5
