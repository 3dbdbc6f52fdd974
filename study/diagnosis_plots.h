// PNG figures of a diagnosis (plot/plot.h):
//   ses.png          squared envelope spectrum of the chosen band with dashed, labelled markers at
//                    each family's harmonics (one colour per family) and thin ones at sidebands;
//                    the band is in the title
//   spectrogram.png  STFT power in dB (viridis) of the record
//   kurtogram.png    the fast-kurtogram map (levels x frequency), chosen band framed
#pragma once

#include <span>
#include <string>
#include <vector>

#include "dsp/diagnose.h"

namespace spallkit::study {

// Writes the three PNGs into `dir` (created if missing) and returns their paths. `signal` is the
// record the diagnosis analysed (for the spectrogram). Throws InputError if dir cannot be made
// or a file cannot be written.
std::vector<std::string> WriteDiagnosisPlots(const dsp::Diagnosis& diagnosis,
                                             std::span<const double> signal,
                                             const std::string& dir);

}  // namespace spallkit::study
