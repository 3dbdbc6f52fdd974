#include "core/record_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/hdf5.h"
#include "core/input_file.h"

namespace spallkit {
namespace {

// Jitter allowed on a time column, as a fraction of the step (see record.h).
constexpr double kRelativeTimeTolerance = 1e-4;
// Agreement required between a "# fs=" comment and the time column.
constexpr double kRateAgreement = 1e-4;
// The largest printing rounding credited to a time value, as a fraction of the step.
constexpr double kMaxRounding = 0.05;

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) {
    s.remove_prefix(1);
  }
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) {
    s.remove_suffix(1);
  }
  return s;
}

std::string_view Unquote(std::string_view s) {
  s = Trim(s);
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = Trim(s.substr(1, s.size() - 2));
  return s;
}

// A column name without a trailing unit in parentheses or brackets: "accel_z (m/s^2)" ->
// "accel_z".
std::string_view WithoutUnit(std::string_view header) {
  if (header.empty() || (header.back() != ')' && header.back() != ']')) return header;
  const char open = header.back() == ')' ? '(' : '[';
  const size_t at = header.rfind(open);
  if (at == std::string_view::npos || at == 0) return header;
  std::string_view stem = header.substr(0, at);
  while (!stem.empty() && (stem.back() == ' ' || stem.back() == '\t')) stem.remove_suffix(1);
  return stem.empty() ? header : stem;
}

std::string Lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string FormatNumber(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

// Parses a whole cell as a number. Leading '+' is accepted (from_chars does not take it).
bool ParseNumber(std::string_view cell, double* value) {
  const char* begin = cell.data();
  const char* end = begin + cell.size();
  if (begin != end && *begin == '+') ++begin;
  if (begin == end) return false;
  const auto [ptr, ec] = std::from_chars(begin, end, *value);
  return ec == std::errc() && ptr == end;
}

// How finely a time column was printed, to tell rounding by the writer from real jitter.
// Two writer models: fixed decimals ("%.9f": the finest last-digit position seen is the rounding
// unit everywhere) and significant digits ("%g", shortest round-trip: the rounding unit grows with
// |t|). The estimate for a value is the larger of the two, which is exact for either writer and
// never smaller than the truth; trailing zeros stripped by "%g" cannot fool it because the finest
// and the longest cells decide.
class PrintResolution {
 public:
  void Add(std::string_view cell) {
    int decimals = 0, exponent = 0, significant = 0;
    bool leading = true, after_dot = false;
    size_t i = 0;
    for (; i < cell.size(); ++i) {
      const char c = cell[i];
      if (c == '.') {
        after_dot = true;
      } else if (c >= '0' && c <= '9') {
        if (after_dot) ++decimals;
        if (c != '0') leading = false;
        if (!leading) ++significant;
      } else if (c == 'e' || c == 'E') {
        break;
      }
    }
    if (i < cell.size()) {
      const char* b = cell.data() + i + 1;
      const char* end = cell.data() + cell.size();
      if (b != end && *b == '+') ++b;
      std::from_chars(b, end, exponent);
    }
    finest_exp_ = std::min(finest_exp_, std::clamp(exponent - decimals, -320, 320));
    max_significant_ = std::max(max_significant_, significant);
  }
  // Half a unit of the writer's last digit at value t (an upper bound of its rounding error).
  double HalfUnit(double t) const {
    const double fixed = 0.5 * std::pow(10.0, finest_exp_);
    if (t == 0 || max_significant_ == 0) return fixed;
    const double magnitude = std::floor(std::log10(std::abs(t)));
    const double sig = 0.5 * std::pow(10.0, magnitude - max_significant_ + 1);
    return std::max(fixed, sig);
  }

 private:
  int finest_exp_ = 320;
  int max_significant_ = 0;
};

enum class Separator { kComma, kSemicolon, kTab, kBlanks };

Separator DetectSeparator(std::string_view line) {
  if (line.find('\t') != std::string_view::npos) return Separator::kTab;
  if (line.find(';') != std::string_view::npos) return Separator::kSemicolon;
  if (line.find(',') != std::string_view::npos) return Separator::kComma;
  return Separator::kBlanks;
}

// Splits one line into cells (views into the line), trimmed and unquoted.
void SplitLine(std::string_view line, Separator sep, std::vector<std::string_view>* cells) {
  cells->clear();
  if (sep == Separator::kBlanks) {
    size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      if (i >= line.size()) break;
      size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
      cells->push_back(Unquote(line.substr(i, j - i)));
      i = j;
    }
    return;
  }
  const char c = sep == Separator::kComma ? ',' : sep == Separator::kSemicolon ? ';' : '\t';
  // A separator that ends the line (some DAQ exporters write one) does not open another cell.
  if (!line.empty() && line.back() == c) line.remove_suffix(1);
  size_t start = 0;
  while (true) {
    const size_t pos = line.find(c, start);
    if (pos == std::string_view::npos) {
      cells->push_back(Unquote(line.substr(start)));
      return;
    }
    cells->push_back(Unquote(line.substr(start, pos - start)));
    start = pos + 1;
  }
}

