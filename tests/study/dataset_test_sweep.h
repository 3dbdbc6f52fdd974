// A tiny 12-case sweep for the dataset tests (hybrid model, 2 ms per case on a coarse housing
// mesh: each case takes a fraction of a second) and a comparison of two case files.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/hdf5.h"

namespace spallkit::study {

// Writes the sweep into `dir` (created) and returns its path.
inline std::string WriteTinySweep(const std::string& dir, int random_cases = 2) {
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/tiny.toml";
  std::ofstream(path) << "[base]\nscene = \"" SPALLKIT_SOURCE_DIR
                         "/datasets/scenes/paper-verification.toml\"\n"
                         "[base.set]\n"
                         "\"model.fidelity\" = \"hybrid\"\n"
                         "\"mesh.size_mm\" = 2.0\n"
                         "\"run.duration_s\" = 0.002\n"
                         "\"operation.ramp_s\" = 0.001\n"
                         "\"operation.load_ramp_s\" = 0.001\n"
                         "\"run.output_rate_hz\" = 20000.0\n"
                         "[grid]\n"
                         "\"defects.0.width_mm\" = [0.8, 1.6, 2.2]\n"
                         "\"operation.speed_rpm\" = [1000.0, 2000.0]\n"
                         "[random]\n"
                         "cases = "
                      << random_cases
                      << "\nseed = 3\n"
                         "\"operation.radial_load_n\" = { uniform = [5000.0, 12000.0] }\n";
  return path;
}

// Every dataset bit-identical and every root attribute equal except wall_seconds.
inline void ExpectSameCaseFile(const std::string& a, const std::string& b) {
  const h5::File fa = h5::File::OpenReadOnly(a), fb = h5::File::OpenReadOnly(b);
  ASSERT_EQ(fa.ListDatasets(), fb.ListDatasets()) << a << " vs " << b;
  for (const std::string& d : fa.ListDatasets()) {
    // Bitwise: NaN samples (the cage slip ratio at rest) compare equal to themselves.
    const std::vector<double> da = fa.ReadDataset(d), db = fb.ReadDataset(d);
    EXPECT_TRUE(da.size() == db.size() &&
                std::memcmp(da.data(), db.data(), da.size() * sizeof(double)) == 0)
        << a << ": " << d;
  }
  ASSERT_EQ(fa.ListAttributes("/"), fb.ListAttributes("/"));
  for (const std::string& name : fa.ListAttributes("/")) {
    if (name == "wall_seconds") continue;
    try {
      EXPECT_EQ(fa.ReadDoubleAttribute("/", name), fb.ReadDoubleAttribute("/", name)) << name;
    } catch (const std::exception&) {
      EXPECT_EQ(fa.ReadStringAttribute("/", name), fb.ReadStringAttribute("/", name)) << name;
    }
  }
}

}  // namespace spallkit::study
