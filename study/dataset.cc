#include "study/dataset.h"

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include "core/atomic_file.h"
#include "core/bearing.h"
#include "core/constants.h"
#include "core/error.h"
#include "core/hdf5.h"
#include "sim/bearing/fidelity_choice.h"
#include "sim/bearing/simulation.h"
#include "study/case_post.h"

namespace spallkit::study {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string FailedMarker(const SweepCase& c) { return c.id + ".failed"; }

// One line (the message of a failed case, kept on one CSV row).
std::string OneLine(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

// The folder records which sweep it holds (sweep.toml); another sweep file is refused, and so is
// a folder with files of its own (its index.csv or index.json would be overwritten). Writes
// nothing.
void CheckFolder(const Sweep& sweep, const std::string& out_dir) {
  std::error_code ec;
  if (!fs::exists(out_dir, ec)) return;
  if (!fs::is_directory(out_dir, ec))
    throw InputError(out_dir + ": exists and is not a folder (expected the dataset folder)");
  const fs::path copy = fs::path(out_dir) / "sweep.toml";
  if (fs::exists(copy, ec)) {
    if (ReadText(copy) != sweep.text)
      throw InputError(copy.string() +
                       ": the folder holds a dataset of another sweep file (the texts differ); "
                       "use another --out or remove the folder");
    return;
  }
  // Temporaries are another rank's sweep.toml being written (MPI) or a killed run's leftovers.
  bool own_files = false;
  for (const auto& entry : fs::directory_iterator(out_dir, ec))
    if (entry.path().filename().string().find(".tmp-") == std::string::npos) own_files = true;
  if (own_files)
    throw InputError(out_dir +
                     ": not empty and not a dataset folder (no sweep.toml); use a new or empty "
                     "folder");
}

// Creates the folder and records the sweep in it (after CheckFolder and the cases' scenes).
void ClaimFolder(const Sweep& sweep, const std::string& out_dir) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec || !fs::is_directory(out_dir))
    throw InputError(out_dir + ": cannot create the dataset folder (" + ec.message() + ")");
  const fs::path copy = fs::path(out_dir) / "sweep.toml";
  if (!fs::exists(copy)) WriteFileAtomically(copy.string(), sweep.text);
}

// Runs one case and writes its file; returns the finished entry.
IndexEntry RunCase(const Sweep& sweep, const SweepCase& c, const std::string& out_dir) {
  const auto start = Clock::now();
  IndexEntry entry;
  entry.sweep_case = c;
  const sim::Scene scene = CaseScene(sweep, c);
  sim::SimulationOptions so;
  // Long cases can checkpoint ([solver] checkpoint_interval_s in base.set) and resume mid-case.
  const fs::path file = fs::path(out_dir) / CaseFileName(c);
  if (scene.solver.checkpoint_interval_s > 0) {
    so.checkpoint_path = file.string() + ".ckpt";
    so.resume = fs::exists(so.checkpoint_path);
  }
  sim::Simulation simulation(scene, so);
  const sim::SimulationSummary summary = simulation.Run();
  entry.wall_seconds = Seconds(start);
  entry.labels = MakeLabels(scene).ToJson();

  AtomicFile out(file.string());
  {
    h5::File f = h5::File::Create(out.temp_path());
    // The attributes `spall simulate` writes, then the case's.
    f.SetAttribute("/", "spallkit_version", SPALLKIT_VERSION);
    f.SetAttribute("/", "scene", scene.effective_toml);
    f.SetAttribute("/", "mesh_quality", simulation.model().mesh_quality().Report());
    f.SetAttribute("/", "steps", static_cast<double>(summary.steps));
    f.SetAttribute("/", "energy_balance_error", summary.energy_balance_error);
    simulation.recorder().Write(&f);
    PostProcessCase(sweep, c, scene, &f, &entry.labels);

    nlohmann::ordered_json parameters = nlohmann::ordered_json::object();
    for (const auto& [key, value] : c.parameters) parameters[key] = value;
    nlohmann::ordered_json case_json = {{"case_id", c.id},
                                        {"index", c.index},
                                        {"parameters", parameters},
                                        {"labels", entry.labels},
                                        {"overrides", CaseOverrides(sweep, c)}};
    f.SetAttribute("/", "case_id", c.id);
    f.SetAttribute("/", "case_json", case_json.dump());
    for (const auto& [key, value] : entry.labels.items()) {
      if (value.is_number())
        f.SetAttribute("/", key, value.get<double>());
      else if (value.is_string())
        f.SetAttribute("/", key, value.get<std::string>());
    }
    f.SetAttribute("/", "wall_seconds", entry.wall_seconds);
    f.Close();
  }
  out.Commit();
  if (!so.checkpoint_path.empty()) fs::remove(so.checkpoint_path);
  entry.status = CaseStatus::kOk;
  entry.file = CaseFileName(c);
  return entry;
}

