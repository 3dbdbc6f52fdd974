#include "identify/width_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "core/constants.h"
#include "core/error.h"
#include "identify/chi_square.h"

namespace spallkit::identify {
namespace {

template <typename T>
T Emg(const T& tau, const T& rise, const T& decay) {
  using std::erfc;
  using std::exp;
  using std::sqrt;
  const T a = rise / decay;
  const T x = tau / rise;
  const T arg = T(0.5) * a * a - tau / decay;
  if (arg > T(40.0)) {  // far before the event: the Gaussian tail (asymptotic form of erfc)
    return exp(-T(0.5) * x * x) / (sqrt(T(2.0 * kPi)) * (a - x));
  }
  return T(0.5) * exp(arg) * erfc((a - x) / T(std::sqrt(2.0)));
}

// The noise's own correlation: a Gaussian of its correlation time (one sample when white).
double NoisePeak(double tau, double width) {
  const double u = tau / std::max(width, 1e-12);
  return std::exp(-0.5 * u * u);
}

// tau_d1 / tau_d, in [kMinRingDownRatio, 1]: each side of the pair peak decays with one of the
// two events' ring-downs, the zero-lag peak with the slowest event's, so tau_d1 <= tau_d. Without
// that bound the pair peak takes the zero-lag peak's tail (a long tau_d1 just after a sharp
// zero-lag peak: a delay read short).
constexpr double kMinRingDownRatio = 0.01;
double RingDownRatio(const EntryExitFit& f) {
  return std::clamp(f.PairDecayS() / f.decay_s, kMinRingDownRatio, 1.0);
}

template <typename T>
T Symmetric(const T& tau, const T& rise, const T& decay) {
  return T(0.5) * (Emg(tau, rise, decay) + Emg(-tau, rise, decay));
}

// The residuals of the correlation model. lin = {c, P_0, P_1, P_noise}, delay = {dt},
// shape = {sigma_0, tau_d, sigma_1 - sigma_0} and, with the pair peak's own ring-down,
// tau_d1 / tau_d (SharedRingDown false: a block of 4, else of 3).
template <bool SharedRingDown>
struct CorrelationResidual {
  const EnvelopeCorrelation* r;
  int lags;
  double noise_s;
  template <typename T>
  bool operator()(const T* lin, const T* delay, const T* shape, T* residuals) const {
    for (int i = 0; i < lags; ++i) {
      const T tau(r->TauSeconds(i));
      T pair_decay = shape[1];
      if constexpr (!SharedRingDown) pair_decay = shape[1] * shape[3];
      const T m = lin[0] + lin[1] * Symmetric(tau, shape[0], shape[1]) +
                  lin[2] * Symmetric(tau - delay[0], shape[0] + shape[2], pair_decay) +
                  lin[3] * NoisePeak(r->TauSeconds(i), noise_s);
      residuals[i] = (T(r->mean[i]) - m) / r->sigma[i];
    }
    return true;
  }
};

// The model's three shape columns at lag i: zero-lag peak, pair peak, noise peak.
double ZeroLagColumn(const EnvelopeCorrelation& r, int i, const EntryExitFit& f) {
  return SymmetricEventShape(r.TauSeconds(i), f.rise_s, f.decay_s);
}
double PairColumn(const EnvelopeCorrelation& r, int i, const EntryExitFit& f) {
  return SymmetricEventShape(r.TauSeconds(i) - f.delay_s, f.delay_rise_s, f.PairDecayS());
}
double NoiseColumn(const EnvelopeCorrelation& r, int i, const EntryExitFit& f) {
  return NoisePeak(r.TauSeconds(i), f.noise_correlation_s);
}

// The model from f's linear part and its three columns (lags values each).
void ModelFromColumns(const EntryExitFit& f,
                      const double* zero,
                      const double* pair,
                      const double* noise,
                      std::vector<double>* m) {
  for (size_t i = 0; i < m->size(); ++i)
    (*m)[i] =
        f.offset + f.zero_lag_power * zero[i] + f.delay_power * pair[i] + f.noise_power * noise[i];
}

// The three columns at f's delay and shape.
struct Columns {
  std::vector<double> zero, pair, noise;
  Columns(const EnvelopeCorrelation& r, int lags, const EntryExitFit& f)
      : zero(lags), pair(lags), noise(lags) {
    for (int i = 0; i < lags; ++i)
      zero[i] = ZeroLagColumn(r, i, f), pair[i] = PairColumn(r, i, f),
      noise[i] = NoiseColumn(r, i, f);
  }
};

std::vector<double> ModelOf(const EnvelopeCorrelation& r, int lags, const EntryExitFit& f) {
  const Columns c(r, lags, f);
  std::vector<double> m(lags);
  ModelFromColumns(f, c.zero.data(), c.pair.data(), c.noise.data(), &m);
  return m;
}

double Chi2Of(const EnvelopeCorrelation& r, const std::vector<double>& model) {
  return ChiSquare(r.mean, r.sigma, model);
}

// Weighted linear least squares for (c, P_0, P_1, P_noise) given the three shape columns (lags
// values each); false if a power is negative or the system singular.
bool LinearPartOf(const EnvelopeCorrelation& r,
                  int lags,
                  const double* zero,
                  const double* pair,
                  const double* noise,
                  EntryExitFit* f) {
  constexpr int kN = 4;
  double a[kN][kN] = {{0}}, x[kN] = {0};
  for (int i = 0; i < lags; ++i) {
    const double row[kN] = {1.0, zero[i], pair[i], noise[i]};
    const double w = 1.0 / (r.sigma[i] * r.sigma[i]);
    for (int p = 0; p < kN; ++p) {
      x[p] += w * row[p] * r.mean[i];
      for (int q = 0; q < kN; ++q) a[p][q] += w * row[p] * row[q];
    }
  }
  for (int c = 0; c < kN; ++c) {  // Gaussian elimination, partial pivoting
    int piv = c;
    for (int p = c + 1; p < kN; ++p)
      if (std::abs(a[p][c]) > std::abs(a[piv][c])) piv = p;
    if (!(std::abs(a[piv][c]) > 1e-300)) return false;
    std::swap(a[c], a[piv]);
    std::swap(x[c], x[piv]);
    for (int p = c + 1; p < kN; ++p) {
      const double m = a[p][c] / a[c][c];
      for (int q = c; q < kN; ++q) a[p][q] -= m * a[c][q];
      x[p] -= m * x[c];
    }
  }
  for (int p = kN - 1; p >= 0; --p) {
    for (int q = p + 1; q < kN; ++q) x[p] -= a[p][q] * x[q];
    x[p] /= a[p][p];
  }
  if (x[1] < 0 || x[2] < 0 || x[3] < 0 || !std::isfinite(x[0])) return false;
  f->offset = x[0];
  f->zero_lag_power = x[1];
  f->delay_power = x[2];
  f->noise_power = x[3];
  return true;
}

// The same at f's delay and shape.
bool LinearPart(const EnvelopeCorrelation& r, int lags, EntryExitFit* f) {
  const Columns c(r, lags, *f);
  return LinearPartOf(r, lags, c.zero.data(), c.pair.data(), c.noise.data(), f);
}

struct Bounds {
  double min_delay, max_delay, min_rise, max_rise, min_decay, max_decay, noise_correlation;
  bool shared_ring_down;  // WidthFitOptions::shared_ring_down
};

// The correlation model as a Ceres problem on (lin, delay, shape) = ((c, P_0, P_1, P_noise),
// delay, (rise, decay, delay rise - rise[, pair ring-down / decay])), with the bounds every fit of
// it keeps: P_0 and P_noise >= 0 and the shape within `bd`.
void AddCorrelationModel(const EnvelopeCorrelation& r,
                         int lags,
                         const Bounds& bd,
                         double noise_correlation_s,
                         double* lin,
                         double* delay,
                         double* shape,
                         ceres::Problem* problem) {
  // A shared ring-down leaves shape[3] out of the problem (its block is the first three).
  ceres::CostFunction* cost =
      bd.shared_ring_down
          ? static_cast<ceres::CostFunction*>(
                new ceres::AutoDiffCostFunction<CorrelationResidual<true>, ceres::DYNAMIC, 4, 1, 3>(
                    new CorrelationResidual<true>{&r, lags, noise_correlation_s}, lags))
          : new ceres::AutoDiffCostFunction<CorrelationResidual<false>, ceres::DYNAMIC, 4, 1, 4>(
                new CorrelationResidual<false>{&r, lags, noise_correlation_s}, lags);
  problem->AddResidualBlock(cost, nullptr, lin, delay, shape);
  problem->SetParameterLowerBound(lin, 1, 0.0);
  problem->SetParameterLowerBound(lin, 3, 0.0);
  problem->SetParameterLowerBound(shape, 0, bd.min_rise);
  problem->SetParameterUpperBound(shape, 0, bd.max_rise);
  problem->SetParameterLowerBound(shape, 1, bd.min_decay);
  problem->SetParameterUpperBound(shape, 1, bd.max_decay);
  problem->SetParameterLowerBound(shape, 2, 0.0);
  problem->SetParameterUpperBound(shape, 2, bd.max_rise);
  if (!bd.shared_ring_down) {
    problem->SetParameterLowerBound(shape, 3, kMinRingDownRatio);
    problem->SetParameterUpperBound(shape, 3, 1.0);
  }
}

ceres::Solver::Summary SolveQuietly(int max_iterations, ceres::Problem* problem) {
  ceres::Solver::Options so;
  so.max_num_iterations = max_iterations;
  so.linear_solver_type = ceres::DENSE_QR;
  so.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(so, problem, &summary);
  return summary;
}

EntryExitFit Fit(const EnvelopeCorrelation& r,
                 int lags,
                 const Bounds& bd,
                 const EntryExitFit* start,
                 int grid,
                 double* delay_se,
                 int max_iterations = 50) {
  EntryExitFit best;
  best.chi2 = std::numeric_limits<double>::infinity();
  if (start) {
    best = *start;
    if (!LinearPart(r, lags, &best)) best = *start;
    best.model = ModelOf(r, lags, best);
    best.chi2 = Chi2Of(r, best.model);
  } else {
    // The pair peak's ring-down as a fraction of the zero-lag peak's (RingDownRatio).
    const std::vector<double> ring_down_ratios =
        bd.shared_ring_down ? std::vector<double>{0.0} : std::vector<double>{1.0, 0.5, 0.25};
    // The zero-lag and noise columns depend on (rise, decay) only, the pair column on the rest:
    // each is evaluated once per value it depends on, and only the best keeps its model.
    std::vector<double> zero(lags), pair(lags), noise(lags), model(lags);
    EntryExitFit f;
    f.noise_correlation_s = bd.noise_correlation;
    for (int i = 0; i < lags; ++i) noise[i] = NoiseColumn(r, i, f);
    for (double rise : {0.05e-3, 0.15e-3, 0.4e-3})
      for (double decay : {0.15e-3, 0.4e-3, 1.0e-3}) {
        f.rise_s = std::clamp(rise, bd.min_rise, bd.max_rise);
        f.decay_s = std::clamp(decay, bd.min_decay, bd.max_decay);
        for (int i = 0; i < lags; ++i) zero[i] = ZeroLagColumn(r, i, f);
        for (double extra : {0.0, 0.1e-3})
          for (double ring_down_ratio : ring_down_ratios)
            for (int g = 0; g < grid; ++g) {
              f.delay_rise_s = std::min(f.rise_s + extra, bd.max_rise + f.rise_s);
              f.delay_decay_s = ring_down_ratio > 0 ? ring_down_ratio * f.decay_s : 0.0;
              f.delay_s = bd.min_delay + (bd.max_delay - bd.min_delay) * g / std::max(1, grid - 1);
              for (int i = 0; i < lags; ++i) pair[i] = PairColumn(r, i, f);
              if (!LinearPartOf(r, lags, zero.data(), pair.data(), noise.data(), &f)) continue;
              ModelFromColumns(f, zero.data(), pair.data(), noise.data(), &model);
              f.chi2 = Chi2Of(r, model);
              if (f.chi2 < best.chi2) best = f;
            }
      }
    if (std::isfinite(best.chi2)) {
      best.model = ModelOf(r, lags, best);
    } else {
      best = EntryExitFit{};
      best.noise_correlation_s = bd.noise_correlation;
      best.rise_s = best.delay_rise_s = bd.min_rise;
      best.decay_s = bd.min_decay;
      best.delay_s = bd.min_delay;
      best.model = ModelOf(r, lags, best);
      best.chi2 = Chi2Of(r, best.model);
    }
  }
  double lin[4] = {best.offset, best.zero_lag_power, best.delay_power, best.noise_power};
  double delay[1] = {best.delay_s};
  double shape[4] = {best.rise_s,
                     best.decay_s,
                     std::max(0.0, best.delay_rise_s - best.rise_s),
                     RingDownRatio(best)};
  ceres::Problem problem;
  AddCorrelationModel(r, lags, bd, best.noise_correlation_s, lin, delay, shape, &problem);
  problem.SetParameterLowerBound(lin, 2, 0.0);
  problem.SetParameterLowerBound(delay, 0, bd.min_delay);
  problem.SetParameterUpperBound(delay, 0, bd.max_delay);
  SolveQuietly(max_iterations, &problem);
  EntryExitFit f;
  f.offset = lin[0];
  f.zero_lag_power = lin[1];
  f.delay_power = lin[2];
  f.noise_power = lin[3];
  f.noise_correlation_s = best.noise_correlation_s;
  f.delay_s = delay[0];
  f.rise_s = shape[0];
  f.decay_s = shape[1];
  f.delay_rise_s = shape[0] + shape[2];
  f.delay_decay_s = bd.shared_ring_down ? 0.0 : shape[1] * shape[3];
  f.model = ModelOf(r, lags, f);
  f.chi2 = Chi2Of(r, f.model);
  const bool improved = f.chi2 <= best.chi2;
  if (delay_se) {
    *delay_se = 0.0;
    ceres::Covariance::Options co;
    co.algorithm_type = ceres::DENSE_SVD;
    co.null_space_rank = -1;
    ceres::Covariance cov(co);
    std::vector<std::pair<const double*, const double*>> blocks = {{delay, delay}};
    if (improved && cov.Compute(blocks, &problem)) {
      double c = 0.0;
      if (cov.GetCovarianceBlock(delay, delay, &c)) *delay_se = std::sqrt(std::max(0.0, c));
    }
  }
  return improved ? f : best;
}

// chi2 of the best fit without the second event (P_1 = 0, the rest refitted from `best`).
double NullChi2(const EnvelopeCorrelation& r,
                int lags,
                const Bounds& bd,
                const EntryExitFit& best) {
  double lin[4] = {best.offset, best.zero_lag_power, 0.0, best.noise_power};
  double delay[1] = {best.delay_s};
  double shape[4] = {best.rise_s,
                     best.decay_s,
                     std::max(0.0, best.delay_rise_s - best.rise_s),
                     RingDownRatio(best)};
  ceres::Problem problem;
  AddCorrelationModel(r, lags, bd, best.noise_correlation_s, lin, delay, shape, &problem);
  problem.SetManifold(lin, new ceres::SubsetManifold(4, {2}));
  problem.SetParameterBlockConstant(delay);
  return 2.0 * SolveQuietly(50, &problem).final_cost;
}

// Mean and pooled standard error over blocks (a subset `use` of them, with repetition).
void Summarise(EnvelopeCorrelation* r, const std::vector<int>& use) {
  const int lags = static_cast<int>(r->blocks.front().size());
  std::vector<double> sum(lags, 0.0);
  double count = 0.0;
  for (int b : use) {
    for (int i = 0; i < lags; ++i) sum[i] += r->blocks[b][i];
    count += r->block_counts[b];
  }
  r->mean.assign(lags, 0.0);
  for (int i = 0; i < lags; ++i) r->mean[i] = sum[i] / std::max(1.0, count);
  // Scatter of the block means about the mean, weighted by the block sizes.
  std::vector<double> var(lags, 0.0);
  double w2 = 0.0;
  for (int b : use) {
    const double c = r->block_counts[b];
    if (c <= 0) continue;
    w2 += c * c;
    for (int i = 0; i < lags; ++i) {
      const double d = r->blocks[b][i] / c - r->mean[i];
      var[i] += c * c * d * d;
    }
  }
  const double nb = static_cast<double>(use.size());
  r->sigma.assign(lags, 0.0);
  for (int i = 0; i < lags; ++i) {
    double v = 0.0;
    int m = 0;
    for (int j = std::max(0, i - 2); j <= std::min(lags - 1, i + 2); ++j, ++m) v += var[j];
    r->sigma[i] = std::sqrt(v / m * nb / std::max(1.0, nb - 1.0)) / std::max(1.0, count);
  }
  const double peak = std::abs(r->mean[0]);
  for (double& s : r->sigma) s = std::max(s, 1e-9 * peak + 1e-300);
}

}  // namespace

bool WidthFitOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  if (!(min_delay_s >= 0 && max_delay_s > min_delay_s))
    return fail("width fit: need 0 <= min_delay_s < max_delay_s");
  if (!(tail_s > 0)) return fail("width fit: tail_s must be > 0");
  if (delay_grid < 2) return fail("width fit: delay_grid must be >= 2");
  if (bootstrap < 0) return fail("width fit: bootstrap must be >= 0");
  if (min_blocks < 2) return fail("width fit: min_blocks must be >= 2");
  return true;
}

