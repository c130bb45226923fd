#include "postfx/gaussian_fft.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>

namespace vsil {
namespace {

// FFTW's planner (plan creation and destruction, thread setup) is process-wide and not thread
// safe; every call into it takes this lock. Executing a plan needs no lock.
std::mutex& fftwPlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

void initFftwThreadsLocked() {
  static bool done = false;
  if (!done) {
    if (fftwf_init_threads() == 0) throw std::runtime_error("fftwf_init_threads failed");
    done = true;
  }
}

// Owner of an FFTW-aligned array (fftwf_malloc aligns for SIMD, as the planner assumed when it
// planned on arrays from the same allocator; that is what makes new-array execution legal).
template <typename T>
struct FftwArray {
  explicit FftwArray(std::size_t count) : data(static_cast<T*>(fftwf_malloc(sizeof(T) * count))) {
    if (!data) throw std::bad_alloc();
  }
  ~FftwArray() { fftwf_free(data); }
  FftwArray(const FftwArray&) = delete;
  FftwArray& operator=(const FftwArray&) = delete;
  T* data;
};

std::size_t complexCount(cv::Size padded) {
  return std::size_t(padded.height) * std::size_t(padded.width / 2 + 1);
}

}  // namespace

struct FftGaussianBlur::Plans {
  fftwf_plan forward = nullptr;   // real (height x width) -> half spectrum
  fftwf_plan backward = nullptr;  // half spectrum -> real, unnormalized
  // Work arrays of finished blur() calls, kept for the next ones (allocating and faulting in a
  // few MB per call cost about as much as a transform). Guarded by the owner's mutex_.
  struct Work {
    Work(std::size_t realCount, std::size_t complexCount)
        : real(realCount), spectrum(complexCount) {}
    FftwArray<float> real;
    FftwArray<fftwf_complex> spectrum;
    // The running sum of blurSum()'s products, made on its first use with two parts or more.
    std::unique_ptr<FftwArray<fftwf_complex>> sum;
  };
  std::vector<std::unique_ptr<Work>> idle;
  ~Plans() {
    std::lock_guard lock(fftwPlannerMutex());
    if (forward) fftwf_destroy_plan(forward);
    if (backward) fftwf_destroy_plan(backward);
  }
};

int gaussianReach(double sigma, cv::Point2d shift) {
  const double extra = std::max(std::abs(shift.x), std::abs(shift.y));
  return int(std::ceil(kGaussianReachSigmas * sigma + extra));
}

cv::Mat1f sampledGaussianKernel(double sigma, cv::Point2d shift) {
  if (!(sigma > 0) || !std::isfinite(sigma)) {
    throw std::invalid_argument("Gaussian sigma must be positive and finite, got " +
                                std::to_string(sigma));
  }
  const int reach = gaussianReach(sigma, shift);
  const int size = 2 * reach + 1;
  // Separable: the product of two sampled 1D Gaussians, each normalized in double.
  std::vector<double> gx(size), gy(size);
  double sumX = 0, sumY = 0;
  for (int i = 0; i < size; ++i) {
    const double dx = i - reach - shift.x, dy = i - reach - shift.y;
    gx[i] = std::exp(-dx * dx / (2 * sigma * sigma));
    gy[i] = std::exp(-dy * dy / (2 * sigma * sigma));
    sumX += gx[i];
    sumY += gy[i];
  }
  cv::Mat1f kernel(size, size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) kernel(y, x) = float(gy[y] / sumY * gx[x] / sumX);
  }
  return kernel;
}

int fftFriendlySize(int n) {
  for (int candidate = std::max(n, 1);; ++candidate) {
    int rest = candidate;
    for (int p : {2, 3, 5, 7}) {
      while (rest % p == 0) rest /= p;
    }
    if (rest == 1) return candidate;
  }
}

FftGaussianBlur::FftGaussianBlur() : FftGaussianBlur(Options{}) {}
FftGaussianBlur::FftGaussianBlur(Options options) : options_(options) {}
FftGaussianBlur::~FftGaussianBlur() = default;

int fftPaddedLength(int n) {
  for (int candidate = std::max(n, 2);; ++candidate) {
    if (candidate % 2 != 0) continue;  // r2c/c2r run fastest on even lengths
    int rest = candidate;
    for (int p : {2, 3, 5}) {
      while (rest % p == 0) rest /= p;
    }
    if (rest == 1) return candidate;
  }
}

