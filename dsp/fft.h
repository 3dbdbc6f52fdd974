// FFTW transforms behind small objects, with plans made once per process and reused.
//
// Planning is the expensive part of FFTW for large sizes: even with FFTW_ESTIMATE a 480,000-point
// real plan costs about as much as several executions (twiddle tables are rebuilt whenever the
// last plan using them is destroyed). So plans live in a process-wide cache keyed by kind, size,
// batch count and placement, are created on first use under a mutex (FFTW's planner is not
// thread-safe) and kept until ForgetFftPlans() or exit. Execution uses FFTW's new-array interface
// on each object's own aligned scratch buffers, so different objects may run concurrently in
// different threads; one object must not be used by two threads at once.
//
// Rigor: FFTW_ESTIMATE by default. FFTW_MEASURE finds faster plans for awkward sizes but planning
// a 480,000-point transform that way takes seconds, far more than a record analysed once saves;
// PlanRigor::kMeasure is there for sizes reused thousands of times.
//
// Data are passed as raw pointers to std::complex<double>, which is layout-compatible with
// fftw_complex. Transforms are unnormalised, as in FFTW: Forward then Inverse multiplies by n.
#pragma once

#include <complex>
#include <cstddef>
#include <memory>
#include <vector>

namespace spallkit::dsp {

enum class PlanRigor { kEstimate, kMeasure };

// Arrays from fftw_malloc, with the SIMD alignment FFTW's plans are made for: passing them to
// RealFft / ComplexFft avoids the copy through scratch that unaligned arrays need.
struct FftwDeleter {
  void operator()(void* p) const;
};
template <class T>
using FftwArray = std::unique_ptr<T[], FftwDeleter>;
FftwArray<std::complex<double>> AllocateComplex(size_t n);
FftwArray<double> AllocateReal(size_t n);

// Real <-> half-complex transforms of size n: Forward maps n reals to n/2+1 complex bins
// X_k = sum_t x_t exp(-2 pi i k t / n); Inverse maps n/2+1 bins back to n reals (times n).
class RealFft {
 public:
  explicit RealFft(int n, PlanRigor rigor = PlanRigor::kEstimate);
  ~RealFft();
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;

  int size() const { return n_; }
  int bins() const { return n_ / 2 + 1; }

  void Forward(const double* in, std::complex<double>* out);
  // `in` is not modified (the c2r transform runs on a copy).
  void Inverse(const std::complex<double>* in, double* out);

 private:
  double* RealScratch();
  std::complex<double>* SpectrumScratch();

  int n_;
  double* real_ = nullptr;                // fftw_malloc'ed on first need, n reals
  std::complex<double>* spec_ = nullptr;  // fftw_malloc'ed on first need, n/2+1 bins
  void* forward_ = nullptr;               // fftw_plan
  void* inverse_ = nullptr;               // fftw_plan
};

// Complex transform of size n with the given sign: -1 (FFTW_FORWARD) or +1 (FFTW_BACKWARD).
// With howmany > 1 it transforms howmany contiguous blocks of n (in[j*n .. j*n+n-1]) in one call,
// which the kurtogram uses to do all nodes of a level at once.
class ComplexFft {
 public:
  ComplexFft(int n, int sign, int howmany = 1, PlanRigor rigor = PlanRigor::kEstimate);
  ~ComplexFft();
  ComplexFft(const ComplexFft&) = delete;
  ComplexFft& operator=(const ComplexFft&) = delete;

  int size() const { return n_; }
  int howmany() const { return howmany_; }
  int sign() const { return sign_; }

  // in and out hold size()*howmany() values; in == out (in place) is allowed.
  void Execute(const std::complex<double>* in, std::complex<double>* out);

 private:
  int n_, sign_, howmany_;
  std::complex<double>* in_ = nullptr;
  std::complex<double>* out_ = nullptr;
  void* plan_ = nullptr;          // cached fftw_plan (out of place), not owned
  void* plan_inplace_ = nullptr;  // cached in-place plan, fetched on first in-place call
  PlanRigor rigor_;
};

// Destroys every cached plan (and FFTW's accumulated wisdom). Only call it when no RealFft or
// ComplexFft object exists; mainly for leak checkers.
void ForgetFftPlans();

// Single-precision complex transform (fftwf), same interface as ComplexFft without batching.
// Used where the result feeds a statistic that needs ~6 digits, not 15 (the kurtogram's node
// envelopes): twice the SIMD width and half the memory traffic of double.
class ComplexFftF {
 public:
  ComplexFftF(int n, int sign, PlanRigor rigor = PlanRigor::kEstimate);
  int size() const { return n_; }
  // in and out must come from AllocateComplexF (FFTW's alignment) and must differ.
  void Execute(const std::complex<float>* in, std::complex<float>* out);

 private:
  int n_;
  void* plan_ = nullptr;  // cached fftwf_plan (out of place), not owned
};
FftwArray<std::complex<float>> AllocateComplexF(size_t n);

// Smallest n' >= n whose only prime factors are 2, 3, 5 and 7 (sizes FFTW handles fastest).
int FftFriendlySize(int n);

// Smallest n' >= n that is 7-smooth and a multiple of 64: where any size >= n will do (zero
// padding of a decimated envelope), this is the one to use. With FFTW_ESTIMATE plans, sizes rich
// in 5s and 7s (60025 = 5^2 7^4, 1875 = 3 5^4) ran up to twice as slow per point as nearby sizes
// with a 2^6 factor; over the kurtogram's 18 rows this choice saved 35 % of the transform time.
int FftFastSize(int n);

}  // namespace spallkit::dsp
