// Antoni's fast kurtogram (Antoni 2007, MSSP 21:108-124) on the 1/3-binary band tree.
//
// Band partition (identical to Antoni's Fast_Kurtogram and MATLAB's kurtogram): level 0 is
// [0, fs/2]; binary level k has 2^k nodes of width fs / 2^(k+1); the ternary level k + log2(3) - 1
// (printed 1.6, 2.6, ...) has 3 * 2^(k-1) nodes of width fs / (3 * 2^k). Rows are
// 0, 1, 1.6, 2, 2.6, ..., L-1, L-0.4, L: 2L rows in all.
//
// Implementation: the frequency-domain equivalent of the filter bank, not the 16-tap filters.
// Each node's complex envelope c is the ideal band-pass of the one-sided spectrum of the whole
// record (one forward FFT, shared with the SES) sampled on a grid of m >= 2B points over the
// record (B = bins in the node), by an inverse FFT of size m. Why: (1) the passbands are exact
// and adjacent, with none of the ripple and overlap of the short quasi-analytic filters (which
// shift the best node when a resonance sits on an edge); (2) the decimation is exact: |c|^2 spans
// +-(B-1) bins and |c|^4 +-2(B-1), so with m >= 2B - 1 the moments <|c|^2>, <|c|^4> over the
// samples equal those of the continuous envelope (Antoni's filter bank keeps the same factor-2
// oversampling, rate fs/2^k for bands fs/2^(k+1) wide; critical sampling, m >= B, would halve the
// cost but misses envelope peaks: 27 % kurtosis error in nodes of 1000 bins on test signals).
// Rows form two chains in which each node is the union of two children: binary L, ..., 1, 0 and
// ternary L-0.4, ..., 1.6. Only the deepest row of a chain is transformed directly; a parent's
// even samples are the sum of its children's (bins sit at k mod m on every grid, a phase choice
// that leaves |c| unchanged) and its odd samples one transform of half its size, so the other
// rows cost half. The transforms run in single precision (fftwf, spectrum scaled to unit RMS bin
// first): the kurtosis is within ~1e-7 relative of the double-precision definition (tests check
// 1e-6 against the full-rate envelope).
// The record is treated as periodic (as any FFT method does, and as the filter bank's start-up
// transient does): a jump between its last and first samples acts as one impulse. It matters only
// in nodes with almost no energy of their own, e.g. far from the lines of a pure synthetic tone.
//
// Per node: K = <|c|^4> / <|c|^2>^2 - 2 (0 for Gaussian noise, -1 for a pure tone), clipped at 0.
// The mean of the record is removed (bin 0 zeroed), so the DC node sees no offset; a node is
// half-open [low, high) in bins except the last one of a level, which also takes the Nyquist bin.
// A node holding less than 1e-20 of the record's energy (only rounding residue) reports 0.
// Nodes whose centre is below options.min_center_hz are computed and shown but never chosen as
// `best` (use it to keep shaft-rate knocks and the DC region out of the choice).
#pragma once

#include <span>
#include <vector>

#include "dsp/band.h"
#include "dsp/envelope.h"

namespace spallkit::dsp {

struct KurtogramOptions {
  // Deepest binary level L. 0: automatic, min(9, floor(log2 N) - 7) (Antoni's bound log2 N - 7,
  // capped at 9, the level of MATLAB's bearing example, whose nodes are fs/1024 wide).
  // Allowed: 1 <= L <= floor(log2 N) - 4 (nodes of at least 8 FFT bins); else InputError.
  int max_level = 0;
  double min_center_hz = 0;  // nodes centred below this are never `best`
  // Threads (OpenMP) over the two chains of rows (binary, ternary), so at most 2 are used;
  // 0 = OpenMP's default. The result does not depend on it. Default 1: callers that run several
  // analyses at once (tests, sweeps) should not oversubscribe.
  int threads = 1;
  // Keep the squared envelopes |c|^2 of every node in rows whose node width lies in
  // [keep_envelopes_min_hz, keep_envelopes_max_hz] (Kurtogram::squared_envelopes), so that a
  // caller (the diagnosis) can take those nodes' squared envelope spectra from them with one
  // forward transform each, instead of demodulating the band a second time. Default: none kept.
  // The samples are exact (ideal band-pass, 2x oversampled, see above), so the SES of a node up
  // to its width in cyclic frequency is alias-free.
  double keep_envelopes_min_hz = 0;
  double keep_envelopes_max_hz = -1;
  // Optional: vectors whose memory the kept envelopes reuse (moved into
  // Kurtogram::squared_envelopes, which the caller may move back after use). ~2 MB per kept row at
  // 10 s, 48 kHz: fresh allocations would cost page faults on every call.
  std::vector<std::vector<float>>* envelope_buffers = nullptr;
};

struct KurtogramNode {
  double level = 0;  // 0, 1, 1.585 (printed 1.6), 2, ...
  int index = 0;     // 0 .. nodes-1 in the level, low to high frequency
  double center_hz = 0, bandwidth_hz = 0, kurtosis = 0;
  Band band() const { return {center_hz - 0.5 * bandwidth_hz, center_hz + 0.5 * bandwidth_hz}; }
};

struct Kurtogram {
  std::vector<double> levels;                 // 0, 1, 1.585, 2, 2.585, ..., L
  std::vector<std::vector<double>> kurtosis;  // per level row: kurtosis of each node, low to high
  KurtogramNode best;                         // highest kurtosis among eligible nodes
  double sample_rate_hz = 0;
  int max_level = 0;  // L actually used
  int samples = 0;    // N, the record's length

  // Rows kept by KurtogramOptions::keep_envelopes_*: squared_envelopes[row] holds each node's
  // |c|^2 (node after node, envelope_sizes[row] samples each, in single precision and in the
  // kurtogram's internal scale); empty for the other rows. The true squared envelope (a sine of
  // amplitude A in the node gives A^2, EnvelopeAnalyzer's convention) is envelope_gain2 times it.
  // Sample s of a node lies at time s * N / (m fs); the node's bins sit at k mod m, which only
  // rotates the phase of c, so |c|^2 is the band's squared envelope itself.
  std::vector<std::vector<float>> squared_envelopes;
  std::vector<int> envelope_sizes;
  double envelope_gain2 = 0;

  // FFT bins [*lo, *hi) of node `index` of row `row` (the last node of a row also holds Nyquist).
  void NodeBins(int row, int index, int* lo, int* hi) const;

  // Width of the nodes of row r, and all nodes (row by row), for other band selectors.
  double BandwidthHz(int row) const;
  std::vector<KurtogramNode> Nodes() const;
};

// Throws InputError if x is too short (< 64 samples), has non-finite samples, fs <= 0 or
// max_level is out of range.
Kurtogram FastKurtogram(std::span<const double> x,
                        double fs_hz,
                        const KurtogramOptions& options = {});

// Same, reusing the record's spectrum already computed by an EnvelopeAnalyzer (no second FFT).
Kurtogram FastKurtogram(const EnvelopeAnalyzer& analyzer, const KurtogramOptions& options = {});

}  // namespace spallkit::dsp
