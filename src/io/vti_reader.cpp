// VTK XML ImageData (.vti): one piece, one point-data array (the active Scalars, else the
// first), stored as ascii, inline base64 ("binary") or appended (raw or base64), each binary
// form optionally compressed by vtkZLibDataCompressor, with UInt32 or UInt64 headers.
// Format notes: docs.vtk.org "VTK File Formats" (XML section) and the Kitware wiki
// "VTK_XML_Formats"; a binary block starts with a byte count, or with the compression header
// [#blocks][block size][last partial block size][compressed size of each block].
#include <limits>
#include <optional>

#include <tinyxml2.h>

#include "core/error.h"
#include "io/base64.h"
#include "io/file_access.h"
#include "io/inflate.h"
#include "io/readers.h"
#include "io/sample_codec.h"
#include "io/text_fields.h"

namespace vsil::io {
namespace {

using tinyxml2::XMLElement;

struct Encoding {
  bool bigEndian = false;
  std::size_t headerWordSize = 4;  // UInt32 or UInt64 block headers
  bool compressed = false;
};

std::string attribute(const XMLElement* element, const char* name, const char* fallback = "") {
  const char* value = element->Attribute(name);
  return value ? value : fallback;
}

const XMLElement* requireChild(const std::string& path, const XMLElement* parent,
                               const char* name) {
  const XMLElement* child = parent->FirstChildElement(name);
  if (!child) {
    throwInputError(path, std::string("<") + parent->Name() + "> has no <" + name + "> element");
  }
  return child;
}

StoredType parseVtkType(const std::string& path, const std::string& name) {
  if (name == "UInt8") return StoredType::UInt8;
  if (name == "Int8") return StoredType::Int8;
  if (name == "UInt16") return StoredType::UInt16;
  if (name == "Int16") return StoredType::Int16;
  if (name == "Float32") return StoredType::Float32;
  if (name == "Float64") return StoredType::Float64;  // converted to float32 when finite
  throwInputError(path, "DataArray type " + quote(name) +
                            " is not supported (UInt8, Int8, UInt16, Int16, Float32, Float64)");
}

// "x0 x1 y0 y1 z0 z1" -> samples per axis.
glm::ivec3 dimsFromExtent(const std::string& path, const std::string& extent) {
  const auto tokens = splitWhitespace(extent);
  if (tokens.size() != 6) {
    throwInputError(path, "WholeExtent " + quote(extent) + " needs 6 integers");
  }
  glm::ivec3 dims;
  for (int axis = 0; axis < 3; ++axis) {
    const std::int64_t first = parseInteger(path, "WholeExtent", tokens[2 * axis]);
    const std::int64_t last = parseInteger(path, "WholeExtent", tokens[2 * axis + 1]);
    constexpr std::int64_t kBound = std::int64_t(1) << 40;  // keeps last - first + 1 exact
    if (first < -kBound || first > kBound || last < -kBound || last > kBound ||
        last - first + 1 > std::numeric_limits<int>::max()) {
      throwInputError(path, "WholeExtent " + quote(extent) + " is out of range");
    }
    if (last < first) throwInputError(path, "WholeExtent " + quote(extent) + " is empty");
    dims[axis] = int(last - first + 1);
  }
  return dims;
}

// Reads one binary data block (the header words, then the data), checking every size against
// what is there before touching it, and returns the `expected` payload bytes.
class BlockReader {
 public:
  BlockReader(const std::string& path, std::span<const std::uint8_t> block, Encoding encoding)
      : path_(path), block_(block), encoding_(encoding) {}

