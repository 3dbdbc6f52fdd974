// Tests for the record readers: every accepted layout, and one test per kind of bad input, each
// checking that the message is one line naming the file, the line and what was expected.
#include "core/record_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/hdf5.h"
#include "tests/measured_data.h"

namespace spallkit {
namespace {

namespace fs = std::filesystem;

class RecordTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("spallkit_record_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& name, const std::string& contents) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << contents;
    return path;
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  // The InputError message of reading `path`, or "(no exception)".
  static std::string ErrorOf(const std::string& path, const RecordOptions& options = {}) {
    try {
      ReadRecord(path, options);
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.find('\n'), std::string::npos) << "multi-line message: " << msg;
      return msg;
    }
    return "(no exception)";
  }

  fs::path dir_;
};

// Time column text the way the CWRU export prints it: n/fs with 9 decimals.
std::string CwruLikeCsv(double fs, size_t n, const std::string& header = "time_s,accel_g") {
  std::string s = header + "\n";
  char line[96];
  for (size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / fs;
    std::snprintf(line, sizeof line, "%.9f,%.17g\n", t, std::sin(2 * M_PI * 100 * t));
    s += line;
  }
  return s;
}

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)

TEST_F(RecordTest, CwruLikeHeaderAndNineDecimalTimeGiveTheExactRate) {
  // 9-decimal rounding is 2.4e-5 of a step at 48 kHz: the reader must accept it as uniform.
  for (double fs : {12000.0, 48000.0}) {
    const std::string path = Write("cwru.csv", CwruLikeCsv(fs, 20000));
    const Record r = ReadRecord(path);
    EXPECT_EQ(r.samples.size(), 20000u);
    EXPECT_NEAR(r.sample_rate_hz, fs, fs * 1e-8);
    EXPECT_EQ(r.channel, "accel_g");
    EXPECT_EQ(r.units, "g");
    EXPECT_EQ(r.source, path);
    EXPECT_NEAR(r.samples[5], std::sin(2 * M_PI * 100 * 5 / fs), 1e-15);
    EXPECT_NEAR(r.duration_s(), 20000 / fs, 1e-9);
  }
}

TEST_F(RecordTest, HeaderlessUniformFirstColumnIsTime) {
  const std::string path = Write("plain.txt", "0.0 1.5\n0.001 -2\n0.002 3e-1\n0.003 4\n");
  const Record r = ReadRecord(path);
  EXPECT_NEAR(r.sample_rate_hz, 1000.0, 1e-9);
  EXPECT_EQ(r.samples, (std::vector<double>{1.5, -2, 0.3, 4}));
  EXPECT_EQ(r.channel, "column 0");
  EXPECT_EQ(r.units, "");
}

TEST_F(RecordTest, HeaderlessNonMonotonicFirstColumnIsData) {
  const std::string path = Write("two.csv", "1,10\n3,20\n2,30\n");
  RecordOptions options;
  options.sample_rate_hz = 500;
  Record r = ReadRecord(path, options);
  EXPECT_EQ(r.samples, (std::vector<double>{1, 3, 2}));  // default: first non-time column
  EXPECT_EQ(r.sample_rate_hz, 500);
  options.channel = "1";  // 0-based data-column index
  r = ReadRecord(path, options);
  EXPECT_EQ(r.samples, (std::vector<double>{10, 20, 30}));
  EXPECT_EQ(r.channel, "column 1");
}

TEST_F(RecordTest, SingleColumnWithFsCommentAndCrlfAndBom) {
  const std::string path = Write(
      "one.dat", "\xEF\xBB\xBF# exported by a DAQ\r\n# fs = 48000 Hz\r\n\r\n0.25\r\n-0.5\r\n1\r\n");
  const Record r = ReadRecord(path);
  EXPECT_EQ(r.sample_rate_hz, 48000);
  EXPECT_EQ(r.samples, (std::vector<double>{0.25, -0.5, 1}));
}

