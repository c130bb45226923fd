// core/image_file's PNG codec (libpng) against OpenCV's imgcodecs, which vsil wrote and read its
// PNGs with before and which the tests still link: the same file bytes written, the same pixels
// and layout read, for every PNG colour type, bit depth and interlacing a user's file may have.
#include <csetjmp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <png.h>
#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "core/image_file.h"
#include "test_support.h"

namespace vsil {
namespace {

// A test image: noise in the left half (little to compress), ramps in the right (runs).
cv::Mat testImage(int rows, int cols, int type, unsigned seed) {
  cv::Mat image(rows, cols, type);
  cv::theRNG().state = seed;
  cv::randu(image, 0, CV_MAT_DEPTH(type) == CV_16U ? 65536 : 256);
  const int channels = image.channels();
  for (int y = 0; y < rows; ++y) {
    for (int x = cols / 2; x < cols; ++x) {
      for (int c = 0; c < channels; ++c) {
        const int value = (x * 7 + y * 3 + c * 50) % 256;
        if (image.depth() == CV_16U) {
          image.ptr<std::uint16_t>(y)[x * channels + c] = std::uint16_t(value * 257);
        } else {
          image.ptr<std::uint8_t>(y)[x * channels + c] = std::uint8_t(value);
        }
      }
    }
  }
  return image;
}

bool samePixels(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() && cv::norm(a, b, cv::NORM_INF) == 0;
}

TEST(PngFile, WritesTheBytesOpenCvWrote) {
  for (const int depth : {CV_8U, CV_16U}) {
    for (const int channels : {1, 3, 4}) {
      for (const cv::Size size : {cv::Size(1, 1), cv::Size(37, 23), cv::Size(301, 257)}) {
        SCOPED_TRACE("depth " + std::to_string(depth) + ", " + std::to_string(channels) +
                     " channels, " + std::to_string(size.width) + "x" +
                     std::to_string(size.height));
        const cv::Mat image =
            testImage(size.height, size.width, CV_MAKETYPE(depth, channels), 7u + channels);
        std::vector<std::uint8_t> opencv;
        ASSERT_TRUE(cv::imencode(".png", image, opencv));
        const std::vector<std::uint8_t> ours = encodePng(image);
        EXPECT_EQ(ours, opencv);
        EXPECT_TRUE(samePixels(cv::imdecode(ours, cv::IMREAD_UNCHANGED), image));
      }
    }
  }
}

TEST(PngFile, RefusesWhatPngCannotHold) {
  EXPECT_THROW(encodePng(cv::Mat1f(4, 4, 0.5f)), std::runtime_error);
  EXPECT_THROW(encodePng(cv::Mat(4, 4, CV_8UC2, cv::Scalar(1, 2))), std::runtime_error);
  EXPECT_THROW(encodePng(cv::Mat()), std::runtime_error);
  EXPECT_THROW(encodePng("empty.png", cv::Mat()), InputError);
}

// A PNG file of any colour type and bit depth, written with libpng itself. `samples` holds the
// rows' samples as PNG stores them (RGB order, palette indices), one value per sample.
struct PngSpec {
  int colorType;
  int bitDepth;
  bool interlaced = false;
  bool transparency = false;  // a tRNS chunk
};

std::string describe(const PngSpec& spec) {
  return "colour type " + std::to_string(spec.colorType) + ", " + std::to_string(spec.bitDepth) +
         " bits" + (spec.interlaced ? ", interlaced" : "") + (spec.transparency ? ", tRNS" : "");
}

bool writeWithLibpng(const std::filesystem::path& path, const PngSpec& spec, int width, int height,
                     png_bytepp rows, png_colorp palette, int paletteSize) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return false;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), spec.bitDepth, spec.colorType,
               spec.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_byte alphas[16];
  for (int i = 0; i < 16; ++i) alphas[i] = png_byte(i * 17);
  png_color_16 transparent{};
  transparent.gray = transparent.red = png_uint_16(1);
  transparent.green = transparent.blue = png_uint_16(2);
  if (spec.colorType == PNG_COLOR_TYPE_PALETTE) {
    png_set_PLTE(png, info, palette, paletteSize);
    if (spec.transparency) png_set_tRNS(png, info, alphas, paletteSize, nullptr);
  } else if (spec.transparency) {
    png_set_tRNS(png, info, nullptr, 0, &transparent);
  }
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return std::fclose(file) == 0;
}