// Splits "Time (s)" / "t [ms]" into ("time", "s"): lower-cased base name (blanks -> '_') and the
// unit in brackets, if any.
std::pair<std::string, std::string> SplitNameAndUnit(std::string_view header) {
  std::string_view name = Trim(header);
  std::string unit;
  for (const auto& [open, close] : {std::pair{'(', ')'}, std::pair{'[', ']'}}) {
    const size_t a = name.rfind(open);
    const size_t b = name.rfind(close);
    if (a != std::string_view::npos && b != std::string_view::npos && b > a &&
        b == name.size() - 1) {
      unit = std::string(Trim(name.substr(a + 1, b - a - 1)));
      name = Trim(name.substr(0, a));
      break;
    }
  }
  std::string base = Lower(name);
  std::replace(base.begin(), base.end(), ' ', '_');
  return {base, unit};
}

// If `header` names a time column, returns the factor that converts its values to seconds.
std::optional<double> TimeColumnScale(std::string_view header) {
  auto [base, unit] = SplitNameAndUnit(header);
  auto unit_scale = [](const std::string& u) -> std::optional<double> {
    const std::string l = Lower(u);
    if (l.empty() || l == "s" || l == "sec" || l == "secs" || l == "seconds") return 1.0;
    if (l == "ms") return 1e-3;
    if (l == "us" || l == "µs") return 1e-6;
    return std::nullopt;
  };
  std::string suffix;
  const size_t underscore = base.rfind('_');
  std::string stem = base;
  if (underscore != std::string::npos) {
    suffix = base.substr(underscore + 1);
    stem = base.substr(0, underscore);
    if (suffix != "s" && suffix != "sec" && suffix != "ms" && suffix != "us") {
      stem = base;
      suffix.clear();
    }
  }
  static const char* kStems[] = {"t", "time", "times", "timestamp", "sec", "secs", "seconds"};
  if (std::find(std::begin(kStems), std::end(kStems), stem) == std::end(kStems)) {
    return std::nullopt;
  }
  if (!unit.empty() && !suffix.empty()) return std::nullopt;  // "time_s (ms)": ambiguous
  return unit_scale(unit.empty() ? suffix : unit);
}

// Units of a signal column from its header (see record.h).
std::string UnitsFromHeader(std::string_view header) {
  const auto [name, unit] = SplitNameAndUnit(header);
  if (!unit.empty()) return unit;
  const auto base = name;  // a lambda may not capture a structured binding before C++20 in clang 14
  auto ends_with = [&](const std::string& s) {
    return base.size() > s.size() && base.compare(base.size() - s.size(), s.size(), s) == 0;
  };
  if (ends_with("_m_s2")) return "m/s^2";
  if (ends_with("_mm_s")) return "mm/s";
  if (ends_with("_m_s")) return "m/s";
  if (ends_with("_g")) return "g";
  if (ends_with("_v")) return "V";
  return "";
}

// "# fs=48000", "# fs: 48000 Hz", "# sample_rate_hz = 48000". Returns the rate or nullopt when
// the comment is something else; throws when the key is right but the value is not.
std::optional<double> ParseRateComment(std::string_view comment,
                                       const std::string& name,
                                       size_t line_no) {
  std::string_view body = Trim(comment);
  const size_t sep = body.find_first_of("=:");
  if (sep == std::string_view::npos) return std::nullopt;
  const std::string key = Lower(Trim(body.substr(0, sep)));
  if (key != "fs" && key != "sample_rate_hz" && key != "sample_rate" && key != "sampling_rate" &&
      key != "samplerate") {
    return std::nullopt;
  }
  std::string_view value = Trim(body.substr(sep + 1));
  if (value.size() >= 2 && Lower(value.substr(value.size() - 2)) == "hz") {
    value = Trim(value.substr(0, value.size() - 2));
  }
  double fs = 0;
  if (!ParseNumber(value, &fs) || !std::isfinite(fs) || fs <= 0) {
    throw InputError(name + ":" + std::to_string(line_no) + ": '# " + key +
                     "=' expects a positive sample rate in Hz, found '" + std::string(value) + "'");
  }
  return fs;
}

