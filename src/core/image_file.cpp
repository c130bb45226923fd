#include "core/image_file.h"

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <png.h>
#include <zlib.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/limits.h"

namespace vsil {

namespace {

// libpng reports an error by calling a function that must not return: onPngError keeps the
// message and jumps back to the setjmp of the function that called libpng (writePngImage,
// readPngLayout, readPngRows: frames holding no C++ object the jump would skip). Warnings (a
// valid file's unusual colour profile) are dropped: libpng prints nothing on stderr itself.
struct PngMessages {
  char error[160] = "";
};

[[noreturn]] void onPngError(png_structp png, png_const_charp message) {
  auto* messages = static_cast<PngMessages*>(png_get_error_ptr(png));
  std::snprintf(messages->error, sizeof messages->error, "%s", message);
  png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}

// Where png_write_* puts the bytes: a vector growing in place (no exception may cross libpng).
void appendPngBytes(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
  bool grown = true;
  try {
    out->insert(out->end(), data, data + length);
  } catch (...) {  // std::bad_alloc
    grown = false;
  }
  if (!grown) png_error(png, "out of memory");
}

void flushNothing(png_structp) {}

// png_write_* with its setjmp in a frame holding no C++ object; false when libpng failed.
bool writePngImage(png_structp png, png_infop info, const cv::Mat& image, png_bytepp rows,
                   std::vector<std::uint8_t>* bytes) {
  if (setjmp(png_jmpbuf(png))) return false;
  const int channels = image.channels();
  png_set_write_fn(png, bytes, appendPngBytes, flushNothing);
  png_set_IHDR(png, info, png_uint_32(image.cols), png_uint_32(image.rows),
               image.depth() == CV_16U ? 16 : 8,
               channels == 1   ? PNG_COLOR_TYPE_GRAY
               : channels == 3 ? PNG_COLOR_TYPE_RGB
                               : PNG_COLOR_TYPE_RGB_ALPHA,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // The settings of OpenCV's encoder, which wrote vsil's PNGs before (the same bytes): the Sub
  // filter and zlib's fastest level with run-length matching, quick on rendered images.
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_compression_level(png, Z_BEST_SPEED);
  png_set_compression_strategy(png, Z_RLE);
  png_write_info(png, info);
  if (channels > 1) png_set_bgr(png);              // cv::Mat holds BGR(A), PNG stores RGB(A)
  if (image.depth() == CV_16U) png_set_swap(png);  // PNG's 16-bit samples are big-endian
  png_write_image(png, rows);
  png_write_end(png, info);
  return true;
}

}  // namespace

std::vector<std::uint8_t> encodePng(const cv::Mat& image) {
  const int channels = image.channels();
  if (image.empty() || (image.depth() != CV_8U && image.depth() != CV_16U) ||
      (channels != 1 && channels != 3 && channels != 4)) {
    throw std::runtime_error("PNG encoding failed: PNG holds 8- or 16-bit grey, BGR or BGRA, not " +
                             std::to_string(channels) + " channels of OpenCV depth " +
                             std::to_string(image.depth()));
  }
  std::vector<png_bytep> rows(std::size_t(image.rows));
  for (int y = 0; y < image.rows; ++y) rows[std::size_t(y)] = const_cast<png_bytep>(image.ptr(y));
  std::vector<std::uint8_t> bytes;
  PngMessages messages;
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &messages, onPngError, onPngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  const bool written = info && writePngImage(png, info, image, rows.data(), &bytes);
  png_destroy_write_struct(&png, info ? &info : nullptr);
  if (!written) {
    throw std::runtime_error(std::string("PNG encoding failed: ") +
                             (info ? messages.error : "out of memory"));
  }
  return bytes;
}

void requirePngName(const std::string& flag, const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (!extension.empty() && extension != ".png") {
    throwInputError(flag + " " + path.string(), "vsil writes PNG images; name the file .png");
  }
}

std::vector<std::uint8_t> encodePng(const std::filesystem::path& path, const cv::Mat& image) {
  if (image.empty()) throwInputError(path.string(), "refusing to write an empty image");
  try {
    return encodePng(image);
  } catch (const std::runtime_error& error) {
    throwInputError(path.string(), error.what());
  }
}

void writePng(const std::filesystem::path& path, const cv::Mat& image) {
  writeFileAtomically(path, encodePng(path, image));
}

namespace {

// And notes it as one the command reads (atomic_file.h noteInputFile).
void requireRegularFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throwInputError(path.string(),
                    std::filesystem::exists(path, ec) ? "is not a regular file" : "no such file");
  }
  noteInputFile(path);
}

std::uint32_t bigEndian32(const unsigned char* bytes) {
  return std::uint32_t(bytes[0]) << 24 | std::uint32_t(bytes[1]) << 16 |
         std::uint32_t(bytes[2]) << 8 | std::uint32_t(bytes[3]);
}

// The bytes png_read_* takes, from memory.
struct PngSource {
  const unsigned char* data;
  std::size_t size;
  std::size_t at = 0;
};

void takePngBytes(png_structp png, png_bytep out, png_size_t length) {
  auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
  if (length > source->size - source->at) png_error(png, "the data ends early");
  std::memcpy(out, source->data + source->at, length);
  source->at += length;
}

struct PngLayout {
  int width = 0, height = 0, channels = 0, depth = CV_8U;
};

// Reads the header and sets libpng's transformations so that the rows come out as OpenCV's
// IMREAD_UNCHANGED gave them, which vsil read PNGs with before: 8 or 16 bits per sample
// (1, 2 and 4 widened to 8); grey stays one channel (a tRNS chunk ignored); RGB and palettes
// become BGR, or BGRA with a tRNS chunk; grey with alpha and RGBA become BGRA.
bool readPngLayout(png_structp png, png_infop info, PngSource* source, PngLayout* layout) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_read_fn(png, source, takePngBytes);
  png_read_info(png, info);
  const int bitDepth = png_get_bit_depth(png, info), colorType = png_get_color_type(png, info);
  const bool transparency = png_get_valid(png, info, PNG_INFO_tRNS) != 0;
  int channels = 1;
  if (colorType == PNG_COLOR_TYPE_RGB || colorType == PNG_COLOR_TYPE_PALETTE) {
    channels = transparency ? 4 : 3;
  } else if (colorType == PNG_COLOR_TYPE_GRAY_ALPHA || colorType == PNG_COLOR_TYPE_RGB_ALPHA) {
    channels = 4;
  }
  if (colorType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colorType == PNG_COLOR_TYPE_GRAY && bitDepth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (transparency && channels == 4) png_set_tRNS_to_alpha(png);
  if (colorType == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
  if (channels > 1) png_set_bgr(png);
  if (bitDepth == 16) png_set_swap(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const std::size_t sampleBytes = bitDepth == 16 ? 2 : 1;
  *layout = {int(png_get_image_width(png, info)), int(png_get_image_height(png, info)), channels,
             bitDepth == 16 ? CV_16U : CV_8U};
  if (png_get_channels(png, info) != channels ||
      png_get_rowbytes(png, info) !=
          std::size_t(layout->width) * std::size_t(channels) * sampleBytes) {
    png_error(png, "unexpected sample layout");
  }
  return true;
}

// png_read_image and png_read_end into `rows`, its setjmp in a frame holding no C++ object.
bool readPngRows(png_structp png, png_infop info, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, info);
  return true;
}

// The decoded image, or empty with messages.error saying why.
cv::Mat decodePng(const std::vector<unsigned char>& bytes, PngMessages& messages) {
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, &messages, onPngError, onPngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    std::snprintf(messages.error, sizeof messages.error, "out of memory");
    return {};
  }
  PngSource source{bytes.data(), bytes.size()};
  PngLayout layout;
  cv::Mat image;
  if (readPngLayout(png, info, &source, &layout)) {
    image.create(layout.height, layout.width, CV_MAKETYPE(layout.depth, layout.channels));
    std::vector<png_bytep> rows(std::size_t(image.rows));
    for (int y = 0; y < image.rows; ++y) rows[std::size_t(y)] = image.ptr(y);
    if (!readPngRows(png, info, rows.data())) image.release();
  }
  png_destroy_read_struct(&png, &info, nullptr);
  return image;
}

}  // namespace

