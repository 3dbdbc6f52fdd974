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

// The k-th smallest (0-based) of each window data[starts[a], starts[a] + w), out[a] the value
// SelectKth returns. For windows that overlap much, in order (a running median): the previous
// window's answer brackets the next one between two pivots a few percent either side, so a
// window costs one pass that counts the values below the lower pivot and keeps those between,
// and a selection among the few kept; where the answer falls outside, SelectKth. Requires
// 0 <= k < w and every window inside data.
void SlidingSelectKth(
    const double* data, std::span<const int> starts, int w, int k, std::span<double> out);

}  // namespace spallkit::dsp