double EventShape(double tau_s, double rise_s, double decay_s) {
  return Emg(tau_s, rise_s, decay_s);
}

double SymmetricEventShape(double tau_s, double rise_s, double decay_s) {
  return Symmetric(tau_s, rise_s, decay_s);
}

EnvelopeCorrelation CorrelateInZone(std::span<const double> se,
                                    double rate_hz,
                                    const std::vector<char>& in_zone,
                                    int lags,
                                    int block_samples) {
  const int n = static_cast<int>(se.size());
  EnvelopeCorrelation r;
  r.rate_hz = rate_hz;
  std::vector<double> zone_values;
  for (int i = 0; i < n; ++i)
    if (in_zone.empty() || in_zone[i]) zone_values.push_back(se[i]);
  if (zone_values.empty()) return r;
  std::nth_element(
      zone_values.begin(), zone_values.begin() + zone_values.size() / 2, zone_values.end());
  r.floor = zone_values[zone_values.size() / 2];
  block_samples = std::max(1, block_samples);
  const int nblocks = (n + block_samples - 1) / block_samples;
  r.blocks.assign(nblocks, std::vector<double>(lags, 0.0));
  r.block_counts.assign(nblocks, 0.0);
  for (int t = 0; t + lags <= n; ++t) {
    if (!(in_zone.empty() || in_zone[t])) continue;
    const int b = t / block_samples;
    const double a = se[t] - r.floor;
    double* row = r.blocks[b].data();
    for (int i = 0; i < lags; ++i) row[i] += a * (se[t + i] - r.floor);
    r.block_counts[b] += 1.0;
  }
  // Drop empty blocks.
  std::vector<std::vector<double>> blocks;
  std::vector<double> counts;
  for (int b = 0; b < nblocks; ++b)
    if (r.block_counts[b] > 0) {
      blocks.push_back(std::move(r.blocks[b]));
      counts.push_back(r.block_counts[b]);
    }
  r.blocks = std::move(blocks);
  r.block_counts = std::move(counts);
  if (r.blocks.empty()) return r;
  std::vector<int> all(r.blocks.size());
  for (size_t b = 0; b < all.size(); ++b) all[b] = static_cast<int>(b);
  Summarise(&r, all);
  return r;
}