  std::vector<std::uint8_t> read(std::size_t expected, const std::string& layout) {
    if (!encoding_.compressed) {
      const std::uint64_t count = word(0);
      if (count != expected) {
        throwInputError(path_, "DataArray header says " + std::to_string(count) + " bytes, " +
                                   std::to_string(expected) + " expected" + layout);
      }
      const std::size_t start = encoding_.headerWordSize;
      if (block_.size() - start < expected) {
        throwInputError(path_, "DataArray holds " + std::to_string(block_.size() - start) +
                                   " bytes, " + std::to_string(expected) + " expected" + layout);
      }
      const auto data = block_.subspan(start, expected);
      return {data.begin(), data.end()};
    }
    const std::uint64_t blocks = word(0), blockSize = word(1), lastSize = word(2);
    if (blocks == 0 || blockSize == 0 || lastSize > blockSize) {
      throwInputError(path_, "compression header (" + std::to_string(blocks) + " blocks of " +
                                 std::to_string(blockSize) + ", last " + std::to_string(lastSize) +
                                 ") is invalid");
    }
    // blocks - 1 full blocks and a last one; compare without overflowing.
    const std::uint64_t last = lastSize ? lastSize : blockSize;
    if (blocks - 1 > expected / blockSize || (blocks - 1) * blockSize + last != expected) {
      throwInputError(path_, "compression header describes " + std::to_string(blocks) +
                                 " blocks of " + std::to_string(blockSize) + " bytes, not the " +
                                 std::to_string(expected) + " bytes expected" + layout);
    }
    word(2 + blocks);  // the header is all there
    std::uint64_t offset = (3 + blocks) * encoding_.headerWordSize;
    checkInflatable(path_, "zlib data", block_.size() - offset, expected);
    std::vector<std::uint8_t> bytes(expected);
    for (std::uint64_t i = 0; i < blocks; ++i) {
      const std::uint64_t size = word(3 + i);
      if (size > block_.size() - offset) {
        throwInputError(path_, "zlib block " + std::to_string(i) + " is truncated (" +
                                   std::to_string(block_.size() - offset) + " of " +
                                   std::to_string(size) + " bytes)");
      }
      const std::uint64_t outSize = i + 1 == blocks ? last : blockSize;
      inflateExactly(path_, "zlib block " + std::to_string(i),
                     block_.subspan(std::size_t(offset), std::size_t(size)),
                     std::span(bytes).subspan(std::size_t(i * blockSize), std::size_t(outSize)),
                     DeflateWrapper::Zlib);
      offset += size;
    }
    return bytes;
  }

 private:
  std::uint64_t word(std::uint64_t index) const {
    const std::size_t size = encoding_.headerWordSize;
    if (index >= block_.size() / size) {
      throwInputError(path_, "DataArray block header is truncated (" +
                                 std::to_string(block_.size()) + " bytes)");
    }
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < size; ++i) {
      const std::size_t shift = 8 * (encoding_.bigEndian ? size - 1 - i : i);
      value |= std::uint64_t(block_[std::size_t(index) * size + i]) << shift;
    }
    return value;
  }

  const std::string& path_;
  std::span<const std::uint8_t> block_;
  Encoding encoding_;
};

// The file split into the XML to parse and the appended data after the '_' marker (raw bytes
// that an XML parser must not see).
struct SplitFile {
  std::string xml;
  std::string_view appended;  // starts just after '_'
  std::string appendedEncoding;
};

SplitFile splitAppendedData(const std::string& path, const std::string& file) {
  SplitFile split;
  const std::size_t tag = file.find("<AppendedData");
  if (tag == std::string::npos) {
    split.xml = file;
    return split;
  }
  const std::size_t close = file.find('>', tag);
  const std::size_t underscore = close == std::string::npos ? close : file.find('_', close);
  if (underscore == std::string::npos) {
    throwInputError(path, "<AppendedData> has no '_' marker before its data");
  }
  split.xml = file.substr(0, underscore) + "</AppendedData></VTKFile>";
  split.appended = std::string_view(file).substr(underscore + 1);
  return split;
}

}  // namespace