TEST_F(RecordTest, SeparatorsAreDetected) {
  const std::string expected_header = "accel";
  for (const auto& [name, text] : std::vector<std::pair<std::string, std::string>>{
           {"semi.csv", "time;accel\n0;1\n0.5;2\n1;3\n"},
           {"tab.tsv", "time\taccel\n0\t1\n0.5\t2\n1\t3\n"},
           {"blank.txt", "  time    accel\n0   1\n  0.5 2  \n1      3\n"},
           {"quoted.csv", "\"time\",\"accel\"\n0, 1\n0.5 ,+2\n1,3\n"}}) {
    const Record r = ReadRecord(Write(name, text));
    EXPECT_EQ(r.samples, (std::vector<double>{1, 2, 3})) << name;
    EXPECT_DOUBLE_EQ(r.sample_rate_hz, 2.0) << name;
    EXPECT_EQ(r.channel, expected_header) << name;
  }
}

TEST_F(RecordTest, TimeHeaderVariantsAndUnits) {
  // Milliseconds are scaled: step 0.05 ms -> 20 kHz.
  Record r = ReadRecord(Write("ms.csv", "Time (ms),Accel Y (m/s^2)\n0,1\n0.05,2\n0.1,3\n"));
  EXPECT_NEAR(r.sample_rate_hz, 20000, 1e-6);
  EXPECT_EQ(r.channel, "Accel Y (m/s^2)");
  EXPECT_EQ(r.units, "m/s^2");
  r = ReadRecord(Write("us.csv", "accel_y_m_s2,t [us]\n1,0\n2,50\n3,100\n"));
  EXPECT_NEAR(r.sample_rate_hz, 20000, 1e-6);  // time need not be the first column
  EXPECT_EQ(r.units, "m/s^2");
  r = ReadRecord(Write("time_ms.csv", "time_ms,v_mm_s\n0,1\n1,2\n2,3\n"));
  EXPECT_NEAR(r.sample_rate_hz, 1000, 1e-9);
  EXPECT_EQ(r.units, "mm/s");
}

TEST_F(RecordTest, ChannelByNameCaseInsensitiveOrIndex) {
  const std::string path = Write("multi.csv", "time_s,DE_g,FE_g,BA_g\n0,1,10,100\n0.1,2,20,200\n");
  RecordOptions options;
  options.channel = "FE_g";
  EXPECT_EQ(ReadRecord(path, options).samples, (std::vector<double>{10, 20}));
  options.channel = "ba_G";
  EXPECT_EQ(ReadRecord(path, options).samples, (std::vector<double>{100, 200}));
  options.channel = "0";  // the time column is not counted
  EXPECT_EQ(ReadRecord(path, options).channel, "DE_g");
  options.channel = "2";
  EXPECT_EQ(ReadRecord(path, options).channel, "BA_g");
}

TEST_F(RecordTest, GivenRateOverridesTheTimeColumn) {
  const std::string path = Write("jitter.csv", "time_s,a\n0,1\n0.1,2\n0.25,3\n");
  RecordOptions options;
  options.sample_rate_hz = 10;
  const Record r = ReadRecord(path, options);
  EXPECT_EQ(r.sample_rate_hz, 10);
  EXPECT_EQ(r.samples.size(), 3u);
}

TEST_F(RecordTest, FsCommentMustAgreeWithTimeColumn) {
  EXPECT_NEAR(ReadRecord(Write("ok.csv", "# fs=10\ntime,a\n0,1\n0.1,2\n0.2,3\n")).sample_rate_hz,
              10,
              1e-12);
  const std::string path = Write("bad.csv", "time,a\n# fs=12000\n0,1\n0.1,2\n0.2,3\n");
  const std::string msg = ErrorOf(path);
  EXPECT_CONTAINS(msg, path + ":2: '# fs=12000' disagrees with the time column (10 Hz)");
}

TEST_F(RecordTest, JitterJustInsideToleranceIsAcceptedJustOutsideRejected) {
  // Exactly printed times (17 digits), one sample displaced by 0.5e-4 and 2e-4 of a step.
  auto make = [](double displacement_steps) {
    std::string s = "t,x\n";
    char line[96];
    for (int i = 0; i < 100; ++i) {
      double t = i * 1e-3;
      if (i == 50) t += displacement_steps * 1e-3;
      std::snprintf(line, sizeof line, "%.17g,%d\n", t, i);
      s += line;
    }
    return s;
  };
  EXPECT_NO_THROW(ReadRecord(Write("in.csv", make(0.5e-4))));
  const std::string path = Write("out.csv", make(2e-4));
  const std::string msg = ErrorOf(path);
  EXPECT_CONTAINS(msg, path + ":52: field 1 ('t'): non-uniform time");  // row 50 is line 52
}