cv::Mat readImage(const std::filesystem::path& path) {
  // PNG only (what vsil writes): "is not a PNG image" for other formats. An image vsil could
  // have written: at most kMaxImageSide pixels a side.
  const cv::Size size = readPngSize(path);
  if (size.width > limits::kMaxImageSide || size.height > limits::kMaxImageSide) {
    throwInputError(path.string(), std::to_string(size.width) + "x" + std::to_string(size.height) +
                                       " pixels is over the limit of " +
                                       std::to_string(limits::kMaxImageSide) + " per side");
  }
  return readPng(path);
}

cv::Size readPngSize(const std::filesystem::path& path) {
  requireRegularFile(path);
  // The signature, then the IHDR chunk: length 13, "IHDR", width and height (big-endian).
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  unsigned char head[24] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(head), sizeof head);
  const std::streamsize got = in.gcount();
  if (got == 0) throwInputError(path.string(), "is empty, not a PNG image");
  if (got < std::streamsize(sizeof head) || std::memcmp(head, kSignature, 8) != 0 ||
      std::memcmp(head + 12, "IHDR", 4) != 0) {
    throwInputError(path.string(), "is not a PNG image");
  }
  // IHDR holds 13 bytes; a shorter one would have its width and height read from what follows.
  if (const std::uint32_t length = bigEndian32(head + 8); length != 13) {
    throwInputError(path.string(), "is not a valid PNG image (its IHDR chunk holds " +
                                       std::to_string(length) + " bytes, 13 expected)");
  }
  const std::uint32_t width = bigEndian32(head + 16), height = bigEndian32(head + 20);
  constexpr std::uint32_t kLargest = 0x7fffffff;  // the PNG specification's limit
  if (width == 0 || height == 0 || width > kLargest || height > kLargest) {
    throwInputError(path.string(), "is not a valid PNG image (its header declares " +
                                       std::to_string(width) + "x" + std::to_string(height) +
                                       " pixels)");
  }
  return {int(width), int(height)};
}

