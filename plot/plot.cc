#include "plot/plot.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"

namespace spallkit::plot {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr int kMinSize = 200;
constexpr int kMaxSize = 8000;
// Sub-pixel precision for polylines (OpenCV "shift": coordinates are multiplied by 2^shift).
constexpr int kShift = 4;
constexpr double kSubpixel = 1 << kShift;

cv::Scalar Bgr(Rgb c) { return cv::Scalar(c.b, c.g, c.r); }
cv::Scalar Gray(int v) { return cv::Scalar(v, v, v); }
const cv::Scalar kBlack = Gray(0);
const cv::Scalar kText = Gray(30);
const cv::Scalar kGrid = Gray(228);
const cv::Scalar kMinorGrid = Gray(243);

Rgb Lighten(Rgb c, double amount) {
  auto mix = [&](unsigned char v) {
    return static_cast<unsigned char>(std::lround(v + (255 - v) * amount));
  };
  return {mix(c.r), mix(c.g), mix(c.b)};
}

// Sizes scale with the image so that a 1600 x 800 plot uses Hershey scales 0.5 (ticks) to 0.8
// (title): readable at 100 % zoom; larger images get proportionally larger text.
struct Style {
  explicit Style(int width, int height)
      : f(std::clamp(std::min(width / 1600.0, height / 800.0), 0.75, 2.5)) {}
  double f;
  double title() const { return 0.8 * f; }
  double label() const { return 0.62 * f; }
  double tick() const { return 0.5 * f; }
  double marker(bool thin) const { return (thin ? 0.4 : 0.45) * f; }
  double legend() const { return 0.5 * f; }
  int stroke() const { return f >= 1.6 ? 2 : 1; }
  int pad() const { return static_cast<int>(std::lround(10 * f)); }
  int tick_len() const { return static_cast<int>(std::lround(5 * f)); }
};

// Text with superscripts: "m/s^2", "(m/s^2)^2", "10^-3", "x^{n+1}". Hershey fonts have no '^'
// glyph worth showing and no superscript digits, so the part after '^' is drawn smaller and raised.
struct Segment {
  std::string text;
  bool superscript = false;
};

std::vector<Segment> ParseRichText(const std::string& text) {
  std::vector<Segment> segments(1);
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '^' && i + 1 < text.size()) {
      size_t j = i + 1;
      std::string sup;
      if (text[j] == '{') {
        const size_t close = text.find('}', j);
        if (close != std::string::npos) {
          sup = text.substr(j + 1, close - j - 1);
          j = close + 1;
        }
      } else {
        if (text[j] == '-' || text[j] == '+') sup += text[j++];
        while (j < text.size() &&
               (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '.')) {
          sup += text[j++];
        }
      }
      if (!sup.empty()) {
        segments.push_back({sup, true});
        segments.push_back({});
        i = j - 1;
        continue;
      }
    }
    segments.back().text += text[i];
  }
  return segments;
}

constexpr double kSuperscriptScale = 0.7;

// Width, cap height and descent of (rich) text; `baseline` receives the descent below the baseline.
cv::Size TextSize(const std::string& text, double scale, int thickness, int* baseline = nullptr) {
  int width = 0, height = 0, descent = 0;
  for (const Segment& seg : ParseRichText(text)) {
    if (seg.text.empty()) continue;
    int base = 0;
    const cv::Size s = cv::getTextSize(
        seg.text, kFont, seg.superscript ? scale * kSuperscriptScale : scale, thickness, &base);
    width += s.width + (seg.superscript ? 2 : 0);
    if (!seg.superscript) {
      height = std::max(height, s.height);
      descent = std::max(descent, base);
    }
  }
  if (height == 0) {
    int base = 0;
    height = cv::getTextSize("0", kFont, scale, thickness, &base).height;
    descent = base;
  }
  if (baseline) *baseline = descent;
  return {width, height};
}

// Coverage mask of rendered text (255 = ink), with the position of the baseline and of the left
// edge of the text inside it.
struct TextMask {
  cv::Mat mask;
  int origin_x = 0;    // column of the text start
  int baseline_y = 0;  // row of the baseline
  cv::Size size;       // TextSize of the text
};

TextMask RenderTextMask(const std::string& text, double scale, int thickness) {
  TextMask tm;
  int descent = 0;
  tm.size = TextSize(text, scale, thickness, &descent);
  const int raise = static_cast<int>(std::lround(0.55 * tm.size.height));
  const int sup_height =
      cv::getTextSize("0", kFont, scale * kSuperscriptScale, thickness, nullptr).height;
  const int ascent = std::max(tm.size.height, raise + sup_height) + 1;
  const int margin = 2 + thickness;
  tm.origin_x = margin;
  tm.baseline_y = margin + ascent;
  tm.mask = cv::Mat::zeros(tm.baseline_y + descent + margin, tm.size.width + 2 * margin, CV_8U);
  int x = margin;
  for (const Segment& seg : ParseRichText(text)) {
    if (seg.text.empty()) continue;
    const double s = seg.superscript ? scale * kSuperscriptScale : scale;
    const int y = seg.superscript ? tm.baseline_y - raise : tm.baseline_y;
    if (seg.superscript) x += 1;
    cv::putText(tm.mask, seg.text, {x, y}, kFont, s, cv::Scalar(255), thickness, cv::LINE_AA);
    x += cv::getTextSize(seg.text, kFont, s, thickness, nullptr).width + (seg.superscript ? 1 : 0);
  }
  return tm;
}

