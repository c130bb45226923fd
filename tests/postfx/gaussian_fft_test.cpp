// FftGaussianBlur against an independent direct convolution, zero padding, determinism.
#include "postfx/gaussian_fft.h"

#include <cmath>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

namespace vsil {
namespace {

cv::Mat1f randomImage(cv::Size size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  cv::Mat1f image(size);
  for (auto& v : image) v = value(rng);
  return image;
}

// Direct spatial convolution in double, zero outside the image, with the same sampled kernel.
cv::Mat1d directConvolution(const cv::Mat1f& image, const cv::Mat1f& kernel) {
  const int reach = kernel.rows / 2;
  cv::Mat1d out(image.size(), 0.0);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      double sum = 0;
      for (int dy = -reach; dy <= reach; ++dy) {
        const int sy = y - dy;
        if (sy < 0 || sy >= image.rows) continue;
        for (int dx = -reach; dx <= reach; ++dx) {
          const int sx = x - dx;
          if (sx < 0 || sx >= image.cols) continue;
          sum += double(kernel(dy + reach, dx + reach)) * image(sy, sx);
        }
      }
      out(y, x) = sum;
    }
  }
  return out;
}

struct FftCase {
  cv::Size size;
  double sigma;
  cv::Point2d shift;
};

class FftMatchesDirect : public ::testing::TestWithParam<FftCase> {};