namespace {

// The fit's bounds for a record sampled at rate_hz.
Bounds BoundsOf(const WidthFitOptions& o, double rate_hz) {
  Bounds bd;
  bd.min_delay = o.min_delay_s > 0 ? o.min_delay_s : 2.0 / rate_hz;
  bd.max_delay = o.max_delay_s;
  bd.min_rise = 0.5 / rate_hz;
  bd.max_rise = 0.6e-3;
  bd.min_decay = 0.5 / rate_hz;
  bd.max_decay = 3.0e-3;
  bd.noise_correlation = std::max(o.noise_correlation_s, 0.5 / rate_hz);
  bd.shared_ring_down = o.shared_ring_down;
  return bd;
}

}  // namespace

WidthFit FitEntryExit(std::span<const double> se,
                      double rate_hz,
                      const std::vector<char>& in_zone,
                      int block_samples,
                      const WidthFitOptions& o) {
  std::string error;
  if (!o.IsValid(&error)) throw InputError(error);
  WidthFit out;
  const int lags = static_cast<int>(std::ceil((o.max_delay_s + o.tail_s) * rate_hz)) + 1;
  if (lags + 2 >= static_cast<int>(se.size())) {
    out.message = "record shorter than the delays searched";
    return out;
  }
  out.correlation = CorrelateInZone(se, rate_hz, in_zone, lags, block_samples);
  out.blocks = static_cast<int>(out.correlation.blocks.size());
  if (out.blocks < o.min_blocks) {
    out.message = "only " + std::to_string(out.blocks) + " cage revolutions with load-zone samples";
    return out;
  }
  const Bounds bd = BoundsOf(o, rate_hz);
  out.best = Fit(out.correlation, lags, bd, nullptr, o.delay_grid, &out.delay_standard_error_s);
  out.usable = true;
  out.delay_low_s = out.delay_high_s = out.best.delay_s;
  // Significance of the second event: the likelihood-ratio statistic against no second event,
  // in units of the best fit's reduced chi2 and of the lags' correlation length (R is smooth
  // over about 2 rise times, so neighbouring lags are not independent).
  const double chi2_0 = NullChi2(out.correlation, lags, bd, out.best);
  const double scale = std::max(1.0, out.best.chi2 / std::max(1, lags - 8));
  const double corr = std::max(1.0, 2.0 * out.best.rise_s * rate_hz);
  out.delay_power_significance = std::sqrt(std::max(0.0, chi2_0 - out.best.chi2) / (scale * corr));
  AddDelayInterval(o, &out);
  return out;
}