// Alpha-blends `color` into img through `mask` placed with its top-left corner at (x, y).
void BlendMask(cv::Mat& img, const cv::Mat& mask, int x, int y, const cv::Scalar& color) {
  const cv::Rect target = cv::Rect(x, y, mask.cols, mask.rows) & cv::Rect(0, 0, img.cols, img.rows);
  for (int r = target.y; r < target.y + target.height; ++r) {
    const unsigned char* m = mask.ptr<unsigned char>(r - y);
    cv::Vec3b* p = img.ptr<cv::Vec3b>(r);
    for (int c = target.x; c < target.x + target.width; ++c) {
      const double a = m[c - x] / 255.0;
      if (a <= 0) continue;
      for (int k = 0; k < 3; ++k) {
        p[c][k] = cv::saturate_cast<unsigned char>(p[c][k] * (1 - a) + color[k] * a);
      }
    }
  }
}

enum class HAlign { kLeft, kCenter, kRight };
enum class VAlign { kTop, kMiddle, kBaseline };

// Draws text with its anchor at (x, y) aligned as asked (vertical alignment by the cap height of
// the normal-size text, so superscripts do not shift a label).
void Text(cv::Mat& img,
          const std::string& text,
          double x,
          double y,
          double scale,
          const cv::Scalar& color,
          int thickness,
          HAlign h,
          VAlign v) {
  if (text.empty()) return;
  const TextMask tm = RenderTextMask(text, scale, thickness);
  double left = x;
  if (h == HAlign::kCenter) left -= tm.size.width / 2.0;
  if (h == HAlign::kRight) left -= tm.size.width;
  double baseline = y;
  if (v == VAlign::kTop) baseline += tm.size.height;
  if (v == VAlign::kMiddle) baseline += tm.size.height / 2.0;
  BlendMask(img,
            tm.mask,
            static_cast<int>(std::lround(left)) - tm.origin_x,
            static_cast<int>(std::lround(baseline)) - tm.baseline_y,
            color);
}