Volume readVti(const std::string& path, const VolumeLimits& limits) {
  // A valid file holds at most the volume in base64 (4/3 of its float bytes) or ascii; twice
  // the memory limit bounds it without reading hostile sizes.
  const std::string file = readWholeFile(path, std::uint64_t(limits.maxBytes) * 2 + (16u << 20));
  const SplitFile split = splitAppendedData(path, file);

  tinyxml2::XMLDocument doc;
  if (doc.Parse(split.xml.data(), split.xml.size()) != tinyxml2::XML_SUCCESS) {
    throwInputError(path, std::string("is not valid XML: ") + doc.ErrorName() + " at line " +
                              std::to_string(doc.ErrorLineNum()));
  }
  const XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != "VTKFile") {
    throwInputError(path, "is not a VTK XML file (no <VTKFile> root)");
  }
  if (attribute(root, "type") != "ImageData") {
    throwInputError(path, "is a VTK XML " + quote(attribute(root, "type")) +
                              " file; only ImageData (.vti) is read");
  }
  Encoding encoding;
  const std::string byteOrder = attribute(root, "byte_order", "LittleEndian");
  if (byteOrder != "LittleEndian" && byteOrder != "BigEndian") {
    throwInputError(path, "byte_order " + quote(byteOrder) + " is unknown");
  }
  encoding.bigEndian = byteOrder == "BigEndian";
  const std::string headerType = attribute(root, "header_type", "UInt32");
  if (headerType != "UInt32" && headerType != "UInt64") {
    throwInputError(path, "header_type " + quote(headerType) + " is neither UInt32 nor UInt64");
  }
  encoding.headerWordSize = headerType == "UInt64" ? 8 : 4;
  const std::string compressor = attribute(root, "compressor");
  if (!compressor.empty() && compressor != "vtkZLibDataCompressor") {
    throwInputError(
        path, "compressor " + quote(compressor) + " is not supported (only vtkZLibDataCompressor)");
  }
  encoding.compressed = !compressor.empty();

  const XMLElement* image = requireChild(path, root, "ImageData");
  const glm::ivec3 dims = dimsFromExtent(path, attribute(image, "WholeExtent"));
  checkVolumeSize(path, dims, limits);
  const XMLElement* piece = requireChild(path, image, "Piece");
  if (piece->NextSiblingElement("Piece")) {
    throwInputError(path, "holds several pieces; only single-piece files are read");
  }
  if (const char* extent = piece->Attribute("Extent")) {
    if (dimsFromExtent(path, extent) != dims) {
      throwInputError(path, "Piece Extent " + quote(extent) + " differs from WholeExtent");
    }
  }

  const XMLElement* pointData = requireChild(path, piece, "PointData");
  const XMLElement* array = pointData->FirstChildElement("DataArray");
  if (const char* active = pointData->Attribute("Scalars")) {
    for (const XMLElement* a = array; a; a = a->NextSiblingElement("DataArray")) {
      if (attribute(a, "Name") == active) {
        array = a;
        break;
      }
    }
  }
  if (!array) throwInputError(path, "<PointData> has no <DataArray>");
  const std::string components = attribute(array, "NumberOfComponents", "1");
  if (components != "1") {
    throwInputError(path, "DataArray has " + quote(components) +
                              " components; only scalar (1-component) data is read");
  }

  const StoredType type = parseVtkType(path, attribute(array, "type"));
  Volume volume = namedVolume(path);
  volume.dims = dims;
  volume.type = sampleTypeOf(type);
  volume.spacing = parseSpacing(path, "Spacing", attribute(image, "Spacing", "1 1 1"));
  const std::size_t expected = payloadBytes(dims, type);
  const std::string layout = " (" + describeLayout(dims, type) + ")";

  const std::string format = attribute(array, "format", "ascii");
  const char* text = array->GetText();
  if (format == "ascii") {
    volume.samples = parseTextSamples(path, text ? text : "", volume.voxelCount(), type);
    return volume;
  }
  std::vector<std::uint8_t> decoded;  // base64 forms, decoded
  std::span<const std::uint8_t> block;
  if (format == "binary") {
    decoded = decodeBase64(path, text ? text : "");
    block = decoded;
  } else if (format == "appended") {
    if (split.appended.data() == nullptr) {
      throwInputError(path, "DataArray is appended but the file has no <AppendedData>");
    }
    const std::int64_t offset = parseInteger(path, "DataArray offset", attribute(array, "offset"));
    if (offset < 0 || std::uint64_t(offset) > split.appended.size()) {
      throwInputError(
          path, "DataArray offset " + std::to_string(offset) + " lies outside the appended data");
    }
    const std::string_view data = split.appended.substr(std::size_t(offset));
    const XMLElement* appendedData = root->FirstChildElement("AppendedData");
    const std::string appendedEncoding =
        appendedData ? attribute(appendedData, "encoding", "raw") : "raw";
    if (appendedEncoding == "base64") {
      decoded = decodeBase64(path, data.substr(0, data.find('<')));
      block = decoded;
    } else if (appendedEncoding == "raw") {
      block = {reinterpret_cast<const std::uint8_t*>(data.data()), data.size()};
    } else {
      throwInputError(path, "AppendedData encoding " + quote(appendedEncoding) + " is unknown");
    }
  } else {
    throwInputError(path,
                    "DataArray format " + quote(format) + " is unknown (ascii, binary, appended)");
  }
  const auto bytes = BlockReader(path, block, encoding).read(expected, layout);
  volume.samples = decodeSamples(path, bytes, type, encoding.bigEndian);
  return volume;
}

}  // namespace vsil::io
