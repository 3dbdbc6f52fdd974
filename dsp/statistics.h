// Time-domain condition indicators of a record.
#pragma once

#include <span>

namespace spallkit::dsp {

// Moments are central and population-normalised (divide by N). kurtosis is the plain (Pearson)
// kurtosis, 3 for Gaussian data, 1.5 for a sine; crest_factor = peak / rms with rms including the
// mean (the usual sensor-level RMS). For a constant record, kurtosis and skewness are 0 (undefined
// spread) and crest_factor is 1 (0 if all samples are 0).
struct TimeStatistics {
  double mean = 0, rms = 0, peak = 0, crest_factor = 0, kurtosis = 0, skewness = 0;
  int count = 0;
};

// Throws InputError if x is empty or holds a non-finite sample.
TimeStatistics ComputeTimeStatistics(std::span<const double> x);

// sum v_j^2 with independent vector accumulators: a plain loop is one serial chain of dependent
// additions (the compiler may not reassociate them), several times slower on long spectra.
double SumOfSquares(std::span<const double> v);

}  // namespace spallkit::dsp