struct TimeCheck {
  bool ok = false;
  double dt = 0;
  size_t bad_row = 0;  // first offending row when !ok
  bool decreasing = false;
  double deviation_steps = 0;
};

// Strict increase and uniformity of a time column (rule in record.h).
TimeCheck CheckUniformTime(const std::vector<double>& t, const PrintResolution& resolution) {
  TimeCheck check;
  const size_t n = t.size();
  if (n < 2) return check;
  for (size_t i = 1; i < n; ++i) {
    if (!(t[i] > t[i - 1])) {
      check.bad_row = i;
      check.decreasing = true;
      return check;
    }
  }
  check.dt = (t[n - 1] - t[0]) / static_cast<double>(n - 1);
  // Printing rounding is allowed for, up to kMaxRounding steps: a coarser column cannot show
  // whether the samples are uniform, and a gap of a whole step must always be caught.
  auto half_resolution = [&](size_t i) {
    return std::min(resolution.HalfUnit(t[i]), kMaxRounding * check.dt);
  };
  const double q_ends = std::max(half_resolution(0), half_resolution(n - 1));
  for (size_t i = 0; i < n; ++i) {
    const double expected = t[0] + static_cast<double>(i) * check.dt;
    const double deviation = std::abs(t[i] - expected);
    const double tol = kRelativeTimeTolerance * check.dt + half_resolution(i) + q_ends;
    if (deviation > tol) {
      check.bad_row = i;
      check.deviation_steps = deviation / check.dt;
      return check;
    }
  }
  check.ok = true;
  return check;
}

