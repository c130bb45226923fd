// VTK XML ImageData (.vti): one piece, one point-data array (the active Scalars, else the
// first), stored as ascii, inline base64 ("binary") or appended (raw or base64), each binary
// form optionally compressed by vtkZLibDataCompressor, with UInt32 or UInt64 headers.
// Format notes: docs.vtk.org "VTK File Formats" (XML section) and the Kitware wiki
// "VTK_XML_Formats"; a binary block starts with a byte count, or with the compression header
// [#blocks][block size][last partial block size][compressed size of each block]; blocks are
// zlib streams (vtkZLibDataCompressor), LZ4 blocks (vtkLZ4DataCompressor) or xz streams
// (vtkLZMADataCompressor), io/block_codec.h.
#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <optional>
#include <thread>
#include <vector>

#include <tinyxml2.h>

#include "core/error.h"
#include "core/limits.h"
#include "io/base64.h"
#include "io/block_codec.h"
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
  BlockCodec codec = BlockCodec::Zlib;  // when compressed
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
  // Converted to float32, exact up to 2^24 (the others counted).
  if (name == "Int32") return StoredType::Int32;
  if (name == "UInt32") return StoredType::UInt32;
  if (name == "Int64") return StoredType::Int64;
  if (name == "UInt64") return StoredType::UInt64;
  throwInputError(path, "DataArray type " + quote(name) +
                            " is not supported (UInt8, Int8, UInt16, Int16, Int32, UInt32, Int64, "
                            "UInt64, Float32, Float64)");
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

// The bytes of one DataArray's binary block: in memory (decoded base64) or in the file
// (appended raw data, read as needed).
class BlockSource {
 public:
  explicit BlockSource(std::span<const std::uint8_t> memory)
      : memory_(memory), size_(memory.size()) {}
  BlockSource(const FileReader& file, std::uint64_t offset, std::uint64_t size)
      : file_(&file), offset_(offset), size_(size) {}

  std::uint64_t size() const { return size_; }
  const FileReader* file() const { return file_; }
  std::uint64_t fileOffset() const { return offset_; }
  // Bytes [at, at + count), which the caller has checked lie within size(); read into
  // `scratch` when they are in the file.
  std::span<const std::uint8_t> view(std::uint64_t at, std::uint64_t count,
                                     std::vector<std::uint8_t>& scratch) const {
    if (!file_) return memory_.subspan(std::size_t(at), std::size_t(count));
    scratch.resize(std::size_t(count));
    file_->readAt(offset_ + at, scratch);
    return scratch;
  }

 private:
  std::span<const std::uint8_t> memory_;
  const FileReader* file_ = nullptr;
  std::uint64_t offset_ = 0;
  std::uint64_t size_ = 0;
};

// Reads one binary data block (the header words, then the data) into the sink, checking every
// size against what is there before touching it.
class BlockReader {
 public:
  BlockReader(const std::string& path, const BlockSource& block, Encoding encoding,
              const LoadOptions& options)
      : path_(path), block_(block), encoding_(encoding), options_(options) {}

  void read(std::uint64_t expected, const std::string& layout, SampleSink& sink) {
    const std::uint64_t wordSize = encoding_.headerWordSize;
    if (!encoding_.compressed) {
      readHeader(1);
      const std::uint64_t count = word(0);
      if (count != expected) {
        throwInputError(path_, "DataArray header says " + std::to_string(count) + " bytes, " +
                                   std::to_string(expected) + " expected" + layout);
      }
      if (block_.size() - wordSize < expected) {
        throwInputError(path_, "DataArray holds " + std::to_string(block_.size() - wordSize) +
                                   " bytes, " + std::to_string(expected) + " expected" + layout);
      }
      if (block_.file()) {
        readUncompressed(*block_.file(), block_.fileOffset() + wordSize, sink, options_);
      } else {
        std::vector<std::uint8_t> unused;
        sink.put(0, block_.view(wordSize, expected, unused));
        sink.finish();
      }
      return;
    }
    readHeader(3);
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
    readHeader(3 + blocks);  // the header is all there
    const std::uint64_t dataStart = (3 + blocks) * wordSize;
    checkDecompressible(path_, std::string(blockCodecName(encoding_.codec)) + " data",
                        encoding_.codec, block_.size() - dataStart, expected);
    inflateBlocks(dataStart, blocks, blockSize, last, sink);
  }

