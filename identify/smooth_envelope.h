// Squared envelope through a smooth (Hann-shaped) band-pass, at the record's own sample rate: what
// the width fit correlates. The diagnosis's envelopes use ideal (brick-wall) bands, whose impulse
// response rings as sin(pi B t) / (pi B t): an impact's squared envelope then has side lobes at
// multiples of 1 / B (1.2 ms in an 833 Hz band) as strong as a spall's entry event (4.5 % of the
// peak for the first), which the width fit would take for a second event. The Hann window's side
// lobes are below -31 dB.
#pragma once

#include <span>
#include <vector>

namespace spallkit::identify {

// |analytic signal of x band-passed by a Hann window over [low_hz, high_hz]|^2, one value per
// sample of x. Throws InputError if the band is empty or beyond fs/2.
std::vector<double> SmoothBandSquaredEnvelope(std::span<const double> x,
                                              double fs_hz,
                                              double low_hz,
                                              double high_hz);

}  // namespace spallkit::identify