// Text rotated 90 degrees counter-clockwise (reads bottom to top), blended through its rotated
// coverage mask so that the anti-aliasing survives. (x, y) is the top-left corner of the rotated
// box; returns its size.
cv::Size RotatedText(cv::Mat& img,
                     const std::string& text,
                     int x,
                     int y,
                     double scale,
                     const cv::Scalar& color,
                     int thickness) {
  const TextMask tm = RenderTextMask(text, scale, thickness);
  cv::Mat rotated;
  cv::rotate(tm.mask, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  BlendMask(img, rotated, x, y, color);
  return rotated.size();
}

void DashedVLine(cv::Mat& img, int x, int y0, int y1, const cv::Scalar& color, int thickness) {
  const int on = 7, off = 5;
  for (int y = y0; y < y1; y += on + off) {
    cv::line(img, {x, y}, {x, std::min(y + on, y1)}, color, thickness, cv::LINE_AA);
  }
}

std::vector<unsigned char> EncodePng(const cv::Mat& img) {
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", img, png)) throw InputError("PNG encoding failed");
  return png;
}

void WritePng(const std::string& path, const std::vector<unsigned char>& png) {
  if (path.empty()) throw InputError("plot: empty output path");
  WriteFileAtomically(path, std::string(png.begin(), png.end()));
}

void CheckSize(int width, int height, const char* what) {
  if (width < kMinSize || width > kMaxSize || height < kMinSize || height > kMaxSize) {
    throw InputError(std::string(what) + ": image size " + std::to_string(width) + " x " +
                     std::to_string(height) + " outside [200, 8000] pixels");
  }
}

// A linear or log10 axis mapping data values to pixels.
struct Axis {
  double lo = 0, hi = 1;  // data range (positive for log)
  bool log = false;
  double p0 = 0, p1 = 1;  // pixel positions of lo and hi
  double T(double v) const { return log ? std::log10(v) : v; }
  double ToPixel(double v) const { return p0 + (T(v) - T(lo)) / (T(hi) - T(lo)) * (p1 - p0); }
};

struct Tick {
  double value;
  std::string label;  // empty for minor ticks
};

std::vector<Tick> LinearTicks(double lo, double hi, int target) {
  std::vector<Tick> ticks;
  const std::vector<double> values = NiceTicks(lo, hi, target);
  const double step = values.size() >= 2 ? values[1] - values[0] : std::abs(hi - lo);
  for (double v : values) ticks.push_back({v, FormatTick(v, step)});
  return ticks;
}

std::string DecadeLabel(int k) {
  if (k >= -3 && k <= 4) return FormatTick(std::pow(10.0, k), std::pow(10.0, k));
  return "1e" + std::to_string(k);
}

// Log ticks: labelled decades; 2 and 5 labelled as well when the range spans few decades;
// unlabelled minor ticks at 2..9 otherwise.
std::vector<Tick> LogTicks(double lo, double hi) {
  std::vector<Tick> ticks;
  const int k0 = static_cast<int>(std::floor(std::log10(lo) + 1e-9));
  const int k1 = static_cast<int>(std::ceil(std::log10(hi) - 1e-9));
  const bool few = k1 - k0 <= 2;
  for (int k = k0; k <= k1; ++k) {
    const double decade = std::pow(10.0, k);
    for (int m = 1; m <= 9; ++m) {
      const double v = m * decade;
      if (v < lo * (1 - 1e-9) || v > hi * (1 + 1e-9)) continue;
      std::string label;
      if (m == 1)
        label = DecadeLabel(k);
      else if (few && (m == 2 || m == 5))
        label = FormatTick(v, decade);
      ticks.push_back({v, label});
    }
  }
  return ticks;
}

struct Range {
  double lo = 0, hi = 0;
  bool valid = false;
  void Add(double v) {
    if (!std::isfinite(v)) return;
    if (!valid) {
      lo = hi = v;
      valid = true;
    } else {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
};

std::string Num(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// Pixel-column decimation for long series: for each pixel column keep the first, minimum,
// maximum and last points, so peaks survive (the point of a spectrum plot) and drawing stays fast.
std::vector<std::vector<cv::Point>> SeriesPolylines(const LineSeries& s,
                                                    const Axis& ax,
                                                    const Axis& ay) {
  std::vector<std::vector<cv::Point>> lines(1);
  const size_t n = s.y.size();
  const double x_span_px = std::abs(ax.p1 - ax.p0);
  const bool decimate = n > 4 * static_cast<size_t>(x_span_px + 1);
  auto x_of = [&](size_t i) { return s.x.empty() ? static_cast<double>(i) : s.x[i]; };
  auto point = [&](double px, double py) {
    // Keep coordinates bounded so that far-away points do not overflow int after the shift.
    px = std::clamp(px, -1e5, 1e5);
    py = std::clamp(py, -1e5, 1e5);
    return cv::Point(static_cast<int>(std::lround(px * kSubpixel)),
                     static_cast<int>(std::lround(py * kSubpixel)));
  };
  long current_col = std::numeric_limits<long>::min();
  double first = 0, last = 0, mn = 0, mx = 0;
  size_t i_mn = 0, i_mx = 0;
  bool have = false;
  auto flush = [&] {
    if (!have) return;
    const double px = static_cast<double>(current_col);
    auto& line = lines.back();
    line.push_back(point(px, first));
    if (i_mn < i_mx) {
      line.push_back(point(px, mn));
      line.push_back(point(px, mx));
    } else {
      line.push_back(point(px, mx));
      line.push_back(point(px, mn));
    }
    line.push_back(point(px, last));
    have = false;
  };
  for (size_t i = 0; i < n; ++i) {
    const double x = x_of(i), y = s.y[i];
    if (!std::isfinite(x) || !std::isfinite(y) || (ay.log && y <= 0) || (ax.log && x <= 0)) {
      flush();
      if (!lines.back().empty()) lines.emplace_back();
      continue;
    }
    const double px = ax.ToPixel(x), py = ay.ToPixel(y);
    if (!decimate) {
      lines.back().push_back(point(px, py));
      continue;
    }
    const long col = static_cast<long>(std::floor(px));
    if (have && col != current_col) flush();
    if (!have) {
      current_col = col;
      first = last = mn = mx = py;
      i_mn = i_mx = i;
      have = true;
    } else {
      last = py;
      if (py < mn) mn = py, i_mn = i;
      if (py > mx) mx = py, i_mx = i;
    }
  }
  flush();
  return lines;
}

}  // namespace

Rgb PaletteColor(size_t index) {
  static const Rgb kTableau[10] = {{31, 119, 180},
                                   {255, 127, 14},
                                   {44, 160, 44},
                                   {214, 39, 40},
                                   {148, 103, 189},
                                   {140, 86, 75},
                                   {227, 119, 194},
                                   {127, 127, 127},
                                   {188, 189, 34},
                                   {23, 190, 207}};
  return kTableau[index % 10];
}

std::vector<double> NiceTicks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!std::isfinite(lo) || !std::isfinite(hi)) return ticks;
  if (hi < lo) std::swap(lo, hi);
  if (hi == lo) return {lo};
  target = std::max(target, 1);
  const double raw = (hi - lo) / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / magnitude;
  // The nice step closest to the raw one (geometric midpoints 1.41, 3.16, 7.07).
  double step = 10 * magnitude;
  if (norm < 1.41)
    step = magnitude;
  else if (norm < 3.16)
    step = 2 * magnitude;
  else if (norm < 7.07)
    step = 5 * magnitude;
  const double eps = step * 1e-9;
  const double first = std::ceil((lo - eps) / step);
  for (double k = first;; k += 1) {
    double v = k * step;
    if (v > hi + eps) break;
    if (std::abs(v) < eps) v = 0;  // no "-0"
    ticks.push_back(v);
    if (ticks.size() > 1000) break;
  }
  return ticks;
}

std::string FormatTick(double value, double step) {
  step = std::abs(step);
  if (!(step > 0) || !std::isfinite(step)) step = std::abs(value) > 0 ? std::abs(value) : 1;
  if (std::abs(value) < step * 1e-9) return "0";
  char buf[64];
  const double big = std::max(std::abs(value), step);
  if (big >= 1e6 || big < 1e-4) {
    // Exponent form with as many mantissa digits as the step needs.
    const int digits = std::clamp(
        static_cast<int>(std::floor(std::log10(std::abs(value))) - std::floor(std::log10(step))),
        0,
        10);
    std::snprintf(buf, sizeof buf, "%.*e", digits, value);
    // "1.5e+06" -> "1.5e6", "2e-05" -> "2e-5"
    std::string s = buf;
    const size_t e = s.find('e');
    std::string mant = s.substr(0, e);
    int exp = std::stoi(s.substr(e + 1));
    return mant + "e" + std::to_string(exp);
  }
  int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  // Steps like 0.25 or 2.5 need one more digit than their magnitude says.
  const double scaled = step * std::pow(10.0, decimals);
  if (std::abs(scaled - std::round(scaled)) > 1e-6 * scaled) ++decimals;
  std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 12), value);
  return buf;
}

