// Cepstrum pre-whitening (Borghesani et al. 2013, MSSP 36:370-384).
//
// x_w = IFFT(X / |X|): every spectral line and resonance is flattened to unit magnitude, keeping
// only the phase, i.e. only quefrency 0 of the real cepstrum survives. It removes discrete
// (gear, shaft) lines and the colouring of the transfer path without a speed reference, which
// makes bearing impulses stand out. Bins with |X| below 1e-12 * max|X| (and DC, as the mean is
// removed) are set to zero rather than amplified. The result is scaled to the RMS of x with its
// mean removed, so it keeps the input's units and level.
#pragma once

#include <complex>
#include <span>
#include <vector>

namespace spallkit::dsp {

// Throws InputError if x has fewer than 8 samples or a non-finite sample.
std::vector<double> CepstrumPrewhiten(std::span<const double> x);

// The same on a one-sided spectrum (n/2+1 bins of an n-point real record), in place: what
// CepstrumPrewhiten does between its forward and inverse FFTs. The result is the spectrum of
// CepstrumPrewhiten(x). See also EnvelopeAnalyzer::Prewhitened, which uses it to save two FFTs.
void WhitenSpectrum(std::span<std::complex<double>> spectrum, int n);

}  // namespace spallkit::dsp
