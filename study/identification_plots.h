// PNG figures of an identification (`spall identify --plot-dir`): what each fit saw and chose.
//   cage_average.png  the cage-synchronous average (+/- its standard errors, model tolerance
//                     included) with the most probable count's humps, and the K = 1 fit
//   sidebands.png     |S_jm| over the noise for each spin harmonic j against the sideband order m
//   delay.png         the load-zone autocorrelation of the squared envelope with the entry-exit
//                     model and the fitted delay
#pragma once

#include <string>

#include "identify/identify.h"

namespace spallkit::study {

// Writes the figures that apply (none without a roller signature). Creates dir. Throws
// InputError when it cannot be written.
void WriteIdentificationPlots(const identify::Identification& id, const std::string& dir);

}  // namespace spallkit::study
