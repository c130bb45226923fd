// FFT Gaussian blur (postfx broadening) against OpenCV's spatial GaussianBlur, sigma 1..32 at
// 512² and 1024². The FFT's cost should stay flat in sigma; the spatial filter's grows.
// Each benchmark checks its output after timing. Table with ratios: vsil_fft_table.
#include <benchmark/benchmark.h>

#include <opencv2/imgproc.hpp>

#include "postfx/broaden.h"
#include "postfx/gaussian_fft.h"

namespace {

cv::Mat1f benchImage(int size) {
  cv::Mat1f image(size, size, 0.0f);
  cv::circle(image, {size / 2, size / 2}, size / 3, 1.0, 1);
  cv::line(image, {0, size / 5}, {size - 1, size / 2}, 1.0, 1);
  return image;
}

void BM_FftGaussianBlur(benchmark::State& state) {
  const int size = int(state.range(0));
  const double sigma = double(state.range(1));
  const cv::Mat1f image = benchImage(size);
  vsil::FftGaussianBlur blur;
  cv::Mat1f out = blur.blur(image, sigma);  // plans and spectrum outside the timing
  for (auto _ : state) {
    out = blur.blur(image, sigma);
    benchmark::DoNotOptimize(out.data);
  }
  state.SetItemsProcessed(state.iterations() * int64_t(size) * size);
  if (std::abs(cv::sum(out)[0] - cv::sum(image)[0]) > 1e-2 * cv::sum(image)[0]) {
    state.SkipWithError("blur does not preserve the image's mass");
  }
}

// The whole broadening of one-pixel lines (density, orientation split, blur, threshold): its
// cost should not grow with the width.
void BM_BroadenMask512(benchmark::State& state) {
  const int width = int(state.range(0));
  cv::Mat1b lines(512, 512, std::uint8_t(0));
  cv::circle(lines, {256, 256}, 170, 255, 1);
  cv::line(lines, {100, 300}, {400, 0}, 255, 1);  // exactly diagonal
  cv::line(lines, {0, 100}, {511, 260}, 255, 1);  // oblique
  vsil::FftGaussianBlur blur;
  cv::Mat1b band = vsil::broadenMask(lines, width, blur);  // plans outside the timing
  for (auto _ : state) {
    band = vsil::broadenMask(lines, width, blur);
    benchmark::DoNotOptimize(band.data);
  }
  if (cv::countNonZero(band) < cv::countNonZero(lines)) {
    state.SkipWithError("the band must cover the lines");
  }
}
BENCHMARK(BM_BroadenMask512)->Arg(3)->Arg(8)->Arg(40)->Unit(benchmark::kMillisecond);

void BM_OpenCvGaussianBlur(benchmark::State& state) {
  const int size = int(state.range(0));
  const double sigma = double(state.range(1));
  const cv::Mat1f image = benchImage(size);
  cv::Mat1f out;
  for (auto _ : state) {
    cv::GaussianBlur(image, out, cv::Size(), sigma, sigma, cv::BORDER_CONSTANT);
    benchmark::DoNotOptimize(out.data);
  }
  state.SetItemsProcessed(state.iterations() * int64_t(size) * size);
}

void sizesAndSigmas(benchmark::internal::Benchmark* b) {
  for (int size : {512, 1024}) {
    for (int sigma : {1, 2, 4, 8, 16, 32}) b->Args({size, sigma});
  }
  b->ArgNames({"size", "sigma"})->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_FftGaussianBlur)->Apply(sizesAndSigmas);
BENCHMARK(BM_OpenCvGaussianBlur)->Apply(sizesAndSigmas);

}  // namespace
