// Order statistics (medians) of long arrays, for the robust noise floor and the record checks.
#pragma once

#include <span>

namespace spallkit::dsp {

// k-th smallest (0-based) of data[0, n): the value std::nth_element returns (an order statistic
// is unique as a value), by quickselect with median-of-3 pivots over a branch-free, order-keeping
// partition (AVX-512 compress where the CPU has it, chosen at run time). data is not modified;
// scratch must hold 3 (n + 8) values. Requires 0 <= k < n.
double SelectKth(const double* data, int n, int k, double* scratch);

// The same with its own scratch.
double SelectKth(std::span<const double> data, int k);

}  // namespace spallkit::dsp