 private:
  // Reads the first `count` header words, or throws when the block is shorter (or the header
  // alone would be larger than the memory limit).
  void readHeader(std::uint64_t count) {
    if (count > block_.size() / encoding_.headerWordSize) {
      throwInputError(path_, "DataArray block header is truncated (" +
                                 std::to_string(block_.size()) + " bytes)");
    }
    if (count * encoding_.headerWordSize > options_.limits.maxBytes) {
      throwInputError(path_, "compression header of " + std::to_string(count - 3) +
                                 " blocks is larger than the --max-memory limit");
    }
    header_ = block_.view(0, count * encoding_.headerWordSize, headerBytes_);
  }

  std::uint64_t word(std::uint64_t index) const {
    const std::size_t size = encoding_.headerWordSize;
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < size; ++i) {
      const std::size_t shift = 8 * (encoding_.bigEndian ? size - 1 - i : i);
      value |= std::uint64_t(header_[std::size_t(index) * size + i]) << shift;
    }
    return value;
  }

  // The compressed blocks, in batches of a few MiB of compressed bytes; within a batch the blocks
  // are inflated on every core (each block is an independent stream whose output has its own place
  // in the volume). Errors are those a block-by-block reading meets first: the lowest block's.
  void inflateBlocks(std::uint64_t dataStart, std::uint64_t blocks, std::uint64_t blockSize,
                     std::uint64_t lastSize, SampleSink& sink) {
    constexpr std::uint64_t kBatchBytes = std::uint64_t(16) << 20;
    const std::size_t sampleSize = sink.sampleSize();
    // Blocks that start within a sample cannot be placed on their own: one thread, in order.
    const bool aligned = blockSize % sampleSize == 0;
    const int threads = aligned ? limits::workerThreads() : 1;
    SampleSink::Appender inOrder(sink, 0);
    const std::string codecName = blockCodecName(encoding_.codec);
    const std::uint64_t compressedTotal = block_.size() - dataStart;
    std::vector<std::uint8_t> batchBytes;
    std::uint64_t offset = dataStart;  // of block `first`
    for (std::uint64_t first = 0; first < blocks;) {
      // Blocks first .. end - 1: at most kBatchBytes (at least one block), none truncated.
      std::vector<std::uint64_t> starts;  // offsets within the batch
      std::uint64_t bytes = 0, end = first;
      std::optional<std::uint64_t> truncated;
      while (end < blocks && (end == first || bytes + word(3 + end) <= kBatchBytes)) {
        const std::uint64_t size = word(3 + end);
        if (size > block_.size() - (offset + bytes)) {
          truncated = end;
          break;
        }
        starts.push_back(bytes);
        bytes += size;
        ++end;
      }
      const auto batch = block_.view(offset, bytes, batchBytes);
      std::atomic<std::uint64_t> failed{blocks};
      std::vector<std::pair<std::uint64_t, std::exception_ptr>> errors(std::size_t(threads),
                                                                       {blocks, nullptr});
      auto work = [&](int thread) {
        for (std::uint64_t b = first + std::uint64_t(thread); b < end && b < failed;
             b += std::uint64_t(threads)) {
          try {
            const auto compressed =
                batch.subspan(std::size_t(starts[b - first]), std::size_t(word(3 + b)));
            const std::uint64_t outSize = b + 1 == blocks ? lastSize : blockSize;
            SampleSink::Appender own(sink, b * blockSize / sampleSize);
            SampleSink::Appender& appender = aligned ? own : inOrder;
            decompressBlock(path_, codecName + " block " + std::to_string(b), encoding_.codec,
                            compressed, outSize,
                            [&](std::span<const std::uint8_t> out) { appender.append(out); });
          } catch (...) {
            errors[std::size_t(thread)] = {b, std::current_exception()};
            for (std::uint64_t seen = failed; b < seen && !failed.compare_exchange_weak(seen, b);) {
            }
            return;
          }
        }
      };
      {
        std::vector<std::jthread> pool;
        for (int t = 1; t < threads; ++t) pool.emplace_back(work, t);
        work(0);
      }
      const auto error =
          std::min_element(errors.begin(), errors.end(),
                           [](const auto& a, const auto& b) { return a.first < b.first; });
      if (error->second) std::rethrow_exception(error->second);
      if (truncated) {
        throwInputError(path_, codecName + " block " + std::to_string(*truncated) +
                                   " is truncated (" +
                                   std::to_string(block_.size() - (offset + bytes)) + " of " +
                                   std::to_string(word(3 + *truncated)) + " bytes)");
      }
      offset += bytes;
      first = end;
      if (options_.progress) options_.progress(offset - dataStart, compressedTotal);
    }
    sink.finish();
  }

  const std::string& path_;
  const BlockSource& block_;
  Encoding encoding_;
  const LoadOptions& options_;
  std::vector<std::uint8_t> headerBytes_;
  std::span<const std::uint8_t> header_;
};