std::filesystem::path writeSpec(const std::filesystem::path& dir, const PngSpec& spec) {
  const int width = 13, height = 9;
  const int channels = spec.colorType == PNG_COLOR_TYPE_GRAY         ? 1
                       : spec.colorType == PNG_COLOR_TYPE_PALETTE    ? 1
                       : spec.colorType == PNG_COLOR_TYPE_GRAY_ALPHA ? 2
                       : spec.colorType == PNG_COLOR_TYPE_RGB        ? 3
                                                                     : 4;
  const int levels = spec.colorType == PNG_COLOR_TYPE_PALETTE ? 16 : 1 << spec.bitDepth;
  const int bitsPerRow = width * channels * spec.bitDepth;
  std::vector<std::vector<png_byte>> rowBytes(height, std::vector<png_byte>((bitsPerRow + 7) / 8));
  for (int y = 0; y < height; ++y) {
    int bit = 0;
    for (int i = 0; i < width * channels; ++i, bit += spec.bitDepth) {
      const unsigned value = unsigned((i * 5 + y * 11 + i * y) % levels);
      if (spec.bitDepth == 16) {
        rowBytes[y][i * 2] = png_byte(value >> 8);
        rowBytes[y][i * 2 + 1] = png_byte(value & 0xff);
      } else {
        rowBytes[y][bit / 8] |= png_byte(value << (8 - spec.bitDepth - bit % 8));
      }
    }
  }
  std::vector<png_bytep> rows;
  for (auto& row : rowBytes) rows.push_back(row.data());
  png_color palette[16];
  for (int i = 0; i < 16; ++i)
    palette[i] = {png_byte(i * 16), png_byte(255 - i * 9), png_byte(i * 3)};
  const auto path =
      dir / ("t" + std::to_string(spec.colorType) + "_" + std::to_string(spec.bitDepth) +
             (spec.interlaced ? "i" : "") + (spec.transparency ? "t" : "") + ".png");
  EXPECT_TRUE(writeWithLibpng(path, spec, width, height, rows.data(), palette,
                              spec.bitDepth < 4 ? 1 << spec.bitDepth : 16))
      << describe(spec);
  return path;
}

TEST(PngFile, ReadsEveryKindOfPngAsOpenCvDid) {
  const auto dir = test::scratchDir();
  std::vector<PngSpec> specs;
  for (const bool interlaced : {false, true}) {
    for (const bool transparency : {false, true}) {
      for (const int depth : {1, 2, 4, 8, 16})
        specs.push_back({PNG_COLOR_TYPE_GRAY, depth, interlaced, transparency});
      for (const int depth : {1, 2, 4, 8})
        specs.push_back({PNG_COLOR_TYPE_PALETTE, depth, interlaced, transparency});
      for (const int depth : {8, 16})
        specs.push_back({PNG_COLOR_TYPE_RGB, depth, interlaced, transparency});
    }
    for (const int depth : {8, 16}) {
      specs.push_back({PNG_COLOR_TYPE_GRAY_ALPHA, depth, interlaced});
      specs.push_back({PNG_COLOR_TYPE_RGB_ALPHA, depth, interlaced});
    }
  }
  for (const PngSpec& spec : specs) {
    SCOPED_TRACE(describe(spec));
    const auto path = writeSpec(dir, spec);
    const cv::Mat opencv = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(opencv.empty());
    const cv::Mat ours = readPng(path);
    EXPECT_EQ(ours.type(), opencv.type());
    EXPECT_TRUE(samePixels(ours, opencv));
    EXPECT_TRUE(samePixels(readImage(path), opencv));
  }
}

TEST(PngFile, ReadsBackWhatItWrites) {
  const auto dir = test::scratchDir();
  for (const int type : {CV_8UC1, CV_8UC3, CV_8UC4, CV_16UC1, CV_16UC3, CV_16UC4}) {
    const cv::Mat image = testImage(31, 45, type, unsigned(type));
    writePng(dir / "x.png", image);
    EXPECT_TRUE(samePixels(readPng(dir / "x.png"), image)) << "type " << type;
  }
}

TEST(PngFile, OtherFormatsAreRefusedNamingTheFile) {
  const auto dir = test::scratchDir();
  const auto bmp = dir / "picture.bmp";
  ASSERT_TRUE(cv::imwrite(bmp.string(), testImage(8, 8, CV_8UC3, 1)));
  try {
    readImage(bmp);
    FAIL() << "a BMP file was read";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("picture.bmp"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("is not a PNG image"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace vsil