void AddDelayInterval(const WidthFitOptions& o, WidthFit* fit) {
  WidthFit& out = *fit;
  if (!out.usable || o.bootstrap < 10) return;
  const double rate_hz = out.correlation.rate_hz;
  const int lags = static_cast<int>(out.correlation.mean.size());
  const Bounds bd = BoundsOf(o, rate_hz);
  std::mt19937_64 rng(o.seed);
  std::uniform_int_distribution<int> pick(0, out.blocks - 1);
  std::vector<double> delays;
  EnvelopeCorrelation resample = out.correlation;
  for (int b = 0; b < o.bootstrap; ++b) {
    std::vector<int> use(out.blocks);
    for (int& u : use) u = pick(rng);
    Summarise(&resample, use);
    // From the best fit and from the grid's best: a resample may sit in another basin.
    EntryExitFit f = Fit(resample, lags, bd, &out.best, o.delay_grid, nullptr, 20);
    delays.push_back(f.delay_s);
  }
  std::sort(delays.begin(), delays.end());
  auto q = [&](double p) {
    const double x = p * (delays.size() - 1);
    const size_t i = static_cast<size_t>(x);
    return i + 1 < delays.size() ? delays[i] + (x - i) * (delays[i + 1] - delays[i]) : delays[i];
  };
  // Percentiles of a block bootstrap with few blocks are too narrow (the resamples hold fewer
  // distinct blocks than the record): the interval is also at least +/- t(0.95, n-1) times
  // the bootstrap standard deviation corrected by n / (n - 1).
  double m = 0, m2 = 0;
  for (double v : delays) m += v, m2 += v * v;
  m /= delays.size();
  const double sd = std::sqrt(std::max(0.0, m2 / delays.size() - m * m));
  const double nb = out.blocks;
  const double t95 = nb >= 31 ? 1.70 : 1.645 + 2.0 / (nb - 1.0);  // one-sided 95 % of t
  const double half = t95 * sd * std::sqrt(nb / (nb - 1.0));
  out.delay_low_s = std::max(bd.min_delay, std::min(q(0.05), out.best.delay_s - half));
  out.delay_high_s = std::min(bd.max_delay, std::max(q(0.95), out.best.delay_s + half));
}

}  // namespace spallkit::identify
