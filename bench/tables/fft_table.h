#pragma once
// FFT Gaussian blur (postfx) against OpenCV's spatial GaussianBlur: median times per sigma and
// image size, and their ratio. The broadening's cost should not grow with sigma (the line width);
// the spatial filter's grows linearly.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vsil::bench {

struct FftTableRow {
  int size = 0;  // square images, pixels per side
  double sigma = 0;
  double fftMs = 0;      // FftGaussianBlur::blur, plans and spectrum cached (warm)
  double spatialMs = 0;  // cv::GaussianBlur, kernel 2·ceil(3 sigma)+1 (OpenCV's own choice)
  double fftMinMs = 0, fftMaxMs = 0;  // over the repetitions
  double spatialMinMs = 0, spatialMaxMs = 0;
  double ratio = 0;          // fftMs / spatialMs
  double maxDifference = 0;  // max |fft - spatial| on the benchmark image (a sanity check)
};

struct FftTableSpec {
  std::vector<int> sizes{512, 1024};
  std::vector<double> sigmas{1, 2, 4, 8, 16, 32};
  int repetitions = 15;  // the median of these is reported
  int threads = 0;       // FftGaussianBlur::Options::threads (0: automatic)
};

std::vector<FftTableRow> measureFftTable(const FftTableSpec& spec = {});
std::string formatFftTable(const std::vector<FftTableRow>& rows);  // Markdown
nlohmann::json fftTableJson(const std::vector<FftTableRow>& rows);

}  // namespace vsil::bench
