// NRRD (teem.sourceforge.net/nrrd/format.html): attached (.nrrd) and detached (.nhdr) headers,
// raw, gzip and ascii encodings, 3D scalar volumes only.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/upright.h"
#include "io/file_access.h"
#include "io/inflate.h"
#include "io/readers.h"
#include "io/sample_codec.h"
#include "io/text_fields.h"

namespace vsil::io {
namespace {

// A header longer than this is not a header.
constexpr std::size_t kMaxHeaderBytes = limits::kMaxHeaderBytes;

struct NrrdHeader {
  std::map<std::string, std::string> fields;  // field name (lower case, spaces kept) -> value
  std::uint64_t dataOffset = 0;               // attached data: the byte after the blank line
  bool ended = false;                         // a blank line closed the header

  const std::string* find(std::initializer_list<const char*> names) const {
    for (const char* name : names) {
      if (auto it = fields.find(name); it != fields.end()) return &it->second;
    }
    return nullptr;
  }
};

NrrdHeader parseHeader(const std::string& path, std::uint64_t fileSize) {
  const std::size_t readSize = std::size_t(std::min<std::uint64_t>(fileSize, kMaxHeaderBytes));
  std::ifstream in(path, std::ios::binary);
  std::string text(readSize, '\0');
  in.read(text.data(), std::streamsize(readSize));
  text.resize(std::size_t(in.gcount()));

  if (!text.starts_with("NRRD000") || text.size() < 8 || text[7] < '1' || text[7] > '5') {
    throwInputError(path, "is not a NRRD file (the first line must be NRRD0001 .. NRRD0005)");
  }
  NrrdHeader header;
  std::size_t pos = text.find('\n');
  int lineNumber = 1;
  while (pos != std::string::npos && pos + 1 < text.size()) {
    const std::size_t start = pos + 1;
    const std::size_t newline = text.find('\n', start);
    ++lineNumber;
    if (newline == std::string::npos && text.size() == kMaxHeaderBytes) {
      throwInputError(
          path, "header has no end within its first " + std::to_string(kMaxHeaderBytes) + " bytes");
    }
    const std::size_t end = newline == std::string::npos ? text.size() : newline;
    std::string_view line(text.data() + start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = newline;
    if (line.empty()) {
      header.ended = true;
      header.dataOffset = end + 1;
      break;
    }
    if (line.front() == '#') continue;
    if (line.find(":=") != std::string_view::npos) continue;  // key/value pairs: not ours
    const std::size_t colon = line.find(": ");
    if (colon == std::string_view::npos) {
      throwInputError(path, "header line " + std::to_string(lineNumber) + " " + quote(line) +
                                " is neither 'field: value' nor a comment");
    }
    // The format's rule: a field given twice is an error (which one would hold?).
    const std::string field = toLower(trim(line.substr(0, colon)));
    const std::string value(trim(line.substr(colon + 2)));
    if (!header.fields.emplace(field, value).second) {
      throwInputError(path, "header line " + std::to_string(lineNumber) + ": field " +
                                quote(field) + " is given twice");
    }
    // The file names of "data file: LIST" follow as lines of their own: said before they are
    // read as malformed fields.
    if ((field == "data file" || field == "datafile") && value.starts_with("LIST")) {
      throwInputError(path, "data file " + quote(value) + ": multi-file data is not supported");
    }
  }
  return header;
}

StoredType parseType(const std::string& path, const std::string& name) {
  static const std::map<std::string, StoredType> aliases = {
      {"uchar", StoredType::UInt8},
      {"unsigned char", StoredType::UInt8},
      {"uint8", StoredType::UInt8},
      {"uint8_t", StoredType::UInt8},
      {"signed char", StoredType::Int8},
      {"int8", StoredType::Int8},
      {"int8_t", StoredType::Int8},
      {"short", StoredType::Int16},
      {"short int", StoredType::Int16},
      {"signed short", StoredType::Int16},
      {"signed short int", StoredType::Int16},
      {"int16", StoredType::Int16},
      {"int16_t", StoredType::Int16},
      {"ushort", StoredType::UInt16},
      {"unsigned short", StoredType::UInt16},
      {"unsigned short int", StoredType::UInt16},
      {"uint16", StoredType::UInt16},
      {"uint16_t", StoredType::UInt16},
      {"int", StoredType::Int32},
      {"signed int", StoredType::Int32},
      {"int32", StoredType::Int32},
      {"int32_t", StoredType::Int32},
      {"uint", StoredType::UInt32},
      {"unsigned int", StoredType::UInt32},
      {"uint32", StoredType::UInt32},
      {"uint32_t", StoredType::UInt32},
      {"longlong", StoredType::Int64},
      {"long long", StoredType::Int64},
      {"long long int", StoredType::Int64},
      {"signed long long", StoredType::Int64},
      {"signed long long int", StoredType::Int64},
      {"int64", StoredType::Int64},
      {"int64_t", StoredType::Int64},
      {"ulonglong", StoredType::UInt64},
      {"unsigned long long", StoredType::UInt64},
      {"unsigned long long int", StoredType::UInt64},
      {"uint64", StoredType::UInt64},
      {"uint64_t", StoredType::UInt64},
      {"float", StoredType::Float32},
      {"double", StoredType::Float64},
  };
  if (auto it = aliases.find(toLower(name)); it != aliases.end()) return it->second;
  throwInputError(
      path,
      "type " + quote(name) +
          " is not supported (uint8, int8, uint16, int16, int32, uint32, int64, uint64, float, "
          "double)");
}

// "(1,0,-0.5)": a vector of `field`.
glm::dvec3 parseVector(const std::string& path, const std::string& field, std::string_view text) {
  std::string_view vector = text;
  if (vector.size() < 2 || vector.front() != '(' || vector.back() != ')') {
    throwInputError(path, field + " vector " + quote(text) + " is not '(x,y,z)'");
  }
  vector = vector.substr(1, vector.size() - 2);
  glm::dvec3 result(0.0);
  int components = 0;
  while (true) {
    const std::size_t comma = vector.find(',');
    const double value = parseReal(path, field, trim(vector.substr(0, comma)));
    if (components < 3) result[components] = value;
    ++components;
    if (comma == std::string_view::npos) break;
    vector.remove_prefix(comma + 1);
  }
  if (components != 3)
    throwInputError(path, field + " vector " + quote(text) + " needs 3 components");
  return result;
}

// "(1,0,0) (0,2,0) (0,0,0.5)": each axis's step in the space; the spacing along an axis is the
// length of its vector.
struct SpaceDirections {
  glm::dvec3 spacing;
  glm::dmat3 columns;  // column a: axis a's vector
};

SpaceDirections parseSpaceDirections(const std::string& path, const std::string& text) {
  const std::string field = "space directions";
  const auto vectors = splitWhitespace(text);
  if (vectors.size() != 3) {
    throwInputError(path, field + " needs 3 vectors, found " + std::to_string(vectors.size()));
  }
  SpaceDirections result;
  for (int axis = 0; axis < 3; ++axis) {
    if (vectors[axis] == "none") throwInputError(path, field + " has 'none' for a spatial axis");
    result.columns[axis] = parseVector(path, field, vectors[axis]);
    result.spacing[axis] = glm::length(result.columns[axis]);
  }
  checkSpacing(path, field, result.spacing);
  // vsil reads the spacing alone (the lengths), which only means something for axes spanning
  // space: parallel or coplanar vectors would make the volume flat. (DICOM's orientations are
  // checked alike.) The volume of the unit vectors' parallelepiped: 1 for orthogonal axes.
  const glm::dmat3& c = result.columns;
  const glm::dmat3 unit(c[0] / result.spacing[0], c[1] / result.spacing[1],
                        c[2] / result.spacing[2]);
  if (!(std::abs(glm::determinant(unit)) > 1e-6)) {
    throwInputError(path, field + " " + quote(text) +
                              ": the three axes do not span space (two are parallel, or all "
                              "three lie in one plane)");
  }
  return result;
}

// The letters of the +x, +y, +z of NRRD's anatomical spaces ("LPS" for left-posterior-superior
// and its -time variant), "" for the others (scanner-xyz, 3D-right-handed, ...).
std::string anatomicalSpaceAxes(const std::string& space) {
  std::string name = toLower(space);
  if (name.ends_with("-time")) {
    name.resize(name.size() - 5);
  } else if (name.size() == 4 && name.back() == 't') {  // RAST, LAST, LPST
    name.pop_back();
  }
  if (name == "right-anterior-superior" || name == "ras") return "RAS";
  if (name == "left-anterior-superior" || name == "las") return "LAS";
  if (name == "left-posterior-superior" || name == "lps") return "LPS";
  return "";
}

// Where the payload lives: the data file (detached) or this file after the header (attached).
struct Payload {
  std::string path;   // the file holding the samples
  std::string label;  // how messages refer to it
  std::uint64_t offset = 0;
  std::uint64_t size = 0;  // bytes from offset to the end of that file
};

Payload locatePayload(const std::string& path, const NrrdHeader& header, std::uint64_t fileSize) {
  Payload payload;
  const std::string* dataFile = header.find({"data file", "datafile"});
  if (!dataFile) {
    if (!header.ended || header.dataOffset >= fileSize) {
      throwInputError(path, "has no data: neither a 'data file' field nor data after the header");
    }
    payload.path = path;
    payload.label = "payload after the header";
    payload.offset = header.dataOffset;
    payload.size = fileSize - header.dataOffset;
    return payload;
  }
  if (dataFile->starts_with("LIST") || splitWhitespace(*dataFile).size() > 1) {
    throwInputError(path, "data file " + quote(*dataFile) + ": multi-file data is not supported");
  }
  payload.label = "data file " + quote(*dataFile);
  payload.path = dataFilePath(path, payload.label, *dataFile);
  try {
    payload.size = regularFileSize(payload.path);
  } catch (const InputError& e) {
    throwInputError(path, "data file " + quote(*dataFile) + ": " + e.what());
  }
  return payload;
}

// 'kinds' and 'space units' describe the axes: each of the three must be a spatial (domain)
// axis, and one unit must serve all three, or the samples are not a scalar volume with one
// spacing (an RGB image's colour axis was read as a third spatial axis).
void checkAxisKinds(const std::string& path, const NrrdHeader& header) {
  if (const std::string* kinds = header.find({"kinds"})) {
    const auto names = splitWhitespace(*kinds);
    if (names.size() != 3) {
      throwInputError(path, "kinds " + quote(*kinds) + " names " + std::to_string(names.size()) +
                                " axes, not the 3 of 'dimension'");
    }
    for (std::size_t axis = 0; axis < names.size(); ++axis) {
      const std::string kind = toLower(names[axis]);
      if (kind != "domain" && kind != "space" && kind != "???" && kind != "none") {
        throwInputError(path, "kinds: axis " + std::to_string(axis + 1) + " is " +
                                  quote(names[axis]) +
                                  ", not a spatial axis: vsil reads 3D scalar volumes");
      }
    }
  }
  if (const std::string* units = header.find({"space units"})) {
    // Quoted strings, one per axis of the space, which may hold blanks ("milli meter").
    std::vector<std::string_view> names;
    std::string_view rest = trim(*units);
    while (!rest.empty()) {
      const std::size_t close = rest.size() > 1 ? rest.find('"', 1) : std::string_view::npos;
      if (rest[0] != '"' || close == std::string_view::npos) {
        throwInputError(path, "space units " + quote(*units) + " are not quoted strings");
      }
      names.push_back(rest.substr(1, close - 1));
      rest = trim(rest.substr(close + 1));
    }
    if (names.size() != 3) {
      throwInputError(path, "space units " + quote(*units) + " name " +
                                std::to_string(names.size()) + " axes, not 3");
    }
    if (std::adjacent_find(names.begin(), names.end(), std::not_equal_to<>()) != names.end()) {
      throwInputError(path, "space units " + quote(*units) +
                                " differ between axes: vsil takes one unit for the spacing");
    }
  }
}

}  // namespace

Volume readNrrd(const std::string& path, const LoadOptions& options) {
  const std::uint64_t fileSize = regularFileSize(path);
  const NrrdHeader header = parseHeader(path, fileSize);
  auto required = [&](std::initializer_list<const char*> names) -> const std::string& {
    if (const std::string* value = header.find(names)) return *value;
    throwInputError(path, std::string("header lacks the required field '") + *names.begin() + "'");
  };

  const std::string& dimension = required({"dimension"});
  if (parseInteger(path, "dimension", dimension) != 3) {
    throwInputError(path, "dimension " + quote(dimension) +
                              " is not supported: vsil reads 3D scalar volumes (dimension: 3)");
  }
  const StoredType type = parseType(path, required({"type"}));
  const glm::ivec3 dims = parseDims(path, "sizes", required({"sizes"}));
  checkAxisKinds(path, header);
  planVolume(path, dims, keptSampleType(type), options.limits, options.region);
  const std::string encoding = toLower(required({"encoding"}));

  glm::dvec3 spacing(1.0);
  // An anatomical space with the axes' directions in it places the volume in a patient's frame
  // (recorded, not applied: core/upright.h stands it superior up by it).
  std::optional<Orientation> placement;
  if (const std::string* directions = header.find({"space directions"})) {
    // The format's rule: an axis has one or the other.
    if (header.find({"spacings"})) {
      throwInputError(path, "has both 'space directions' and 'spacings' (the format allows one)");
    }
    const SpaceDirections parsed = parseSpaceDirections(path, *directions);
    spacing = parsed.spacing;
    const std::string* space = header.find({"space"});
    const std::string spaceAxes = space ? anatomicalSpaceAxes(*space) : "";
    if (!spaceAxes.empty()) {
      const std::string* origin = header.find({"space origin"});
      const glm::dvec3 at =
          origin ? parseVector(path, "space origin", trim(*origin)) : glm::dvec3(0);
      if (glm::any(glm::isnan(at)) || glm::any(glm::isinf(at))) {
        throwInputError(path, "space origin " + quote(trim(*origin)) + " is not finite");
      }
      const glm::dmat3& c = parsed.columns;
      placement = Orientation{"space", spaceAxes,
                              glm::dmat4(glm::dvec4(c[0], 0), glm::dvec4(c[1], 0),
                                         glm::dvec4(c[2], 0), glm::dvec4(at, 1)),
                              anatomicalAxes(c, spaceAxes)};
    }
  } else if (const std::string* spacings = header.find({"spacings"})) {
    spacing = parseSpacing(path, "spacings", *spacings);
  }

  bool bigEndian = false;
  const std::string* endian = header.find({"endian"});
  if (endian && *endian != "little" && *endian != "big") {
    throwInputError(path, "endian " + quote(*endian) + " is neither 'little' nor 'big'");
  }
  if (endian) bigEndian = *endian == "big";
  const bool textEncoding = encoding == "ascii" || encoding == "text" || encoding == "txt";
  if (!endian && storedSize(type) > 1 && !textEncoding) {
    throwInputError(path, std::string("header lacks the field 'endian', required for ") +
                              storedTypeName(type) + " samples");
  }
  std::int64_t byteSkip = 0;
  if (const std::string* skip = header.find({"byte skip", "byteskip"})) {
    byteSkip = parseInteger(path, "byte skip", *skip);
    if (byteSkip < -1) throwInputError(path, "byte skip " + *skip + " is below -1");
  }
  if (const std::string* skip = header.find({"line skip", "lineskip"})) {
    if (parseInteger(path, "line skip", *skip) != 0) {
      throwInputError(path, "line skip is not supported");
    }
  }

  const Payload payload = locatePayload(path, header, fileSize);
  const std::uint64_t expected = payloadBytes(dims, type);
  const std::string layout = " (" + describeLayout(dims, type) + ")";
  const std::string format =
      "NRRD (" + encoding + ", " + (payload.path == path ? "attached" : "detached") + ")";

  const auto start = [&] {
    Volume volume = startVolume(path, dims, type, spacing, options);
    volume.format = format;
    if (placement) {
      volume.orientations.push_back(*placement);
      volume.orientations.back().worldFromIndex *= fileFromKept(subsetOf(volume));
    }
    return volume;
  };

  if (encoding == "raw") {
    std::uint64_t offset = payload.offset;
    std::uint64_t available = payload.size;
    if (byteSkip == -1) {  // the data are the last `expected` bytes of the file
      offset += available >= expected ? available - expected : 0;
      available = std::min<std::uint64_t>(available, expected);
    } else if (std::uint64_t(byteSkip) > available) {
      throwInputError(path, "byte skip " + std::to_string(byteSkip) + " passes the end of the " +
                                payload.label + " (" + std::to_string(available) + " bytes)");
    } else {
      offset += std::uint64_t(byteSkip);
      available -= std::uint64_t(byteSkip);
    }
    if (available != expected) {
      throwInputError(path, payload.label + " holds " + std::to_string(available) + " bytes, " +
                                std::to_string(expected) + " expected" + layout);
    }
    Volume volume = start();
    SampleSink sink(path, volume, subsetOf(volume), type, bigEndian);
    readUncompressed(FileReader(payload.path), offset, sink, options);
    return volume;
  }
  if (encoding == "gzip" || encoding == "gz") {
    if (byteSkip < 0) throwInputError(path, "byte skip -1 is only allowed with raw encoding");
    // No bound on the payload's size: gzip reads on through NUL padding and further members,
    // so a stream of the expected size may come with any amount of them (inflateStream stops
    // at the first byte beyond the samples, and reads padding without keeping it).
    const std::uint64_t inflated = expected + std::uint64_t(byteSkip);
    const std::string what = "gzip " + payload.label;
    checkInflatable(path, what, payload.size, inflated);
    Volume volume = start();
    SampleSink sink(path, volume, subsetOf(volume), type, bigEndian);
    // Streamed: compressed pieces in, inflated pieces straight into the sink, which keeps only
    // the samples of the subset (a compressed stream cannot be entered in the middle).
    const FileReader file(payload.path);
    constexpr std::uint64_t kPiece = std::uint64_t(1) << 20;
    std::vector<std::uint8_t> compressed;
    std::uint64_t read = 0, skipped = 0;
    inflateStream(
        path, what, DeflateWrapper::Gzip, inflated,
        [&]() -> std::span<const std::uint8_t> {
          compressed.resize(std::size_t(std::min(kPiece, payload.size - read)));
          file.readAt(payload.offset + read, compressed);
          read += compressed.size();
          if (options.progress) options.progress(read, payload.size);
          return compressed;
        },
        [&](std::span<const std::uint8_t> bytes) {
          const auto skip =
              std::size_t(std::min<std::uint64_t>(bytes.size(), std::uint64_t(byteSkip) - skipped));
          skipped += skip;
          sink.append(bytes.subspan(skip));
        });
    sink.finishAppending();
    return volume;
  }
  if (textEncoding) {
    // Up to 64 characters per sample is generous for any printed number.
    const std::uint64_t maxText = payloadBytes(dims, StoredType::UInt8) * 64 + 4096;
    if (payload.size > maxText) {
      throwInputError(path, payload.label + " holds " + std::to_string(payload.size) +
                                " bytes, too many for ascii text of" + layout);
    }
    Volume volume = start();
    SampleSink sink(path, volume, subsetOf(volume), type, bigEndian);
    const auto bytes = readFileBytes(payload.path, payload.offset, payload.size);
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    parseTextSamples(path, text, type, sink, TextAfterSamples::WhitespaceOnly);
    return volume;
  }
  throwInputError(path, "encoding " + quote(encoding) + " is not supported (raw, gzip, ascii)");
}

}  // namespace vsil::io
