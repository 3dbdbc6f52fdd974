// Logarithm and exponential written so that a loop calling them vectorises.
//
// libm's log1p / exp are calls the compiler cannot vectorise without -ffast-math and glibc's
// vector variants (libmvec), which a portable build does not assume. Eigen's array log/exp
// vectorise but at the build's baseline width with no run-time dispatch, and are slower than these
// on the pair-score loop (bench/diagnose_benchmark BM_BandFourCombs; docs/PERFORMANCE.md). These
// are branch-free versions of fdlibm's algorithms (Sun's e_log.c and e_exp.c: the same reductions
// and minimax coefficients, errors below 1 ulp), restricted to the ranges a detection statistic
// needs, so that there are no special cases to branch on:
//   LogAtLeastOne(x)   = ln x,      x in [1, 2^1023], finite;
//   Log1pNonNegative(y) = ln(1 + y), y in [0, 2^1023], finite;
//   ExpNonPositive(x)  = e^x,       x <= 0; e^x for x < -708 is returned as e^-708 (~3e-308).
// Outside those ranges the results are meaningless (no error is raised). With fused multiply-add
// (a multi-versioned caller, core/multiversion.h) the results move by round-off only.
// Verified against libm in tests/dsp/vector_math_test.cc (within 2 ulp).
#pragma once

#include <cstdint>
#include <cstring>

namespace spallkit::dsp {

namespace vector_math_detail {

inline uint64_t Bits(double x) {
  uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}

inline double FromBits(uint64_t u) {
  double x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}

}  // namespace vector_math_detail

inline double LogAtLeastOne(double x) {
  using namespace vector_math_detail;
  constexpr double kLn2Hi = 6.93147180369123816490e-01;  // 0x3fe62e42 fee00000
  constexpr double kLn2Lo = 1.90821492927058770002e-10;  // 0x3dea39ef 35793c76
  constexpr double kLg1 = 6.666666666666735130e-01, kLg2 = 3.999999999940941908e-01,
                   kLg3 = 2.857142874366239149e-01, kLg4 = 2.222219843214978396e-01,
                   kLg5 = 1.818357216161805012e-01, kLg6 = 1.531383769920937332e-01,
                   kLg7 = 1.479819860511658591e-01;
  // x = 2^k m with m in [sqrt(2)/2, sqrt(2)): shifting the exponent field by the high word of
  // sqrt(2)/2 moves the binade boundary to sqrt(2) (fdlibm's reduction, on the whole word).
  constexpr uint64_t kOffset = uint64_t{0x3ff00000 - 0x3fe6a09e} << 32;
  const uint64_t u = Bits(x) + kOffset;
  // k as a double without an integer conversion (x >= 1: 0 <= k <= 1023): the biased exponent
  // placed in the mantissa of 2^52.
  const double k = FromBits((u >> 52) | 0x4330000000000000ull) - (4503599627370496.0 + 1023.0);
  const double m = FromBits((u & 0x000fffffffffffffull) + (uint64_t{0x3fe6a09e} << 32));
  const double f = m - 1.0;
  const double hfsq = 0.5 * f * f;
  const double s = f / (2.0 + f);
  const double z = s * s;
  const double w = z * z;
  const double t1 = w * (kLg2 + w * (kLg4 + w * kLg6));
  const double t2 = z * (kLg1 + w * (kLg3 + w * (kLg5 + w * kLg7)));
  const double r = t2 + t1;
  return k * kLn2Hi - ((hfsq - (s * (hfsq + r) + k * kLn2Lo)) - f);
}

// ln(1 + y) from the logarithm of u = fl(1 + y) and the rounding error of that sum, (u - 1) - y,
// to first order: ln(1 + y) = ln u - ((u - 1) - y) / u.
inline double Log1pNonNegative(double y) {
  const double u = 1.0 + y;
  return LogAtLeastOne(u) - ((u - 1.0) - y) / u;
}

inline double ExpNonPositive(double x) {
  using namespace vector_math_detail;
  constexpr double kLn2Hi = 6.93147180369123816490e-01;
  constexpr double kLn2Lo = 1.90821492927058770002e-10;
  constexpr double kInvLn2 = 1.44269504088896338700e+00;
  constexpr double kP1 = 1.66666666666666019037e-01, kP2 = -2.77777777770155933842e-03,
                   kP3 = 6.61375632143793436117e-05, kP4 = -1.65339022054652515390e-06,
                   kP5 = 4.13813679705723846039e-08;
  constexpr double kShifter = 6755399441055744.0;  // 1.5 * 2^52: adding it rounds to an integer
  x = x < -708.0 ? -708.0 : x;
  // x = k ln2 + r, |r| <= ln2 / 2; k = round(x / ln2) read from the low bits of the shifted sum.
  const double shifted = x * kInvLn2 + kShifter;
  const double k = shifted - kShifter;
  const uint64_t k_bits = Bits(shifted) - Bits(kShifter);  // k in two's complement
  const double hi = x - k * kLn2Hi;
  const double lo = k * kLn2Lo;
  const double r = hi - lo;
  const double t = r * r;
  const double c = r - t * (kP1 + t * (kP2 + t * (kP3 + t * (kP4 + t * kP5))));
  const double y = 1.0 - ((lo - (r * c) / (2.0 - c)) - hi);
  // 2^k for -1022 <= k <= 0: the biased exponent k + 1023 in the exponent field.
  return y * FromBits((k_bits + 1023) << 52);
}

}  // namespace spallkit::dsp