IndexEntry RunCaseRecordingFailure(const Sweep& sweep,
                                   const SweepCase& c,
                                   const std::string& out_dir) {
  try {
    return RunCase(sweep, c, out_dir);
  } catch (const std::exception& e) {
    IndexEntry entry;
    entry.sweep_case = c;
    entry.status = CaseStatus::kFailed;
    entry.error = OneLine(e.what());
    entry.labels = MakeLabels(CaseScene(sweep, c)).ToJson();
    WriteFileAtomically((fs::path(out_dir) / FailedMarker(c)).string(), entry.error + "\n");
    return entry;
  }
}

// Temporary files of killed runs ("case-00003.h5.tmp-1234"), by case file name. Other temporary
// files (index, sweep copy, failure markers) are removed here when the process that wrote them
// is gone: another process on the folder may be writing its own at this moment.
std::set<std::string> StaleTemporaries(const std::string& out_dir) {
  std::set<std::string> case_files;
  for (const auto& e : fs::directory_iterator(out_dir)) {
    const std::string name = e.path().filename().string();
    const auto tmp = name.find(".tmp-");
    if (tmp == std::string::npos) continue;
    if (name.find(".h5.tmp-") != std::string::npos) {
      case_files.insert(name);
      continue;
    }
    const long pid = std::strtol(name.c_str() + tmp + 5, nullptr, 10);
    if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) fs::remove(e.path());
  }
  return case_files;
}

std::string CsvCell(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"') out += '"';
    out += ch;
  }
  return out + "\"";
}

std::string CsvValue(const nlohmann::ordered_json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return CsvCell(v.get<std::string>());
  if (v.is_number_float()) return TomlValueText(v.get<double>());
  if (v.is_array()) return CsvCell(TomlValueText(nlohmann::json::parse(v.dump())));
  return CsvCell(v.dump());
}

}  // namespace

const char* CaseStatusName(CaseStatus status) {
  switch (status) {
    case CaseStatus::kOk:
      return "ok";
    case CaseStatus::kFailed:
      return "failed";
    case CaseStatus::kPending:
      break;
  }
  return "pending";
}

std::string CaseFileName(const SweepCase& c) { return c.id + ".h5"; }

nlohmann::ordered_json CaseLabels::ToJson() const {
  return {{"fault_class", fault_class},
          {"defect_count", defect_count},
          {"rollers", rollers},
          {"width_mm", width_mm},
          {"depth_mm", depth_mm},
          {"angle_deg", angle_deg},
          {"speed_rpm", speed_rpm},
          {"radial_load_n", radial_load_n},
          {"diametral_clearance_mm", diametral_clearance_mm},
          {"mu_dynamic", mu_dynamic},
          {"shaft_hz", shaft_hz},
          {"f_b_hz", f_b_hz},
          {"f_c_hz", f_c_hz},
          {"fidelity", fidelity},
          {"duration_s", duration_s},
          {"output_rate_hz", output_rate_hz}};
}

namespace {
// Twelve significant digits: labels converted from SI read 1000 rpm, not 999.9999999999999.
double Round12(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.12g", x);
  return std::strtod(buf, nullptr);
}
}  // namespace

CaseLabels MakeLabels(const sim::Scene& scene) {
  CaseLabels l;
  l.defect_count = static_cast<int>(scene.defects.size());
  l.fault_class = scene.defects.empty() ? "healthy" : "roller";
  for (size_t i = 0; i < scene.defects.size(); ++i) {
    if (i) l.rollers += ';';
    l.rollers += std::to_string(scene.defects[i].roller);
  }
  if (!scene.defects.empty()) {
    l.width_mm = Round12(scene.defects[0].width_m * 1e3);
    l.depth_mm = Round12(scene.defects[0].depth_m * 1e3);
    l.angle_deg = Round12(scene.defects[0].angle_rad * 180.0 / kPi);
  }
  const double shaft_hz = scene.operation.inner_ring_speed_rad_s / (2 * kPi);
  l.shaft_hz = Round12(shaft_hz);
  l.speed_rpm = Round12(shaft_hz * 60.0);
  l.radial_load_n = scene.operation.radial_load_n;
  l.diametral_clearance_mm = Round12(scene.geometry.diametral_clearance_m * 1e3);
  l.mu_dynamic = scene.friction.mu_dynamic;
  if (shaft_hz > 0) {
    const BearingFrequencies f = ComputeFrequencies(scene.geometry.bearing, shaft_hz);
    l.f_b_hz = Round12(f.f_b_hz);
    l.f_c_hz = Round12(f.cage_hz);
  }
  l.fidelity = sim::FidelityName(sim::ChooseFidelity(scene).fidelity);  // "auto" resolved
  l.duration_s = scene.run.duration_s;
  l.output_rate_hz = scene.run.output_rate_hz;
  return l;
}

