// MetaImage (ITK's MetaIO; "MetaIO Documentation" on the ITK wiki / docs.itk.org): a text header
// of `Key = Value` lines ending with ElementDataFile, whose value is LOCAL (the data follow the
// header in the same file, .mha) or the data file's name relative to the header (.mhd with .raw
// or, compressed, .zraw). 3D scalar images; binary (either byte order) or ASCII; raw or zlib
// (CompressedData, CompressedDataSize); HeaderSize bytes skipped before the data (-1: the data
// are the last bytes of the file). 32- and 64-bit integers are kept as float32 (sample_codec.h).
#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "core/error.h"
#include "core/limits.h"
#include "io/file_access.h"
#include "io/inflate.h"
#include "io/readers.h"
#include "io/sample_codec.h"
#include "io/text_fields.h"

namespace vsil::io {
namespace {

struct MetaImageHeader {
  std::map<std::string, std::string> fields;  // key (lower case) -> value, ElementDataFile too
  std::uint64_t dataOffset = 0;               // the byte after the ElementDataFile line

  const std::string* find(const char* lowerKey) const {
    const auto it = fields.find(lowerKey);
    return it == fields.end() ? nullptr : &it->second;
  }
};

MetaImageHeader parseMetaImageHeader(const std::string& path, std::uint64_t fileSize) {
  constexpr std::size_t kMaxBytes = limits::kMaxHeaderBytes;
  const std::size_t readSize = std::size_t(std::min<std::uint64_t>(fileSize, kMaxBytes));
  std::string text(readSize, '\0');
  FileReader(path).readAt(0, std::span(reinterpret_cast<std::uint8_t*>(text.data()), readSize));

  MetaImageHeader header;
  std::size_t start = 0;
  int lineNumber = 0;
  while (start < text.size()) {
    const std::size_t newline = text.find('\n', start);
    if (newline == std::string::npos && readSize == kMaxBytes && fileSize > kMaxBytes) {
      throwInputError(path, "header has no ElementDataFile line within its first " +
                                std::to_string(kMaxBytes) + " bytes");
    }
    const std::size_t end = newline == std::string::npos ? text.size() : newline;
    std::string_view line = trim(std::string_view(text).substr(start, end - start));
    start = end + 1;
    ++lineNumber;
    if (line.empty()) continue;
    const std::size_t equals = line.find('=');
    if (equals == std::string_view::npos) {
      throwInputError(path, "header line " + std::to_string(lineNumber) + " " + quote(line) +
                                " is not 'Key = Value' (is this a MetaImage file?)");
    }
    const std::string key = toLower(trim(line.substr(0, equals)));
    if (!header.fields.emplace(key, trim(line.substr(equals + 1))).second) {
      throwInputError(path, "header line " + std::to_string(lineNumber) + ": field " + quote(key) +
                                " is given twice");
    }
    if (key == "elementdatafile") {  // always the last field: the data may follow
      header.dataOffset = std::min<std::uint64_t>(start, fileSize);
      return header;
    }
  }
  throwInputError(path, "header lacks the required field 'ElementDataFile'");
}

StoredType parseMetaElementType(const std::string& path, const std::string& name) {
  static const std::map<std::string, StoredType> types = {
      {"MET_UCHAR", StoredType::UInt8},     {"MET_CHAR", StoredType::Int8},
      {"MET_USHORT", StoredType::UInt16},   {"MET_SHORT", StoredType::Int16},
      {"MET_UINT", StoredType::UInt32},     {"MET_INT", StoredType::Int32},
      {"MET_ULONG", StoredType::UInt32},  // MetaIO's long is 4 bytes on every platform
      {"MET_LONG", StoredType::Int32},      {"MET_ULONG_LONG", StoredType::UInt64},
      {"MET_LONG_LONG", StoredType::Int64}, {"MET_FLOAT", StoredType::Float32},
      {"MET_DOUBLE", StoredType::Float64},
  };
  if (const auto it = types.find(name); it != types.end()) return it->second;
  throwInputError(path, "ElementType " + quote(name) +
                            " is not supported (MET_UCHAR, MET_CHAR, MET_USHORT, MET_SHORT, "
                            "MET_UINT, MET_INT, MET_ULONG, MET_LONG, MET_ULONG_LONG, "
                            "MET_LONG_LONG, MET_FLOAT, MET_DOUBLE)");
}

bool parseMetaBool(const std::string& path, const std::string& field, const std::string& value) {
  const std::string lower = toLower(value);
  if (lower == "true" || lower == "1") return true;
  if (lower == "false" || lower == "0") return false;
  throwInputError(path, field + " " + quote(value) + " is neither True nor False");
}

// Where the samples are: after the header (LOCAL) or in the data file.
struct MetaPayload {
  std::string path;   // the file holding them
  std::string label;  // how messages name it
  std::uint64_t offset = 0;
  std::uint64_t size = 0;  // bytes from offset to the end of that file
};

MetaPayload locateMetaPayload(const std::string& path, const MetaImageHeader& header,
                              std::uint64_t fileSize) {
  const std::string& dataFile = *header.find("elementdatafile");
  const std::string field = "ElementDataFile " + quote(dataFile);
  if (dataFile.empty()) throwInputError(path, "ElementDataFile is empty");
  if (toLower(dataFile) == "local") {
    return {path, "data after the header", header.dataOffset, fileSize - header.dataOffset};
  }
  if (toLower(dataFile).starts_with("list")) {
    throwInputError(path, field + ": a list of files (one per slice) is not supported");
  }
  if (dataFile.find('%') != std::string::npos) {
    throwInputError(path, field + ": a file name pattern (one file per slice) is not supported");
  }
  MetaPayload payload{dataFilePath(path, field, dataFile), "data file " + quote(dataFile), 0, 0};
  try {
    payload.size = regularFileSize(payload.path);
  } catch (const InputError& e) {
    throwInputError(path, "data file " + quote(dataFile) + ": " + e.what());
  }
  return payload;
}

}  // namespace

Volume readMetaImage(const std::string& path, const LoadOptions& options) {
  const std::uint64_t fileSize = regularFileSize(path);
  const MetaImageHeader header = parseMetaImageHeader(path, fileSize);
  auto required = [&](const char* lowerKey, const char* name) -> const std::string& {
    if (const std::string* value = header.find(lowerKey)) return *value;
    throwInputError(path, std::string("header lacks the required field '") + name + "'");
  };
  auto flag = [&](std::initializer_list<std::pair<const char*, const char*>> keys, bool fallback) {
    for (const auto& [lowerKey, name] : keys) {
      if (const std::string* value = header.find(lowerKey))
        return parseMetaBool(path, name, *value);
    }
    return fallback;
  };

  if (const std::string* objectType = header.find("objecttype")) {
    if (toLower(*objectType) != "image") {
      throwInputError(path, "ObjectType " + quote(*objectType) +
                                " is not supported: vsil reads images (ObjectType = Image)");
    }
  }
  const std::string& nDims = required("ndims", "NDims");
  if (parseInteger(path, "NDims", nDims) != 3) {
    throwInputError(
        path, "NDims " + quote(nDims) + " is not supported: vsil reads 3D volumes (NDims = 3)");
  }
  if (const std::string* channels = header.find("elementnumberofchannels")) {
    if (parseInteger(path, "ElementNumberOfChannels", *channels) != 1) {
      throwInputError(path, "ElementNumberOfChannels " + quote(*channels) +
                                " is not supported: vsil reads scalar volumes (1 channel)");
    }
  }
  const StoredType type = parseMetaElementType(path, required("elementtype", "ElementType"));
  const glm::ivec3 dims = parseDims(path, "DimSize", required("dimsize", "DimSize"));
  planVolume(path, dims, keptSampleType(type), options.limits, options.region);

  glm::dvec3 spacing(1.0);
  if (const std::string* s = header.find("elementspacing")) {
    spacing = parseSpacing(path, "ElementSpacing", *s);
  } else if (const std::string* size = header.find("elementsize")) {
    spacing = parseSpacing(path, "ElementSize", *size);
  }
  // Two names for the byte order: given both, they must agree (readers differ on which wins).
  const bool bigEndian = flag({{"binarydatabyteordermsb", "BinaryDataByteOrderMSB"},
                               {"elementbyteordermsb", "ElementByteOrderMSB"}},
                              false);
  if (header.find("binarydatabyteordermsb") && header.find("elementbyteordermsb") &&
      flag({{"elementbyteordermsb", "ElementByteOrderMSB"}}, false) != bigEndian) {
    throwInputError(path,
                    "BinaryDataByteOrderMSB and ElementByteOrderMSB disagree: which byte "
                    "order do the samples have?");
  }
  // MetaIO writers always write BinaryData; without it, binary is what such files hold.
  const bool binary = flag({{"binarydata", "BinaryData"}}, true);
  const bool compressed = flag({{"compresseddata", "CompressedData"}}, false);
  if (compressed && !binary) throwInputError(path, "CompressedData needs BinaryData = True");
  std::int64_t headerSize = 0;
  if (const std::string* skip = header.find("headersize")) {
    headerSize = parseInteger(path, "HeaderSize", *skip);
    if (headerSize < -1) throwInputError(path, "HeaderSize " + *skip + " is below -1");
  }
  std::optional<std::uint64_t> compressedSize;
  if (const std::string* size = header.find("compresseddatasize")) {
    const std::int64_t value = parseInteger(path, "CompressedDataSize", *size);
    if (value <= 0) throwInputError(path, "CompressedDataSize " + *size + " is not positive");
    compressedSize = std::uint64_t(value);
  }

  const MetaPayload payload = locateMetaPayload(path, header, fileSize);
  const std::uint64_t expected = payloadBytes(dims, type);
  const std::string layout = " (" + describeLayout(dims, type) + ")";
  // Named by the file's own extension (a .mhd may hold its data LOCAL, as a .mha does).
  auto format = [&](const char* encoding) {
    const std::string extension = toLower(std::filesystem::path(path).extension().string());
    return std::string("MetaImage (") + (extension == ".mhd" ? ".mhd" : ".mha") + ", " + encoding +
           ")";
  };
  // The payload's bytes: HeaderSize skipped, or (-1) the last `tail` bytes of the file.
  std::uint64_t offset = payload.offset, available = payload.size;
  auto skipHeader = [&](std::uint64_t tail) {
    if (headerSize == -1) {
      offset += available >= tail ? available - tail : 0;
      available = std::min(available, tail);
    } else if (std::uint64_t(headerSize) > available) {
      throwInputError(path, "HeaderSize " + std::to_string(headerSize) + " passes the end of the " +
                                payload.label + " (" + std::to_string(available) + " bytes)");
    } else {
      offset += std::uint64_t(headerSize);
      available -= std::uint64_t(headerSize);
    }
  };

  if (compressed) {
    if (headerSize == -1 && !compressedSize) {
      throwInputError(path, "HeaderSize -1 with CompressedData needs CompressedDataSize");
    }
    skipHeader(compressedSize.value_or(0));
    if (compressedSize && *compressedSize > available) {
      throwInputError(path, "CompressedDataSize " + std::to_string(*compressedSize) +
                                " passes the end of the " + payload.label + " (" +
                                std::to_string(available) + " bytes)");
    }
    const std::uint64_t size = compressedSize.value_or(available);
    // No bound on the size: padding may follow the stream (inflateStream stops at the first
    // byte beyond the samples, and reads padding without keeping it).
    const std::string what = "zlib " + payload.label;
    checkInflatable(path, what, size, expected);
    Volume volume = startVolume(path, dims, type, spacing, options);
    volume.format = format("zlib");
    SampleSink sink(path, volume, subsetOf(volume), type, bigEndian);
    const FileReader file(payload.path);
    // MetaIO writes zlib streams; gzip ones (magic 1f 8b) are read too.
    std::uint8_t magic[2] = {0, 0};
    if (size >= 2) file.readAt(offset, magic);
    const DeflateWrapper wrapper =
        magic[0] == 0x1f && magic[1] == 0x8b ? DeflateWrapper::Gzip : DeflateWrapper::Zlib;
    constexpr std::uint64_t kPiece = std::uint64_t(1) << 20;
    std::vector<std::uint8_t> piece;
    std::uint64_t read = 0;
    inflateStream(
        path, what, wrapper, expected,
        [&]() -> std::span<const std::uint8_t> {
          piece.resize(std::size_t(std::min(kPiece, size - read)));
          file.readAt(offset + read, piece);
          read += piece.size();
          if (options.progress) options.progress(read, size);
          return piece;
        },
        [&](std::span<const std::uint8_t> bytes) { sink.append(bytes); });
    sink.finishAppending();
    return volume;
  }
  if (!binary) {
    if (headerSize == -1) throwInputError(path, "HeaderSize -1 needs BinaryData = True");
    skipHeader(0);
    // Up to 64 characters per sample is generous for any printed number.
    const std::uint64_t maxText = payloadBytes(dims, StoredType::UInt8) * 64 + 4096;
    if (available > maxText) {
      throwInputError(path, payload.label + " holds " + std::to_string(available) +
                                " bytes, too many for ASCII text of" + layout);
    }
    Volume volume = startVolume(path, dims, type, spacing, options);
    volume.format = format("ASCII");
    SampleSink sink(path, volume, subsetOf(volume), type, bigEndian);
    const auto bytes = readFileBytes(payload.path, offset, available);
    parseTextSamples(path,
                     std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                     type, sink, TextAfterSamples::WhitespaceOnly);
    return volume;
  }
  skipHeader(expected);
  if (available != expected) {
    throwInputError(path, payload.label + " holds " + std::to_string(available) + " bytes, " +
                              std::to_string(expected) + " expected" + layout);
  }
  Volume volume = startVolume(path, dims, type, spacing, options);
  volume.format = format("raw");
  SampleSink sink(path, volume, subsetOf(volume), type, bigEndian);
  readUncompressed(FileReader(payload.path), offset, sink, options);
  return volume;
}

}  // namespace vsil::io