std::string Plural(size_t n, const char* word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

void ValidateOptionRate(const RecordOptions& options, const std::string& name) {
  if (std::isnan(options.sample_rate_hz) || options.sample_rate_hz < 0 ||
      std::isinf(options.sample_rate_hz) || options.sample_rate_hz > kMaxSampleRateHz) {
    throw InputError(name + ": sample rate must be a positive number of Hz up to " +
                     FormatNumber(kMaxSampleRateHz) + ", got " +
                     FormatNumber(options.sample_rate_hz));
  }
}

std::string ReadWholeFile(const std::string& path) { return ReadInputFile(path, "a record file"); }

bool IsAllDigits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

Record ParseCsvRecord(std::string_view text,
                      const std::string& name,
                      const RecordOptions& options) {
  ValidateOptionRate(options, name);
  if (text.size() >= 3 && static_cast<unsigned char>(text[0]) == 0xEF &&
      static_cast<unsigned char>(text[1]) == 0xBB && static_cast<unsigned char>(text[2]) == 0xBF) {
    text.remove_prefix(3);  // UTF-8 byte-order mark
  }

  std::optional<double> comment_rate;
  size_t comment_rate_line = 0;
  std::vector<std::string> headers;
  size_t header_line = 0;
  Separator sep = Separator::kComma;
  bool first_content = true;
  size_t num_fields = 0;
  std::vector<std::vector<double>> columns;
  std::vector<size_t> row_line;     // line number of each data row (for messages)
  PrintResolution time_resolution;  // of the time candidate column
  size_t time_candidate = 0;        // column index whose printing resolution is tracked
  std::vector<std::string_view> cells;
  cells.reserve(16);

  auto field_name = [&](size_t c) {
    std::string s = "field " + std::to_string(c + 1);
    if (c < headers.size() && !headers[c].empty()) s += " ('" + headers[c] + "')";
    return s;
  };

  size_t line_no = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    const std::string_view content = Trim(line);
    if (content.empty()) continue;
    if (content.front() == '#') {
      if (auto fs = ParseRateComment(content.substr(1), name, line_no)) {
        comment_rate = fs;
        comment_rate_line = line_no;
      }
      continue;
    }
    if (first_content) {
      first_content = false;
      sep = DetectSeparator(content);
      SplitLine(content, sep, &cells);
      num_fields = cells.size();
      bool is_header = false;
      for (std::string_view cell : cells) {
        double v;
        if (!ParseNumber(cell, &v)) is_header = true;
      }
      columns.assign(num_fields, {});
      const size_t estimate = text.size() / std::max<size_t>(line.size() + 1, 4) + 1;
      for (auto& col : columns) col.reserve(estimate);
      row_line.reserve(estimate);
      if (is_header) {
        for (std::string_view cell : cells) headers.emplace_back(cell);
        header_line = line_no;
        for (size_t c = 0; c < headers.size(); ++c) {
          if (TimeColumnScale(headers[c])) {
            time_candidate = c;
            break;
          }
        }
        continue;
      }
    }
    SplitLine(content, sep, &cells);
    if (cells.size() != num_fields) {
      throw InputError(name + ":" + std::to_string(line_no) + ": " + Plural(cells.size(), "field") +
                       ", expected " + std::to_string(num_fields) +
                       (headers.empty() ? " (as in the first data row)" : " (as in the header)"));
    }
    for (size_t c = 0; c < num_fields; ++c) {
      double v;
      if (cells[c].empty()) {
        throw InputError(name + ":" + std::to_string(line_no) + ": " + field_name(c) +
                         " is empty, expected a number");
      }
      if (!ParseNumber(cells[c], &v)) {
        throw InputError(name + ":" + std::to_string(line_no) + ": " + field_name(c) +
                         ": expected a number, found '" + std::string(cells[c].substr(0, 40)) +
                         "'");
      }
      if (!std::isfinite(v)) {
        throw InputError(name + ":" + std::to_string(line_no) + ": " + field_name(c) + ": '" +
                         std::string(cells[c]) + "' is not a finite number");
      }
      columns[c].push_back(v);
    }
    time_resolution.Add(cells[time_candidate]);
    row_line.push_back(line_no);
  }

  if (first_content) {
    throw InputError(name + ": empty file, expected a header and/or rows of numbers");
  }
  const size_t rows = row_line.size();
  if (rows == 0) {
    throw InputError(name + ": no data rows after the header (line " + std::to_string(header_line) +
                     ")");
  }
  if (rows < 2) {
    throw InputError(name + ":" + std::to_string(row_line[0]) +
                     ": only 1 data row, a record needs at least 2 samples");
  }

  // Find the time column.
  std::optional<size_t> time_col;
  double time_scale = 1.0;
  TimeCheck time_check;
  if (!headers.empty()) {
    for (size_t c = 0; c < headers.size(); ++c) {
      if (auto scale = TimeColumnScale(headers[c])) {
        time_col = c;
        time_scale = *scale;
        break;
      }
    }
  } else if (num_fields >= 2 && rows >= 3) {
    const TimeCheck check = CheckUniformTime(columns[0], time_resolution);
    if (check.ok) {
      time_col = 0;
      time_check = check;
    }
  }

  // Sample rate.
  double fs = 0;
  if (options.sample_rate_hz > 0) {
    fs = options.sample_rate_hz;
  } else {
    std::optional<double> time_rate;
    if (time_col) {
      if (!time_check.ok) time_check = CheckUniformTime(columns[*time_col], time_resolution);
      if (!time_check.ok) {
        const size_t r = time_check.bad_row;
        const std::string where =
            name + ":" + std::to_string(row_line[r]) + ": " + field_name(*time_col) + ": ";
        if (time_check.decreasing) {
          throw InputError(where + "time " + FormatNumber(columns[*time_col][r]) +
                           " does not increase (previous " +
                           FormatNumber(columns[*time_col][r - 1]) +
                           "); expected strictly increasing time");
        }
        throw InputError(where + "non-uniform time: " + FormatNumber(columns[*time_col][r]) +
                         " is " + FormatNumber(time_check.deviation_steps) +
                         " steps off the uniform grid (step " + FormatNumber(time_check.dt) +
                         "); resample the "
                         "record or give the sample rate");
      }
      time_rate = 1.0 / (time_check.dt * time_scale);
    }
    if (comment_rate) {
      if (time_rate && std::abs(*time_rate - *comment_rate) > kRateAgreement * *comment_rate) {
        throw InputError(name + ":" + std::to_string(comment_rate_line) + ": '# fs=" +
                         FormatNumber(*comment_rate) + "' disagrees with the time column (" +
                         FormatNumber(*time_rate) + " Hz); fix one or give the sample rate");
      }
      fs = *comment_rate;
    } else if (time_rate) {
      fs = *time_rate;
    } else {
      throw InputError(name +
                       ": no sample rate: no time column (time_s, t, Time (s), ...) and no "
                       "'# fs=' comment; give the sample rate");
    }
  }

  // Channel.
  std::vector<size_t> data_cols;
  for (size_t c = 0; c < num_fields; ++c) {
    if (!time_col || c != *time_col) data_cols.push_back(c);
  }
  if (data_cols.empty()) {
    throw InputError(name + ": only a time column, expected at least one signal column");
  }
  auto list_columns = [&] {
    std::string s;
    for (size_t k = 0; k < data_cols.size(); ++k) {
      if (k) s += ", ";
      s += headers.empty() ? std::to_string(k) : "'" + headers[data_cols[k]] + "'";
    }
    return s;
  };
  size_t chosen = data_cols[0];
  size_t chosen_index = 0;
  const std::string channel(Trim(options.channel));
  if (!channel.empty()) {
    std::optional<size_t> found;
    for (size_t k = 0; k < data_cols.size() && !found; ++k) {
      if (!headers.empty() && headers[data_cols[k]] == channel) found = k;
    }
    for (size_t k = 0; k < data_cols.size() && !found; ++k) {
      if (!headers.empty() && Lower(headers[data_cols[k]]) == Lower(channel)) found = k;
    }
    // The name without its unit: 'accel_z' for a column 'accel_z (m/s^2)' (spall simulate --csv
    // writes units so) or 'accel_z [g]'; refused when two columns share the name.
    for (size_t k = 0; k < data_cols.size() && !found && !headers.empty(); ++k) {
      if (Lower(WithoutUnit(headers[data_cols[k]])) != Lower(channel)) continue;
      for (size_t other = k + 1; other < data_cols.size(); ++other)
        if (Lower(WithoutUnit(headers[data_cols[other]])) == Lower(channel))
          throw InputError(name + ": channel '" + channel + "' names more than one column ('" +
                           headers[data_cols[k]] + "', '" + headers[data_cols[other]] +
                           "'); give the whole column name");
      found = k;
    }
    if (!found && IsAllDigits(channel)) {
      size_t index = 0;
      std::from_chars(channel.data(), channel.data() + channel.size(), index);
      if (channel.size() > 9 || index >= data_cols.size()) {
        throw InputError(name + ": channel index " + channel + " out of range: the file has " +
                         Plural(data_cols.size(), "signal column") + " (0-based index 0.." +
                         std::to_string(data_cols.size() - 1) + ", time column not counted)");
      }
      found = index;
    }
    if (!found) {
      if (!headers.empty() && time_col && Lower(headers[*time_col]) == Lower(channel)) {
        throw InputError(name + ": channel '" + channel +
                         "' is the time column; choose a signal column: " + list_columns());
      }
      throw InputError(name + ": channel '" + channel + "' not found; signal columns are " +
                       list_columns() + " (or a 0-based index)");
    }
    chosen_index = *found;
    chosen = data_cols[chosen_index];
  }

  Record record;
  record.samples = std::move(columns[chosen]);
  record.sample_rate_hz = fs;
  if (!headers.empty() && !headers[chosen].empty()) {
    record.channel = headers[chosen];
    record.units = UnitsFromHeader(headers[chosen]);
  } else {
    record.channel = "column " + std::to_string(chosen_index);
  }
  record.source = name;
  return record;
}