// ---- bad input: one test per case -------------------------------------------------------------

TEST_F(RecordTest, MissingFile) {
  const std::string path = Path("nope.csv");
  EXPECT_CONTAINS(ErrorOf(path), path + ": cannot open (No such file or directory)");
  EXPECT_CONTAINS(ErrorOf(Path("nope.h5")), "nope.h5: cannot open");
}

TEST_F(RecordTest, DirectoryInsteadOfFile) {
  EXPECT_EQ(ErrorOf(dir_.string()), dir_.string() + ": is a directory, expected a record file");
}

TEST_F(RecordTest, TrailingSeparatorIsNotAnExtraField) {
  const Record r = ReadRecord(Write("trail.csv", "time_s,a,\n0,1,\n0.5,2,\n1,3,\n"));
  EXPECT_EQ(r.samples, (std::vector<double>{1, 2, 3}));
  const std::string path = Write("trail_missing.csv", "time_s,a,b,\n0,1,2,\n0.5,2,\n");
  EXPECT_EQ(ErrorOf(path), path + ":3: 2 fields, expected 3 (as in the header)");
}

TEST_F(RecordTest, EmptyFileAndCommentsOnly) {
  std::string path = Write("empty.csv", "");
  EXPECT_EQ(ErrorOf(path), path + ": empty file, expected a header and/or rows of numbers");
  path = Write("comments.csv", "# nothing\n\n   \n");
  EXPECT_EQ(ErrorOf(path), path + ": empty file, expected a header and/or rows of numbers");
}

TEST_F(RecordTest, HeaderOnly) {
  const std::string path = Write("header.csv", "# fs=100\ntime_s,accel_g\n");
  EXPECT_EQ(ErrorOf(path), path + ": no data rows after the header (line 2)");
}

TEST_F(RecordTest, SingleRow) {
  const std::string path = Write("one.csv", "time_s,accel_g\n0,1\n");
  EXPECT_CONTAINS(ErrorOf(path), path + ":2: only 1 data row");
}

TEST_F(RecordTest, NonNumericCellNamesLineAndField) {
  const std::string path = Write("abc.csv", "# c\ntime_s,accel_g\n0,1\n0.1,abc\n0.2,3\n");
  EXPECT_EQ(ErrorOf(path), path + ":4: field 2 ('accel_g'): expected a number, found 'abc'");
  const std::string comma = Write("decimal_comma.csv", "t;a\n0;1,5\n1;2,5\n");
  EXPECT_CONTAINS(ErrorOf(comma), comma + ":2: field 2 ('a'): expected a number, found '1,5'");
}

TEST_F(RecordTest, NanAndInfAreRejected) {
  std::string path = Write("nan.csv", "time_s,accel_g\n0,1\n0.1,nan\n0.2,3\n");
  EXPECT_EQ(ErrorOf(path), path + ":3: field 2 ('accel_g'): 'nan' is not a finite number");
  path = Write("inf.csv", "0,1\n1,-inf\n");
  EXPECT_CONTAINS(ErrorOf(path), path + ":2: field 2: '-inf' is not a finite number");
}

TEST_F(RecordTest, DecreasingTime) {
  const std::string path = Write("dec.csv", "time_s,a\n0,1\n0.1,2\n0.1,3\n0.3,4\n");
  EXPECT_CONTAINS(ErrorOf(path),
                  path + ":4: field 1 ('time_s'): time 0.1 does not increase (previous 0.1)");
}

TEST_F(RecordTest, NonUniformTime) {
  const std::string path = Write("gap.csv", "time_s,a\n0,1\n0.1,2\n0.2,3\n0.4,4\n0.5,5\n");
  const std::string msg = ErrorOf(path);
  EXPECT_CONTAINS(msg, path + ":");
  EXPECT_CONTAINS(msg, "non-uniform time");
  EXPECT_CONTAINS(msg, "give the sample rate");
}

