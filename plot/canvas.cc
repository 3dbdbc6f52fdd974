#include "plot/canvas.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>

#include "core/atomic_file.h"

namespace spallkit::plot::internal {

Rgb Lighten(Rgb c, double amount) {
  auto mix = [&](unsigned char v) {
    return static_cast<unsigned char>(std::lround(v + (255 - v) * amount));
  };
  return {mix(c.r), mix(c.g), mix(c.b)};
}

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

namespace {
constexpr double kSuperscriptScale = 0.7;
}  // namespace

cv::Size TextSize(const std::string& text, double scale, int thickness, int* baseline) {
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

void Text(cv::Mat& img,
          const std::string& text,
          cv::Point2d at,
          const TextStyle& ts,
          HAlign h,
          VAlign v) {
  if (text.empty()) return;
  const TextMask tm = RenderTextMask(text, ts.scale, ts.thickness);
  double left = at.x;
  if (h == HAlign::kCenter) left -= tm.size.width / 2.0;
  if (h == HAlign::kRight) left -= tm.size.width;
  double baseline = at.y;
  if (v == VAlign::kTop) baseline += tm.size.height;
  if (v == VAlign::kMiddle) baseline += tm.size.height / 2.0;
  BlendMask(img,
            tm.mask,
            static_cast<int>(std::lround(left)) - tm.origin_x,
            static_cast<int>(std::lround(baseline)) - tm.baseline_y,
            ts.color);
}

cv::Size RotatedText(cv::Mat& img,
                     const std::string& text,
                     cv::Point top_left,
                     const TextStyle& ts) {
  const TextMask tm = RenderTextMask(text, ts.scale, ts.thickness);
  cv::Mat rotated;
  cv::rotate(tm.mask, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  BlendMask(img, rotated, top_left.x, top_left.y, ts.color);
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

std::string Num(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

void DrawTitleAndAxisLabels(
    cv::Mat& img, const Style& st, const cv::Rect& area, int pad, const AxisTitles& titles) {
  const std::string& title = titles.title;
  const std::string& x_label = titles.x_label;
  const std::string& y_label = titles.y_label;
  if (!title.empty()) {
    double scale = st.title();
    while (scale > 0.3 && TextSize(title, scale, st.stroke() + 1).width > img.cols - 2 * pad) {
      scale *= 0.9;
    }
    Text(img,
         title,
         {img.cols / 2.0, static_cast<double>(pad)},
         {scale, kBlack, st.stroke() + 1},
         HAlign::kCenter,
         VAlign::kTop);
  }
  if (!x_label.empty()) {
    Text(img,
         x_label,
         {area.x + area.width / 2.0, static_cast<double>(img.rows - pad - 2)},
         {st.label(), kBlack, st.stroke()},
         HAlign::kCenter,
         VAlign::kBaseline);
  }
  if (!y_label.empty()) {
    const cv::Size ts = TextSize(y_label, st.label(), st.stroke());
    RotatedText(img,
                y_label,
                {pad, area.y + area.height / 2 - ts.width / 2},
                {st.label(), kBlack, st.stroke()});
  }
}

void DrawXTick(
    cv::Mat& img, const Style& st, cv::Point top, int len, int pad, const std::string& label) {
  cv::line(img, top, {top.x, top.y + len}, kBlack, 1);
  Text(img,
       label,
       cv::Point(top.x, top.y + len + pad / 2),
       {st.tick()},
       HAlign::kCenter,
       VAlign::kTop);
}

void DrawYTick(cv::Mat& img,
               const Style& st,
               cv::Point right,
               int len,
               int label_x,
               const std::string& label) {
  cv::line(img, {right.x - len, right.y}, right, kBlack, 1);
  Text(img, label, cv::Point(label_x, right.y), {st.tick()}, HAlign::kRight, VAlign::kMiddle);
}

}  // namespace spallkit::plot::internal
