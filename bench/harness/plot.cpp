#include "harness/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string_view>
#include <utility>

#include <opencv2/imgproc.hpp>

namespace vsil::bench {
namespace {

constexpr int kPanelHeight = 520;
constexpr int kLeft = 70, kRight = 20, kTop = 84, kBottom = 170;
constexpr int kBarWidth = 9, kGroupGap = 14;
constexpr auto kFont = cv::FONT_HERSHEY_SIMPLEX;

const cv::Scalar kColors[] = {{180, 119, 31}, {14, 127, 255},  {44, 160, 44},
                              {40, 39, 214},  {189, 103, 148}, {75, 86, 140}};

// ASCII only: putText's Hershey fonts have no '²', 'σ' or '–'. Other characters become one '?'
// per code point.
std::string ascii(const std::string& text) {
  static const std::pair<std::string_view, std::string_view> kReplacements[] = {
      {"²", "^2"}, {"³", "^3"}, {"σ", "s"}, {"–", "-"}};
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = text[i];
    if (c < 0x80) {
      out += char(c);
      ++i;
      continue;
    }
    const auto* replacement =
        std::find_if(std::begin(kReplacements), std::end(kReplacements),
                     [&](const auto& r) { return text.compare(i, r.first.size(), r.first) == 0; });
    if (replacement != std::end(kReplacements)) {
      out += replacement->second;
      i += replacement->first.size();
      continue;
    }
    if ((c & 0xC0) == 0xC0) out += '?';  // a lead byte; continuation bytes are dropped
    ++i;
  }
  return out;
}

cv::Scalar colorOf(const PlotSpec& plot, int series) {
  const int index = plot.series[series].color >= 0 ? plot.series[series].color : series;
  return kColors[index % 6];
}

cv::Mat drawPanel(const PlotSpec& plot) {
  const int seriesCount = int(plot.series.size());
  const int groupWidth = seriesCount * kBarWidth + kGroupGap;
  const int width = std::max(640, kLeft + kRight + int(plot.groups.size()) * groupWidth);
  cv::Mat3b image(kPanelHeight, width, cv::Vec3b(255, 255, 255));
  const int plotBottom = kPanelHeight - kBottom, plotHeight = plotBottom - kTop;

  double lo = INFINITY, hi = 0;
  for (const auto& group : plot.values) {
    for (double v : group) {
      if (std::isfinite(v) && v > 0) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
  }
  if (!(hi > 0)) {
    lo = 0.1;
    hi = 1;
  }
  // Axis range: whole decades (log) or 0..a round maximum (linear).
  double axisLo = 0, axisHi = hi * 1.1;
  if (plot.logScale) {
    axisLo = std::floor(std::log10(lo));
    axisHi = std::ceil(std::log10(hi));
    if (axisHi <= axisLo) axisHi = axisLo + 1;
  }
  auto yOf = [&](double v) {
    const double t = plot.logScale ? (std::log10(v) - axisLo) / (axisHi - axisLo) : v / axisHi;
    return plotBottom - int(std::lround(std::clamp(t, 0.0, 1.0) * plotHeight));
  };

  cv::putText(image, ascii(plot.title), {kLeft, 28}, kFont, 0.6, {0, 0, 0}, 1, cv::LINE_AA);
  // Grid and value labels.
  std::vector<double> ticks;
  if (plot.logScale) {
    for (double e = axisLo; e <= axisHi + 1e-9; e += 1) ticks.push_back(std::pow(10.0, e));
  } else {
    for (int i = 0; i <= 4; ++i) ticks.push_back(axisHi * i / 4);
  }
  for (double tick : ticks) {
    const int y = plot.logScale || tick > 0 ? yOf(tick) : plotBottom;
    cv::line(image, {kLeft, y}, {width - kRight, y}, {220, 220, 220}, 1);
    char label[32];
    std::snprintf(label, sizeof label, "%g", tick);
    cv::putText(image, label, {8, y + 4}, kFont, 0.4, {60, 60, 60}, 1, cv::LINE_AA);
  }
  cv::putText(image, ascii(plot.valueLabel) + (plot.logScale ? " (log)" : ""), {8, kTop - 16},
              kFont, 0.4, {60, 60, 60}, 1, cv::LINE_AA);
  cv::line(image, {kLeft, plotBottom}, {width - kRight, plotBottom}, {0, 0, 0}, 1);

  for (std::size_t g = 0; g < plot.groups.size(); ++g) {
    const int x0 = kLeft + kGroupGap / 2 + int(g) * groupWidth;
    for (int s = 0; s < seriesCount; ++s) {
      const double v =
          g < plot.values.size() && s < int(plot.values[g].size()) ? plot.values[g][s] : NAN;
      const int x = x0 + s * kBarWidth;
      const cv::Scalar color = colorOf(plot, s);
      if (!(std::isfinite(v) && v > 0)) {
        cv::putText(image, "x", {x + 1, plotBottom - 3}, kFont, 0.3, color, 1, cv::LINE_AA);
        continue;
      }
      const cv::Rect bar(x, yOf(v), kBarWidth - 1, plotBottom - yOf(v));
      if (plot.series[s].reference) {
        cv::rectangle(image, bar, color, 1);
        for (int y = bar.y + 3; y < bar.y + bar.height; y += 4) {
          cv::line(image, {bar.x, y}, {bar.x + bar.width - 1, y - 3}, color, 1);
        }
      } else {
        cv::rectangle(image, bar, color, cv::FILLED);
      }
    }
    // Group label, rotated by drawing it into a small image and transposing.
    const std::string label = ascii(plot.groups[g]);
    int baseline = 0;
    const cv::Size textSize = cv::getTextSize(label, kFont, 0.4, 1, &baseline);
    cv::Mat3b text(textSize.height + baseline + 2, textSize.width + 2, cv::Vec3b(255, 255, 255));
    cv::putText(text, label, {1, textSize.height + 1}, kFont, 0.4, {0, 0, 0}, 1, cv::LINE_AA);
    cv::Mat3b rotated;
    cv::rotate(text, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
    const int lx = x0 + (seriesCount * kBarWidth - rotated.cols) / 2;
    const cv::Rect target(std::max(0, lx), plotBottom + 4, rotated.cols,
                          std::min(rotated.rows, kBottom - 8));
    if (target.x + target.width <= image.cols) {
      rotated(cv::Rect(0, 0, target.width, target.height)).copyTo(image(target));
    }
  }
  // Legend, one line under the title.
  int lx = kLeft;
  for (int s = 0; s < seriesCount; ++s) {
    const cv::Rect box(lx, 38, 10, 10);
    if (plot.series[s].reference) {
      cv::rectangle(image, box, colorOf(plot, s), 1);
    } else {
      cv::rectangle(image, box, colorOf(plot, s), cv::FILLED);
    }
    const std::string name = ascii(plot.series[s].name);
    cv::putText(image, name, {lx + 14, 48}, kFont, 0.4, {0, 0, 0}, 1, cv::LINE_AA);
    int baseline = 0;
    lx += 24 + cv::getTextSize(name, kFont, 0.4, 1, &baseline).width;
  }
  return image;
}

}  // namespace

cv::Mat drawPlots(const std::vector<const PlotSpec*>& plots) {
  std::vector<cv::Mat> panels;
  int width = 0;
  for (const PlotSpec* plot : plots) {
    if (plot->series.empty() || plot->groups.empty()) continue;
    panels.push_back(drawPanel(*plot));
    width = std::max(width, panels.back().cols);
  }
  if (panels.empty()) return {};
  for (auto& panel : panels) {
    if (panel.cols < width) {
      cv::copyMakeBorder(panel, panel, 0, 0, 0, width - panel.cols, cv::BORDER_CONSTANT,
                         cv::Scalar(255, 255, 255));
    }
  }
  cv::Mat out;
  cv::vconcat(panels, out);
  return out;
}

}  // namespace vsil::bench
