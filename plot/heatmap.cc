#include "plot/heatmap.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "plot/axis.h"
#include "plot/canvas.h"

namespace spallkit::plot {
namespace {
using namespace internal;

// Checks the grid and returns the colour range [*v_lo, *v_hi] (data range unless fixed).
void ResolveColorRange(const Heatmap& map, const std::string& name, double* v_low, double* v_high) {
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
  *v_low = v_lo;
  *v_high = v_hi;
}

struct Layout {
  int pad = 0, tl = 0, tick_h = 0, label_h = 0, bar_w = 0, ctick_w = 0;
  bool categorical = false;  // y ticks are the rows' labels
  std::vector<Tick> yticks, cticks;
  cv::Rect area;  // the cells
};

Layout MakeLayout(
    const Heatmap& map, const Style& st, const std::string& name, double v_lo, double v_hi) {
  const int pad = st.pad();
  const int tl = st.tick_len();
  const int tick_h = TextSize("0", st.tick(), 1).height;
  // Thickness of a rotated axis label: the height of its rendered mask (ascent, descent,
  // margins).
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

  return {pad, tl, tick_h, label_h, bar_w, ctick_w, categorical, yticks, cticks, area};
}

// Cells: normalise to 0..255, viridis, nearest-neighbour upscaling keeps cells crisp; the
// highlighted cell framed in white.
void DrawCells(cv::Mat& img,
               const Heatmap& map,
               const Style& st,
               const cv::Rect& area,
               double v_lo,
               double v_hi) {
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
}

// Frame, x ticks, y ticks (numeric or the rows' labels).
void DrawAxes(cv::Mat& img, const Heatmap& map, const Style& st, const Layout& layout) {
  const cv::Rect& area = layout.area;
  const int pad = layout.pad, tl = layout.tl, tick_h = layout.tick_h;
  const bool categorical = layout.categorical;
  const std::vector<Tick>& yticks = layout.yticks;
  // (row0_at_top) or at the bottom.
  auto y_to_px = [&](double y) {
    const double u = (y - map.y_min) / (map.y_max - map.y_min);
    return map.row0_at_top ? area.y + u * area.height : area.y + area.height - u * area.height;
  };
  auto x_to_px = [&](double x) {
    return area.x + (x - map.x_min) / (map.x_max - map.x_min) * area.width;
  };
  cv::rectangle(img, cv::Rect(area.x - 1, area.y - 1, area.width + 2, area.height + 2), kBlack, 1);
  const std::vector<Tick> xticks = LinearTicks(map.x_min, map.x_max, std::max(4, area.width / 150));
  for (const Tick& t : xticks) {
    const int px = static_cast<int>(std::lround(x_to_px(t.value)));
    DrawXTick(img, st, {px, area.y + area.height}, tl, pad, t.label);
  }
  if (categorical) {
    const double ch = static_cast<double>(area.height) / map.rows;
    const int every = std::max(1, static_cast<int>(std::ceil((tick_h + 4) / ch)));
    for (int r = 0; r < map.rows; r += every) {
      const int draw_r = map.row0_at_top ? r : map.rows - 1 - r;
      const int py = static_cast<int>(std::lround(area.y + (draw_r + 0.5) * ch));
      DrawYTick(img, st, {area.x - 1, py}, tl - 1, area.x - tl - pad / 2, map.y_tick_labels[r]);
    }
  } else {
    for (const Tick& t : yticks) {
      const int py = static_cast<int>(std::lround(y_to_px(t.value)));
      DrawYTick(img, st, {area.x - 1, py}, tl - 1, area.x - tl - pad / 2, t.label);
    }
  }
}

// Colorbar: v_lo at the bottom, v_hi at the top, ticks and the rotated label on its right.
void DrawColorbar(cv::Mat& img,
                  const Heatmap& map,
                  const Style& st,
                  const Layout& layout,
                  double v_lo,
                  double v_hi) {
  const cv::Rect& area = layout.area;
  const int pad = layout.pad, tl = layout.tl, bar_w = layout.bar_w, ctick_w = layout.ctick_w;
  const std::vector<Tick>& cticks = layout.cticks;
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
    Text(img,
         t.label,
         cv::Point(x0 + tl + pad / 2, py),
         {st.tick()},
         HAlign::kLeft,
         VAlign::kMiddle);
  }
  if (!map.colorbar_label.empty()) {
    const cv::Size ts = TextSize(map.colorbar_label, st.label(), st.stroke());
    RotatedText(
        img,
        map.colorbar_label,
        {bar.x + bar.width + tl + pad / 2 + ctick_w + pad, bar.y + bar.height / 2 - ts.width / 2},
        {st.label(), kBlack, st.stroke()});
  }
}

}  // namespace

std::vector<unsigned char> RenderHeatmapPng(const Heatmap& map) {
  CheckSize(map.width, map.height, "heatmap");
  const std::string name = "heatmap '" + map.title + "'";
  double v_lo = 0, v_hi = 0;
  ResolveColorRange(map, name, &v_lo, &v_hi);
  const Style st(map.width, map.height);
  const Layout layout = MakeLayout(map, st, name, v_lo, v_hi);
  cv::Mat img(map.height, map.width, CV_8UC3, cv::Scalar(255, 255, 255));
  DrawCells(img, map, st, layout.area, v_lo, v_hi);
  DrawAxes(img, map, st, layout);
  DrawColorbar(img, map, st, layout, v_lo, v_hi);
  DrawTitleAndAxisLabels(img, st, layout.area, layout.pad, {map.title, map.x_label, map.y_label});
  return EncodePng(img);
}

void WriteHeatmap(const std::string& png_path, const Heatmap& map) {
  RenderToFile(png_path, [&] { return RenderHeatmapPng(map); });
}

}  // namespace spallkit::plot
