#include "dsp/diagnosis_benchmark.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/input_file.h"
#include "core/record_io.h"

namespace spallkit::dsp {

std::optional<Verdict> ParseTruth(const std::string& fault) {
  if (fault == "normal" || fault == "healthy") return Verdict::kHealthy;
  if (fault == "inner_race") return Verdict::kInnerRace;
  if (fault.rfind("outer_race", 0) == 0) return Verdict::kOuterRace;
  if (fault == "ball" || fault == "roller" || fault == "rolling_element")
    return Verdict::kRollingElement;
  if (fault == "cage") return Verdict::kCage;
  return std::nullopt;
}

namespace {

using nlohmann::json;

[[noreturn]] void Bad(const std::string& manifest, size_t i, const std::string& what) {
  throw InputError(manifest + ": record " + std::to_string(i) + ": " + what);
}

double Number(const json& e, const char* key, const std::string& manifest, size_t i) {
  const auto it = e.find(key);
  if (it == e.end() || !it->is_number())
    Bad(manifest, i, std::string("key '") + key + "' must be a number");
  return it->get<double>();
}

LabelledRecord ParseEntry(const json& e,
                          const std::filesystem::path& folder,
                          const std::string& manifest,
                          size_t i) {
  if (!e.is_object()) Bad(manifest, i, "expected an object");
  LabelledRecord r;
  if (!e.contains("file") || !e["file"].is_string())
    Bad(manifest, i, "key 'file' must be a string (the record's path)");
  r.name = e["file"].get<std::string>();
  r.path = (folder / r.name).string();
  if (!e.contains("fault") || !e["fault"].is_string())
    Bad(manifest, i, "key 'fault' must be a string (the ground truth)");
  r.fault = e["fault"].get<std::string>();
  const auto truth = ParseTruth(r.fault);
  if (!truth)
    Bad(manifest,
        i,
        "key 'fault' = '" + r.fault +
            "': expected normal, healthy, inner_race, outer_race*, ball, roller, "
            "rolling_element or cage");
  r.truth = *truth;
  const char* rpm_key = e.contains("rpm_from_file") ? "rpm_from_file" : "rpm";
  const double rpm = Number(e, rpm_key, manifest, i);
  if (!(rpm > 0.0 && std::isfinite(rpm)))
    Bad(manifest, i, std::string("key '") + rpm_key + "' must be > 0 rpm");
  r.shaft_hz = rpm / 60.0;
  if (e.contains("fs_hz")) {
    r.sample_rate_hz = Number(e, "fs_hz", manifest, i);
    if (!(r.sample_rate_hz > 0.0 && std::isfinite(r.sample_rate_hz)))
      Bad(manifest, i, "key 'fs_hz' must be > 0");
  }
  // "column", not "channel": measured-data manifests use "channel" to describe the sensor.
  if (e.contains("column")) {
    if (!e["column"].is_string()) Bad(manifest, i, "key 'column' must be a string");
    r.channel = e["column"].get<std::string>();
  }
  try {
    if (e.contains("bearing_geometry")) {
      const json& g = e["bearing_geometry"];
      if (!g.is_object()) Bad(manifest, i, "key 'bearing_geometry' must be an object");
      const double z = Number(g, "n_rolling_elements", manifest, i);
      r.bearing = CustomBearing(
          static_cast<int>(z),
          Number(g, "element_diameter_mm", manifest, i),
          Number(g, "pitch_diameter_mm", manifest, i),
          g.contains("contact_angle_deg") ? Number(g, "contact_angle_deg", manifest, i) : 0.0);
      if (g.contains("bearing") && g["bearing"].is_string())
        r.bearing.name = g["bearing"].get<std::string>();
    } else if (e.contains("bearing") && e["bearing"].is_string()) {
      r.bearing = CatalogBearing(e["bearing"].get<std::string>());
    } else {
      Bad(manifest, i, "needs 'bearing' (catalogue name) or 'bearing_geometry'");
    }
  } catch (const InputError& err) {
    const std::string m = err.what();
    if (m.rfind(manifest, 0) == 0) throw;
    Bad(manifest, i, m);
  }
  return r;
}

}  // namespace

std::vector<LabelledRecord> ReadBenchmarkManifest(const std::string& manifest_path) {
  const std::string text = ReadInputFile(manifest_path, "a manifest (JSON)");
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {  // also numbers the parser cannot hold (1e400)
    throw InputError(manifest_path + ": not valid JSON (" + e.what() + ")");
  }
  const json* list = &j;
  if (j.is_object() && j.contains("records")) list = &j["records"];
  if (!list->is_array())
    throw InputError(manifest_path + ": expected an array of records or {\"records\": [...]}");
  if (list->empty()) throw InputError(manifest_path + ": no records");
  const std::filesystem::path folder = std::filesystem::path(manifest_path).parent_path();
  std::vector<LabelledRecord> out;
  for (size_t i = 0; i < list->size(); ++i) {
    try {
      out.push_back(ParseEntry((*list)[i], folder, manifest_path, i));
    } catch (const json::exception& e) {  // a value of the wrong type
      throw InputError(manifest_path + ": record " + std::to_string(i) + ": " + e.what());
    }
  }
  return out;
}

BenchmarkResult RunDiagnosisBenchmark(const std::vector<LabelledRecord>& records,
                                      const DiagnoseOptions& options,
                                      const BenchmarkProgress& progress) {
  BenchmarkResult result;
  for (const LabelledRecord& rec : records) {
    BenchmarkRow row;
    row.record = rec;
    try {
      RecordOptions ro;
      ro.sample_rate_hz = rec.sample_rate_hz;
      ro.channel = rec.channel;
      const Record record = ReadRecord(rec.path, ro);
      row.duration_s = record.duration_s();
      const auto t0 = std::chrono::steady_clock::now();
      const Diagnosis d = Diagnose(record, rec.bearing, rec.shaft_hz, options);
      row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      row.verdict = d.verdict;
      row.confident = d.warnings.empty();
      row.band = d.band;
      row.measured_shaft_hz = d.measured_shaft_hz;
      if (const FamilyDetection* best = d.Best()) {
        row.p_value = best->p_value;
        row.best_family = ComponentName(best->component);
        row.measured_hz = best->fundamental_hz;
        for (const auto& f : d.families)
          if (f.component == best->component) row.kinematic_hz = f.fundamental_hz;
        row.evidence = best->reason;
      }
    } catch (const std::exception& e) {
      row.error = e.what();
    }
    if (!row.verdict) {
      ++result.refused;
    } else {
      ++result.confusion[static_cast<int>(rec.truth)][static_cast<int>(*row.verdict)];
      result.correct += *row.verdict == rec.truth;
      result.false_alarms += rec.truth == Verdict::kHealthy && *row.verdict != Verdict::kHealthy;
    }
    result.healthy_records += rec.truth == Verdict::kHealthy;
    result.total_seconds += row.seconds;
    result.rows.push_back(std::move(row));
    if (progress)
      progress(static_cast<int>(result.rows.size()), static_cast<int>(records.size()), rec.path);
  }
  return result;
}

std::string BenchmarkResult::BriefReport() const {
  std::string out;
  char buf[512];
  std::snprintf(buf,
                sizeof buf,
                "%-40s %-16s %-16s %-9s %-16s %-13s %s\n",
                "record",
                "truth",
                "verdict",
                "p-value",
                "band (Hz)",
                "f meas/kin",
                "ms");
  out += buf;
  for (const auto& r : rows) {
    if (!r.verdict) {
      std::snprintf(buf,
                    sizeof buf,
                    "%-40s %-16s REFUSED: %s\n",
                    r.record.name.c_str(),
                    VerdictName(r.record.truth),
                    r.error.c_str());
      out += buf;
      continue;
    }
    char band[48], rates[48];
    std::snprintf(band, sizeof band, "%.0f-%.0f", r.band.low_hz, r.band.high_hz);
    std::snprintf(rates, sizeof rates, "%.2f/%.2f", r.measured_hz.value_or(0.0), r.kinematic_hz);
    std::snprintf(buf,
                  sizeof buf,
                  "%-40s %-16s %-16s %-9.2g %-16s %-13s %.1f%s%s\n",
                  r.record.name.c_str(),
                  VerdictName(r.record.truth),
                  VerdictName(*r.verdict),
                  r.p_value,
                  band,
                  rates,
                  r.seconds * 1e3,
                  *r.verdict == r.record.truth ? "" : "   <- wrong",
                  r.confident ? "" : " (warnings)");
    out += buf;
  }
  out += "\nconfusion matrix (rows: truth, columns: verdict)\n";
  std::snprintf(buf, sizeof buf, "%-16s", "");
  out += buf;
  for (int v = 0; v < kVerdicts; ++v) {
    std::snprintf(buf, sizeof buf, " %15s", VerdictName(static_cast<Verdict>(v)));
    out += buf;
  }
  out += "\n";
  for (int t = 0; t < kVerdicts; ++t) {
    int total = 0;
    for (int v = 0; v < kVerdicts; ++v) total += confusion[t][v];
    if (total == 0) continue;
    std::snprintf(buf, sizeof buf, "%-16s", VerdictName(static_cast<Verdict>(t)));
    out += buf;
    for (int v = 0; v < kVerdicts; ++v) {
      std::snprintf(buf, sizeof buf, " %15d", confusion[t][v]);
      out += buf;
    }
    out += "\n";
  }
  const int analysed = static_cast<int>(rows.size()) - refused;
  const double signal_s = SignalSeconds();
  std::snprintf(buf,
                sizeof buf,
                "correct %d of %d analysed (%d refused); false alarms %d of %d healthy; "
                "%.1f ms per record, %.2f ms per second of signal\n",
                correct,
                analysed,
                refused,
                false_alarms,
                healthy_records,
                analysed > 0 ? 1e3 * total_seconds / analysed : 0.0,
                signal_s > 0 ? 1e3 * total_seconds / signal_s : 0.0);
  out += buf;
  return out;
}

std::string BenchmarkResult::ToJson(int indent) const {
  using nlohmann::ordered_json;
  ordered_json j;
  ordered_json rows_json = ordered_json::array();
  for (const auto& r : rows) {
    ordered_json rj;
    rj["file"] = r.record.name;
    rj["fault"] = r.record.fault;
    rj["truth"] = VerdictName(r.record.truth);
    rj["verdict"] = r.verdict ? ordered_json(VerdictName(*r.verdict)) : ordered_json(nullptr);
    rj["correct"] = r.verdict && *r.verdict == r.record.truth;
    rj["error"] = r.error;
    rj["confident"] = r.confident;
    rj["best_family"] = r.best_family;
    rj["p_value"] = r.p_value;
    rj["band"] = {{"low_hz", r.band.low_hz}, {"high_hz", r.band.high_hz}};
    rj["measured_shaft_hz"] =
        r.measured_shaft_hz ? ordered_json(*r.measured_shaft_hz) : ordered_json(nullptr);
    rj["measured_hz"] = r.measured_hz ? ordered_json(*r.measured_hz) : ordered_json(nullptr);
    rj["kinematic_hz"] = r.kinematic_hz;
    rj["evidence"] = r.evidence;
    rj["duration_s"] = r.duration_s;
    rj["seconds"] = r.seconds;
    rows_json.push_back(rj);
  }
  j["records"] = rows_json;
  ordered_json classes = ordered_json::array();
  for (int c = 0; c < kVerdicts; ++c) classes.push_back(VerdictName(static_cast<Verdict>(c)));
  j["classes"] = classes;
  ordered_json m = ordered_json::array();
  for (int t = 0; t < kVerdicts; ++t) {
    ordered_json row = ordered_json::array();
    for (int v = 0; v < kVerdicts; ++v) row.push_back(confusion[t][v]);
    m.push_back(row);
  }
  j["confusion"] = m;  // [truth][verdict], in the order of "classes"
  j["correct"] = correct;
  j["refused"] = refused;
  j["false_alarms"] = false_alarms;
  j["healthy_records"] = healthy_records;
  j["seconds_total"] = total_seconds;
  j["signal_seconds_total"] = SignalSeconds();
  return j.dump(indent);
}

double BenchmarkResult::SignalSeconds() const {
  double total = 0.0;
  for (const auto& r : rows)
    if (r.verdict) total += r.duration_s;
  return total;
}

}  // namespace spallkit::dsp
