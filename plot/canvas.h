// Drawing on an OpenCV image: colours, sizes, text with superscripts, rotated labels, dashed
// lines, titles, PNG encoding and atomic PNG files. Shared by the line plot and heatmap renderers;
// internal to plot/ (it exposes OpenCV types, the public headers do not).
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "plot/color.h"

namespace spallkit::plot::internal {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr int kMinSize = 200;
constexpr int kMaxSize = 8000;
// Sub-pixel precision for polylines (OpenCV "shift": coordinates are multiplied by 2^shift).
constexpr int kShift = 4;
constexpr double kSubpixel = 1 << kShift;

inline cv::Scalar Bgr(Rgb c) { return cv::Scalar(c.b, c.g, c.r); }
inline cv::Scalar Gray(int v) { return cv::Scalar(v, v, v); }
inline const cv::Scalar kBlack = Gray(0);
inline const cv::Scalar kText = Gray(30);
inline const cv::Scalar kGrid = Gray(228);
inline const cv::Scalar kMinorGrid = Gray(243);

Rgb Lighten(Rgb c, double amount);

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
std::vector<Segment> ParseRichText(const std::string& text);

// Width, cap height and descent of (rich) text; `baseline` receives the descent below the baseline.
cv::Size TextSize(const std::string& text, double scale, int thickness, int* baseline = nullptr);

// Coverage mask of rendered text (255 = ink), with the position of the baseline and of the left
// edge of the text inside it.
struct TextMask {
  cv::Mat mask;
  int origin_x = 0;    // column of the text start
  int baseline_y = 0;  // row of the baseline
  cv::Size size;       // TextSize of the text
};
TextMask RenderTextMask(const std::string& text, double scale, int thickness);

// Alpha-blends `color` into img through `mask` placed with its top-left corner at (x, y).
void BlendMask(cv::Mat& img, const cv::Mat& mask, int x, int y, const cv::Scalar& color);

enum class HAlign { kLeft, kCenter, kRight };
enum class VAlign { kTop, kMiddle, kBaseline };

// How text is drawn: Hershey scale (Style's sizes), colour and stroke thickness.
struct TextStyle {
  double scale = 0.5;
  cv::Scalar color = kText;
  int thickness = 1;
};

// Draws text with its anchor at `at` aligned as asked (vertical alignment by the cap height of
// the normal-size text, so superscripts do not shift a label).
void Text(
    cv::Mat& img, const std::string& text, cv::Point2d at, const TextStyle& ts, HAlign h, VAlign v);

// Text rotated 90 degrees counter-clockwise (reads bottom to top), blended through its rotated
// coverage mask so that the anti-aliasing survives. `top_left` is the top-left corner of the
// rotated box; returns its size.
cv::Size RotatedText(cv::Mat& img,
                     const std::string& text,
                     cv::Point top_left,
                     const TextStyle& ts);

void DashedVLine(cv::Mat& img, int x, int y0, int y1, const cv::Scalar& color, int thickness);

std::vector<unsigned char> EncodePng(const cv::Mat& img);
// Writes PNG bytes atomically (core/atomic_file.h).
void WritePng(const std::string& path, const std::vector<unsigned char>& png);
// Throws InputError unless both sides are in [200, 8000] pixels.
void CheckSize(int width, int height, const char* what);
// "%g" of a value, for messages.
std::string Num(double v);

// A plot's title and axis labels.
struct AxisTitles {
  std::string title, x_label, y_label;
};

// Title centred on top (shrunk to fit), x label under the plot area, y label rotated on the left.
void DrawTitleAndAxisLabels(
    cv::Mat& img, const Style& st, const cv::Rect& area, int pad, const AxisTitles& titles);

// A tick below the plot area: a mark of `len` pixels down from `top` and its label centred under
// it, `pad` / 2 lower.
void DrawXTick(
    cv::Mat& img, const Style& st, cv::Point top, int len, int pad, const std::string& label);
// A tick left of the plot area: a mark of `len` pixels left from `right` and its label
// right-aligned at x = label_x, centred on the mark.
void DrawYTick(
    cv::Mat& img, const Style& st, cv::Point right, int len, int label_x, const std::string& label);

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

}  // namespace spallkit::plot::internal
