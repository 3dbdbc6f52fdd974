#include "core/bearing.h"

#include <gtest/gtest.h>

#include "core/error.h"

using spallkit::CatalogBearing;
using spallkit::ComputeFrequencies;

// The paper's verification: f_b = 115.08 Hz and f_c = 8.31 Hz for N205EM at 1200 rpm.
TEST(BearingKinematics, N205EMAt1200RpmMatchesThePaper) {
  const auto f = ComputeFrequencies(CatalogBearing("N205EM"), 1200.0 / 60.0);
  EXPECT_NEAR(f.f_b_hz, 115.08, 0.01);
  EXPECT_NEAR(f.cage_hz, 8.31, 0.005);
  EXPECT_NEAR(f.bpfo_hz, 108.052, 0.001);
  EXPECT_NEAR(f.bpfi_hz, 151.948, 0.001);
}

// CWRU's published drive-end orders (multiples of shaft speed).
TEST(BearingKinematics, Cwru6205OrdersMatchPublishedValues) {
  const auto f = ComputeFrequencies(CatalogBearing("6205"), 1.0);
  EXPECT_NEAR(f.bpfi_hz, 5.4152, 2e-4);
  EXPECT_NEAR(f.bpfo_hz, 3.5848, 2e-4);
  EXPECT_NEAR(f.cage_hz, 0.39828, 1e-4);
  EXPECT_NEAR(f.f_b_hz, 4.7135, 2e-4);
}

// CWRU fan end 6203: BPFI 4.9469, BPFO 3.0530, FTF 0.3817, 2xBSF 3.9874.
TEST(BearingKinematics, Cwru6203OrdersMatchPublishedValues) {
  const auto f = ComputeFrequencies(CatalogBearing("6203"), 1.0);
  EXPECT_NEAR(f.bpfi_hz, 4.9469, 2e-3);
  EXPECT_NEAR(f.bpfo_hz, 3.0530, 2e-3);
  EXPECT_NEAR(f.cage_hz, 0.3817, 3e-4);
  EXPECT_NEAR(f.f_b_hz, 3.9874, 3e-3);
}

TEST(BearingKinematics, UnknownNameAndBadSpeedAreInputErrors) {
  EXPECT_THROW(CatalogBearing("X999"), spallkit::InputError);
  EXPECT_THROW(ComputeFrequencies(CatalogBearing("6205"), 0.0), spallkit::InputError);
  EXPECT_THROW(spallkit::CustomBearing(9, 40.0, 39.0, 0.0), spallkit::InputError);
}
