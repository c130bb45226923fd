#pragma once
// Reading files with every failure turned into an InputError that names the path: missing,
// a directory, empty, unreadable, shorter than needed, or larger than a caller's bound.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "core/unique_fd.h"

namespace vsil::io {

// The type of what `path` names, following links (not_found where nothing is). Throws
// InputError "`where`: cannot be examined: ..." where the system cannot tell (a loop of links,
// no permission to look), which std::filesystem's throwing calls report as an exception.
std::filesystem::file_type fileTypeAt(const std::filesystem::path& path, const std::string& where);

// The size of a regular, non-empty file. Throws for a missing path, a directory or other
// non-regular file, an empty file, or one that cannot be opened for reading.
std::uint64_t regularFileSize(const std::string& path);

// Exactly `count` bytes starting at `offset` (the caller has checked the file is long enough;
// a short read still throws).
std::vector<std::uint8_t> readFileBytes(const std::string& path, std::uint64_t offset,
                                        std::uint64_t count);

// A file open for reading at any offset, from several threads at once (pread).
class FileReader {
 public:
  // Throws InputError naming the path when it cannot be opened.
  explicit FileReader(const std::string& path);
  FileReader(const FileReader&) = delete;
  FileReader& operator=(const FileReader&) = delete;

  const std::string& path() const { return path_; }
  // Exactly out.size() bytes at `offset`; a short read throws InputError naming the path.
  void readAt(std::uint64_t offset, std::span<std::uint8_t> out) const;

 private:
  std::string path_;
  UniqueFd fd_;
};

// The whole file as bytes in a string, refusing files larger than `maxBytes` before reading.
std::string readWholeFile(const std::string& path, std::uint64_t maxBytes);

}  // namespace vsil::io
