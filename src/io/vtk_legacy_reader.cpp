// Legacy VTK (.vtk) DATASET STRUCTURED_POINTS with one SCALARS point array, ASCII or BINARY.
// Binary legacy data are big-endian by the VTK specification (docs.vtk.org, "Simple Legacy
// Formats"). Data after the array (a trailing newline, further arrays) are ignored.
#include <fstream>
#include <optional>

#include "core/error.h"
#include "io/file_access.h"
#include "io/readers.h"
#include "io/sample_codec.h"
#include "io/text_fields.h"

namespace vsil::io {
namespace {

// The header (everything before the samples) must lie within this many bytes.
constexpr std::size_t kMaxLegacyHeaderBytes = 64 * 1024;

struct LegacyHeader {
  bool binary = false;
  std::optional<glm::ivec3> dims;
  glm::dvec3 spacing{1.0};
  std::optional<std::int64_t> pointCount;
  std::optional<StoredType> type;
  std::uint64_t dataOffset = 0;
};

StoredType parseLegacyType(const std::string& path, std::string_view name) {
  const std::string lower = toLower(name);
  if (lower == "unsigned_char") return StoredType::UInt8;
  if (lower == "char") return StoredType::Int8;
  if (lower == "unsigned_short") return StoredType::UInt16;
  if (lower == "short") return StoredType::Int16;
  // The wider integers are kept as float32 (sample_codec.h). VTK's "long" and "unsigned_long"
  // are as wide as the writer's C long (4 or 8 bytes), which the file does not say: refused.
  if (lower == "int") return StoredType::Int32;
  if (lower == "unsigned_int") return StoredType::UInt32;
  if (lower == "vtktypeint64") return StoredType::Int64;
  if (lower == "vtktypeuint64") return StoredType::UInt64;
  if (lower == "float") return StoredType::Float32;
  if (lower == "double") return StoredType::Float64;  // converted to float32 when finite
  throwInputError(path, "SCALARS type " + quote(name) +
                            " is not supported (unsigned_char, char, unsigned_short, short, int, "
                            "unsigned_int, vtktypeint64, vtktypeuint64, float, double)");
}

// Walks the header line by line, keeping the byte offset of each line.
class LineCursor {
 public:
  explicit LineCursor(std::string_view text) : text_(text) {}
  bool atEnd() const { return pos_ >= text_.size(); }
  std::size_t offset() const { return pos_; }
  std::string_view rest() const { return text_.substr(pos_); }
  int lineNumber() const { return line_; }
  // The next line without its end; nullopt when the text ends before a newline.
  std::optional<std::string_view> next() {
    const std::size_t newline = text_.find('\n', pos_);
    if (newline == std::string_view::npos) return std::nullopt;
    std::string_view line = text_.substr(pos_, newline - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = newline + 1;
    ++line_;
    return line;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 0;
};

LegacyHeader parseHeader(const std::string& path, std::string_view text) {
  LineCursor cursor(text);
  auto nextLine = [&](const char* what) {
    const auto line = cursor.next();
    if (!line) {
      throwInputError(path, std::string("header ends before ") + what + " (within its first " +
                                std::to_string(kMaxLegacyHeaderBytes) + " bytes)");
    }
    return *line;
  };
  if (!nextLine("the version line").starts_with("# vtk DataFile Version")) {
    throwInputError(path, "is not a legacy VTK file (no '# vtk DataFile Version' line)");
  }
  nextLine("the title line");
  LegacyHeader header;
  bool spacingGiven = false;
  // Old writers leave blank lines between the header lines.
  std::string mode;
  while (mode.empty()) mode = toLower(trim(nextLine("the ASCII/BINARY line")));
  if (mode != "ascii" && mode != "binary") {
    throwInputError(path, "line " + std::to_string(cursor.lineNumber()) + " " + quote(mode) +
                              " is neither ASCII nor BINARY");
  }
  header.binary = mode == "binary";

  while (true) {
    const std::string_view line = nextLine("the SCALARS data");
    const auto tokens = splitWhitespace(line);
    if (tokens.empty()) continue;
    const std::string keyword = toLower(tokens[0]);
    const std::string where =
        "line " + std::to_string(cursor.lineNumber()) + " " + printableText(keyword);
    const auto argument = [&](std::size_t i) {
      if (i >= tokens.size()) throwInputError(path, where + " lacks an argument");
      return tokens[i];
    };
    const std::string_view arguments =
        line.substr(std::size_t(tokens[0].data() + tokens[0].size() - line.data()));
    if (keyword == "dataset") {
      if (toLower(argument(1)) != "structured_points") {
        throwInputError(
            path, "DATASET " + quote(argument(1)) + " is not supported (STRUCTURED_POINTS only)");
      }
    } else if (keyword == "dimensions") {
      if (header.dims) throwInputError(path, where + ": DIMENSIONS is given twice");
      header.dims = parseDims(path, "DIMENSIONS", arguments);
    } else if (keyword == "spacing" || keyword == "aspect_ratio") {
      if (spacingGiven) throwInputError(path, where + ": SPACING is given twice");
      spacingGiven = true;
      header.spacing = parseSpacing(path, "SPACING", arguments);
    } else if (keyword == "origin") {
      // Position only; vsil places volumes by their box.
    } else if (keyword == "point_data") {
      header.pointCount = parseInteger(path, "POINT_DATA", argument(1));
    } else if (keyword == "scalars") {
      if (!header.pointCount) throwInputError(path, "SCALARS comes before POINT_DATA");
      header.type = parseLegacyType(path, argument(2));
      if (tokens.size() > 3 && parseInteger(path, "SCALARS components", tokens[3]) != 1) {
        throwInputError(path, "SCALARS has " + std::string(tokens[3]) +
                                  " components; only scalar (1-component) data is read");
      }
      // LOOKUP_TABLE is optional in practice; when present it is the last header line. VTK
      // reads it as a keyword in any case after any whitespace, blank lines included (a binary
      // payload was once read from the line itself, every sample shifted). Without it the
      // payload starts on the next line, whatever its bytes.
      const std::string_view rest = cursor.rest();
      const std::size_t keywordAt = rest.find_first_not_of(" \t\r\n");
      if (keywordAt != std::string_view::npos &&
          toLower(rest.substr(keywordAt, 12)) == "lookup_table") {
        while (trim(nextLine("the LOOKUP_TABLE line end")).empty()) {
        }
      }
      header.dataOffset = cursor.offset();
      return header;
    } else if (keyword == "cell_data" || keyword == "field" || keyword == "vectors" ||
               keyword == "color_scalars" || keyword == "normals" || keyword == "tensors") {
      throwInputError(path, quote(tokens[0]) + " before the SCALARS point data is not supported");
    } else {
      throwInputError(path, where + ": unknown keyword " + quote(tokens[0]));
    }
  }
}

}  // namespace

Volume readLegacyVtk(const std::string& path, const LoadOptions& options) {
  const std::uint64_t fileSize = regularFileSize(path);
  std::string start(std::size_t(std::min<std::uint64_t>(fileSize, kMaxLegacyHeaderBytes)), '\0');
  {
    std::ifstream in(path, std::ios::binary);
    in.read(start.data(), std::streamsize(start.size()));
  }
  const LegacyHeader header = parseHeader(path, start);
  if (!header.dims) throwInputError(path, "header lacks DIMENSIONS");
  const glm::ivec3 dims = *header.dims;
  const StoredType type = *header.type;
  planVolume(path, dims, keptSampleType(type), options.limits, options.region);

  const std::uint64_t points = payloadBytes(dims, StoredType::UInt8);
  if (*header.pointCount < 0 || std::uint64_t(*header.pointCount) != points) {
    throwInputError(path, "POINT_DATA " + std::to_string(*header.pointCount) + " differs from " +
                              std::to_string(points) + " points of DIMENSIONS");
  }
  const std::uint64_t available = fileSize - header.dataOffset;
  if (header.binary) {
    const std::uint64_t expected = payloadBytes(dims, type);
    if (available < expected) {
      throwInputError(path, "payload holds " + std::to_string(available) + " bytes, " +
                                std::to_string(expected) + " expected (" +
                                describeLayout(dims, type) + ")");
    }
    Volume volume = startVolume(path, dims, type, header.spacing, options);
    volume.format = "legacy VTK STRUCTURED_POINTS (BINARY)";
    SampleSink sink(path, volume, subsetOf(volume), type, /*bigEndian=*/true);
    readUncompressed(FileReader(path), header.dataOffset, sink, options);
    return volume;
  }
  // Up to 64 characters per sample is generous for any printed number; later sections are
  // not needed.
  const std::uint64_t wanted = points * 64 + 4096;
  Volume volume = startVolume(path, dims, type, header.spacing, options);
  volume.format = "legacy VTK STRUCTURED_POINTS (ASCII)";
  SampleSink sink(path, volume, subsetOf(volume), type, /*bigEndian=*/true);
  const auto bytes = readFileBytes(path, header.dataOffset, std::min(available, wanted));
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  parseTextSamples(path, text, type, sink, TextAfterSamples::KeywordOrNothing);
  return volume;
}

}  // namespace vsil::io