// The part of the file to parse as XML: all of it, or, when it has appended data, what comes
// before the data's '_' marker (raw bytes that an XML parser must not see, and that are read
// later, only as far as needed), with the open elements closed.
struct XmlPart {
  std::string xml;
  std::optional<std::uint64_t> appendedOffset;  // the file offset just after '_'
};

XmlPart readXmlPart(const std::string& path, const FileReader& file, std::uint64_t fileSize,
                    std::uint64_t maxXmlBytes) {
  constexpr std::size_t kPiece = std::size_t(1) << 20;
  const std::string tagName = "<AppendedData";
  std::string head;
  std::size_t tag = std::string::npos;
  while (true) {
    const std::size_t searched = head.size();
    const std::size_t piece = std::size_t(std::min<std::uint64_t>(kPiece, fileSize - searched));
    if (searched >= maxXmlBytes && piece > 0) {
      throwInputError(path, "holds more than " + std::to_string(maxXmlBytes) +
                                " bytes of XML, more than this format may need within the memory "
                                "limit");
    }
    head.resize(searched + piece);
    file.readAt(searched,
                std::span(reinterpret_cast<std::uint8_t*>(head.data()) + searched, piece));
    if (tag == std::string::npos) {
      tag = head.find(tagName, searched >= tagName.size() ? searched - tagName.size() : 0);
    }
    if (tag != std::string::npos) {
      const std::size_t close = head.find('>', tag);
      const std::size_t underscore = close == std::string::npos ? close : head.find('_', close);
      if (underscore != std::string::npos) {
        head.resize(underscore);
        return {head + "</AppendedData></VTKFile>", underscore + 1};
      }
    }
    if (head.size() == fileSize) {
      if (tag != std::string::npos) {
        throwInputError(path, "<AppendedData> has no '_' marker before its data");
      }
      return {head, std::nullopt};
    }
  }
}

}  // namespace

