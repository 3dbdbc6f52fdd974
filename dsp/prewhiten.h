// Cepstrum pre-whitening (Borghesani et al. 2013, MSSP 36:370-384).
//
// x_w = IFFT(X / |X|): every spectral line and resonance is flattened to unit magnitude, keeping
// only the phase, i.e. only quefrency 0 of the real cepstrum survives. It removes discrete
// (gear, shaft) lines and the colouring of the transfer path without a speed reference, which
// makes bearing impulses stand out. Bins with |X| below 1e-12 * max|X| (and DC, as the mean is
// removed) are set to zero rather than amplified. The result is scaled to the RMS of x with its
// mean removed, so it keeps the input's units and level.
#pragma once

#include <span>
#include <vector>

namespace spallkit::dsp {

// Throws InputError if x has fewer than 8 samples or a non-finite sample.
std::vector<double> CepstrumPrewhiten(std::span<const double> x);

}  // namespace spallkit::dsp