TEST_F(RecordTest, UnknownChannelAndIndexOutOfRange) {
  const std::string path = Write("ch.csv", "time_s,DE_g,FE_g\n0,1,2\n0.1,2,3\n");
  RecordOptions options;
  options.channel = "BA_g";
  EXPECT_EQ(ErrorOf(path, options),
            path +
                ": channel 'BA_g' not found; signal columns are 'DE_g', 'FE_g' (or a 0-based "
                "index)");
  options.channel = "2";
  EXPECT_EQ(ErrorOf(path, options),
            path +
                ": channel index 2 out of range: the file has 2 signal columns (0-based index "
                "0..1, time column not counted)");
  options.channel = "time_s";
  EXPECT_CONTAINS(ErrorOf(path, options), "is the time column");
}

// A channel may be named without the unit its column carries ('accel_z' for 'accel_z (m/s^2)',
// as spall simulate --csv writes them, or 'DE [g]'), unless two columns share that name.
TEST_F(RecordTest, ChannelNamedWithoutItsUnit) {
  const std::string path =
      Write("units.csv", "time (s),accel_y (m/s^2),accel_z (m/s^2),DE [g]\n0,1,2,3\n0.1,4,5,6\n");
  RecordOptions options;
  options.channel = "accel_z";
  EXPECT_EQ(ReadRecord(path, options).samples, (std::vector<double>{2, 5}));
  options.channel = "de";
  EXPECT_EQ(ReadRecord(path, options).samples, (std::vector<double>{3, 6}));
  options.channel = "accel_y (m/s^2)";
  EXPECT_EQ(ReadRecord(path, options).samples, (std::vector<double>{1, 4}));
  const std::string twice = Write("twice.csv", "time_s,a (g),a (m/s^2)\n0,1,2\n0.1,3,4\n");
  options.channel = "a";
  EXPECT_EQ(ErrorOf(twice, options),
            twice +
                ": channel 'a' names more than one column ('a (g)', 'a (m/s^2)'); give the "
                "whole column name");
}

TEST_F(RecordTest, RowWithMissingOrExtraFields) {
  std::string path = Write("short.csv", "time_s,a,b\n0,1,2\n0.1,2\n");
  EXPECT_EQ(ErrorOf(path), path + ":3: 2 fields, expected 3 (as in the header)");
  path = Write("empty_cell.csv", "time_s,a,b\n0,1,2\n0.1,,3\n");
  EXPECT_EQ(ErrorOf(path), path + ":3: field 2 ('a') is empty, expected a number");
  path = Write("long.txt", "0 1\n1 2 3\n");
  EXPECT_EQ(ErrorOf(path), path + ":2: 3 fields, expected 2 (as in the first data row)");
}

TEST_F(RecordTest, NoSampleRateAnywhere) {
  const std::string path = Write("nofs.csv", "a,b\n1,2\n3,4\n");
  EXPECT_CONTAINS(ErrorOf(path), path + ": no sample rate");
}

