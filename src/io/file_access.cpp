#include "io/file_access.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/atomic_file.h"
#include "core/error.h"

namespace vsil::io {
namespace {

std::ifstream openForReading(const std::string& path) {
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int error = errno;
    throwInputError(path, std::string("cannot be opened for reading") +
                              (error ? std::string(": ") + std::strerror(error) : ""));
  }
  noteInputFile(path);  // no output of the command may replace it (core/atomic_file.h)
  return in;
}

}  // namespace

std::filesystem::file_type fileTypeAt(const std::filesystem::path& path, const std::string& where) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (status.type() == std::filesystem::file_type::not_found) return status.type();
  if (error) throwInputError(where, "cannot be examined: " + error.message());
  return status.type();
}

std::uint64_t regularFileSize(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::file_type type = fileTypeAt(path, path);
  if (type == fs::file_type::not_found) throwInputError(path, "no such file");
  if (type == fs::file_type::directory) throwInputError(path, "is a directory, not a file");
  if (type != fs::file_type::regular) throwInputError(path, "is not a regular file");
  std::error_code error;
  const std::uintmax_t size = fs::file_size(path, error);
  if (error) throwInputError(path, "cannot be examined: " + error.message());
  if (size == 0) {
    // A size of 0 is also what /proc and /sys report for files that hold something (or that
    // cannot be read at all, /proc/self/mem): one byte read tells them from an empty file.
    const UniqueFd file(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
    if (!file.valid()) openForReading(path);  // says why it cannot be opened
    char byte = 0;
    if (::read(file.get(), &byte, 1) == 0) throwInputError(path, "file is empty");
    throwInputError(path, "is a special file (its size reads as 0), not a volume file");
  }
  openForReading(path);  // permissions: fail here with a clear message rather than later
  return size;
}

std::vector<std::uint8_t> readFileBytes(const std::string& path, std::uint64_t offset,
                                        std::uint64_t count) {
  std::ifstream in = openForReading(path);
  std::vector<std::uint8_t> bytes(count);
  in.seekg(std::streamoff(offset));
  in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(count));
  if (!in || std::uint64_t(in.gcount()) != count) {
    throwInputError(path, "could not read " + std::to_string(count) + " bytes at offset " +
                              std::to_string(offset) + " (file changed or unreadable)");
  }
  return bytes;
}

FileReader::FileReader(const std::string& path) : path_(path) {
  errno = 0;
  fd_ = UniqueFd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (!fd_.valid()) {
    throwInputError(path, std::string("cannot be opened for reading: ") + std::strerror(errno));
  }
  noteInputFile(path);
}

void FileReader::readAt(std::uint64_t offset, std::span<std::uint8_t> out) const {
  std::size_t done = 0;
  while (done < out.size()) {
    const ssize_t got =
        ::pread(fd_.get(), out.data() + done, out.size() - done, off_t(offset + done));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) {
      throwInputError(path_, "could not read " + std::to_string(out.size()) + " bytes at offset " +
                                 std::to_string(offset) + " (file changed or unreadable)");
    }
    done += std::size_t(got);
  }
}

std::string readWholeFile(const std::string& path, std::uint64_t maxBytes) {
  const std::uint64_t size = regularFileSize(path);
  if (size > maxBytes) {
    throwInputError(path, "file of " + std::to_string(size) + " bytes is larger than the " +
                              std::to_string(maxBytes) + " bytes this format may need within " +
                              "the memory limit");
  }
  std::ifstream in = openForReading(path);
  std::string text(size, '\0');
  in.read(text.data(), std::streamsize(size));
  if (std::uint64_t(in.gcount()) != size) {
    throwInputError(path, "could not read its " + std::to_string(size) + " bytes");
  }
  return text;
}

}  // namespace vsil::io