TEST_P(FftMatchesDirect, EveryPixelWithin1e4) {
  const auto [size, sigma, shift] = GetParam();
  const cv::Mat1f image = randomImage(size, 7);
  FftGaussianBlur blur;
  const cv::Mat1f fft = blur.blur(image, sigma, shift);
  const cv::Mat1d direct = directConvolution(image, sampledGaussianKernel(sigma, shift));
  // 1e-4: the bound for float images with values in [0, 1]; single-precision FFTs of
  // these sizes are good to about 1e-6.
  int failures = 0;
  for (int y = 0; y < size.height && failures < 5; ++y) {
    for (int x = 0; x < size.width && failures < 5; ++x) {
      if (std::abs(fft(y, x) - direct(y, x)) > 1e-4) {
        ADD_FAILURE() << "at (" << x << ", " << y << "): fft " << fft(y, x) << " direct "
                      << direct(y, x);
        ++failures;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(SizesAndSigmas, FftMatchesDirect,
                         ::testing::Values(FftCase{{64, 64}, 1.0, {}}, FftCase{{31, 29}, 0.8, {}},
                                           FftCase{{97, 101}, 3.0, {}}, FftCase{{127, 61}, 7.3, {}},
                                           FftCase{{53, 89}, 12.0, {}},
                                           FftCase{{40, 37}, 2.0, {0.25, 0.25}},
                                           FftCase{{71, 73}, 4.5, {0.25, 0.25}}),
                         [](const auto& info) {
                           const auto& c = info.param;
                           return std::to_string(c.size.width) + "x" +
                                  std::to_string(c.size.height) + "_sigma" +
                                  std::to_string(int(c.sigma * 10)) +
                                  (c.shift.x != 0 ? "_shifted" : "");
                         });

TEST(FftGaussianBlur, KernelSumsToOne) {
  for (double sigma : {0.5, 1.0, 3.7, 20.0}) {
    EXPECT_NEAR(cv::sum(sampledGaussianKernel(sigma))[0], 1.0, 1e-5) << "sigma " << sigma;
  }
}

TEST(FftGaussianBlur, PaddedSizeHasSmallPrimesAndRoomForTheKernel) {
  const cv::Size padded = FftGaussianBlur::paddedSize({509, 257}, 4.0);
  const int reach = gaussianReach(4.0);
  // One reach of zeros is enough (gaussian_fft.cpp, paddedSize); even, 5-smooth lengths.
  EXPECT_GE(padded.width, 509 + reach);
  EXPECT_GE(padded.height, 257 + reach);
  EXPECT_EQ(fftFriendlySize(padded.width), padded.width);
  EXPECT_EQ(padded.width % 2, 0);
  EXPECT_EQ(fftPaddedLength(1031), 1080);  // 2³·3³·5
  EXPECT_EQ(fftFriendlySize(1031), 1050);  // 1031 is prime; 1050 = 2·3·5²·7
}

// A line along the left border must not wrap onto the right border: there the result is what
// the direct convolution gives, zero beyond the kernel's reach.
TEST(FftGaussianBlur, LineAtOneBorderLeavesTheOppositeBorderUntouched) {
  for (double sigma : {2.0, 8.0, 20.0}) {
    const cv::Size size(160, 120);
    FftGaussianBlur blur;
    cv::Mat1f leftLine(size, 0.0f), topLine(size, 0.0f);
    leftLine.col(0).setTo(1000.0f);  // bright, as a wide line's intensity is
    topLine.row(0).setTo(1000.0f);
    const cv::Mat1f fromLeft = blur.blur(leftLine, sigma);
    const cv::Mat1f fromTop = blur.blur(topLine, sigma);
    // Round-off of single-precision transforms, relative to the 1000 put in: far below any
    // threshold broadening uses (>= 3e-4 of a line's peak).
    const float allowed = 1000.0f * 2e-6f;
    for (int y = 0; y < size.height; ++y) {
      ASSERT_LT(std::abs(fromLeft(y, size.width - 1)), allowed)
          << "right border at (" << size.width - 1 << ", " << y << "), sigma " << sigma;
    }
    for (int x = 0; x < size.width; ++x) {
      ASSERT_LT(std::abs(fromTop(size.height - 1, x)), allowed)
          << "bottom border at (" << x << ", " << size.height - 1 << "), sigma " << sigma;
    }
    EXPECT_GT(fromLeft(size.height / 2, 0), 10.0f) << "the line itself must still be there";
  }
}

TEST(FftGaussianBlur, SameBytesEveryRunAndEveryObject) {
  const cv::Mat1f image = randomImage({300, 211}, 3);
  FftGaussianBlur first, second;
  const cv::Mat1f a = first.blur(image, 5.0);
  const cv::Mat1f b = first.blur(image, 5.0);  // cached plan and spectrum
  const cv::Mat1f c = second.blur(image, 5.0);
  EXPECT_EQ(0, std::memcmp(a.data, b.data, a.total() * sizeof(float)));
  EXPECT_EQ(0, std::memcmp(a.data, c.data, a.total() * sizeof(float)));
  EXPECT_EQ(first.cachedPlans(), 1u);
  EXPECT_EQ(first.cachedSpectra(), 1u);
}

TEST(FftGaussianBlur, BlurSumIsTheSumOfTheShiftedBlurs) {
  const cv::Mat1f first = randomImage({123, 97}, 5), second = randomImage({123, 97}, 6);
  FftGaussianBlur blur;
  const cv::Point2d shiftA(0.25, 0.25), shiftB(0.25, 0.0);
  const FftGaussianBlur::ShiftedImage parts[] = {{&first, shiftA}, {&second, shiftB}};
  const cv::Mat1f sum = blur.blurSum(parts, 3.0);
  const cv::Mat1f expected = blur.blur(first, 3.0, shiftA) + blur.blur(second, 3.0, shiftB);
  EXPECT_LT(cv::norm(sum, expected, cv::NORM_INF), 1e-5);
  const cv::Mat1f again = blur.blurSum(parts, 3.0);  // reused work arrays
  EXPECT_EQ(0, std::memcmp(sum.data, again.data, sum.total() * sizeof(float)));
  // One part: the same bytes as blur().
  const cv::Mat1f one = blur.blurSum({parts, 1}, 3.0);
  const cv::Mat1f plain = blur.blur(first, 3.0, shiftA);
  EXPECT_EQ(0, std::memcmp(one.data, plain.data, one.total() * sizeof(float)));
  const cv::Mat1f other(5, 7, 0.0f);
  const FftGaussianBlur::ShiftedImage mismatched[] = {{&first, shiftA}, {&other, shiftB}};
  EXPECT_THROW(blur.blurSum(mismatched, 3.0), std::invalid_argument);
}

TEST(FftGaussianBlur, RejectsBadSigma) {
  FftGaussianBlur blur;
  const cv::Mat1f image(8, 8, 0.0f);
  EXPECT_THROW(blur.blur(image, 0.0), std::invalid_argument);
  EXPECT_THROW(blur.blur(image, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace vsil
