#include "dsp/fft.h"

#include <fftw3.h>

#include <cstring>
#include <mutex>

#include "core/error.h"

namespace spallkit::dsp {
namespace {

// FFTW's planner (plan creation and destruction) is not thread-safe; execution is.
std::mutex& PlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

unsigned Flags(PlanRigor rigor) {
  return rigor == PlanRigor::kMeasure ? FFTW_MEASURE : FFTW_ESTIMATE;
}

fftw_complex* AsFftw(std::complex<double>* p) { return reinterpret_cast<fftw_complex*>(p); }

bool SameAlignment(const void* a, const void* b) {
  return fftw_alignment_of(const_cast<double*>(static_cast<const double*>(a))) ==
         fftw_alignment_of(const_cast<double*>(static_cast<const double*>(b)));
}

}  // namespace

RealFft::RealFft(int n, PlanRigor rigor) : n_(n) {
  SPALLKIT_CHECK(n >= 1, "RealFft size must be positive, got " << n);
  std::lock_guard<std::mutex> lock(PlannerMutex());
  real_ = static_cast<double*>(fftw_malloc(sizeof(double) * n));
  spec_ = static_cast<std::complex<double>*>(fftw_malloc(sizeof(fftw_complex) * (n / 2 + 1)));
  // FFTW_MEASURE overwrites the arrays while planning; they are scratch here, so that is fine.
  forward_ = fftw_plan_dft_r2c_1d(n, real_, AsFftw(spec_), Flags(rigor));
  inverse_ = fftw_plan_dft_c2r_1d(n, AsFftw(spec_), real_, Flags(rigor));
  SPALLKIT_CHECK(forward_ && inverse_, "FFTW could not plan a real transform of size " << n);
}

RealFft::~RealFft() {
  std::lock_guard<std::mutex> lock(PlannerMutex());
  fftw_destroy_plan(static_cast<fftw_plan>(forward_));
  fftw_destroy_plan(static_cast<fftw_plan>(inverse_));
  fftw_free(real_);
  fftw_free(spec_);
}

void RealFft::Forward(const double* in, std::complex<double>* out) {
  const auto plan = static_cast<fftw_plan>(forward_);
  // The r2c out-of-place plan preserves its input, so the caller's array can be used directly.
  if (SameAlignment(in, real_) && SameAlignment(out, spec_) &&
      static_cast<const void*>(in) != static_cast<const void*>(out)) {
    fftw_execute_dft_r2c(plan, const_cast<double*>(in), AsFftw(out));
    return;
  }
  std::memcpy(real_, in, sizeof(double) * n_);
  fftw_execute(plan);
  std::memcpy(static_cast<void*>(out), spec_, sizeof(fftw_complex) * (n_ / 2 + 1));
}

void RealFft::Inverse(const std::complex<double>* in, double* out) {
  // c2r destroys its input, so it always runs on the scratch copy.
  std::memcpy(static_cast<void*>(spec_), in, sizeof(fftw_complex) * (n_ / 2 + 1));
  const auto plan = static_cast<fftw_plan>(inverse_);
  if (SameAlignment(out, real_)) {
    fftw_execute_dft_c2r(plan, AsFftw(spec_), out);
    return;
  }
  fftw_execute(plan);
  std::memcpy(out, real_, sizeof(double) * n_);
}

ComplexFft::ComplexFft(int n, int sign, int howmany, PlanRigor rigor)
    : n_(n), sign_(sign), howmany_(howmany), rigor_(rigor) {
  SPALLKIT_CHECK(n >= 1 && howmany >= 1, "ComplexFft size " << n << " x " << howmany);
  SPALLKIT_CHECK(sign == FFTW_FORWARD || sign == FFTW_BACKWARD, "ComplexFft sign " << sign);
  std::lock_guard<std::mutex> lock(PlannerMutex());
  const size_t total = static_cast<size_t>(n) * howmany;
  in_ = static_cast<std::complex<double>*>(fftw_malloc(sizeof(fftw_complex) * total));
  out_ = static_cast<std::complex<double>*>(fftw_malloc(sizeof(fftw_complex) * total));
  plan_ = fftw_plan_many_dft(
      1, &n_, howmany, AsFftw(in_), nullptr, 1, n, AsFftw(out_), nullptr, 1, n, sign, Flags(rigor));
  SPALLKIT_CHECK(plan_, "FFTW could not plan a complex transform of size " << n);
}

ComplexFft::~ComplexFft() {
  std::lock_guard<std::mutex> lock(PlannerMutex());
  fftw_destroy_plan(static_cast<fftw_plan>(plan_));
  if (plan_inplace_) fftw_destroy_plan(static_cast<fftw_plan>(plan_inplace_));
  fftw_free(in_);
  fftw_free(out_);
}

void ComplexFft::Execute(const std::complex<double>* in, std::complex<double>* out) {
  const size_t bytes = sizeof(fftw_complex) * static_cast<size_t>(n_) * howmany_;
  if (in == out) {
    if (!plan_inplace_) {
      std::lock_guard<std::mutex> lock(PlannerMutex());
      // Planned on the scratch array (FFTW_MEASURE would overwrite the caller's data).
      plan_inplace_ = fftw_plan_many_dft(1,
                                         &n_,
                                         howmany_,
                                         AsFftw(in_),
                                         nullptr,
                                         1,
                                         n_,
                                         AsFftw(in_),
                                         nullptr,
                                         1,
                                         n_,
                                         sign_,
                                         Flags(rigor_));
      SPALLKIT_CHECK(plan_inplace_, "FFTW could not plan an in-place transform of size " << n_);
    }
    const auto plan = static_cast<fftw_plan>(plan_inplace_);
    if (SameAlignment(out, in_)) {
      fftw_execute_dft(plan, AsFftw(out), AsFftw(out));
    } else {
      std::memcpy(static_cast<void*>(in_), in, bytes);
      fftw_execute_dft(plan, AsFftw(in_), AsFftw(in_));
      std::memcpy(static_cast<void*>(out), in_, bytes);
    }
    return;
  }
  const auto plan = static_cast<fftw_plan>(plan_);
  // Out-of-place complex plans preserve their input by default (only c2r destroys it), so the
  // caller's arrays are used directly when their alignment matches the plan's.
  if (SameAlignment(in, in_) && SameAlignment(out, out_)) {
    fftw_execute_dft(plan, AsFftw(const_cast<std::complex<double>*>(in)), AsFftw(out));
    return;
  }
  std::memcpy(static_cast<void*>(in_), in, bytes);
  fftw_execute(plan);
  std::memcpy(static_cast<void*>(out), out_, bytes);
}

int FftFriendlySize(int n) {
  if (n <= 1) return 1;
  for (int m = n;; ++m) {
    int r = m;
    for (int p : {2, 3, 5, 7}) {
      while (r % p == 0) r /= p;
    }
    if (r == 1) return m;
  }
}

}  // namespace spallkit::dsp
