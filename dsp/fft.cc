#include "dsp/fft.h"

#include <fftw3.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <mutex>

#include "core/error.h"

namespace spallkit::dsp {
namespace {

enum class Kind { kR2c, kC2r, kC2c };

struct PlanKey {
  Kind kind;
  int n, sign, howmany;
  bool inplace;
  PlanRigor rigor;
  auto operator<=>(const PlanKey&) const = default;
};

// FFTW's planner (plan creation and destruction) is not thread-safe; execution is.
std::mutex& PlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

std::map<PlanKey, fftw_plan>& PlanCache() {
  static std::map<PlanKey, fftw_plan> cache;
  return cache;
}

std::map<PlanKey, fftwf_plan>& PlanCacheF() {
  static std::map<PlanKey, fftwf_plan> cache;
  return cache;
}

fftw_complex* AsFftw(std::complex<double>* p) { return reinterpret_cast<fftw_complex*>(p); }

// The cached plan for a key, made on first use on temporary fftw_malloc'ed arrays (so
// FFTW_MEASURE never overwrites caller data). fftw_malloc gives every array the same SIMD
// alignment, which is what new-array execution requires.
fftw_plan CachedPlan(const PlanKey& key) {
  std::lock_guard<std::mutex> lock(PlannerMutex());
  auto& cache = PlanCache();
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  const unsigned flags = key.rigor == PlanRigor::kMeasure ? FFTW_MEASURE : FFTW_ESTIMATE;
  const size_t total = static_cast<size_t>(key.n) * key.howmany;
  fftw_plan plan = nullptr;
  switch (key.kind) {
    case Kind::kR2c: {
      double* in = fftw_alloc_real(key.n);
      fftw_complex* out = fftw_alloc_complex(key.n / 2 + 1);
      plan = fftw_plan_dft_r2c_1d(key.n, in, out, flags);
      fftw_free(in);
      fftw_free(out);
      break;
    }
    case Kind::kC2r: {
      fftw_complex* in = fftw_alloc_complex(key.n / 2 + 1);
      double* out = fftw_alloc_real(key.n);
      plan = fftw_plan_dft_c2r_1d(key.n, in, out, flags);
      fftw_free(in);
      fftw_free(out);
      break;
    }
    case Kind::kC2c: {
      int n = key.n;
      fftw_complex* in = fftw_alloc_complex(total);
      fftw_complex* out = key.inplace ? in : fftw_alloc_complex(total);
      plan = fftw_plan_many_dft(
          1, &n, key.howmany, in, nullptr, 1, n, out, nullptr, 1, n, key.sign, flags);
      if (out != in) fftw_free(out);
      fftw_free(in);
      break;
    }
  }
  SPALLKIT_CHECK(plan, "FFTW could not plan a transform of size " << key.n);
  cache.emplace(key, plan);
  return plan;
}

bool SameAlignment(const void* a, const void* b) {
  return fftw_alignment_of(const_cast<double*>(static_cast<const double*>(a))) ==
         fftw_alignment_of(const_cast<double*>(static_cast<const double*>(b)));
}

}  // namespace

void FftwDeleter::operator()(void* p) const { fftw_free(p); }

FftwArray<std::complex<double>> AllocateComplex(size_t n) {
  return FftwArray<std::complex<double>>(
      reinterpret_cast<std::complex<double>*>(fftw_alloc_complex(std::max<size_t>(n, 1))));
}

FftwArray<double> AllocateReal(size_t n) {
  return FftwArray<double>(fftw_alloc_real(std::max<size_t>(n, 1)));
}

void ForgetFftPlans() {
  std::lock_guard<std::mutex> lock(PlannerMutex());
  for (auto& [key, plan] : PlanCache()) fftw_destroy_plan(plan);
  PlanCache().clear();
  for (auto& [key, plan] : PlanCacheF()) fftwf_destroy_plan(plan);
  PlanCacheF().clear();
  fftw_cleanup();
  fftwf_cleanup();
}

FftwArray<std::complex<float>> AllocateComplexF(size_t n) {
  return FftwArray<std::complex<float>>(
      reinterpret_cast<std::complex<float>*>(fftwf_alloc_complex(std::max<size_t>(n, 1))));
}

ComplexFftF::ComplexFftF(int n, int sign, PlanRigor rigor) : n_(n) {
  SPALLKIT_CHECK(n >= 1, "ComplexFftF size " << n);
  SPALLKIT_CHECK(sign == FFTW_FORWARD || sign == FFTW_BACKWARD, "ComplexFftF sign " << sign);
  const PlanKey key{Kind::kC2c, n, sign, 1, false, rigor};
  std::lock_guard<std::mutex> lock(PlannerMutex());
  auto& cache = PlanCacheF();
  if (auto it = cache.find(key); it != cache.end()) {
    plan_ = it->second;
    return;
  }
  fftwf_complex* in = fftwf_alloc_complex(n);
  fftwf_complex* out = fftwf_alloc_complex(n);
  fftwf_plan plan = fftwf_plan_dft_1d(
      n, in, out, sign, rigor == PlanRigor::kMeasure ? FFTW_MEASURE : FFTW_ESTIMATE);
  fftwf_free(in);
  fftwf_free(out);
  SPALLKIT_CHECK(plan, "FFTW could not plan a single-precision transform of size " << n);
  cache.emplace(key, plan);
  plan_ = plan;
}

void ComplexFftF::Execute(const std::complex<float>* in, std::complex<float>* out) {
  SPALLKIT_CHECK(static_cast<const void*>(in) != static_cast<const void*>(out),
                 "ComplexFftF is out of place");
  fftwf_execute_dft(static_cast<fftwf_plan>(plan_),
                    reinterpret_cast<fftwf_complex*>(const_cast<std::complex<float>*>(in)),
                    reinterpret_cast<fftwf_complex*>(out));
}

RealFft::RealFft(int n, PlanRigor rigor) : n_(n) {
  SPALLKIT_CHECK(n >= 1, "RealFft size must be positive, got " << n);
  forward_ = CachedPlan({Kind::kR2c, n, 0, 1, false, rigor});
  inverse_ = CachedPlan({Kind::kC2r, n, 0, 1, false, rigor});
}

// The scratch arrays are made on first need: a forward transform between aligned arrays uses
// none, and untouched megabytes still cost their allocation.
double* RealFft::RealScratch() {
  if (!real_) real_ = fftw_alloc_real(n_);
  return real_;
}

std::complex<double>* RealFft::SpectrumScratch() {
  if (!spec_) spec_ = reinterpret_cast<std::complex<double>*>(fftw_alloc_complex(n_ / 2 + 1));
  return spec_;
}

RealFft::~RealFft() {
  fftw_free(real_);
  fftw_free(spec_);
}

void RealFft::Forward(const double* in, std::complex<double>* out) {
  const auto plan = static_cast<fftw_plan>(forward_);
  // The r2c out-of-place plan preserves its input, so the caller's arrays are used directly
  // when their alignment matches the plan's.
  // (fftw_alignment_of(nullptr) is 0, the alignment of every fftw_malloc'ed array.)
  if (SameAlignment(in, nullptr) && SameAlignment(out, nullptr) &&
      static_cast<const void*>(in) != static_cast<const void*>(out)) {
    fftw_execute_dft_r2c(plan, const_cast<double*>(in), AsFftw(out));
    return;
  }
  double* real = RealScratch();
  std::complex<double>* spec = SpectrumScratch();
  std::memcpy(real, in, sizeof(double) * n_);
  fftw_execute_dft_r2c(plan, real, AsFftw(spec));
  std::memcpy(static_cast<void*>(out), spec, sizeof(fftw_complex) * (n_ / 2 + 1));
}

void RealFft::Inverse(const std::complex<double>* in, double* out) {
  // c2r destroys its input, so it always runs on the scratch copy.
  std::complex<double>* spec = SpectrumScratch();
  std::memcpy(static_cast<void*>(spec), in, sizeof(fftw_complex) * (n_ / 2 + 1));
  const auto plan = static_cast<fftw_plan>(inverse_);
  if (SameAlignment(out, nullptr)) {
    fftw_execute_dft_c2r(plan, AsFftw(spec), out);
    return;
  }
  double* real = RealScratch();
  fftw_execute_dft_c2r(plan, AsFftw(spec), real);
  std::memcpy(out, real, sizeof(double) * n_);
}

ComplexFft::ComplexFft(int n, int sign, int howmany, PlanRigor rigor)
    : n_(n), sign_(sign), howmany_(howmany), rigor_(rigor) {
  SPALLKIT_CHECK(n >= 1 && howmany >= 1, "ComplexFft size " << n << " x " << howmany);
  SPALLKIT_CHECK(sign == FFTW_FORWARD || sign == FFTW_BACKWARD, "ComplexFft sign " << sign);
  plan_ = CachedPlan({Kind::kC2c, n, sign, howmany, false, rigor});
}

ComplexFft::~ComplexFft() {
  fftw_free(in_);
  fftw_free(out_);
}

void ComplexFft::Execute(const std::complex<double>* in, std::complex<double>* out) {
  const size_t total = static_cast<size_t>(n_) * howmany_;
  const size_t bytes = sizeof(fftw_complex) * total;
  if (in == out) {
    if (!plan_inplace_) plan_inplace_ = CachedPlan({Kind::kC2c, n_, sign_, howmany_, true, rigor_});
    const auto plan = static_cast<fftw_plan>(plan_inplace_);
    if (!in_) in_ = reinterpret_cast<std::complex<double>*>(fftw_alloc_complex(total));
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
  if (!in_) in_ = reinterpret_cast<std::complex<double>*>(fftw_alloc_complex(total));
  // Out-of-place complex plans preserve their input by default (only c2r destroys it), so the
  // caller's arrays are used directly when their alignment matches the plan's.
  if (SameAlignment(in, in_) && SameAlignment(out, in_)) {
    fftw_execute_dft(plan, AsFftw(const_cast<std::complex<double>*>(in)), AsFftw(out));
    return;
  }
  if (!out_) out_ = reinterpret_cast<std::complex<double>*>(fftw_alloc_complex(total));
  std::memcpy(static_cast<void*>(in_), in, bytes);
  fftw_execute_dft(plan, AsFftw(in_), AsFftw(out_));
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

int FftFastSize(int n) {
  for (int m = std::max(64, (n + 63) / 64 * 64);; m += 64) {
    int r = m;
    for (int p : {2, 3, 5, 7}) {
      while (r % p == 0) r /= p;
    }
    if (r == 1) return m;
  }
}

}  // namespace spallkit::dsp