TEST_F(RecordTest, NonPositiveGivenRate) {
  const std::string path = Write("ok.csv", "0,1\n1,2\n2,3\n");
  RecordOptions options;
  for (double bad :
       {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    options.sample_rate_hz = bad;
    EXPECT_CONTAINS(ErrorOf(path, options), path + ": sample rate must be a positive number");
  }
  const std::string comment = Write("zero.csv", "# fs=0\n1\n2\n");
  EXPECT_EQ(ErrorOf(comment),
            comment + ":1: '# fs=' expects a positive sample rate in Hz, found '0'");
}

TEST_F(RecordTest, OnlyATimeColumn) {
  const std::string path = Write("t.csv", "time_s\n0\n0.1\n");
  EXPECT_CONTAINS(ErrorOf(path), path + ": only a time column");
}

// ---- HDF5 -------------------------------------------------------------------------------------

TEST_F(RecordTest, Hdf5SimulateLayoutDefaultAndNamedChannel) {
  const std::string path = Path("run.h5");
  {
    h5::File f = h5::File::Create(path);
    f.WriteDataset("/time", std::vector<double>{0, 5e-5, 1e-4});
    f.WriteDataset("/signals/accel_y", std::vector<double>{1, 2, 3});
    f.WriteDataset("/signals/accel_z", std::vector<double>{4, 5, 6});
    for (const char* d : {"/signals/accel_y", "/signals/accel_z"}) {
      f.SetAttribute(d, "sample_rate_hz", 20000.0);
      f.SetAttribute(d, "units", "m/s^2");
    }
  }
  Record r = ReadRecord(path);
  EXPECT_EQ(r.samples, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(r.sample_rate_hz, 20000);
  EXPECT_EQ(r.units, "m/s^2");
  EXPECT_EQ(r.channel, "/signals/accel_y");
  EXPECT_EQ(r.source, path + ":/signals/accel_y");
  RecordOptions options;
  options.channel = "signals/accel_z";
  r = ReadRecord(path, options);
  EXPECT_EQ(r.samples, (std::vector<double>{4, 5, 6}));
  options.channel = "/signals/accel_x";
  EXPECT_EQ(ErrorOf(path, options),
            path +
                ": dataset /signals/accel_x not found (datasets: /signals/accel_y, "
                "/signals/accel_z, /time)");
}

TEST_F(RecordTest, Hdf5OnlyCandidateIsTheDefaultAndMatlabVectorsAreAccepted) {
  const std::string path = Path("one.hdf5");
  {
    h5::File f = h5::File::Create(path);
    f.WriteDataset2D("/x", std::vector<double>{1, 2, 3, 4}, 1, 4);  // MATLAB [1 x n]
    f.SetAttribute("/x", "sample_rate_hz", 100.0);
    f.WriteDataset("/meta/rpm", std::vector<double>{1200});
  }
  RecordOptions options;
  options.channel = "/x";
  EXPECT_EQ(ReadRecord(path, options).samples, (std::vector<double>{1, 2, 3, 4}));
  const std::string path2 = Path("cand.h5");
  {
    h5::File f = h5::File::Create(path2);
    f.WriteDataset("/a/b", std::vector<double>{1, 2, 3});
    f.SetAttribute("/a/b", "sample_rate_hz", 100.0);
    f.WriteDataset("/time", std::vector<double>{0, 1, 2});
  }
  EXPECT_EQ(ReadRecord(path2).channel, "/a/b");
}

TEST_F(RecordTest, Hdf5BadInputs) {
  const std::string path = Path("bad.h5");
  {
    h5::File f = h5::File::Create(path);
    f.WriteDataset2D("/contact/roller_outer", std::vector<double>(6, 1.0), 2, 3);
    f.WriteDataset("/nofs", std::vector<double>{1, 2, 3});
    f.WriteDataset("/nan", std::vector<double>{1, NAN, 3});
    f.SetAttribute("/nan", "sample_rate_hz", 10.0);
    f.WriteDataset("/zero_fs", std::vector<double>{1, 2});
    f.SetAttribute("/zero_fs", "sample_rate_hz", 0.0);
    f.WriteDataset("/nan2", std::vector<double>{1, 2});
    f.SetAttribute("/nan2", "sample_rate_hz", 10.0);
  }
  RecordOptions options;
  EXPECT_EQ(ErrorOf(path),
            path +
                ": several candidate channels (/nan, /nan2, /zero_fs); choose one as the "
                "channel");
  options.channel = "/contact/roller_outer";
  EXPECT_EQ(ErrorOf(path, options),
            path + ": /contact/roller_outer: expected a 1-D dataset, found shape 2 x 3");
  options.channel = "/nofs";
  EXPECT_EQ(ErrorOf(path, options),
            path + ": /nofs: no sample_rate_hz attribute; give the sample rate");
  options.sample_rate_hz = 50;  // ... which then works
  EXPECT_EQ(ReadRecord(path, options).sample_rate_hz, 50);
  options.sample_rate_hz = 0;
  options.channel = "/nan";
  EXPECT_EQ(ErrorOf(path, options), path + ": /nan: sample 1 is nan, expected finite values");
  options.channel = "/zero_fs";
  EXPECT_EQ(ErrorOf(path, options),
            path + ": /zero_fs: sample_rate_hz = 0, expected a positive number");

  const std::string none = Path("none.h5");
  { h5::File::Create(none).WriteDataset("/time", std::vector<double>{0, 1}); }
  EXPECT_EQ(ErrorOf(none),
            none +
                ": no 1-D dataset with a sample_rate_hz attribute (datasets: /time); choose "
                "one as the channel");
  const std::string text = Write("text.h5", "time_s,a\n0,1\n");
  EXPECT_EQ(ErrorOf(text), text + ": not an HDF5 file");
}

// ---- writing ----------------------------------------------------------------------------------

TEST_F(RecordTest, WriteCsvRecordRoundTripsBitExactly) {
  std::vector<double> t(500), a(500);
  for (size_t i = 0; i < t.size(); ++i) {
    t[i] = static_cast<double>(i) / 20000.0;
    a[i] = std::sin(0.1 * i) * 9.81 + 1e-12 * i;
  }
  const std::string path = Path("out.csv");
  WriteCsvRecord(path, {{"time_s", t}, {"accel_y_m_s2", a}});
  const Record r = ReadRecord(path);
  EXPECT_EQ(r.samples, a);  // bit-exact
  EXPECT_NEAR(r.sample_rate_hz, 20000, 20000 * 1e-12);
  EXPECT_EQ(r.channel, "accel_y_m_s2");
  EXPECT_EQ(r.units, "m/s^2");
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << "temp file left";
  }
  EXPECT_THROW(WriteCsvRecord(path, {{"a", {1, 2}}, {"b", {1}}}), InputError);
  EXPECT_THROW(WriteCsvRecord(path, {{"a,b", {1}}}), InputError);
  EXPECT_THROW(WriteCsvRecord(Path("no/dir/x.csv"), {{"a", {1}}}), InputError);
}

// ---- real data (skipped when absent) ----------------------------------------------------------

TEST(RecordMeasured, CwruRecordsReadWithTheirManifestRates) {
  const fs::path dir = spallkit::testing::MeasuredDataDir();
  struct Expected {
    const char* file;
    double fs;
    size_t n;
  };
  const Expected expected[] = {{"cwru_normal_0hp_rec097_DE_48k.csv", 48000, 144000},
                               {"cwru_IR007_0hp_rec105_DE_12k.csv", 12000, 60000},
                               {"cwru_B007_0hp_rec118_DE_12k.csv", 12000, 60000},
                               {"cwru_OR007at6_0hp_rec130_DE_12k.csv", 12000, 60000}};
  bool any = false;
  for (const Expected& e : expected) {
    const fs::path path = dir / e.file;
    if (!fs::exists(path)) continue;
    any = true;
    const Record r = ReadRecord(path.string());
    EXPECT_EQ(r.samples.size(), e.n) << e.file;
    EXPECT_NEAR(r.sample_rate_hz, e.fs, e.fs * 1e-6) << e.file;
    EXPECT_EQ(r.units, "g") << e.file;
    double sum_sq = 0;
    for (double v : r.samples) sum_sq += v * v;
    const double rms = std::sqrt(sum_sq / r.samples.size());
    EXPECT_GT(rms, 0.01) << e.file;  // accelerometer data in g: tenths of a g
    EXPECT_LT(rms, 5.0) << e.file;
  }
  if (!any) GTEST_SKIP() << "CWRU records not present in " << dir;
}

TEST(RecordSample, BuiltInSampleRecordReads) {
  const fs::path path =
      fs::path(SPALLKIT_SOURCE_DIR) / "datasets/samples/n205em_roller_defect_1200rpm.csv";
  if (!fs::exists(path)) GTEST_SKIP() << "sample record not generated yet";
  const Record r = ReadRecord(path.string());
  EXPECT_NEAR(r.sample_rate_hz, 20000, 1e-6);
  EXPECT_EQ(r.samples.size(), 40000u);
  EXPECT_EQ(r.channel, "accel_y_m_s2");
  EXPECT_EQ(r.units, "m/s^2");
  // The record is impulsive (roller hits ringing a resonance), as the generator documents.
  double mean = 0;
  for (double v : r.samples) mean += v;
  mean /= r.samples.size();
  double m2 = 0, m4 = 0;
  for (double v : r.samples) {
    m2 += (v - mean) * (v - mean);
    m4 += std::pow(v - mean, 4);
  }
  m2 /= r.samples.size();
  m4 /= r.samples.size();
  EXPECT_GT(m4 / (m2 * m2), 4.0);
  EXPECT_NEAR(std::sqrt(m2), 1.1, 0.3);
}

}  // namespace
}  // namespace spallkit