Record ReadCsvRecord(const std::string& path, const RecordOptions& options) {
  ValidateOptionRate(options, path);
  const std::string text = ReadWholeFile(path);
  return ParseCsvRecord(text, path, options);
}

Record ReadHdf5Record(const std::string& path, const RecordOptions& options) {
  ValidateOptionRate(options, path);
  const h5::File file = h5::File::OpenReadOnly(path);
  auto list = [](const std::vector<std::string>& names) {
    std::string s;
    for (size_t i = 0; i < names.size() && i < 12; ++i) s += (i ? ", " : "") + names[i];
    if (names.size() > 12) s += ", ...";
    return s.empty() ? std::string("none") : s;
  };
  std::string dataset(Trim(options.channel));
  if (!dataset.empty() && dataset.front() != '/') dataset = "/" + dataset;
  if (dataset.empty()) {
    if (file.IsDataset("/signals/accel_y")) {
      dataset = "/signals/accel_y";
    } else {
      std::vector<std::string> candidates;
      const std::vector<std::string> all = file.ListDatasets();
      for (const std::string& d : all) {
        const std::vector<size_t> dims = file.DatasetDims(d);
        if (dims.size() == 1 && file.ReadDoubleAttribute(d, "sample_rate_hz")) {
          candidates.push_back(d);
        }
      }
      if (candidates.size() != 1) {
        throw InputError(path + ": " +
                         (candidates.empty()
                              ? "no 1-D dataset with a sample_rate_hz attribute (datasets: " +
                                    list(all) + "); choose one as the channel"
                              : "several candidate channels (" + list(candidates) +
                                    "); choose one as the channel"));
      }
      dataset = candidates[0];
    }
  } else if (!file.IsDataset(dataset)) {
    throw InputError(path + ": dataset " + dataset +
                     " not found (datasets: " + list(file.ListDatasets()) + ")");
  }

  std::vector<size_t> dims;
  std::vector<double> samples = file.ReadDataset(dataset, &dims);
  // 1-D, or a MATLAB-style vector stored as [1 x n] or [n x 1].
  const size_t non_singleton =
      std::count_if(dims.begin(), dims.end(), [](size_t d) { return d != 1; });
  if (dims.empty() || non_singleton > 1) {
    std::string shape;
    for (size_t i = 0; i < dims.size(); ++i) shape += (i ? " x " : "") + std::to_string(dims[i]);
    throw InputError(path + ": " + dataset + ": expected a 1-D dataset, found shape " +
                     (shape.empty() ? std::string("scalar") : shape));
  }
  if (samples.size() < 2) {
    throw InputError(path + ": " + dataset + ": " + Plural(samples.size(), "sample") +
                     ", a record needs at least 2");
  }
  for (size_t i = 0; i < samples.size(); ++i) {
    if (!std::isfinite(samples[i])) {
      throw InputError(path + ": " + dataset + ": sample " + std::to_string(i) + " is " +
                       FormatNumber(samples[i]) + ", expected finite values");
    }
  }

  Record record;
  if (options.sample_rate_hz > 0) {
    record.sample_rate_hz = options.sample_rate_hz;
  } else {
    const std::optional<double> fs = file.ReadDoubleAttribute(dataset, "sample_rate_hz");
    if (!fs) {
      throw InputError(path + ": " + dataset +
                       ": no sample_rate_hz attribute; give the sample rate");
    }
    if (!std::isfinite(*fs) || *fs <= 0) {
      throw InputError(path + ": " + dataset + ": sample_rate_hz = " + FormatNumber(*fs) +
                       ", expected a positive number");
    }
    record.sample_rate_hz = *fs;
  }
  record.samples = std::move(samples);
  record.channel = dataset;
  record.units = file.ReadStringAttribute(dataset, "units").value_or("");
  record.source = path + ":" + dataset;
  return record;
}

