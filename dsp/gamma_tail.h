// Tails of the sum of m independent Exp(1) variables (the comb score's null law, dsp/detection.h).
#pragma once

namespace spallkit::dsp {

// log of the regularised upper incomplete gamma Q(m, x) for integer m >= 1 (sum of m Exp(1)).
double LogGammaUpperTail(int m, double x);
// Smallest x with mult * Q(m, x) <= alpha.
double GammaThreshold(int m, double alpha_over_mult);

}  // namespace spallkit::dsp
