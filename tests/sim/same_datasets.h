// Shared by the resume tests: two simulation files hold the same datasets, bit for bit.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/hdf5.h"

namespace spallkit::testing {

// Both files hold the same datasets (at least min_datasets: a full run's 17) with bit-identical
// samples (NaN equals NaN: the cage slip ratio at rest).
inline void ExpectSameDatasets(const std::string& path_a,
                               const std::string& path_b,
                               size_t min_datasets = 17) {
  h5::File fa = h5::File::OpenReadOnly(path_a), fb = h5::File::OpenReadOnly(path_b);
  const auto names = fa.ListDatasets();
  EXPECT_EQ(names, fb.ListDatasets());
  EXPECT_GE(names.size(), min_datasets);
  for (const std::string& p : names) {
    SCOPED_TRACE(p);
    const auto va = fa.ReadDataset(p), vb = fb.ReadDataset(p);
    ASSERT_EQ(va.size(), vb.size());
    for (size_t i = 0; i < va.size(); ++i)
      if (!(std::isnan(va[i]) && std::isnan(vb[i]))) {
        ASSERT_EQ(va[i], vb[i]) << "sample " << i;
      }
  }
}

}  // namespace spallkit::testing