namespace {

// Title centred on top (shrunk to fit), x label under the plot area, y label rotated on the left.
void DrawTitleAndAxisLabels(cv::Mat& img,
                            const Style& st,
                            const cv::Rect& area,
                            int pad,
                            const std::string& title,
                            const std::string& x_label,
                            const std::string& y_label) {
  if (!title.empty()) {
    double scale = st.title();
    while (scale > 0.3 && TextSize(title, scale, st.stroke() + 1).width > img.cols - 2 * pad) {
      scale *= 0.9;
    }
    Text(img,
         title,
         img.cols / 2.0,
         pad,
         scale,
         kBlack,
         st.stroke() + 1,
         HAlign::kCenter,
         VAlign::kTop);
  }
  if (!x_label.empty()) {
    Text(img,
         x_label,
         area.x + area.width / 2.0,
         img.rows - pad - 2,
         st.label(),
         kBlack,
         st.stroke(),
         HAlign::kCenter,
         VAlign::kBaseline);
  }
  if (!y_label.empty()) {
    const cv::Size ts = TextSize(y_label, st.label(), st.stroke());
    RotatedText(img,
                y_label,
                pad,
                area.y + area.height / 2 - ts.width / 2,
                st.label(),
                kBlack,
                st.stroke());
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Line plots
// ---------------------------------------------------------------------------------------------

std::vector<unsigned char> RenderLinePlotPng(const LinePlot& plot) {
  CheckSize(plot.width, plot.height, "line plot");
  const Style st(plot.width, plot.height);

  // 1. Data ranges and validation.
  Range xr, yr, ypos;
  bool any_point = false;
  for (size_t k = 0; k < plot.series.size(); ++k) {
    const LineSeries& s = plot.series[k];
    if (!s.x.empty() && s.x.size() != s.y.size()) {
      throw InputError("line plot '" + plot.title + "': series " + std::to_string(k) + " ('" +
                       s.label + "') has " + std::to_string(s.x.size()) + " x values and " +
                       std::to_string(s.y.size()) + " y values");
    }
    for (size_t i = 0; i < s.y.size(); ++i) {
      const double x = s.x.empty() ? static_cast<double>(i) : s.x[i];
      const double y = s.y[i];
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      any_point = true;
      xr.Add(x);
      yr.Add(y);
      if (y > 0) ypos.Add(y);
    }
  }
  if (!any_point) throw InputError("line plot '" + plot.title + "': no finite data point");

  Axis ax, ay;
  ax.lo = std::isnan(plot.x_min) ? xr.lo : plot.x_min;
  ax.hi = std::isnan(plot.x_max) ? xr.hi : plot.x_max;
  if (std::isnan(plot.x_min) && std::isnan(plot.x_max) && ax.hi == ax.lo) {
    ax.lo -= 0.5;
    ax.hi += 0.5;
  }
  ay.log = plot.log_y;
  if (plot.log_y) {
    if (!ypos.valid && (std::isnan(plot.y_min) || std::isnan(plot.y_max))) {
      throw InputError("line plot '" + plot.title + "': log y axis but no positive y value");
    }
    // Auto: the positive data range, at most 6 decades below the maximum, 5 % padding in log
    // space; widened to whole decades when it spans less than one.
    double hi = std::isnan(plot.y_max) ? ypos.hi : plot.y_max;
    double lo = std::isnan(plot.y_min) ? std::max(ypos.lo, hi * 1e-6) : plot.y_min;
    if (lo > 0 && hi > 0) {
      const double decades = std::log10(hi / lo);
      if (decades < 1) {
        if (std::isnan(plot.y_min)) lo = std::pow(10.0, std::floor(std::log10(lo) + 1e-9));
        if (std::isnan(plot.y_max)) hi = std::pow(10.0, std::ceil(std::log10(hi) - 1e-9));
      } else {
        if (std::isnan(plot.y_min)) lo /= std::pow(10.0, 0.05 * decades);
        if (std::isnan(plot.y_max)) hi *= std::pow(10.0, 0.05 * decades);
      }
    }
    if (hi <= lo) hi = lo * 10;
    ay.lo = lo;
    ay.hi = hi;
    if (!(ay.lo > 0)) {
      throw InputError("line plot '" + plot.title + "': log y axis needs y_min > 0, got " +
                       Num(ay.lo));
    }
  } else {
    const double span = yr.hi - yr.lo;
    double lo = yr.lo, hi = yr.hi;
    if (span == 0) {
      lo -= std::max(std::abs(lo) * 0.1, 0.5);
      hi += std::max(std::abs(hi) * 0.1, 0.5);
    } else {
      // Non-negative data (spectra) start at exactly 0 when the minimum is close to it.
      lo = (yr.lo >= 0 && yr.lo <= 0.1 * yr.hi) ? 0.0 : yr.lo - 0.05 * span;
      hi = yr.hi + 0.05 * span;
    }
    ay.lo = std::isnan(plot.y_min) ? lo : plot.y_min;
    ay.hi = std::isnan(plot.y_max) ? hi : plot.y_max;
  }
  if (!(ax.hi > ax.lo) || !std::isfinite(ax.lo) || !std::isfinite(ax.hi)) {
    throw InputError("line plot '" + plot.title + "': empty x range [" + Num(ax.lo) + ", " +
                     Num(ax.hi) + "]");
  }
  if (!(ay.hi > ay.lo) || !std::isfinite(ay.lo) || !std::isfinite(ay.hi)) {
    throw InputError("line plot '" + plot.title + "': empty y range [" + Num(ay.lo) + ", " +
                     Num(ay.hi) + "]");
  }

  // 2. Ticks and layout.
  const std::vector<Tick> xticks = LinearTicks(ax.lo, ax.hi, std::max(4, plot.width / 160));
  const std::vector<Tick> yticks = plot.log_y
                                       ? LogTicks(ay.lo, ay.hi)
                                       : LinearTicks(ay.lo, ay.hi, std::max(4, plot.height / 90));
  int ytick_w = 0;
  for (const Tick& t : yticks) ytick_w = std::max(ytick_w, TextSize(t.label, st.tick(), 1).width);
  const int tick_h = TextSize("0", st.tick(), 1).height;
  // Thickness of a rotated axis label: the height of its rendered mask (ascent, descent, margins).
  const int label_h = RenderTextMask("Ag^2", st.label(), st.stroke()).mask.rows;
  const int title_h = TextSize("Ag", st.title(), st.stroke() + 1).height;
  const int pad = st.pad();
  const int left = pad + (plot.y_label.empty() ? 0 : label_h + pad) + ytick_w + pad + st.tick_len();
  const int right =
      2 * pad + TextSize(xticks.empty() ? "" : xticks.back().label, st.tick(), 1).width / 2;
  const int top = pad + (plot.title.empty() ? 0 : title_h + 2 * pad);
  const int bottom =
      st.tick_len() + pad + tick_h + (plot.x_label.empty() ? 0 : pad + label_h) + pad;
  const cv::Rect area(left, top, plot.width - left - right, plot.height - top - bottom);
  if (area.width < 50 || area.height < 50) {
    throw InputError("line plot '" + plot.title + "': image too small for its labels");
  }
  ax.p0 = area.x;
  ax.p1 = area.x + area.width - 1;
  ay.p0 = area.y + area.height - 1;
  ay.p1 = area.y;

  cv::Mat img(plot.height, plot.width, CV_8UC3, cv::Scalar(255, 255, 255));

  // 3. Grid.
  for (const Tick& t : xticks) {
    const int px = static_cast<int>(std::lround(ax.ToPixel(t.value)));
    cv::line(img, {px, area.y}, {px, area.y + area.height - 1}, kGrid, 1);
  }
  for (const Tick& t : yticks) {
    const int py = static_cast<int>(std::lround(ay.ToPixel(t.value)));
    cv::line(
        img, {area.x, py}, {area.x + area.width - 1, py}, t.label.empty() ? kMinorGrid : kGrid, 1);
  }

  // 4. Markers (under the data so that the lines stay readable), labels staggered.
  cv::Mat inner = img(area);
  const Axis ax_in{ax.lo, ax.hi, ax.log, ax.p0 - area.x, ax.p1 - area.x};
  const Axis ay_in{ay.lo, ay.hi, ay.log, ay.p0 - area.y, ay.p1 - area.y};
  std::vector<cv::Rect> label_boxes;
  for (const Marker& m : plot.markers) {
    if (!std::isfinite(m.x) || m.x < ax.lo || m.x > ax.hi) continue;
    const int px = static_cast<int>(std::lround(ax_in.ToPixel(m.x)));
    const Rgb color = m.thin ? Lighten(m.color, 0.35) : m.color;
    const int thickness = m.thin ? 1 : std::max(1, static_cast<int>(std::lround(1.4 * st.f)));
    if (m.dashed) {
      DashedVLine(inner, px, 0, area.height, Bgr(color), thickness);
    } else {
      cv::line(inner, {px, 0}, {px, area.height - 1}, Bgr(color), thickness, cv::LINE_AA);
    }
    if (m.label.empty()) continue;
    const double scale = st.marker(m.thin);
    const cv::Mat label_mask = RenderTextMask(m.label, scale, 1).mask;
    const int box_w = label_mask.rows, box_h = label_mask.cols;  // rotated
    const int gap = 4;
    cv::Rect box(px + 2, gap, box_w, box_h);
    // Move down until the box overlaps no earlier label; give up (no label) past the middle.
    bool placed = false;
    for (int attempt = 0; attempt < 12 && box.y + box.height < area.height * 0.75; ++attempt) {
      bool overlap = false;
      for (const cv::Rect& r : label_boxes) {
        if ((r & box).area() > 0) {
          overlap = true;
          box.y = r.y + r.height + gap;
          break;
        }
      }
      if (!overlap) {
        placed = true;
        break;
      }
    }
    if (!placed) continue;
    label_boxes.push_back(box);
    // A white halo behind the text keeps it readable over grid and data.
    RotatedText(
        inner, m.label, box.x, box.y, scale, Bgr(m.thin ? Lighten(m.color, 0.1) : m.color), 1);
  }

  // 5. Series.
  for (const LineSeries& s : plot.series) {
    const int thickness =
        std::max(1, static_cast<int>(std::lround(s.thickness * std::max(1.0, st.f))));
    for (const auto& line : SeriesPolylines(s, ax_in, ay_in)) {
      if (line.size() == 1) {
        cv::circle(inner,
                   line[0],
                   thickness * static_cast<int>(kSubpixel),
                   Bgr(s.color),
                   -1,
                   cv::LINE_AA,
                   kShift);
      } else if (line.size() > 1) {
        cv::polylines(inner, line, false, Bgr(s.color), thickness, cv::LINE_AA, kShift);
      }
    }
  }

  // 6. Frame, ticks, tick labels.
  cv::rectangle(img, area, kBlack, 1);
  const int tl = st.tick_len();
  for (const Tick& t : xticks) {
    const int px = static_cast<int>(std::lround(ax.ToPixel(t.value)));
    const int y0 = area.y + area.height;
    cv::line(img, {px, y0}, {px, y0 + tl}, kBlack, 1);
    Text(img, t.label, px, y0 + tl + pad / 2, st.tick(), kText, 1, HAlign::kCenter, VAlign::kTop);
  }
  for (const Tick& t : yticks) {
    const int py = static_cast<int>(std::lround(ay.ToPixel(t.value)));
    const int len = t.label.empty() ? tl / 2 : tl;
    cv::line(img, {area.x - len, py}, {area.x, py}, kBlack, 1);
    Text(img,
         t.label,
         area.x - tl - pad / 2,
         py,
         st.tick(),
         kText,
         1,
         HAlign::kRight,
         VAlign::kMiddle);
  }

  // 7. Title and axis labels.
  DrawTitleAndAxisLabels(img, st, area, pad, plot.title, plot.x_label, plot.y_label);

  // 8. Legend.
  std::vector<const LineSeries*> entries;
  for (const LineSeries& s : plot.series) {
    if (!s.label.empty()) entries.push_back(&s);
  }
  if (plot.legend && !entries.empty()) {
    const int sample_w = static_cast<int>(30 * st.f);
    int text_w = 0;
    const int row_h = TextSize("Ag", st.legend(), 1).height + pad;
    for (const LineSeries* s : entries)
      text_w = std::max(text_w, TextSize(s->label, st.legend(), 1).width);
    const int w = pad + sample_w + pad + text_w + pad;
    const int h = pad / 2 + row_h * static_cast<int>(entries.size()) + pad / 2;
    // Top right, below any marker label in the way.
    const int bx = area.x + area.width - w - pad;
    int by = area.y + pad;
    for (const cv::Rect& r : label_boxes) {
      if (r.x + area.x < bx + w && r.x + r.width + area.x > bx) {
        by = std::max(by, area.y + r.y + r.height + pad);
      }
    }
    const cv::Rect box(bx, by, w, h);
    if ((box & area) == box) {
      cv::Mat roi = img(box);
      cv::Mat white(roi.size(), roi.type(), cv::Scalar(255, 255, 255));
      cv::addWeighted(roi, 0.15, white, 0.85, 0, roi);
      cv::rectangle(img, box, Gray(170), 1);
      for (size_t i = 0; i < entries.size(); ++i) {
        const int cy = box.y + pad / 2 + row_h * static_cast<int>(i) + row_h / 2;
        const int thickness =
            std::max(1, static_cast<int>(std::lround(entries[i]->thickness * std::max(1.0, st.f))));
        cv::line(img,
                 {box.x + pad, cy},
                 {box.x + pad + sample_w, cy},
                 Bgr(entries[i]->color),
                 thickness,
                 cv::LINE_AA);
        Text(img,
             entries[i]->label,
             box.x + 2 * pad + sample_w,
             cy,
             st.legend(),
             kText,
             1,
             HAlign::kLeft,
             VAlign::kMiddle);
      }
    }
  }
  return EncodePng(img);
}

namespace {

// Renders with `render` and writes the PNG atomically; a bad plot spec is reported with the path.
template <typename Render>
void RenderToFile(const std::string& png_path, Render render) {
  std::vector<unsigned char> png;
  try {
    png = render();
  } catch (const InputError& e) {
    throw InputError(png_path + ": " + e.what());
  }
  WritePng(png_path, png);
}

}  // namespace

void WriteLinePlot(const std::string& png_path, const LinePlot& plot) {
  RenderToFile(png_path, [&] { return RenderLinePlotPng(plot); });
}

// ---------------------------------------------------------------------------------------------
// Heatmaps
// ---------------------------------------------------------------------------------------------

std::vector<unsigned char> RenderHeatmapPng(const Heatmap& map) {
  CheckSize(map.width, map.height, "heatmap");
  const std::string name = "heatmap '" + map.title + "'";
  if (map.rows <= 0 || map.cols <= 0 ||
      map.values.size() != static_cast<size_t>(map.rows) * static_cast<size_t>(map.cols)) {
    throw InputError(name + ": " + std::to_string(map.values.size()) + " values for " +
                     std::to_string(map.rows) + " x " + std::to_string(map.cols) + " cells");
  }
  if (!(map.x_max > map.x_min) || !(map.y_max > map.y_min)) {
    throw InputError(name + ": empty x or y range");
  }
  Range vr;
  for (double v : map.values) vr.Add(v);
  if (!vr.valid) throw InputError(name + ": no finite value");
  double v_lo = std::isnan(map.v_min) ? vr.lo : map.v_min;
  double v_hi = std::isnan(map.v_max) ? vr.hi : map.v_max;
  if (!(v_hi > v_lo)) {
    if (!std::isnan(map.v_min) && !std::isnan(map.v_max)) {
      throw InputError(name + ": empty colour range [" + Num(v_lo) + ", " + Num(v_hi) + "]");
    }
    const double half = std::max(std::abs(v_lo) * 0.05, 0.5);
    v_lo -= half;
    v_hi += half;
  }

  const Style st(map.width, map.height);
  const int pad = st.pad();
  const int tl = st.tick_len();
  const int tick_h = TextSize("0", st.tick(), 1).height;
  // Thickness of a rotated axis label: the height of its rendered mask (ascent, descent, margins).
  const int label_h = RenderTextMask("Ag^2", st.label(), st.stroke()).mask.rows;
  const int title_h = TextSize("Ag", st.title(), st.stroke() + 1).height;

  // Y ticks: categorical row labels or numeric.
  const bool categorical = map.y_tick_labels.size() == static_cast<size_t>(map.rows);
  std::vector<Tick> yticks;
  if (!categorical) yticks = LinearTicks(map.y_min, map.y_max, std::max(4, map.height / 90));
  int ytick_w = 0;
  if (categorical) {
    for (const std::string& s : map.y_tick_labels)
      ytick_w = std::max(ytick_w, TextSize(s, st.tick(), 1).width);
  } else {
    for (const Tick& t : yticks) ytick_w = std::max(ytick_w, TextSize(t.label, st.tick(), 1).width);
  }
  const std::vector<Tick> cticks = LinearTicks(v_lo, v_hi, std::max(4, map.height / 100));
  int ctick_w = 0;
  for (const Tick& t : cticks) ctick_w = std::max(ctick_w, TextSize(t.label, st.tick(), 1).width);
  const int bar_w = static_cast<int>(std::lround(22 * st.f));
  const int right = 2 * pad + bar_w + tl + pad / 2 + ctick_w + pad +
                    (map.colorbar_label.empty() ? 0 : label_h + pad);
  const int left = pad + (map.y_label.empty() ? 0 : label_h + pad) + ytick_w + pad + tl;
  const int top = pad + (map.title.empty() ? 0 : title_h + 2 * pad);
  const int bottom = tl + pad + tick_h + (map.x_label.empty() ? 0 : pad + label_h) + pad;
  const cv::Rect area(left, top, map.width - left - right, map.height - top - bottom);
  if (area.width < 50 || area.height < 50)
    throw InputError(name + ": image too small for its labels");

  cv::Mat img(map.height, map.width, CV_8UC3, cv::Scalar(255, 255, 255));

  // 1. Cells: normalise to 0..255, viridis, nearest-neighbour upscaling keeps cells crisp.
  cv::Mat levels(map.rows, map.cols, CV_8U);
  cv::Mat missing = cv::Mat::zeros(map.rows, map.cols, CV_8U);
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c) {
      const double v = map.values[static_cast<size_t>(r) * map.cols + c];
      if (!std::isfinite(v)) {
        missing.at<unsigned char>(r, c) = 1;
        levels.at<unsigned char>(r, c) = 0;
        continue;
      }
      const double u = std::clamp((v - v_lo) / (v_hi - v_lo), 0.0, 1.0);
      levels.at<unsigned char>(r, c) = static_cast<unsigned char>(std::lround(u * 255));
    }
  }
  cv::Mat colored;
  cv::applyColorMap(levels, colored, cv::COLORMAP_VIRIDIS);
  colored.setTo(cv::Scalar(215, 215, 215), missing);
  if (!map.row0_at_top) cv::flip(colored, colored, 0);
  cv::Mat cells;
  cv::resize(colored, cells, area.size(), 0, 0, cv::INTER_NEAREST);
  cells.copyTo(img(area));

  // Row r spans [y_min + r*h, y_min + (r+1)*h]; map y to pixels with row 0's edge at the top
  // (row0_at_top) or at the bottom.
  auto y_to_px = [&](double y) {
    const double u = (y - map.y_min) / (map.y_max - map.y_min);
    return map.row0_at_top ? area.y + u * area.height : area.y + area.height - u * area.height;
  };
  auto x_to_px = [&](double x) {
    return area.x + (x - map.x_min) / (map.x_max - map.x_min) * area.width;
  };

  if (map.highlight_row >= 0 && map.highlight_row < map.rows && map.highlight_col >= 0 &&
      map.highlight_col < map.cols) {
    const double cw = static_cast<double>(area.width) / map.cols;
    const double ch = static_cast<double>(area.height) / map.rows;
    const int r = map.row0_at_top ? map.highlight_row : map.rows - 1 - map.highlight_row;
    const cv::Rect cell(static_cast<int>(std::lround(area.x + map.highlight_col * cw)),
                        static_cast<int>(std::lround(area.y + r * ch)),
                        std::max(3, static_cast<int>(std::lround(cw))),
                        std::max(3, static_cast<int>(std::lround(ch))));
    cv::rectangle(img, cell, cv::Scalar(255, 255, 255), std::max(2, static_cast<int>(2 * st.f)));
    cv::rectangle(img, cell, kBlack, 1);
  }

  // 2. Frame and axes.
  cv::rectangle(img, cv::Rect(area.x - 1, area.y - 1, area.width + 2, area.height + 2), kBlack, 1);
  const std::vector<Tick> xticks = LinearTicks(map.x_min, map.x_max, std::max(4, area.width / 150));
  for (const Tick& t : xticks) {
    const int px = static_cast<int>(std::lround(x_to_px(t.value)));
    const int y0 = area.y + area.height;
    cv::line(img, {px, y0}, {px, y0 + tl}, kBlack, 1);
    Text(img, t.label, px, y0 + tl + pad / 2, st.tick(), kText, 1, HAlign::kCenter, VAlign::kTop);
  }
  if (categorical) {
    const double ch = static_cast<double>(area.height) / map.rows;
    const int every = std::max(1, static_cast<int>(std::ceil((tick_h + 4) / ch)));
    for (int r = 0; r < map.rows; r += every) {
      const int draw_r = map.row0_at_top ? r : map.rows - 1 - r;
      const int py = static_cast<int>(std::lround(area.y + (draw_r + 0.5) * ch));
      cv::line(img, {area.x - tl, py}, {area.x - 1, py}, kBlack, 1);
      Text(img,
           map.y_tick_labels[r],
           area.x - tl - pad / 2,
           py,
           st.tick(),
           kText,
           1,
           HAlign::kRight,
           VAlign::kMiddle);
    }
  } else {
    for (const Tick& t : yticks) {
      const int py = static_cast<int>(std::lround(y_to_px(t.value)));
      cv::line(img, {area.x - tl, py}, {area.x - 1, py}, kBlack, 1);
      Text(img,
           t.label,
           area.x - tl - pad / 2,
           py,
           st.tick(),
           kText,
           1,
           HAlign::kRight,
           VAlign::kMiddle);
    }
  }

  // 3. Colorbar: v_lo at the bottom, v_hi at the top.
  const cv::Rect bar(area.x + area.width + 2 * pad, area.y, bar_w, area.height);
  cv::Mat ramp(bar.height, 1, CV_8U);
  for (int r = 0; r < bar.height; ++r) {
    ramp.at<unsigned char>(r, 0) = static_cast<unsigned char>(
        std::lround(255.0 * (bar.height - 1 - r) / std::max(1, bar.height - 1)));
  }
  cv::Mat ramp_color, ramp_wide;
  cv::applyColorMap(ramp, ramp_color, cv::COLORMAP_VIRIDIS);
  cv::resize(ramp_color, ramp_wide, bar.size(), 0, 0, cv::INTER_NEAREST);
  ramp_wide.copyTo(img(bar));
  cv::rectangle(img, cv::Rect(bar.x - 1, bar.y - 1, bar.width + 2, bar.height + 2), kBlack, 1);
  for (const Tick& t : cticks) {
    const int py = static_cast<int>(
        std::lround(bar.y + bar.height - 1 - (t.value - v_lo) / (v_hi - v_lo) * (bar.height - 1)));
    const int x0 = bar.x + bar.width;
    cv::line(img, {x0, py}, {x0 + tl, py}, kBlack, 1);
    Text(img, t.label, x0 + tl + pad / 2, py, st.tick(), kText, 1, HAlign::kLeft, VAlign::kMiddle);
  }
  if (!map.colorbar_label.empty()) {
    const cv::Size ts = TextSize(map.colorbar_label, st.label(), st.stroke());
    RotatedText(img,
                map.colorbar_label,
                bar.x + bar.width + tl + pad / 2 + ctick_w + pad,
                bar.y + bar.height / 2 - ts.width / 2,
                st.label(),
                kBlack,
                st.stroke());
  }

  // 4. Title and labels.
  DrawTitleAndAxisLabels(img, st, area, pad, map.title, map.x_label, map.y_label);
  return EncodePng(img);
}

void WriteHeatmap(const std::string& png_path, const Heatmap& map) {
  RenderToFile(png_path, [&] { return RenderHeatmapPng(map); });
}

}  // namespace spallkit::plot