cv::Size FftGaussianBlur::paddedSize(cv::Size size, double sigma, cv::Point2d shift) {
  // Output pixel x reads input x - dx for |dx| <= reach; with period P the wrapped reads land at
  // P - reach .. P - 1, which are padding (zeros) when P >= n + reach. One reach is enough.
  const int reach = gaussianReach(sigma, shift);
  return {fftPaddedLength(size.width + reach), fftPaddedLength(size.height + reach)};
}

int FftGaussianBlur::threadsFor(cv::Size /*padded*/) const {
  if (options_.threads > 0) return options_.threads;
  // One thread. Measured with vsil_fft_table --threads 1 / 2 at 1024² on the 2-core machine
  // (shared, load ~4.6; two alternating runs): two threads were never faster (sigma 8: 6.9 and
  // 9.3 ms with one, 7.4 and 8.9 ms with two; sigma 32: 13.7/15.2 vs 19.9/17.0 ms).
  return 1;
}

const FftGaussianBlur::Plans& FftGaussianBlur::plansFor(cv::Size padded) {
  // Called with mutex_ held. Plans live as long as this object (a handful of sizes in practice).
  auto& slot = plans_[{padded.width, padded.height}];
  if (slot) return *slot;
  auto plans = std::make_unique<Plans>();
  FftwArray<float> real(std::size_t(padded.width) * padded.height);
  FftwArray<fftwf_complex> spectrum(complexCount(padded));
  {
    std::lock_guard lock(fftwPlannerMutex());
    initFftwThreadsLocked();
    fftwf_plan_with_nthreads(threadsFor(padded));
    // FFTW_ESTIMATE: no timing-dependent choices, so the same plan (and bytes) every run.
    plans->forward =
        fftwf_plan_dft_r2c_2d(padded.height, padded.width, real.data, spectrum.data, FFTW_ESTIMATE);
    plans->backward =
        fftwf_plan_dft_c2r_2d(padded.height, padded.width, spectrum.data, real.data, FFTW_ESTIMATE);
  }
  if (!plans->forward || !plans->backward) {
    throw std::runtime_error("FFTW could not plan a " + std::to_string(padded.width) + "x" +
                             std::to_string(padded.height) + " transform");
  }
  slot = std::move(plans);
  return *slot;
}

std::shared_ptr<const FftGaussianBlur::Spectrum> FftGaussianBlur::spectrumFor(cv::Size padded,
                                                                              double sigma,
                                                                              cv::Point2d shift) {
  // Called with mutex_ held.
  const auto key = std::make_tuple(padded.width, padded.height, sigma, shift.x, shift.y);
  if (auto found = spectra_.find(key); found != spectra_.end()) return found->second;
  if (spectra_.size() >= 32) spectra_.clear();  // a sigma sweep must not grow memory forever

  const Plans& plans = plansFor(padded);
  const cv::Mat1f kernel = sampledGaussianKernel(sigma, shift);
  const int reach = kernel.rows / 2;
  FftwArray<float> real(std::size_t(padded.width) * padded.height);
  std::fill_n(real.data, std::size_t(padded.width) * padded.height, 0.0f);
  // Kernel offset (dx, dy) goes to index (dx mod width, dy mod height): centre at the origin.
  // The 1/(width*height) of FFTW's unnormalized backward transform is folded in here.
  const float scale = 1.0f / (float(padded.width) * float(padded.height));
  for (int dy = -reach; dy <= reach; ++dy) {
    const int row = (dy + padded.height) % padded.height;
    for (int dx = -reach; dx <= reach; ++dx) {
      const int col = (dx + padded.width) % padded.width;
      real.data[std::size_t(row) * padded.width + col] = kernel(dy + reach, dx + reach) * scale;
    }
  }
  auto spectrum = std::make_shared<Spectrum>(complexCount(padded));
  fftwf_execute_dft_r2c(plans.forward, real.data,
                        reinterpret_cast<fftwf_complex*>(spectrum->data()));
  spectra_[key] = spectrum;
  return spectrum;
}

cv::Size FftGaussianBlur::paddedSize(cv::Size size, double sigma,
                                     std::span<const ShiftedImage> parts) {
  cv::Size padded(0, 0);
  for (const ShiftedImage& part : parts) {
    const cv::Size one = paddedSize(size, sigma, part.shift);
    padded = {std::max(padded.width, one.width), std::max(padded.height, one.height)};
  }
  return padded;
}

