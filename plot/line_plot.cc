#include "plot/line_plot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "plot/axis.h"
#include "plot/canvas.h"

namespace spallkit::plot {
namespace {
using namespace internal;

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

// A log axis's range: the positive data range, at most 6 decades below the maximum, 5 % padding
// in log space; widened to whole decades when it spans less than one. Fixed ends (not NaN) win.
void LogRange(const LinePlot& plot,
              const Range& pos,
              double fixed_lo,
              double fixed_hi,
              Axis* a,
              const char* name) {
  if (!pos.valid && (std::isnan(fixed_lo) || std::isnan(fixed_hi))) {
    throw InputError("line plot '" + plot.title + "': log " + name + " axis but no positive " +
                     name + " value");
  }
  double hi = std::isnan(fixed_hi) ? pos.hi : fixed_hi;
  double lo = std::isnan(fixed_lo) ? std::max(pos.lo, hi * 1e-6) : fixed_lo;
  if (lo > 0 && hi > 0) {
    const double decades = std::log10(hi / lo);
    if (decades < 1) {
      if (std::isnan(fixed_lo)) lo = std::pow(10.0, std::floor(std::log10(lo) + 1e-9));
      if (std::isnan(fixed_hi)) hi = std::pow(10.0, std::ceil(std::log10(hi) - 1e-9));
    } else {
      if (std::isnan(fixed_lo)) lo /= std::pow(10.0, 0.05 * decades);
      if (std::isnan(fixed_hi)) hi *= std::pow(10.0, 0.05 * decades);
    }
  }
  if (hi <= lo) hi = lo * 10;
  a->log = true;
  a->lo = lo;
  a->hi = hi;
  if (!(a->lo > 0)) {
    throw InputError("line plot '" + plot.title + "': log " + name + " axis needs " + name +
                     "_min > 0, got " + Num(a->lo));
  }
}

// Axis ranges from the data and the plot's fixed limits; throws InputError for mismatched series,
// no finite point or an empty range.
void ResolveAxes(const LinePlot& plot, Axis* x_axis, Axis* y_axis) {
  Range xr, yr, ypos, xpos;
  bool any_point = false;
  for (size_t k = 0; k < plot.series.size(); ++k) {
    const LineSeries& s = plot.series[k];
    if (!s.x.empty() && s.x.size() != s.y.size()) {
      throw InputError("line plot '" + plot.title + "': series " + std::to_string(k) + " ('" +
                       s.label + "') has " + std::to_string(s.x.size()) + " x values and " +
                       std::to_string(s.y.size()) + " y values");
    }
    if (!s.y_error.empty() && s.y_error.size() != s.y.size()) {
      throw InputError("line plot '" + plot.title + "': series " + std::to_string(k) + " ('" +
                       s.label + "') has " + std::to_string(s.y_error.size()) + " error bars and " +
                       std::to_string(s.y.size()) + " y values");
    }
    for (size_t i = 0; i < s.y.size(); ++i) {
      const double x = s.x.empty() ? static_cast<double>(i) : s.x[i];
      const double y = s.y[i];
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      any_point = true;
      xr.Add(x);
      if (y > 0) ypos.Add(y);
      if (x > 0) xpos.Add(x);
      // The bars are part of the data range (a log axis keeps the positive ends only).
      double e = s.y_error.empty() ? 0.0 : s.y_error[i];
      if (!std::isfinite(e)) e = 0.0;
      for (const double v : {y - e, y + e}) {
        yr.Add(v);
        if (v > 0) ypos.Add(v);
      }
    }
  }
  if (!any_point) throw InputError("line plot '" + plot.title + "': no finite data point");

  Axis ax, ay;
  if (plot.log_x) {
    LogRange(plot, xpos, plot.x_min, plot.x_max, &ax, "x");
  } else {
    ax.lo = std::isnan(plot.x_min) ? xr.lo : plot.x_min;
    ax.hi = std::isnan(plot.x_max) ? xr.hi : plot.x_max;
    if (std::isnan(plot.x_min) && std::isnan(plot.x_max) && ax.hi == ax.lo) {
      ax.lo -= 0.5;
      ax.hi += 0.5;
    }
  }
  ay.log = plot.log_y;
  if (plot.log_y) {
    LogRange(plot, ypos, plot.y_min, plot.y_max, &ay, "y");
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
  *x_axis = ax;
  *y_axis = ay;
}

struct Layout {
  std::vector<Tick> xticks, yticks;
  cv::Rect area;  // the plot area inside the frame
  int pad = 0;
};

// Ticks and the plot area around them; sets the axes' pixel ends.
Layout MakeLayout(const LinePlot& plot, const Style& st, Axis* x_axis, Axis* y_axis) {
  Axis& ax = *x_axis;
  Axis& ay = *y_axis;
  const std::vector<Tick> xticks = plot.log_x
                                       ? LogTicks(ax.lo, ax.hi)
                                       : LinearTicks(ax.lo, ax.hi, std::max(4, plot.width / 160));
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
  return {xticks, yticks, area, pad};
}

void DrawGrid(cv::Mat& img, const Layout& layout, const Axis& ax, const Axis& ay) {
  const cv::Rect& area = layout.area;
  const std::vector<Tick>& xticks = layout.xticks;
  const std::vector<Tick>& yticks = layout.yticks;
  for (const Tick& t : xticks) {
    const int px = static_cast<int>(std::lround(ax.ToPixel(t.value)));
    cv::line(img, {px, area.y}, {px, area.y + area.height - 1}, kGrid, 1);
  }
  for (const Tick& t : yticks) {
    const int py = static_cast<int>(std::lround(ay.ToPixel(t.value)));
    cv::line(
        img, {area.x, py}, {area.x + area.width - 1, py}, t.label.empty() ? kMinorGrid : kGrid, 1);
  }
}

// Markers (under the data so that the lines stay readable), labels staggered; returns the label
// boxes (in plot-area coordinates).
std::vector<cv::Rect> DrawMarkers(cv::Mat& inner,
                                  const LinePlot& plot,
                                  const Style& st,
                                  const cv::Rect& area,
                                  const Axis& ax,
                                  const Axis& ax_in) {
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
    RotatedText(inner, m.label, box.tl(), {scale, Bgr(m.thin ? Lighten(m.color, 0.1) : m.color)});
  }
  return label_boxes;
}

// LineSeries::y_error: a vertical bar with caps and a dot at each point that has one.
void DrawErrorBars(
    cv::Mat& inner, const LineSeries& s, int thickness, const Axis& ax_in, const Axis& ay_in) {
  auto at = [](double px, double py) {
    return cv::Point(static_cast<int>(std::lround(px * kSubpixel)),
                     static_cast<int>(std::lround(py * kSubpixel)));
  };
  const double cap = 4.0 * thickness;  // half width, pixels
  for (size_t i = 0; i < s.y_error.size(); ++i) {
    const double x = s.x.empty() ? static_cast<double>(i) : s.x[i];
    const double y = s.y[i], e = s.y_error[i];
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(e) || !(e > 0) ||
        (ax_in.log && !(x > 0)) || (ay_in.log && !(y > 0)))
      continue;
    const double lo = ay_in.log ? std::max(y - e, y * 1e-6) : y - e;  // a log axis's bar ends > 0
    const double px = ax_in.ToPixel(x), top = ay_in.ToPixel(y + e), bottom = ay_in.ToPixel(lo);
    const int w = std::max(1, thickness / 2);
    cv::line(inner, at(px, top), at(px, bottom), Bgr(s.color), w, cv::LINE_AA, kShift);
    cv::line(inner, at(px - cap, top), at(px + cap, top), Bgr(s.color), w, cv::LINE_AA, kShift);
    cv::line(
        inner, at(px - cap, bottom), at(px + cap, bottom), Bgr(s.color), w, cv::LINE_AA, kShift);
    cv::circle(inner,
               at(px, ay_in.ToPixel(y)),
               2 * thickness * static_cast<int>(kSubpixel),
               Bgr(s.color),
               -1,
               cv::LINE_AA,
               kShift);
  }
}

void DrawSeries(
    cv::Mat& inner, const LinePlot& plot, const Style& st, const Axis& ax_in, const Axis& ay_in) {
  for (const LineSeries& s : plot.series) {
    const int thickness =
        std::max(1, static_cast<int>(std::lround(s.thickness * std::max(1.0, st.f))));
    if (s.points) {
      for (size_t i = 0; i < s.y.size(); ++i) {
        const double x = s.x.empty() ? static_cast<double>(i) : s.x[i];
        if (!std::isfinite(x) || !std::isfinite(s.y[i]) || (ax_in.log && !(x > 0)) ||
            (ay_in.log && !(s.y[i] > 0)))
          continue;
        const cv::Point2d at(ax_in.ToPixel(x), ay_in.ToPixel(s.y[i]));
        const int radius = 3 * thickness;
        cv::circle(inner,
                   cv::Point(static_cast<int>(std::lround(at.x * kSubpixel)),
                             static_cast<int>(std::lround(at.y * kSubpixel))),
                   radius * static_cast<int>(kSubpixel),
                   Bgr(s.color),
                   -1,
                   cv::LINE_AA,
                   kShift);
        if (i < s.point_labels.size() && !s.point_labels[i].empty())
          Text(inner,
               s.point_labels[i],
               {at.x + radius + 6, at.y},
               {st.marker(false), Bgr(s.color), 1},
               HAlign::kLeft,
               VAlign::kMiddle);
      }
      continue;
    }
    DrawErrorBars(inner, s, thickness, ax_in, ay_in);
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
}

// Frame, ticks, tick labels.
void DrawFrameAndTicks(
    cv::Mat& img, const Style& st, const Layout& layout, const Axis& ax, const Axis& ay) {
  const cv::Rect& area = layout.area;
  const int pad = layout.pad;
  const std::vector<Tick>& xticks = layout.xticks;
  const std::vector<Tick>& yticks = layout.yticks;
  cv::rectangle(img, area, kBlack, 1);
  const int tl = st.tick_len();
  for (const Tick& t : xticks) {
    const int px = static_cast<int>(std::lround(ax.ToPixel(t.value)));
    DrawXTick(img, st, {px, area.y + area.height}, tl, pad, t.label);
  }
  for (const Tick& t : yticks) {
    const int py = static_cast<int>(std::lround(ay.ToPixel(t.value)));
    const int len = t.label.empty() ? tl / 2 : tl;  // minor ticks are shorter
    DrawYTick(img, st, {area.x, py}, len, area.x - tl - pad / 2, t.label);
  }
}

// Legend box in the top-right corner, below any marker label in the way.
void DrawLegend(cv::Mat& img,
                const LinePlot& plot,
                const Style& st,
                const cv::Rect& area,
                int pad,
                const std::vector<cv::Rect>& label_boxes) {
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
             cv::Point(box.x + 2 * pad + sample_w, cy),
             {st.legend()},
             HAlign::kLeft,
             VAlign::kMiddle);
      }
    }
  }
}

}  // namespace

