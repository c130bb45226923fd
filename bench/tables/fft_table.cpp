#include "tables/fft_table.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>

#include <opencv2/imgproc.hpp>

#include "harness/timing_stats.h"
#include "postfx/gaussian_fft.h"

namespace vsil::bench {
namespace {

// A sparse line image like broadening sees: a few hundred one-pixel circles, fixed seed.
cv::Mat1f lineImage(int size) {
  cv::Mat1b lines(size, size, std::uint8_t(0));
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> position(0, size - 1), radius(5, size / 4);
  for (int i = 0; i < 40; ++i) {
    cv::circle(lines, {position(rng), position(rng)}, radius(rng), 255, 1, cv::LINE_8);
  }
  cv::Mat1f image;
  lines.convertTo(image, CV_32F, 1.0 / 255.0);
  return image;
}

template <typename Work>
TimingStats timeMs(int repetitions, Work&& work) {
  std::vector<double> times;
  for (int i = 0; i < repetitions; ++i) {
    const auto start = std::chrono::steady_clock::now();
    work();
    const auto end = std::chrono::steady_clock::now();
    times.push_back(std::chrono::duration<double, std::milli>(end - start).count());
  }
  return summarize(times);
}

}  // namespace

std::vector<FftTableRow> measureFftTable(const FftTableSpec& spec) {
  std::vector<FftTableRow> rows;
  FftGaussianBlur blur(FftGaussianBlur::Options{spec.threads});
  for (int size : spec.sizes) {
    const cv::Mat1f image = lineImage(size);
    for (double sigma : spec.sigmas) {
      FftTableRow row{size, sigma};
      cv::Mat1f fft, spatial;
      fft = blur.blur(image, sigma);  // warm: plans and spectrum made once, outside the timing
      const TimingStats fftTimes = timeMs(spec.repetitions, [&] { fft = blur.blur(image, sigma); });
      const TimingStats spatialTimes = timeMs(spec.repetitions, [&] {
        cv::GaussianBlur(image, spatial, cv::Size(), sigma, sigma, cv::BORDER_CONSTANT);
      });
      row.fftMs = fftTimes.msMedian;
      row.fftMinMs = fftTimes.msMin;
      row.fftMaxMs = fftTimes.msMax;
      row.spatialMs = spatialTimes.msMedian;
      row.spatialMinMs = spatialTimes.msMin;
      row.spatialMaxMs = spatialTimes.msMax;
      row.ratio = row.fftMs / row.spatialMs;
      cv::Mat1f difference = cv::abs(fft - spatial);
      cv::minMaxLoc(difference, nullptr, &row.maxDifference);
      rows.push_back(row);
    }
  }
  return rows;
}

std::string formatFftTable(const std::vector<FftTableRow>& rows) {
  std::string out =
      "| size | sigma | FFT (ms) | GaussianBlur (ms) | FFT/spatial | max diff |\n"
      "| --- | --- | --- | --- | --- | --- |\n";
  for (const auto& r : rows) {
    char line[160];
    std::snprintf(line, sizeof line, "| %d² | %g | %.2f | %.2f | %.2f | %.1e |\n", r.size, r.sigma,
                  r.fftMs, r.spatialMs, r.ratio, r.maxDifference);
    out += line;
  }
  return out;
}

nlohmann::json fftTableJson(const std::vector<FftTableRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& r : rows) {
    out.push_back({{"size", r.size},
                   {"sigma", r.sigma},
                   {"fft_ms", r.fftMs},
                   {"spatial_ms", r.spatialMs},
                   {"ratio_fft_over_spatial", r.ratio},
                   {"max_difference", r.maxDifference}});
  }
  return out;
}

}  // namespace vsil::bench