Record ReadRecord(const std::string& path, const RecordOptions& options) {
  const size_t dot = path.rfind('.');
  const size_t slash = path.rfind('/');
  std::string ext;
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) {
    ext = Lower(path.substr(dot + 1));
  }
  if (ext == "h5" || ext == "hdf5" || ext == "he5") return ReadHdf5Record(path, options);
  return ReadCsvRecord(path, options);
}

void WriteCsvRecord(const std::string& path,
                    const std::vector<std::pair<std::string, std::vector<double>>>& columns) {
  if (columns.empty()) throw InputError(path + ": no columns to write");
  const size_t rows = columns[0].second.size();
  for (const auto& [header, values] : columns) {
    if (header.empty() || header.find_first_of(",\"\n\r") != std::string::npos) {
      throw InputError(path + ": column name '" + header +
                       "' must be non-empty without comma, quote or newline");
    }
    if (values.size() != rows) {
      throw InputError(path + ": column '" + header + "' has " + std::to_string(values.size()) +
                       " values, expected " + std::to_string(rows) + " like '" + columns[0].first +
                       "'");
    }
  }
  std::string out;
  out.reserve(64 + rows * columns.size() * 24);
  for (size_t c = 0; c < columns.size(); ++c) {
    if (c) out += ',';
    out += columns[c].first;
  }
  out += '\n';
  char buffer[64];
  for (size_t r = 0; r < rows; ++r) {
    for (size_t c = 0; c < columns.size(); ++c) {
      if (c) out += ',';
      const double v = columns[c].second[r];
      if (!std::isfinite(v)) {
        throw InputError(path + ": column '" + columns[c].first + "' row " + std::to_string(r) +
                         " is not finite");
      }
      // Shortest representation that reads back to the same double.
      const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
      out.append(buffer, result.ptr);
    }
    out += '\n';
  }
  WriteFileAtomically(path, out);
}

}  // namespace spallkit