bool DatasetOptions::Validate(std::string* error) const {
  std::string e;
  if (out_dir.empty())
    e = "the output folder is empty";
  else if (workers < 1 || workers > 4096)
    e = "workers must be in [1, 4096]";
  else if (part_count < 1 || part_index < 0 || part_index >= part_count)
    e = "part " + std::to_string(part_index) + "/" + std::to_string(part_count) +
        ": expected 0 <= index < count";
  if (error) *error = e;
  return e.empty();
}

std::string DatasetSummary::BriefReport() const {
  char buf[512];
  std::snprintf(buf,
                sizeof buf,
                "dataset %s: %d cases (%d in this part): %d already done, %d run now, %d failed, "
                "%d missing; wall %.1f s, case time %.1f s",
                out_dir.c_str(),
                total_cases,
                part_cases,
                already_done,
                ran,
                failed,
                pending,
                wall_seconds,
                case_seconds);
  return buf;
}

std::vector<IndexEntry> ScanDataset(const Sweep& sweep, const std::string& out_dir) {
  std::vector<IndexEntry> entries;
  const int n = sweep.num_cases();
  entries.reserve(n);
  for (int i = 0; i < n; ++i) {
    IndexEntry entry;
    entry.sweep_case = MakeCase(sweep, i);
    const SweepCase& c = entry.sweep_case;
    const sim::Scene scene = CaseScene(sweep, c);
    entry.labels = MakeLabels(scene).ToJson();
    const fs::path file = fs::path(out_dir) / CaseFileName(c);
    if (fs::exists(file)) {
      const h5::File f = h5::File::OpenReadOnly(file.string());
      if (f.ReadStringAttribute("/", "scene").value_or("") != scene.effective_toml)
        throw InputError(file.string() + ": made from another scene than the sweep's " + c.id +
                         " (was the sweep edited?); use another --out");
      if (auto j = f.ReadStringAttribute("/", "case_json")) {
        const auto parsed = nlohmann::ordered_json::parse(*j, nullptr, false);
        if (parsed.is_object() && parsed.contains("labels")) entry.labels = parsed["labels"];
      }
      entry.wall_seconds = f.ReadDoubleAttribute("/", "wall_seconds").value_or(0.0);
      entry.status = CaseStatus::kOk;
      entry.file = CaseFileName(c);
    } else if (const fs::path marker = fs::path(out_dir) / FailedMarker(c); fs::exists(marker)) {
      entry.status = CaseStatus::kFailed;
      entry.error = OneLine(ReadText(marker));
      while (!entry.error.empty() && entry.error.back() == ' ') entry.error.pop_back();
    }
    entries.push_back(std::move(entry));
  }
  return entries;
}

void WriteIndex(const Sweep& sweep,
                const std::string& out_dir,
                const std::vector<IndexEntry>& entries) {
  const std::vector<std::string> params = sweep.ParameterKeys();
  std::vector<std::string> grid;
  for (const auto& g : sweep.grid) grid.push_back(g.first);
  // Label columns: every label any case has, in first-seen order.
  std::vector<std::string> labels;
  for (const IndexEntry& e : entries)
    for (const auto& [key, value] : e.labels.items())
      if (std::find(labels.begin(), labels.end(), key) == labels.end()) labels.push_back(key);

  std::ostringstream csv;
  csv << "case_id,status,file,wall_s";
  for (const auto& p : params) csv << "," << CsvCell(p);
  for (const auto& l : labels) csv << "," << CsvCell(l);
  csv << ",error\n";
  nlohmann::ordered_json cases = nlohmann::ordered_json::array();
  for (const IndexEntry& e : entries) {
    const SweepCase& c = e.sweep_case;
    csv << c.id << "," << CaseStatusName(e.status) << "," << CsvCell(e.file) << ","
        << TomlValueText(e.wall_seconds);
    nlohmann::ordered_json pj = nlohmann::ordered_json::object();
    for (const auto& [key, value] : c.parameters) pj[key] = value;
    for (const auto& p : params) csv << "," << (pj.contains(p) ? CsvValue(pj[p]) : "");
    for (const auto& l : labels) csv << "," << (e.labels.contains(l) ? CsvValue(e.labels[l]) : "");
    csv << "," << CsvCell(e.error) << "\n";
    nlohmann::ordered_json j = {{"case_id", c.id},
                                {"index", c.index},
                                {"status", CaseStatusName(e.status)},
                                {"file", e.file},
                                {"wall_s", e.wall_seconds},
                                {"parameters", pj},
                                {"labels", e.labels}};
    if (!e.error.empty()) j["error"] = e.error;
    cases.push_back(std::move(j));
  }
  nlohmann::ordered_json index = {{"sweep", fs::path(sweep.path).filename().string()},
                                  {"base_scene", sweep.base_scene},
                                  {"cases_total", static_cast<int>(entries.size())},
                                  {"parameters", params},
                                  {"grid_parameters", grid},
                                  {"cases", cases}};
  WriteFileAtomically((fs::path(out_dir) / "index.csv").string(), csv.str());
  WriteFileAtomically((fs::path(out_dir) / "index.json").string(), index.dump(1) + "\n");
}

