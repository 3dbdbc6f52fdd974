#include "identify/validation.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "core/constants.h"
#include "core/error.h"
#include "core/format.h"
#include "core/hdf5.h"
#include "core/record_io.h"
#include "dsp/diagnose.h"
#include "dsp/envelope.h"
#include "identify/count_fit.h"
#include "sim/bearing/scene.h"

namespace spallkit::identify {
namespace {

// Width classes of the summary's per-width line (m).
constexpr double kWidthClassM = 0.5e-3;
constexpr double kWidthTolerance = 0.15;  // a width "within 15 %" of the truth

double RelativeWidthError(const ValidatedRecord& r) {
  return std::abs(r.width_m - r.true_width_m) / r.true_width_m;
}

// SplitMix64 (portable: the same noise with every standard library) and Box-Muller.
class NormalStream {
 public:
  explicit NormalStream(std::uint64_t seed) : state_(seed) {}
  double Next() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = 0.0;
    while (u1 <= 0.0) u1 = Uniform();
    const double u2 = Uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * kPi * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * kPi * u2);
  }

 private:
  double Uniform() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
  std::uint64_t state_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

// Mean power of x in [low, high] Hz (Parseval over the one-sided spectrum).
double BandPower(const dsp::EnvelopeAnalyzer& a, double low_hz, double high_hz) {
  const auto& s = a.spectrum();
  const double n = a.size();
  double p = 0.0;
  for (size_t k = 1; k < s.size(); ++k) {
    const double f = k * a.resolution_hz();
    if (f >= low_hz && f <= high_hz) p += std::norm(s[k]);
  }
  return 2.0 * p / (n * n);
}

// CPU time of the calling thread (a record's analysis runs on one thread; the workers run
// records side by side).
double CpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

bool ValidationOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  if (!(skip_s >= 0 && std::isfinite(skip_s))) return fail("validation: skip_s must be >= 0");
  if (snr_db.empty()) return fail("validation: give at least one SNR");
  for (double s : snr_db)
    if (std::isnan(s) || s == -std::numeric_limits<double>::infinity())
      return fail("validation: an SNR must be a number or +inf");
  if (!(workers >= 1 && workers <= 256)) return fail("validation: workers must be in [1, 256]");
  return identify.IsValid(error);
}

std::vector<std::string> CaseFiles(const std::string& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw InputError(folder + ": not a folder");
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(folder, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("case-", 0) == 0 && e.path().extension() == ".h5")
      files.push_back(e.path().string());
  }
  if (files.empty())
    throw InputError(folder + ": no case-*.h5 files (a `spall dataset run` folder)");
  std::sort(files.begin(), files.end());
  return files;
}

