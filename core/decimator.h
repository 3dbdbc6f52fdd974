// Streaming low-pass + decimation for signals produced sample by sample (simulator sensors).
//
// The explicit solver advances in steps of a few nanoseconds whose length changes as the mesh
// deforms, while users want accelerations at e.g. 20 kHz. The sensor recorder therefore
//  1. samples the sensor VELOCITY on a uniform fine grid (rate = factor x output rate) and takes
//     differences, which is the exact box-car average of the acceleration over each fine interval
//     (a first, mild anti-alias filter that also copes with the non-uniform solver step), then
//  2. passes that fine-rate signal through this windowed-sinc FIR low-pass (cut-off at 0.8 x the
//     output Nyquist frequency) and keeps every factor-th output sample.
// Only the FIR state is kept (no growth with run length); Push() is allocation-free once the
// output vector has capacity.
#pragma once

#include <vector>

namespace spallkit {

class StreamingDecimator {
 public:
  // factor >= 1: input rate / output rate. taps_per_factor sets the FIR length (taps =
  // 2 * taps_per_factor * factor + 1); 8 gives > 60 dB stop-band rejection with a Blackman window.
  explicit StreamingDecimator(int factor, int taps_per_factor = 8);

  // Feeds one input sample; appends an output sample to *out every `factor` inputs (once the
  // filter has been primed, the first output corresponds to input index 0: the group delay is
  // compensated by starting the filter with the first sample held constant).
  void Push(double x, std::vector<double>* out);

  int factor() const { return factor_; }
  const std::vector<double>& taps() const { return taps_; }

  // State for checkpoint/restart.
  std::vector<double> SaveState() const;
  void RestoreState(const std::vector<double>& state);

 private:
  int factor_;
  std::vector<double> taps_;
  std::vector<double> history_;  // circular buffer of the last taps_.size() inputs
  long long count_ = 0;          // inputs pushed
  int head_ = 0;
};

// Designs a linear-phase low-pass FIR (Blackman-windowed sinc), unit DC gain.
// cutoff is a fraction of the sampling rate (0 < cutoff < 0.5).
std::vector<double> DesignLowPass(int num_taps, double cutoff);

}  // namespace spallkit