cv::Mat readPng(const std::filesystem::path& path) {
  const cv::Size size = readPngSize(path);
  const std::string name = path.string();
  // The largest a PNG of this size can need: 16-bit RGBA rows with their filter bytes, stored
  // (deflate's worst case adds 5 bytes per 64 KiB block), and 1 MiB of other chunks.
  const std::uint64_t raw = std::uint64_t(size.height) * (1 + std::uint64_t(size.width) * 8);
  const std::uint64_t largest = raw + raw / 8192 + (std::uint64_t(1) << 20);
  std::error_code ec;
  const std::uint64_t fileBytes = std::filesystem::file_size(path, ec);
  if (ec) throwInputError(name, "cannot be read (" + ec.message() + ")");
  if (fileBytes > largest) {
    throwInputError(name, std::to_string(fileBytes) + " bytes is more than a " +
                              std::to_string(size.width) + "x" + std::to_string(size.height) +
                              " PNG image can hold");
  }
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  // After the 8-byte signature, chunks: length (big-endian), type, data, CRC of type and data.
  std::size_t at = 8;
  for (;;) {
    if (bytes.size() - at < 12) throwInputError(name, "is truncated (it ends without IEND)");
    const std::uint64_t length = bigEndian32(&bytes[at]);
    std::string type(reinterpret_cast<const char*>(&bytes[at + 4]), 4);
    for (char& c : type) c = std::isalpha(static_cast<unsigned char>(c)) ? c : '?';
    if (length > bytes.size() - at - 12) {
      throwInputError(name, "is truncated (chunk " + type + " at byte " + std::to_string(at) +
                                " ends beyond the file's " + std::to_string(bytes.size()) +
                                " bytes)");
    }
    const uLong crc = crc32(0L, &bytes[at + 4], uInt(length + 4));
    if (crc != bigEndian32(&bytes[at + 8 + length])) {
      throwInputError(
          name, "is corrupt (chunk " + type + " at byte " + std::to_string(at) + " fails its CRC)");
    }
    at += 12 + length;
    if (type == "IEND") break;
  }
  // libpng's warnings (a valid file's colour profile) are dropped; an error's text goes into
  // vsil's one line.
  PngMessages messages;
  cv::Mat image = decodePng(bytes, messages);
  if (image.empty() || image.size() != size) {
    const std::string reason = messages.error;
    throwInputError(name, "not a readable PNG image" + (reason.empty() ? "" : " (" + reason + ")"));
  }
  return image;
}

}  // namespace vsil