namespace {

// One file at every SNR of the options; f is the file's index (it seeds the noise).
std::vector<ValidatedRecord> ValidateFile(const std::string& path,
                                          size_t f,
                                          const ValidationOptions& options) {
  std::vector<ValidatedRecord> out;
  const auto text = h5::File::OpenReadOnly(path).ReadStringAttribute("/", "scene");
  if (!text) throw InputError(path + ": no `scene` attribute (not a spall simulate output)");
  const sim::Scene scene = sim::ParseScene(*text, path + ":scene");
  RecordOptions ro;
  ro.channel = options.channel;
  Record clean = ReadRecord(path, ro);
  if (!DropStart(&clean, options.skip_s) ||
      clean.samples.size() <= dsp::EnvelopeAnalyzer::kMinSamples)
    throw InputError(path + ": record shorter than skip_s");

  const BearingGeometry& g = scene.geometry.bearing;
  const double shaft_hz = scene.operation.inner_ring_speed_rad_s / (2.0 * kPi);
  dsp::DiagnoseOptions dopt;
  dopt.threads = 1;
  IdentifyOptions io = options.identify;
  io.diametral_clearance_m = scene.geometry.diametral_clearance_m;
  io.roller_length_m = scene.geometry.thickness_m;
  if (options.give_load) io.radial_load_n = scene.operation.radial_load_n;

  ValidatedRecord truth;
  truth.file = path;
  truth.true_count = static_cast<int>(scene.defects.size());
  std::vector<int> rollers;
  for (const auto& d : scene.defects) rollers.push_back(d.roller);
  if (!rollers.empty()) {
    const int r0 = *std::min_element(rollers.begin(), rollers.end());
    for (int& r : rollers) r -= r0;
    std::sort(rollers.begin(), rollers.end());
    truth.true_slots = CanonicalSlots(rollers, g.num_elements);
    truth.true_width_m = scene.defects.front().width_m;
  }
  truth.speed_rpm = shaft_hz * 60.0;
  truth.load_n = scene.operation.radial_load_n;
  truth.record_s = clean.duration_s();

  // The clean record's band defines the SNR (the band the analysis would use on it).
  const dsp::Diagnosis clean_d = dsp::Diagnose(clean, g, shaft_hz, dopt);
  const dsp::EnvelopeAnalyzer analyzer(clean.samples, clean.sample_rate_hz);
  const double band_power = BandPower(analyzer, clean_d.band.low_hz, clean_d.band.high_hz);
  const double band_fraction = clean_d.band.width_hz() / (0.5 * clean.sample_rate_hz);

  for (size_t s = 0; s < options.snr_db.size(); ++s) {
    const double snr = options.snr_db[s];
    Record noisy = clean;
    if (std::isfinite(snr)) {
      const double sigma = std::sqrt(band_power / std::pow(10.0, snr / 10.0) / band_fraction);
      NormalStream noise(options.seed * 0x100000001b3ULL + f * 1000003ULL + s * 7919ULL);
      for (double& x : noisy.samples) x += sigma * noise.Next();
    }
    ValidatedRecord r = truth;
    r.snr_db = snr;
    const double t0 = CpuSeconds();
    const dsp::Diagnosis d = std::isfinite(snr) ? dsp::Diagnose(noisy, g, shaft_hz, dopt) : clean_d;
    const Identification id = Identify(noisy, g, shaft_hz, d, io);
    r.cpu_s = CpuSeconds() - t0;
    r.verdict = dsp::VerdictName(d.verdict);
    r.count_stated = id.count_identifiable;
    r.count = id.count;
    r.probabilities = id.probabilities;
    auto argmax = [](const std::vector<double>& p, int* k, double* v) {
      if (p.empty()) return;
      *k = static_cast<int>(std::max_element(p.begin(), p.end()) - p.begin());
      *v = p[*k];
    };
    argmax(id.probabilities_cage, &r.count_cage, &r.p_cage);
    argmax(id.probabilities_sidebands, &r.count_sidebands, &r.p_sidebands);
    r.chi2_scale_cage = id.count_fit.chi2_scale;
    r.chi2_scale_sidebands = id.count_fit.chi2_scale_sidebands;
    r.log_evidence_cage = id.count_fit.log_evidence_cage;
    r.log_evidence_sidebands = id.count_fit.log_evidence_sidebands;
    if (!id.count_fit.best.empty()) {
      const HumpShape& shape = id.count_fit.best[id.count_fit.MostProbable()].shape;
      r.hump_exponent = shape.exponent;
      r.hump_edge_gain = shape.edge_gain;
      r.hump_smear_deg = shape.smear_rad * 180.0 / kPi;
    }
    if (id.count_identifiable) r.count_probability = id.probabilities[id.count];
    r.count_at_least = id.count_at_least;
    r.count_at_least_probability = id.count_at_least_probability;
    if (id.count_identifiable && id.count == r.true_count) {
      std::vector<int> slots;
      for (double p : id.positions_deg)
        slots.push_back(static_cast<int>(std::lround(p * g.num_elements / 360.0)));
      const std::vector<int> stated = CanonicalSlots(slots, g.num_elements);
      r.positions_right = stated == r.true_slots;
      std::vector<int> mirror;
      for (int t : r.true_slots) mirror.push_back((g.num_elements - t) % g.num_elements);
      std::sort(mirror.begin(), mirror.end());
      r.positions_mirrored = !r.positions_right && stated == CanonicalSlots(mirror, g.num_elements);
    }
    r.width_stated = id.width_identifiable;
    r.width_m = id.width_m;
    r.width_low_m = id.width_low_m;
    r.width_high_m = id.width_high_m;
    if (id.width_fit.usable) {
      r.delay_s = id.width_fit.best.delay_s;
      r.delay_low_s = id.width_fit.delay_low_s;
      r.delay_high_s = id.width_fit.delay_high_s;
      r.delay_significance = id.width_fit.delay_power_significance;
      r.pair_power_ratio = id.width_fit.best.PairPowerRatio();
    }
    if (id.width_fit_exclusive.usable) {
      r.exclusive_delay_s = id.width_fit_exclusive.best.delay_s;
      r.exclusive_pair_power_ratio = id.width_fit_exclusive.best.PairPowerRatio();
      r.exclusive_significance = id.width_fit_exclusive.delay_power_significance;
    }
    r.width_from_exclusive_zone = id.width_from_exclusive_zone;
    if (r.true_count > 0 && id.spin_hz > 0) {
      r.true_delay_s = 2.0 * std::asin(std::min(1.0, r.true_width_m / g.element_diameter_m)) /
                       (2.0 * kPi * id.spin_hz);
      if (id.width_fit.usable)
        r.true_release_delay_s = DelayOfWidth(r.true_width_m, g.element_diameter_m, id, io);
    }
    for (size_t i = 0; i < id.reasons.size(); ++i) {
      if (i) r.reasons += "; ";
      r.reasons += id.reasons[i];
    }
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace

ValidationReport ValidateOnFiles(const std::vector<std::string>& files,
                                 const ValidationOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  // Files are independent (the noise is seeded by the file's index), so workers take them in
  // turn and the report keeps the files' order: the same report for any number of workers.
  const size_t n = files.size();
  std::vector<std::vector<ValidatedRecord>> per_file(n);
  std::vector<std::exception_ptr> errors(n);
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;  // guards done and the progress callback
  int done = 0;
  auto work = [&] {
    for (size_t f = next++; f < n && !failed; f = next++) {
      try {
        per_file[f] = ValidateFile(files[f], f, options);
        if (options.progress) {
          std::lock_guard<std::mutex> lock(mutex);
          options.progress(++done, static_cast<int>(n), files[f]);
        }
      } catch (...) {
        errors[f] = std::current_exception();
        failed = true;
      }
    }
  };
  const int workers =
      static_cast<int>(std::min<size_t>(std::max(1, options.workers), std::max<size_t>(n, 1)));
  std::vector<std::thread> pool;
  for (int t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  ValidationReport report;
  for (auto& records : per_file)
    for (auto& r : records) report.records.push_back(std::move(r));
  return report;
}

std::string ValidationReport::Summary() const {
  std::map<double, std::vector<const ValidatedRecord*>> by_snr;
  for (const auto& r : records) by_snr[r.snr_db].push_back(&r);
  std::ostringstream os;
  for (auto it = by_snr.rbegin(); it != by_snr.rend(); ++it) {
    const auto& rs = it->second;
    os << "SNR " << (std::isfinite(it->first) ? FormatNumber("%g dB", it->first) : "clean") << ": "
       << rs.size() << " records\n";
    int max_true = 0, max_stated = 0;
    for (const auto* r : rs) {
      max_true = std::max(max_true, r->true_count);
      if (r->count_stated) max_stated = std::max(max_stated, r->count);
    }
    max_stated = std::max(max_stated, max_true);
    os << "  count confusion (rows truth, columns stated):\n    truth  refused";
    for (int k = 0; k <= max_stated; ++k) os << FormatNumber("%6.0f", k);
    os << "\n";
    int spalled = 0, right = 0, wrong = 0, refused = 0, positions = 0;
    for (int t = 0; t <= max_true; ++t) {
      std::vector<int> row(max_stated + 1, 0);
      int ref = 0, n = 0;
      for (const auto* r : rs) {
        if (r->true_count != t) continue;
        ++n;
        if (!r->count_stated) {
          ++ref;
        } else {
          ++row[r->count];
        }
        if (t > 0) {
          ++spalled;
          if (!r->count_stated)
            ++refused;
          else if (r->count == t)
            ++right, positions += r->positions_right;
          else
            ++wrong;
        }
      }
      if (n == 0) continue;
      os << FormatNumber("    %5.0f", t) << FormatNumber("  %7.0f", ref);
      for (int v : row) os << FormatNumber("%6.0f", v);
      os << "\n";
    }
    int healthy_stated = 0;
    for (const auto* r : rs) healthy_stated += r->true_count == 0 && r->count_stated;
    os << "  spalled records: " << spalled << "; count right " << right << " (positions right "
       << positions << "), wrong " << wrong << ", refused " << refused
       << "; healthy records given a count: " << healthy_stated << "\n";
    // The lower bound "at least k": stated, true count at least k, and where the count was not.
    int bound = 0, bound_right = 0, bound_uncounted = 0, bound_uncounted_above_one = 0;
    for (const auto* r : rs) {
      if (r->count_at_least == 0) continue;
      ++bound;
      bound_right += r->true_count >= r->count_at_least;
      if (!r->count_stated) ++bound_uncounted, bound_uncounted_above_one += r->count_at_least > 1;
    }
    os << "  lower bounds (at least k): " << bound << ", true count >= k on " << bound_right
       << "; on records without a stated count " << bound_uncounted << " (k >= 2 on "
       << bound_uncounted_above_one << ")\n";
    // Reliability: stated P(count) against the fraction right.
    const double edges[] = {0.5, 0.8, 0.95, 0.99, 1.0000001};
    os << "  reliability of stated counts (P bin: stated, right, mean P):";
    for (int b = 0; b + 1 < 5; ++b) {
      int n = 0, ok = 0;
      double p = 0.0;
      for (const auto* r : rs)
        if (r->count_stated && r->count_probability >= edges[b] &&
            r->count_probability < edges[b + 1])
          ++n, ok += r->count == r->true_count, p += r->count_probability;
      if (n)
        os << FormatNumber(" [%.2f", edges[b])
           << FormatNumber("-%.2f): ", std::min(1.0, edges[b + 1])) << n << ", " << ok << ", "
           << FormatNumber("%.3f", p / n) << ";";
    }
    os << "\n";
    // Width.
    std::vector<double> errors;
    int stated = 0, within = 0, covered = 0, with_spall = 0;
    for (const auto* r : rs) {
      if (r->true_count == 0) continue;
      ++with_spall;
      if (!r->width_stated) continue;
      ++stated;
      const double e = RelativeWidthError(*r);
      errors.push_back(e);
      within += e <= kWidthTolerance;
      covered += r->width_low_m <= r->true_width_m && r->true_width_m <= r->width_high_m;
    }
    os << "  width stated on " << stated << " of " << with_spall << " spalled records";
    if (stated) {
      std::sort(errors.begin(), errors.end());
      const double median = errors[errors.size() / 2];
      const double p90 = errors[std::min(errors.size() - 1, (errors.size() * 9) / 10)];
      os << ": within 15 % " << within << ", 90 % interval covers the truth " << covered
         << ", relative error median " << FormatNumber("%.1f %%", 100 * median)
         << ", 90th percentile " << FormatNumber("%.1f %%", 100 * p90);
    }
    os << "\n";
    // The same per class of the true width (0.5 mm classes): where the failures lie.
    std::map<int, std::array<int, 4>> by_width;  // spalled, no roller signature, right, within
    for (const auto* r : rs) {
      if (r->true_count == 0) continue;
      auto& c = by_width[static_cast<int>(std::floor(r->true_width_m / kWidthClassM))];
      ++c[0];
      c[1] += r->verdict != "rolling_element";
      c[2] += r->count_stated && r->count == r->true_count;
      c[3] += r->width_stated && RelativeWidthError(*r) <= kWidthTolerance;
    }
    if (!by_width.empty()) {
      os << "  by true width (spalled; no roller signature, count right, width within 15 %):";
      for (const auto& [cls, c] : by_width)
        os << FormatNumber(" [%.1f", cls * kWidthClassM * 1e3)
           << FormatNumber("-%.1f) mm: ", (cls + 1) * kWidthClassM * 1e3) << c[0] << "; " << c[1]
           << ", " << c[2] << ", " << c[3] << ";";
      os << "\n";
    }
    double cpu = 0.0, secs = 0.0;
    for (const auto* r : rs) cpu += r->cpu_s, secs += r->record_s;
    os << "  CPU (diagnosis + identification, one thread): "
       << FormatNumber("%.2f s per record second\n", secs > 0 ? cpu / secs : 0.0);
  }
  return os.str();
}

std::string ValidationReport::ToCsv() const {
  std::ostringstream os;
  os << "file,snr_db,true_count,true_slots,true_width_mm,speed_rpm,load_n,verdict,count_stated,"
        "count,count_probability,p_true_count,count_cage,p_cage,count_sidebands,p_sidebands,"
        "chi2_scale_cage,chi2_scale_sidebands,positions_right,positions_mirrored,width_stated,"
        "width_mm,width_low_mm,"
        "width_high_mm,true_delay_ms,delay_ms,delay_low_ms,delay_high_ms,delay_significance,"
        "pair_power_ratio,exclusive_delay_ms,exclusive_pair_power_ratio,exclusive_significance,"
        "width_from_exclusive_zone,cpu_s,"
        "log_evidence_cage,log_evidence_sidebands,true_release_delay_ms,hump_exponent,"
        "hump_edge_gain,hump_smear_deg,count_at_least,count_at_least_probability,reasons\n";
  auto joined = [](const std::vector<double>& v) {
    std::string out;
    for (size_t i = 0; i < v.size(); ++i) {
      if (i) out += ';';
      out += FormatNumber("%.6g", v[i]);
    }
    return out;
  };
  for (const auto& r : records) {
    std::string slots;
    for (size_t i = 0; i < r.true_slots.size(); ++i) {
      if (i) slots += ';';
      slots += std::to_string(r.true_slots[i]);
    }
    std::string reasons = r.reasons;
    std::replace(reasons.begin(), reasons.end(), '"', '\'');
    const double p_true = r.true_count < static_cast<int>(r.probabilities.size())
                              ? r.probabilities[r.true_count]
                              : 0.0;
    os << r.file << "," << (std::isfinite(r.snr_db) ? FormatNumber("%g", r.snr_db) : "inf") << ","
       << r.true_count << "," << slots << "," << FormatNumber("%.4f", r.true_width_m * 1e3) << ","
       << FormatNumber("%.1f", r.speed_rpm) << "," << FormatNumber("%.0f", r.load_n) << ","
       << r.verdict << "," << r.count_stated << "," << r.count << ","
       << FormatNumber("%.4g", r.count_probability) << "," << FormatNumber("%.4g", p_true) << ","
       << r.count_cage << "," << FormatNumber("%.4g", r.p_cage) << "," << r.count_sidebands << ","
       << FormatNumber("%.4g", r.p_sidebands) << "," << FormatNumber("%.3g", r.chi2_scale_cage)
       << "," << FormatNumber("%.3g", r.chi2_scale_sidebands) << "," << r.positions_right << ","
       << r.positions_mirrored << "," << r.width_stated << ","
       << FormatNumber("%.4f", r.width_m * 1e3) << "," << FormatNumber("%.4f", r.width_low_m * 1e3)
       << "," << FormatNumber("%.4f", r.width_high_m * 1e3) << ","
       << FormatNumber("%.4f", r.true_delay_s * 1e3) << "," << FormatNumber("%.4f", r.delay_s * 1e3)
       << "," << FormatNumber("%.4f", r.delay_low_s * 1e3) << ","
       << FormatNumber("%.4f", r.delay_high_s * 1e3) << ","
       << FormatNumber("%.3g", r.delay_significance) << ","
       << FormatNumber("%.3g", r.pair_power_ratio) << ","
       << FormatNumber("%.4f", r.exclusive_delay_s * 1e3) << ","
       << FormatNumber("%.3g", r.exclusive_pair_power_ratio) << ","
       << FormatNumber("%.3g", r.exclusive_significance) << "," << r.width_from_exclusive_zone
       << "," << FormatNumber("%.3f", r.cpu_s) << "," << joined(r.log_evidence_cage) << ","
       << joined(r.log_evidence_sidebands) << ","
       << FormatNumber("%.4f", r.true_release_delay_s * 1e3) << ","
       << FormatNumber("%.3g", r.hump_exponent) << "," << FormatNumber("%.3g", r.hump_edge_gain)
       << "," << FormatNumber("%.3g", r.hump_smear_deg) << "," << r.count_at_least << ","
       << FormatNumber("%.4g", r.count_at_least_probability) << ",\"" << reasons << "\"\n";
  }
  return os.str();
}

}  // namespace spallkit::identify
