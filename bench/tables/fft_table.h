#pragma once
// fft: the FFT Gaussian blur of broadening (postfx) against OpenCV's spatial GaussianBlur:
// median times per sigma and image size, and their ratio. The broadening's cost should not grow
// with sigma (the line width); the spatial filter's grows linearly.
#include <vector>

#include "harness/table.h"

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

// The measured rows as the harness reports them: the self-check of each row, two JSON rows per
// (size, sigma) (technique "fft" and "spatial"), the printed and Markdown table, the plot.
TableResult fftTableResult(const std::vector<FftTableRow>& measured, const FftTableSpec& spec);

// `vsil bench --table fft`: --sizes replaces the sizes, --frames sets the repetitions.
TableResult runFftTable(const BenchOptions& options, Progress& progress);

}  // namespace vsil::bench