Volume readVti(const std::string& path, const LoadOptions& options) {
  const std::uint64_t fileSize = regularFileSize(path);
  const FileReader file(path);
  // A valid file's XML holds at most the volume in base64 (4/3 of its bytes) or ascii; twice
  // the memory limit bounds it without reading hostile sizes.
  const std::uint64_t maxXmlBytes = std::uint64_t(options.limits.maxBytes) * 2 + (16u << 20);
  const XmlPart part = readXmlPart(path, file, fileSize, maxXmlBytes);

  tinyxml2::XMLDocument doc;
  if (doc.Parse(part.xml.data(), part.xml.size()) != tinyxml2::XML_SUCCESS) {
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
  if (compressor == "vtkLZ4DataCompressor") {
    encoding.codec = BlockCodec::Lz4;
  } else if (compressor == "vtkLZMADataCompressor") {
    encoding.codec = BlockCodec::Lzma;
  } else if (!compressor.empty() && compressor != "vtkZLibDataCompressor") {
    throwInputError(path, "compressor " + quote(compressor) +
                              " is not supported (vtkZLibDataCompressor, vtkLZ4DataCompressor, "
                              "vtkLZMADataCompressor)");
  }
  encoding.compressed = !compressor.empty();

  const XMLElement* image = requireChild(path, root, "ImageData");
  const glm::ivec3 dims = dimsFromExtent(path, attribute(image, "WholeExtent"));
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
  planVolume(path, dims, keptSampleType(type), options.limits, options.region);
  const glm::dvec3 spacing = parseSpacing(path, "Spacing", attribute(image, "Spacing", "1 1 1"));
  const std::uint64_t expected = payloadBytes(dims, type);
  const std::string layout = " (" + describeLayout(dims, type) + ")";
  const std::string format = attribute(array, "format", "ascii");
  auto start = [&] {
    Volume volume = startVolume(path, dims, type, spacing, options);
    volume.format =
        "VTK XML ImageData (" + format +
        (encoding.compressed ? std::string(", ") + blockCodecName(encoding.codec) : "") + ")";
    return volume;
  };

  // The array's character data: every text node, across comments and child elements (VTK's
  // writer may put an <InformationKey> before the values), joined as XML joins them.
  std::string text;
  for (const tinyxml2::XMLNode* node = array->FirstChild(); node; node = node->NextSibling()) {
    if (const tinyxml2::XMLText* part = node->ToText()) text += part->Value();
  }
  if (format == "ascii") {
    Volume volume = start();
    SampleSink sink(path, volume, subsetOf(volume), type, encoding.bigEndian);
    parseTextSamples(path, text, type, sink, TextAfterSamples::WhitespaceOnly);
    return volume;
  }
  std::vector<std::uint8_t> decoded;  // base64 forms, decoded
  std::optional<BlockSource> block;
  if (format == "binary") {
    decoded = decodeBase64(path, text);
    block.emplace(decoded);
  } else if (format == "appended") {
    if (!part.appendedOffset) {
      throwInputError(path, "DataArray is appended but the file has no <AppendedData>");
    }
    const std::uint64_t appendedSize = fileSize - *part.appendedOffset;
    const std::int64_t offset = parseInteger(path, "DataArray offset", attribute(array, "offset"));
    if (offset < 0 || std::uint64_t(offset) > appendedSize) {
      throwInputError(
          path, "DataArray offset " + std::to_string(offset) + " lies outside the appended data");
    }
    const std::uint64_t dataOffset = *part.appendedOffset + std::uint64_t(offset);
    const XMLElement* appendedData = root->FirstChildElement("AppendedData");
    const std::string appendedEncoding =
        appendedData ? attribute(appendedData, "encoding", "raw") : "raw";
    if (appendedEncoding == "base64") {
      // Text up to the closing tag: read, bounded like the XML, and decoded whole.
      const std::uint64_t size = fileSize - dataOffset;
      if (size > maxXmlBytes) {
        throwInputError(path, "appended base64 data of " + std::to_string(size) +
                                  " bytes is more than this format may need within the memory "
                                  "limit");
      }
      std::string data(std::size_t(size), '\0');
      file.readAt(dataOffset, std::span(reinterpret_cast<std::uint8_t*>(data.data()), data.size()));
      decoded = decodeBase64(path, std::string_view(data).substr(0, data.find('<')));
      block.emplace(decoded);
    } else if (appendedEncoding == "raw") {
      block.emplace(file, dataOffset, fileSize - dataOffset);
    } else {
      throwInputError(path, "AppendedData encoding " + quote(appendedEncoding) + " is unknown");
    }
  } else {
    throwInputError(path,
                    "DataArray format " + quote(format) + " is unknown (ascii, binary, appended)");
  }
  Volume volume = start();
  SampleSink sink(path, volume, subsetOf(volume), type, encoding.bigEndian);
  BlockReader(path, *block, encoding, options).read(expected, layout, sink);
  return volume;
}

}  // namespace vsil::io