std::vector<unsigned char> RenderLinePlotPng(const LinePlot& plot) {
  CheckSize(plot.width, plot.height, "line plot");
  const Style st(plot.width, plot.height);
  Axis ax, ay;
  ResolveAxes(plot, &ax, &ay);
  const Layout layout = MakeLayout(plot, st, &ax, &ay);
  const cv::Rect& area = layout.area;
  cv::Mat img(plot.height, plot.width, CV_8UC3, cv::Scalar(255, 255, 255));
  DrawGrid(img, layout, ax, ay);
  // Markers and series are drawn into the plot area (clipped there).
  cv::Mat inner = img(area);
  const Axis ax_in{ax.lo, ax.hi, ax.log, ax.p0 - area.x, ax.p1 - area.x};
  const Axis ay_in{ay.lo, ay.hi, ay.log, ay.p0 - area.y, ay.p1 - area.y};
  const std::vector<cv::Rect> label_boxes = DrawMarkers(inner, plot, st, area, ax, ax_in);
  DrawSeries(inner, plot, st, ax_in, ay_in);
  DrawFrameAndTicks(img, st, layout, ax, ay);
  DrawTitleAndAxisLabels(img, st, area, layout.pad, {plot.title, plot.x_label, plot.y_label});
  DrawLegend(img, plot, st, area, layout.pad, label_boxes);
  return EncodePng(img);
}

void WriteLinePlot(const std::string& png_path, const LinePlot& plot) {
  RenderToFile(png_path, [&] { return RenderLinePlotPng(plot); });
}

}  // namespace spallkit::plot