cv::Mat1f FftGaussianBlur::blur(const cv::Mat1f& image, double sigma, cv::Point2d shift) {
  const ShiftedImage part{&image, shift};
  return blurSum({&part, 1}, sigma);
}

cv::Mat1f FftGaussianBlur::blurSum(std::span<const ShiftedImage> parts, double sigma) {
  if (parts.empty()) throw std::invalid_argument("FftGaussianBlur::blurSum: no image");
  const cv::Size size = parts.front().image ? parts.front().image->size() : cv::Size();
  for (const ShiftedImage& part : parts) {
    if (!part.image || part.image->empty()) {
      throw std::invalid_argument("FftGaussianBlur::blur: empty image");
    }
    if (part.image->size() != size) {
      throw std::invalid_argument("FftGaussianBlur::blurSum: images differ in size");
    }
  }
  if (!(sigma > 0) || !std::isfinite(sigma)) {
    throw std::invalid_argument("FftGaussianBlur::blur: sigma must be positive and finite");
  }
  const cv::Size padded = paddedSize(size, sigma, parts);
  const Plans* plans = nullptr;
  std::vector<std::shared_ptr<const Spectrum>> kernelSpectra;
  {
    std::lock_guard lock(mutex_);
    for (const ShiftedImage& part : parts) {
      kernelSpectra.push_back(spectrumFor(padded, sigma, part.shift));  // also makes the plans
    }
    plans = &plansFor(padded);
  }

  const std::size_t realCount = std::size_t(padded.width) * padded.height;
  const std::size_t count = complexCount(padded);
  std::unique_ptr<Plans::Work> work;
  {
    std::lock_guard lock(mutex_);
    auto& idle = plans_[{padded.width, padded.height}]->idle;
    if (!idle.empty()) {
      work = std::move(idle.back());
      idle.pop_back();
    }
  }
  if (!work) work = std::make_unique<Plans::Work>(realCount, count);
  if (parts.size() > 1 && !work->sum) work->sum = std::make_unique<FftwArray<fftwf_complex>>(count);
  float* const real = work->real.data;
  fftwf_complex* const spectrum = work->spectrum.data;
  auto* values = reinterpret_cast<std::complex<float>*>(spectrum);
  // With one part the product stays in `spectrum`; with more, each part's product is added to
  // `sum` (the first one written), and `sum` goes through the backward transform.
  auto* sum = parts.size() > 1 ? reinterpret_cast<std::complex<float>*>(work->sum->data) : values;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const cv::Mat1f& image = *parts[p].image;
    // The image in the top-left corner, zeros elsewhere (every element is written: the array
    // holds the previous call's output). The padding on the right and bottom is at least the
    // kernel's reach, so no periodic copy reaches into the image.
    for (int y = 0; y < image.rows; ++y) {
      float* row = real + std::size_t(y) * padded.width;
      std::copy_n(image[y], image.cols, row);
      std::fill(row + image.cols, row + padded.width, 0.0f);
    }
    std::fill(real + std::size_t(image.rows) * padded.width, real + realCount, 0.0f);
    fftwf_execute_dft_r2c(plans->forward, real, spectrum);
    const std::complex<float>* kernel = kernelSpectra[p]->data();
    if (parts.size() == 1) {
      for (std::size_t i = 0; i < count; ++i) values[i] *= kernel[i];
    } else if (p == 0) {
      for (std::size_t i = 0; i < count; ++i) sum[i] = values[i] * kernel[i];
    } else {
      for (std::size_t i = 0; i < count; ++i) sum[i] += values[i] * kernel[i];
    }
  }
  fftwf_execute_dft_c2r(plans->backward, reinterpret_cast<fftwf_complex*>(sum), real);

  cv::Mat1f out(size);
  for (int y = 0; y < size.height; ++y) {
    std::copy_n(real + std::size_t(y) * padded.width, size.width, out[y]);
  }
  {
    std::lock_guard lock(mutex_);
    plans_[{padded.width, padded.height}]->idle.push_back(std::move(work));
  }
  return out;
}

std::size_t FftGaussianBlur::cachedPlans() const {
  std::lock_guard lock(mutex_);
  return plans_.size();
}

std::size_t FftGaussianBlur::cachedSpectra() const {
  std::lock_guard lock(mutex_);
  return spectra_.size();
}

}  // namespace vsil
