// A frequency band [low_hz, high_hz] of a real signal, the unit of demodulation and fault search.
#pragma once

namespace spallkit::dsp {

// Edges in Hz. Used as the demodulation band of an envelope spectrum and as a kurtogram node.
struct Band {
  double low_hz = 0;
  double high_hz = 0;
  double center_hz() const { return 0.5 * (low_hz + high_hz); }
  double width_hz() const { return high_hz - low_hz; }
};

}  // namespace spallkit::dsp
