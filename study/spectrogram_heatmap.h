// Shared pieces of the record and diagnosis figures: squared units for power axes, and an STFT
// spectrogram laid out as a heatmap (time across, frequency up, dB over the 80 dB below the peak).
#pragma once

#include <string>

#include "dsp/spectra.h"
#include "plot/plot.h"

namespace spallkit::study {

// "g" -> "g^2", "m/s^2" -> "(m/s^2)^2": a compound unit is bracketed before squaring.
std::string SquaredUnits(const std::string& units);

// The heatmap of `sg` (from dsp::Stft of a record sampled at `fs_hz` whose first sample is at
// `t0_s`), with axis and colour-bar labels in the record's `units` ("unit" when empty). The
// caller sets the title and the image size.
plot::Heatmap SpectrogramHeatmap(const dsp::Spectrogram& sg,
                                 double fs_hz,
                                 double t0_s,
                                 double duration_s,
                                 const std::string& units);

}  // namespace spallkit::study
