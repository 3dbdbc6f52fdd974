#include "core/decimator.h"

#include <cmath>
#include <numbers>

#include "core/error.h"

namespace spallkit {

std::vector<double> DesignLowPass(int num_taps, double cutoff) {
  SPALLKIT_CHECK(num_taps >= 1 && cutoff > 0 && cutoff < 0.5, "bad FIR design");
  std::vector<double> h(num_taps);
  const double mid = 0.5 * (num_taps - 1);
  double sum = 0.0;
  for (int i = 0; i < num_taps; ++i) {
    const double t = i - mid;
    const double sinc =
        t == 0.0 ? 2.0 * cutoff
                 : std::sin(2.0 * std::numbers::pi * cutoff * t) / (std::numbers::pi * t);
    const double w = num_taps == 1
                         ? 1.0
                         : 0.42 - 0.5 * std::cos(2.0 * std::numbers::pi * i / (num_taps - 1)) +
                               0.08 * std::cos(4.0 * std::numbers::pi * i / (num_taps - 1));
    h[i] = sinc * w;
    sum += h[i];
  }
  for (double& v : h) v /= sum;
  return h;
}

StreamingDecimator::StreamingDecimator(int factor, int taps_per_factor) : factor_(factor) {
  SPALLKIT_CHECK(factor >= 1 && taps_per_factor >= 1, "decimation factor and taps must be >= 1");
  if (factor == 1) {
    taps_ = {1.0};
  } else {
    taps_ = DesignLowPass(2 * taps_per_factor * factor + 1, 0.8 * 0.5 / factor);
  }
  history_.assign(taps_.size(), 0.0);
}

void StreamingDecimator::Push(double x, std::vector<double>* out) {
  const int n = static_cast<int>(taps_.size());
  const int delay = (n - 1) / 2;
  if (count_ == 0) {
    // Prime with the first sample so the start has no artificial step.
    for (double& h : history_) h = x;
  }
  history_[head_] = x;
  head_ = (head_ + 1) % n;
  ++count_;
  // Output k corresponds to input index k * factor, available once `delay` more samples arrived.
  const long long centre = count_ - 1 - delay;
  if (centre < 0 || centre % factor_ != 0) return;
  double acc = 0.0;
  int idx = head_;  // oldest sample
  for (int i = 0; i < n; ++i) {
    acc += taps_[i] * history_[idx];
    idx = idx + 1 == n ? 0 : idx + 1;
  }
  out->push_back(acc);
}

std::vector<double> StreamingDecimator::SaveState() const {
  std::vector<double> s(history_);
  s.push_back(static_cast<double>(count_));
  s.push_back(static_cast<double>(head_));
  return s;
}

void StreamingDecimator::RestoreState(const std::vector<double>& state) {
  SPALLKIT_CHECK(state.size() == history_.size() + 2, "decimator state size mismatch");
  std::copy(state.begin(), state.end() - 2, history_.begin());
  count_ = static_cast<long long>(state[state.size() - 2]);
  head_ = static_cast<int>(state.back());
}

}  // namespace spallkit
