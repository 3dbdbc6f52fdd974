#include "study/case_post.h"

#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "core/constants.h"
#include "core/error.h"
#include "core/record.h"
#include "dsp/diagnose.h"
#include "study/random_stream.h"

namespace spallkit::study {
namespace {

void AddNoise(const Sweep& sweep, const SweepCase& c, h5::File* file) {
  const double snr_db = sweep.post.noise_snr_db;
  for (const std::string& path : file->ListDatasets()) {
    if (path.rfind("/signals/", 0) != 0) continue;
    std::vector<double> x = file->ReadDataset(path);
    if (x.empty()) continue;
    // Keep the attributes: writing the dataset again replaces it.
    std::map<std::string, double> numbers;
    std::map<std::string, std::string> strings;
    for (const std::string& a : file->ListAttributes(path)) {
      try {
        if (auto d = file->ReadDoubleAttribute(path, a)) numbers[a] = *d;
      } catch (const InputError&) {  // not numeric: a string
        if (auto s = file->ReadStringAttribute(path, a)) strings[a] = *s;
      }
    }
    const double mean = std::accumulate(x.begin(), x.end(), 0.0) / x.size();
    double ss = 0;
    for (double v : x) ss += (v - mean) * (v - mean);
    const double sigma = std::sqrt(ss / x.size()) * std::pow(10.0, -snr_db / 20.0);
    // One stream per sensor direction, so duplicated channels get the same noise.
    const std::string channel =
        strings.count("sensor") ? strings["sensor"] + "_" + strings["direction"] : path;
    uint64_t h = 1469598103934665603ULL;  // FNV-1a of the channel name
    for (unsigned char ch : channel) h = (h ^ ch) * 1099511628211ULL;
    RandomStream rng(sweep.seed ^ h, static_cast<uint64_t>(c.index));
    for (double& v : x) v += sigma * rng.Normal();
    file->WriteDataset(path, x);
    for (const auto& [a, v] : numbers) file->SetAttribute(path, a, v);
    for (const auto& [a, v] : strings) file->SetAttribute(path, a, v);
    file->SetAttribute(path, "noise_snr_db", snr_db);
  }
}

void AddDiagnosis(const sim::Scene& scene, h5::File* file, nlohmann::ordered_json* labels) {
  std::string verdict = "not_diagnosed";
  double f_b = std::numeric_limits<double>::quiet_NaN();
  std::string note;
  if (file->IsDataset("/signals/accel_y")) {
    Record record;
    record.samples = file->ReadDataset("/signals/accel_y");
    record.sample_rate_hz = scene.run.output_rate_hz;
    record.channel = "/signals/accel_y";
    record.units = "m/s^2";
    dsp::DiagnoseOptions options;
    options.threads = 1;  // the sweep runs cases in parallel already
    try {
      const dsp::Diagnosis d = dsp::Diagnose(record,
                                             scene.geometry.bearing,
                                             scene.operation.inner_ring_speed_rad_s / (2 * kPi),
                                             options);
      verdict = dsp::VerdictName(d.verdict);
      if (d.measured_f_b_hz) f_b = *d.measured_f_b_hz;
    } catch (const InputError& e) {
      note = e.what();  // too short or otherwise not diagnosable: the labels say so and why
    }
  }
  (*labels)["verdict"] = verdict;
  (*labels)["diagnosed_f_b_hz"] = f_b;
  (*labels)["diagnose_note"] = note;
}

}  // namespace

void PostProcessCase(const Sweep& sweep,
                     const SweepCase& c,
                     const sim::Scene& scene,
                     h5::File* file,
                     nlohmann::ordered_json* labels) {
  if (std::isfinite(sweep.post.noise_snr_db)) {
    AddNoise(sweep, c, file);
    (*labels)["noise_snr_db"] = sweep.post.noise_snr_db;
  }
  if (sweep.post.diagnose) AddDiagnosis(scene, file, labels);
}

}  // namespace spallkit::study
