#pragma once
// Gaussian blur through FFTW (single precision): real-to-complex transform, product with the
// Gaussian's spectrum, complex-to-real transform. The image is zero padded, so nothing wraps
// around from one border to the other: the result equals the direct (spatial) convolution of
// the image, taken as zero outside, with the sampled Gaussian kernel.
//
// One FftGaussianBlur owns a small cache of FFTW plans and reusable work arrays (per padded
// size) and of kernel spectra (per padded size, sigma and shift). Plans are made on one thread at a
// time (FFTW's planner is not thread safe) with FFTW_ESTIMATE, so the output bytes are the same on
// every run; blur() itself may be called from several threads.
#include <complex>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <tuple>
#include <vector>

#include <opencv2/core.hpp>

namespace vsil {

// The kernel reaches this many sigmas (plus its shift) from its centre; beyond, the sampled
// Gaussian is below exp(-18) ~ 1.5e-8 of its peak, far under what can move a threshold that
// postfx places at most exp(-8) below a line's peak (see width_law.h).
inline constexpr double kGaussianReachSigmas = 6.0;

// Radius in pixels of the sampled kernel: offsets -reach..reach on each axis.
int gaussianReach(double sigma, cv::Point2d shift = {});

// The sampled kernel, normalized to sum 1, of size (2 reach + 1)^2 with its centre (offset 0)
// in the middle: value at offset (dx, dy) is proportional to
// exp(-((dx - shift.x)^2 + (dy - shift.y)^2) / (2 sigma^2)).
cv::Mat1f sampledGaussianKernel(double sigma, cv::Point2d shift = {});

// Smallest n' >= n whose prime factors are all 2, 3, 5 or 7 (sizes FFTW transforms fast).
int fftFriendlySize(int n);
// The padded length blur() uses: smallest even n' >= n with prime factors 2, 3 and 5 only
// (measured on bench/: factors of 7 and odd lengths cost up to 2x in r2c/c2r).
int fftPaddedLength(int n);

class FftGaussianBlur {
 public:
  struct Options {
    // Threads for one transform. 0: automatic (one; a second did not pay at 1024² on two
    // cores, see gaussian_fft.cpp). A given
    // setting always gives the same bytes; different settings may differ in the last bits.
    int threads = 0;
  };
  FftGaussianBlur();
  explicit FftGaussianBlur(Options options);
  ~FftGaussianBlur();
  FftGaussianBlur(const FftGaussianBlur&) = delete;
  FftGaussianBlur& operator=(const FftGaussianBlur&) = delete;

  // image convolved with sampledGaussianKernel(sigma, shift), zero outside the image:
  // out(x, y) = sum over (dx, dy) of kernel(dx, dy) * image(x - dx, y - dy).
  // sigma > 0 and finite; image not empty and without NaN.
  cv::Mat1f blur(const cv::Mat1f& image, double sigma, cv::Point2d shift = {});

  // One term of blurSum(): an image and the shift of the kernel it is blurred with.
  struct ShiftedImage {
    const cv::Mat1f* image = nullptr;
    cv::Point2d shift;
  };
  // The sum over `parts` of blur(*part.image, sigma, part.shift), all images of one size, through
  // one forward transform per part and a single backward transform (the spectra add up first).
  // With one part, the same bytes as blur().
  cv::Mat1f blurSum(std::span<const ShiftedImage> parts, double sigma);

  // The padded transform size used for an image of `size` and this kernel.
  static cv::Size paddedSize(cv::Size size, double sigma, cv::Point2d shift = {});
  // ... and for several kernel shifts at once (the largest of their padded sizes).
  static cv::Size paddedSize(cv::Size size, double sigma, std::span<const ShiftedImage> parts);

  // Entries currently cached (for tests of the cache policy).
  std::size_t cachedPlans() const;
  std::size_t cachedSpectra() const;

 private:
  struct Plans;
  using Spectrum = std::vector<std::complex<float>>;
  const Plans& plansFor(cv::Size padded);
  std::shared_ptr<const Spectrum> spectrumFor(cv::Size padded, double sigma, cv::Point2d shift);
  int threadsFor(cv::Size padded) const;

  Options options_;
  mutable std::mutex mutex_;  // guards the caches and every call into FFTW's planner
  std::map<std::pair<int, int>, std::unique_ptr<Plans>> plans_;
  std::map<std::tuple<int, int, double, double, double>, std::shared_ptr<const Spectrum>> spectra_;
};

}  // namespace vsil
