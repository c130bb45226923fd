#include "tables/fft_table.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>

#include <opencv2/imgproc.hpp>

#include "harness/text_table.h"
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

namespace {

// The two filters compute the same convolution (zero outside the image); they may differ by float
// round-off and by the spatial kernel's truncation at 3 sigma (OpenCV's default size). Values are
// in [0, 1] (a line image); 1e-2 catches a wrong sigma or a shifted image.
constexpr double kMaxDifference = 1e-2;

std::string checkOf(const FftTableRow& r) {
  return r.maxDifference <= kMaxDifference ? "ok" : "FAILED: FFT and spatial results differ";
}

std::string sizeLabel(const FftTableRow& r) {
  return std::to_string(r.size) + "²";
}

std::string sigmaLabel(const FftTableRow& r) {
  char sigma[16];
  std::snprintf(sigma, sizeof sigma, "%g", r.sigma);
  return sigma;
}

// Two rows: the FFT's times and the spatial filter's.
std::vector<nlohmann::json> jsonRows(const FftTableRow& r, const FftTableSpec& spec) {
  std::vector<nlohmann::json> rows;
  for (const bool fft : {true, false}) {
    const double med = fft ? r.fftMs : r.spatialMs;
    rows.push_back({{"table", "fft"},
                    {"dataset", "lines"},
                    {"width", r.size},
                    {"height", r.size},
                    {"technique", fft ? "fft" : "spatial"},
                    {"sigma", r.sigma},
                    {"frames", spec.repetitions},
                    {"ms_median", med},
                    {"ms_min", fft ? r.fftMinMs : r.spatialMinMs},
                    {"ms_max", fft ? r.fftMaxMs : r.spatialMaxMs},
                    {"fps", med > 0 ? 1000.0 / med : 0.0},
                    {"ratio_fft_over_spatial", r.ratio},
                    {"max_difference", r.maxDifference},
                    {"check", checkOf(r)}});
  }
  return rows;
}

TextTable textTable(const std::vector<FftTableRow>& measured) {
  TextTable text({"size", "sigma", "FFT ms", "[min–max]", "spatial ms", "[min–max]", "FFT/spatial",
                  "max diff", "check"});
  for (const auto& r : measured) {
    char cells[6][48];
    std::snprintf(cells[0], 48, "%.3f", r.fftMs);
    std::snprintf(cells[1], 48, "[%.3f–%.3f]", r.fftMinMs, r.fftMaxMs);
    std::snprintf(cells[2], 48, "%.3f", r.spatialMs);
    std::snprintf(cells[3], 48, "[%.3f–%.3f]", r.spatialMinMs, r.spatialMaxMs);
    std::snprintf(cells[4], 48, "%.2f", r.ratio);
    std::snprintf(cells[5], 48, "%.1e", r.maxDifference);
    text.addRow({sizeLabel(r), sigmaLabel(r), cells[0], cells[1], cells[2], cells[3], cells[4],
                 cells[5], checkOf(r)});
  }
  return text;
}

PlotSpec plotSpec(const std::vector<FftTableRow>& measured) {
  PlotSpec plot;
  plot.title = "fft: blur time per image (ms)";
  plot.valueLabel = "ms";
  plot.series = {{"FFT", false}, {"GaussianBlur", false}};
  for (const auto& r : measured) {
    plot.groups.push_back(sizeLabel(r) + " σ" + sigmaLabel(r));
    plot.values.push_back({r.fftMs, r.spatialMs});
  }
  return plot;
}

}  // namespace

TableResult fftTableResult(const std::vector<FftTableRow>& measured, const FftTableSpec& spec) {
  TableResult table;
  table.name = "fft";
  table.title = "Broadening cost against sigma: FFT (FFTW, zero padded) vs OpenCV GaussianBlur, ms";
  for (const auto& r : measured) {
    for (auto& row : jsonRows(r, spec)) table.rows.push_back(std::move(row));
    if (checkOf(r) != "ok") {
      table.failures.push_back("fft " + sizeLabel(r) + " sigma " + sigmaLabel(r) + ": " +
                               checkOf(r));
    }
  }
  const TextTable text = textTable(measured);
  table.text = text.plain();
  table.markdown = text.markdown();
  table.plot = plotSpec(measured);
  table.notes.push_back(
      "image: 40 one-pixel circles (fixed seed); FFT plans and kernel spectra cached before "
      "timing; single thread");
  return table;
}

TableResult runFftTable(const BenchOptions& options, Progress& progress) {
  FftTableSpec spec;
  if (!options.sizes.empty()) spec.sizes = options.sizes;
  spec.repetitions = options.frames;
  progress.setTotalCases(1);
  progress.startCase("fft: " + std::to_string(spec.sizes.size() * spec.sigmas.size()) +
                     " sizes × sigmas, " + std::to_string(spec.repetitions) + " repetitions each");
  const auto measured = measureFftTable(spec);
  progress.finish();
  return fftTableResult(measured, spec);
}

}  // namespace vsil::bench