DatasetSummary RunDataset(const Sweep& sweep, const DatasetOptions& options) {
  std::string error;
  if (!options.Validate(&error)) throw InputError("dataset: " + error);
  const auto start = Clock::now();
  // Every case's scene is checked (ScanDataset) before the folder is made: a bad grid value
  // leaves nothing behind.
  CheckFolder(sweep, options.out_dir);
  std::vector<IndexEntry> entries = ScanDataset(sweep, options.out_dir);
  ClaimFolder(sweep, options.out_dir);

  DatasetSummary summary;
  summary.out_dir = options.out_dir;
  summary.total_cases = static_cast<int>(entries.size());
  std::vector<int> todo;
  for (const IndexEntry& e : entries) {
    if (e.sweep_case.index % options.part_count != options.part_index) continue;
    ++summary.part_cases;
    if (e.status == CaseStatus::kOk) ++summary.already_done;
    const bool retry = e.status == CaseStatus::kFailed && options.retry_failed;
    if (e.status == CaseStatus::kPending || retry) todo.push_back(e.sweep_case.index);
  }
  // Leftovers of a killed run for the cases about to run again.
  const std::set<std::string> stale = StaleTemporaries(options.out_dir);
  for (int i : todo) {
    const std::string prefix = CaseFileName(entries[i].sweep_case) + ".tmp-";
    for (auto it = stale.lower_bound(prefix); it != stale.end() && it->rfind(prefix, 0) == 0; ++it)
      fs::remove(fs::path(options.out_dir) / *it);
    fs::remove(fs::path(options.out_dir) / FailedMarker(entries[i].sweep_case));
  }

  std::mutex mutex;  // guards entries, the counters, the index files and the progress callback
  std::atomic<size_t> next{0};
  DatasetProgress progress;
  progress.total = summary.part_cases;
  progress.done = summary.already_done;
  int ran_now = 0;
  // An error outside a case (writing the index, the progress callback) stops every worker and is
  // rethrown once they have joined; a thread must not end the process.
  std::exception_ptr error_in_worker;
  auto work = [&] {
    for (size_t k = next++; k < todo.size(); k = next++) {
      const int i = todo[k];
      {
        std::lock_guard<std::mutex> lock(mutex);
        ++progress.running;
      }
      IndexEntry result = RunCaseRecordingFailure(sweep, entries[i].sweep_case, options.out_dir);
      std::lock_guard<std::mutex> lock(mutex);
      --progress.running;
      ++ran_now;
      if (result.status == CaseStatus::kOk) {
        ++progress.done;
        ++summary.ran;
      } else {
        ++progress.failed;
        ++summary.failed;
      }
      summary.case_seconds += result.wall_seconds;
      entries[i] = std::move(result);
      if (options.write_index) WriteIndex(sweep, options.out_dir, entries);
      if (options.progress) {
        progress.wall_seconds = Seconds(start);
        const int left = static_cast<int>(todo.size()) - ran_now;
        progress.eta_seconds = progress.wall_seconds / ran_now * left;
        progress.last_case = entries[i].sweep_case.id;
        options.progress(progress);
      }
    }
  };
  auto worker = [&] {
    try {
      work();
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      if (!error_in_worker) error_in_worker = std::current_exception();
      next = todo.size();
    }
  };
  const int threads = std::max(1, std::min<int>(options.workers, static_cast<int>(todo.size())));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (error_in_worker) std::rethrow_exception(error_in_worker);

  if (options.write_index) WriteIndex(sweep, options.out_dir, entries);
  summary.pending = summary.part_cases - summary.already_done - summary.ran;
  summary.wall_seconds = Seconds(start);
  return summary;
}

}  // namespace spallkit::study
