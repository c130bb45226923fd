#include "core/image_file.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mutex>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <zlib.h>
#include <opencv2/imgcodecs.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/limits.h"

namespace vsil {

std::vector<std::uint8_t> encodePng(const cv::Mat& image) {
  std::vector<std::uint8_t> bytes;
  if (image.empty() || !cv::imencode(".png", image, bytes)) {
    throw std::runtime_error("PNG encoding failed");
  }
  return bytes;
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

void requireRegularFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throwInputError(path.string(),
                    std::filesystem::exists(path, ec) ? "is not a regular file" : "no such file");
  }
}

std::uint32_t bigEndian32(const unsigned char* bytes) {
  return std::uint32_t(bytes[0]) << 24 | std::uint32_t(bytes[1]) << 16 |
         std::uint32_t(bytes[2]) << 8 | std::uint32_t(bytes[3]);
}

// Sends what is written to stderr (descriptor 2) into a temporary file for its lifetime, for
// libraries that print there themselves; text() reads it back. One at a time (a mutex): a line
// another thread writes meanwhile lands there too, which only a decode's milliseconds risk.
class StderrCapture {
 public:
  StderrCapture() : lock_(mutex()) {
    std::fflush(stderr);
    file_ = std::tmpfile();
    saved_ = ::dup(2);
    if (file_ && saved_ >= 0) ::dup2(::fileno(file_), 2);
  }
  ~StderrCapture() {
    restore();
    if (file_) std::fclose(file_);
  }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  std::string text() const {
    if (!file_) return {};
    std::fflush(stderr);
    std::string result;
    std::rewind(file_);
    char buffer[512];
    std::size_t got = 0;
    while (result.size() < 4096 && (got = std::fread(buffer, 1, sizeof buffer, file_)) > 0) {
      result.append(buffer, got);
    }
    return result;
  }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  void restore() {
    std::fflush(stderr);
    if (saved_ >= 0) {
      ::dup2(saved_, 2);
      ::close(saved_);
      saved_ = -1;
    }
  }
  std::lock_guard<std::mutex> lock_;
  std::FILE* file_ = nullptr;
  int saved_ = -1;
};

}  // namespace

cv::Mat readImage(const std::filesystem::path& path) {
  requireRegularFile(path);
  {
    static constexpr char kSignature[8] = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n'};
    char head[8] = {};
    std::ifstream(path, std::ios::binary).read(head, sizeof head);
    if (std::memcmp(head, kSignature, 8) == 0) {
      // An image vsil could have written: at most kMaxImageSide pixels a side.
      const cv::Size size = readPngSize(path);
      if (size.width > limits::kMaxImageSide || size.height > limits::kMaxImageSide) {
        throwInputError(path.string(), std::to_string(size.width) + "x" +
                                           std::to_string(size.height) +
                                           " pixels is over the limit of " +
                                           std::to_string(limits::kMaxImageSide) + " per side");
      }
      return readPng(path);
    }
  }
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  if (image.empty()) throwInputError(path.string(), "not a readable image");
  return image;
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
  // libpng prints its warnings and errors on stderr itself ("libpng error: IDAT: invalid
  // distance too far back", or a warning about a valid file's colour profile); they are kept
  // off stderr, and an error's text goes into vsil's one line.
  std::string libpngSaid;
  cv::Mat image;
  {
    const StderrCapture capture;
    image = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
    libpngSaid = capture.text();
  }
  if (image.empty() || image.size() != size) {
    std::string reason;
    if (const auto at = libpngSaid.find("libpng error: "); at != std::string::npos) {
      reason = libpngSaid.substr(at + 14);
      reason = reason.substr(0, std::min(reason.find('\n'), std::size_t(120)));
    }
    throwInputError(name, "not a readable PNG image" + (reason.empty() ? "" : " (" + reason + ")"));
  }
  return image;
}

}  // namespace vsil
