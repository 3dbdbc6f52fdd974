#include "study/study_plot.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/format.h"
#include "core/hdf5.h"
#include "plot/plot.h"
#include "sim/bearing/roller_sliding.h"
#include "sim/bearing/scene.h"
#include "study/sweep.h"

namespace spallkit::study {
namespace {
namespace fs = std::filesystem;

struct Quantity {
  const char* name;
  const char* dataset;
  const char* label;  // y axis
  enum Kind { kRms, kKurtosis, kMax } kind;
  double scale;
};

constexpr Quantity kQuantities[] = {
    {"accel_rms", "/signals/accel_y", "vertical acceleration RMS (m/s^2)", Quantity::kRms, 1.0},
    {"accel_z_rms", "/signals/accel_z", "horizontal acceleration RMS (m/s^2)", Quantity::kRms, 1.0},
    {"accel_kurtosis",
     "/signals/accel_y",
     "vertical acceleration kurtosis",
     Quantity::kKurtosis,
     1.0},
    {"cage_slip_rms", "/cage/slip_ratio", "cage sliding ratio RMS (%)", Quantity::kRms, 100.0},
    {"cage_force_rms", "/contact/roller_cage", "roller-cage force RMS (N)", Quantity::kRms, 1.0},
    {"outer_force_max",
     "/contact/roller_outer",
     "largest roller-outer race force (N)",
     Quantity::kMax,
     1.0},
};

// A case's quantity over t >= from_s (all columns of a 2-D dataset together).
double ComputeQuantity(const std::string& file,
                       const std::string& dataset,
                       Quantity::Kind kind,
                       bool remove_mean,
                       double from_s) {
  const h5::File f = h5::File::OpenReadOnly(file);
  if (!f.IsDataset(dataset)) throw InputError("plot study: " + file + ": no " + dataset);
  std::vector<size_t> dims;
  const std::vector<double> data = f.ReadDataset(dataset, &dims);
  const size_t rows = dims.empty() ? 0 : dims[0];
  const size_t cols = rows ? data.size() / rows : 1;
  size_t first = 0;
  if (from_s > 0 && f.IsDataset("/time")) {
    const std::vector<double> t = f.ReadDataset("/time");
    while (first < t.size() && t[first] < from_s) ++first;
  }
  if (first >= rows) throw InputError("plot study: " + file + ": no samples after --from-s");
  // Non-finite samples (the slip ratio at rest) are left out.
  std::vector<double> v;
  for (size_t i = first * cols; i < data.size(); ++i)
    if (std::isfinite(data[i])) v.push_back(data[i]);
  if (v.empty()) throw InputError("plot study: " + file + ": " + dataset + " has no finite sample");
  if (kind == Quantity::kMax) return *std::max_element(v.begin(), v.end());
  double mean = 0;
  if (remove_mean || kind == Quantity::kKurtosis) {
    for (double x : v) mean += x;
    mean /= v.size();
  }
  double m2 = 0, m4 = 0;
  for (double x : v) {
    const double d = x - mean;
    m2 += d * d / v.size();
    m4 += d * d * d * d / v.size();
  }
  return kind == Quantity::kRms ? std::sqrt(m2) : (m2 > 0 ? m4 / (m2 * m2) : 0.0);
}

// Quantities of the defective rollers (the rollers of the case's [[defects]], read from the
// file's effective scene), averaged over them; NaN for a healthy case.
struct DefectiveQuantity {
  const char* name;
  const char* label;
};
constexpr DefectiveQuantity kDefectiveQuantities[] = {
    {"defective_cage_force_rms", "defective roller-cage force RMS (N)"},
    {"defective_rolling_percent", "defective roller rolling time (%)"},
    {"defective_slides_per_cage_rev", "defective roller sliding episodes per cage revolution"},
};

double ComputeDefectiveQuantity(const std::string& file, const std::string& name, double from_s) {
  const h5::File f = h5::File::OpenReadOnly(file);
  const std::optional<std::string> text = f.ReadStringAttribute("/", "scene");
  if (!text) throw InputError("plot study: " + file + ": no scene attribute");
  const sim::Scene scene = sim::ParseScene(*text, file);
  std::vector<int> rollers;
  for (const sim::Defect& d : scene.defects)
    if (std::find(rollers.begin(), rollers.end(), d.roller) == rollers.end())
      rollers.push_back(d.roller);
  if (rollers.empty()) return NAN;
  const std::vector<double> t = f.ReadDataset("/time");
  size_t first = 0;
  while (first < t.size() && t[first] < from_s) ++first;
  if (first >= t.size()) throw InputError("plot study: " + file + ": no samples after --from-s");
  auto column = [&](const char* dataset, int j) {
    if (!f.IsDataset(dataset)) throw InputError("plot study: " + file + ": no " + dataset);
    std::vector<size_t> dims;
    const std::vector<double> data = f.ReadDataset(dataset, &dims);
    const size_t cols = dims.size() == 2 ? dims[1] : 1;
    if (dims.empty() || dims[0] != t.size() || j >= static_cast<int>(cols))
      throw InputError("plot study: " + file + ": " + dataset + " does not match /time");
    std::vector<double> c(t.size());
    for (size_t i = 0; i < t.size(); ++i) c[i] = data[i * cols + j];
    return c;
  };
  double sum = 0;
  for (int j : rollers) {
    if (name == "defective_cage_force_rms") {  // RMS over every defective roller's samples
      const std::vector<double> force = column("/contact/roller_cage", j);
      for (size_t i = first; i < force.size(); ++i) sum += force[i] * force[i];
      continue;
    }
    sim::RollerSlidingOptions so;
    so.from_s = from_s;
    const sim::RollerSlidingSummary s = sim::MeasureRollerSliding(
        t,
        column("/rollers/spin", j),
        f.ReadDataset("/cage/omega"),
        sim::PureRollingRelativeSpin(scene.geometry.bearing,
                                     scene.operation.inner_ring_speed_rad_s),
        so);
    sum +=
        name == "defective_rolling_percent" ? 100.0 * s.rolling_fraction : s.episodes_per_cage_rev;
  }
  if (name == "defective_cage_force_rms")
    return std::sqrt(sum / static_cast<double>((t.size() - first) * rollers.size()));
  return sum / static_cast<double>(rollers.size());
}

// A parameter or label of a case as a number (NaN when absent or not numeric).
const nlohmann::json* Field(const nlohmann::json& c, const std::string& key) {
  for (const char* part : {"parameters", "labels"})
    if (c.contains(part) && c[part].contains(key)) return &c[part][key];
  if (c.contains(key)) return &c[key];
  return nullptr;
}

std::string Describe(const nlohmann::json* v) {
  if (!v) return "-";
  if (v->is_string()) return v->get<std::string>();
  return TomlValueText(*v);
}

}  // namespace

std::vector<std::string> StudyQuantities() {
  std::vector<std::string> names;
  for (const Quantity& q : kQuantities) names.push_back(q.name);
  for (const DefectiveQuantity& q : kDefectiveQuantities) names.push_back(q.name);
  names.push_back("rms:/PATH");
  return names;
}

namespace {

PlottedSeries PlotStudyFromIndex(const std::string& dir,
                                 const StudyPlotOptions& o,
                                 const std::string& png_path,
                                 const std::string& csv_path) {
  const fs::path index_path = fs::path(dir) / "index.json";
  std::ifstream in(index_path);
  if (!in)
    throw InputError("plot study: " + index_path.string() +
                     ": no index (a folder written by `spall dataset run`)");
  const nlohmann::json index = nlohmann::json::parse(in, nullptr, false);
  if (!index.is_object() || !index.contains("cases"))
    throw InputError("plot study: " + index_path.string() + ": not a dataset index");
  if (o.x.empty() || o.y.empty()) throw InputError("plot study: --x and --y are required");
  if (!(o.from_s >= 0))
    throw InputError("plot study: --from-s must be >= 0 s (got " + FormatNumber("%.6g", o.from_s) +
                     ")");

  // y: a computed quantity, rms:/PATH, or a numeric field of the index.
  const Quantity* quantity = nullptr;
  for (const Quantity& q : kQuantities)
    if (o.y == q.name) quantity = &q;
  const DefectiveQuantity* defective = nullptr;
  for (const DefectiveQuantity& q : kDefectiveQuantities)
    if (o.y == q.name) defective = &q;
  const bool rms_path = o.y.rfind("rms:", 0) == 0;
  std::vector<std::string> group = o.group;
  if (!o.group_set) {
    group.clear();
    for (const auto& k : index.value("grid_parameters", nlohmann::json::array()))
      if (k != o.x) group.push_back(k.get<std::string>());
  }

  // group -> x -> the cases' y values (averaged into one point; their spread is its error bar)
  std::map<std::string, std::map<double, std::vector<double>>> points;
  bool x_seen = false, y_seen = false;
  for (const auto& c : index["cases"]) {
    if (c.value("status", "") != "ok") continue;
    const nlohmann::json* xv = Field(c, o.x);
    if (xv) x_seen = true;
    if (!xv || !xv->is_number()) continue;
    double y = NAN;
    const std::string file = (fs::path(dir) / c.value("file", "")).string();
    if (quantity) {
      y = quantity->scale *
          ComputeQuantity(file, quantity->dataset, quantity->kind, true, o.from_s);
    } else if (defective) {
      y_seen = true;
      y = ComputeDefectiveQuantity(file, o.y, o.from_s);
    } else if (rms_path) {
      y = ComputeQuantity(file, o.y.substr(4), Quantity::kRms, false, o.from_s);
    } else if (const nlohmann::json* yv = Field(c, o.y)) {
      y_seen = true;
      if (yv->is_number()) y = yv->get<double>();
    }
    if (!std::isfinite(y)) continue;
    y_seen = true;
    std::string g;
    for (const std::string& k : group) {
      if (!g.empty()) g += ", ";
      g += k + " = " + Describe(Field(c, k));
    }
    points[g][xv->get<double>()].push_back(y);
  }
  if (!x_seen)
    throw InputError("plot study: --x " + o.x + ": no such parameter or label in " +
                     index_path.string());
  for (const std::string& k : group) {
    bool seen = false;
    for (const auto& c : index["cases"]) seen = seen || Field(c, k) != nullptr;
    if (!seen)
      throw InputError("plot study: --group " + k + ": no such parameter or label in " +
                       index_path.string());
  }
  if (!y_seen)
    throw InputError("plot study: --y " + o.y +
                     ": not a label of the index nor one of accel_rms, "
                     "accel_z_rms, accel_kurtosis, cage_slip_rms, cage_force_rms, "
                     "outer_force_max, defective_cage_force_rms, defective_rolling_percent, "
                     "defective_slides_per_cage_rev, rms:/PATH");
  if (points.empty()) throw InputError("plot study: " + dir + ": no finished case with numbers");

  plot::LinePlot p;
  p.width = o.width;
  p.height = o.height;
  const std::string y_label = quantity ? quantity->label : defective ? defective->label : o.y;
  p.title = y_label + " against " + o.x + " (" + fs::path(dir).filename().string() + ")";
  p.x_label = o.x;
  p.y_label = y_label;
  PlottedSeries out;
  out.x_name = o.x;
  std::vector<double> ys, groups, counts, stds;
  std::ostringstream csv;
  csv << "group," << o.x << "," << o.y << ",cases,std\n";
  size_t gi = 0;
  for (const auto& [g, xs] : points) {
    std::string quoted_group = "\"";  // a CSV cell: quotes doubled (string values carry quotes)
    for (char ch : g) quoted_group += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    quoted_group += '"';
    plot::LineSeries s;
    s.label = g.empty() ? o.y : g;
    s.color = plot::PaletteColor(gi);
    s.thickness = 2.0;
    for (const auto& [x, values] : xs) {
      const double n = static_cast<double>(values.size());
      double sum = 0, ss = 0;
      for (double v : values) sum += v;
      const double y = sum / n;
      for (double v : values) ss += (v - y) * (v - y);
      // Sample standard deviation of the cases (0 for one case: no bar).
      const double sd = values.size() > 1 ? std::sqrt(ss / (n - 1)) : 0.0;
      s.x.push_back(x);
      s.y.push_back(y);
      s.y_error.push_back(sd);
      out.x.push_back(x);
      ys.push_back(y);
      groups.push_back(static_cast<double>(gi));
      counts.push_back(n);
      stds.push_back(sd);
      csv << quoted_group << "," << TomlValueText(x) << "," << TomlValueText(y) << ","
          << values.size() << "," << TomlValueText(sd) << "\n";
    }
    p.series.push_back(std::move(s));
    ++gi;
  }
  out.columns = {{o.y, ys}, {"group", groups}, {"cases", counts}, {"std", stds}};
  p.legend = points.size() > 1 || !points.begin()->first.empty();
  // One x (or one y) value would make an empty axis range: widen it. Otherwise the points at
  // the ends keep their whole error bar and dot inside the frame.
  const auto [x_lo, x_hi] = std::minmax_element(out.x.begin(), out.x.end());
  if (*x_lo == *x_hi) {
    p.x_min = *x_lo - 0.5 - 0.1 * std::abs(*x_lo);
    p.x_max = 2 * *x_lo - p.x_min;
  } else {
    p.x_min = *x_lo - 0.04 * (*x_hi - *x_lo);
    p.x_max = *x_hi + 0.04 * (*x_hi - *x_lo);
  }
  const auto [y_lo, y_hi] = std::minmax_element(ys.begin(), ys.end());
  const bool bars = std::any_of(stds.begin(), stds.end(), [](double sd) { return sd > 0; });
  if (*y_lo == *y_hi && !bars) {
    p.y_min = *y_lo - 0.5 - 0.1 * std::abs(*y_lo);
    p.y_max = 2 * *y_lo - p.y_min;
  }
  plot::WriteLinePlot(png_path, p);
  if (!csv_path.empty()) WriteFileAtomically(csv_path, csv.str());
  return out;
}

}  // namespace

PlottedSeries PlotStudy(const std::string& dir,
                        const StudyPlotOptions& o,
                        const std::string& png_path,
                        const std::string& csv_path) {
  try {
    return PlotStudyFromIndex(dir, o, png_path, csv_path);
  } catch (const nlohmann::json::exception& e) {  // an index value of the wrong type
    throw InputError("plot study: " + (fs::path(dir) / "index.json").string() + ": " + e.what());
  }
}

}  // namespace spallkit::study
