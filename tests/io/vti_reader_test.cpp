// VTK XML ImageData round trips: ascii, inline base64, appended raw and base64, each binary
// form with and without zlib blocks, UInt32 and UInt64 headers, both byte orders.
#include <cctype>
#include <limits>

#include <gtest/gtest.h>

#include "io/volume_loader.h"
#include "io_test_files.h"
#include "reference/test_support.h"

namespace vsil {
namespace {

using test::Bytes;

const glm::ivec3 kVtiDims{5, 4, 3};

enum class Format { Ascii, Inline, AppendedRaw, AppendedBase64 };

struct VtiCase {
  SampleType type;
  Format format;
  bool compressed;
  bool header64;
  bool bigEndian;
  // zlib block size in bytes: 32 so the arrays here span several blocks and end in a partial
  // one; 7 makes blocks start within a sample (read in order on one thread, not in parallel).
  std::size_t blockSize = 32;
  std::string codec = "zlib";  // when compressed: zlib, lz4, lzma
};

Bytes compressVtiBlock(const Bytes& part, const std::string& codec) {
  if (codec == "lz4") return test::lz4Bytes(part);
  if (codec == "lzma") return test::xzBytes(part);
  return test::deflateBytes(part, false);
}

std::string vtiCompressorName(const std::string& codec) {
  if (codec == "lz4") return "vtkLZ4DataCompressor";
  if (codec == "lzma") return "vtkLZMADataCompressor";
  return "vtkZLibDataCompressor";
}

const char* vtkTypeName(SampleType type) {
  switch (type) {
    case SampleType::UInt8:
      return "UInt8";
    case SampleType::Int8:
      return "Int8";
    case SampleType::UInt16:
      return "UInt16";
    case SampleType::Int16:
      return "Int16";
    case SampleType::Float32:
      return "Float32";
  }
  return "";
}

// The binary form VTK writes for one array: a header (byte count, or the zlib block table),
// then the data. Returned separately because base64 encodes them separately.
std::pair<Bytes, Bytes> binaryBlock(const Bytes& data, const VtiCase& c) {
  const std::size_t word = c.header64 ? 8 : 4;
  Bytes header;
  if (!c.compressed) {
    test::appendWord(header, data.size(), word, c.bigEndian);
    return {header, data};
  }
  const std::size_t blockSize = c.blockSize;
  const std::size_t blocks = (data.size() + blockSize - 1) / blockSize;
  Bytes body;
  std::vector<std::size_t> sizes;
  for (std::size_t i = 0; i < blocks; ++i) {
    const Bytes part(data.begin() + std::ptrdiff_t(i * blockSize),
                     data.begin() + std::ptrdiff_t(std::min(data.size(), (i + 1) * blockSize)));
    const Bytes packed = compressVtiBlock(part, c.codec);
    sizes.push_back(packed.size());
    body.insert(body.end(), packed.begin(), packed.end());
  }
  test::appendWord(header, blocks, word, c.bigEndian);
  test::appendWord(header, blockSize, word, c.bigEndian);
  test::appendWord(header, data.size() % blockSize, word, c.bigEndian);
  for (std::size_t size : sizes) test::appendWord(header, size, word, c.bigEndian);
  return {header, body};
}

std::string writeVti(const std::filesystem::path& dir, const VtiCase& c,
                     const std::vector<float>& values) {
  const Bytes data = test::encodeSamples(values, c.type, c.bigEndian);
  std::string format, inlineText, appended, appendedEncoding;
  if (c.format == Format::Ascii) {
    format = "ascii";
    for (float v : values) inlineText += std::to_string(v) + " ";
  } else {
    const auto [header, body] = binaryBlock(data, c);
    const std::string base64 = test::encodeBase64(header) + test::encodeBase64(body);
    if (c.format == Format::Inline) {
      format = "binary";
      inlineText = "\n" + base64 + "\n";
    } else {
      format = "appended";
      appendedEncoding = c.format == Format::AppendedRaw ? "raw" : "base64";
      appended =
          c.format == Format::AppendedRaw ? test::asText(header) + test::asText(body) : base64;
    }
  }
  std::string xml =
      std::string("<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" ") +
      "version=\"1.0\" byte_order=\"" + (c.bigEndian ? "BigEndian" : "LittleEndian") +
      "\" header_type=\"" + (c.header64 ? "UInt64" : "UInt32") + "\"" +
      (c.compressed ? " compressor=\"" + vtiCompressorName(c.codec) + "\"" : "") + ">\n" +
      "  <ImageData WholeExtent=\"1 5 0 3 -1 1\" Origin=\"0 0 0\" "
      "Spacing=\"0.5 1 2.25\">\n    <Piece Extent=\"1 5 0 3 -1 1\">\n"
      "      <PointData Scalars=\"density\">\n"
      "        <DataArray type=\"Float32\" Name=\"other\" format=\"ascii\">"
      "bogus</DataArray>\n"
      "        <DataArray type=\"" +
      vtkTypeName(c.type) + "\" Name=\"density\" format=\"" + format + "\" offset=\"0\">" +
      inlineText + "</DataArray>\n" + "      </PointData>\n    </Piece>\n  </ImageData>\n";
  if (!appended.empty()) {
    xml += "  <AppendedData encoding=\"" + appendedEncoding + "\">\n   _" + appended +
           "\n  </AppendedData>\n";
  }
  xml += "</VTKFile>\n";
  test::writeFile(dir / "image.vti", xml);
  return (dir / "image.vti").string();
}

std::string caseName(const VtiCase& c) {
  const char* formats[] = {"ascii", "inline", "appendedraw", "appendedbase64"};
  return std::string(sampleTypeName(c.type)) + "_" + formats[int(c.format)] +
         (c.compressed ? "_" + c.codec : "") + (c.header64 ? "_h64" : "_h32") +
         (c.bigEndian ? "_big" : "") +
         (c.blockSize != 32 ? "_block" + std::to_string(c.blockSize) : "");
}

class VtiRoundTrip : public ::testing::TestWithParam<VtiCase> {};

TEST_P(VtiRoundTrip, ReadsBackTheWrittenSamples) {
  const VtiCase& c = GetParam();
  const auto values = test::testValues(kVtiDims, c.type);
  const Volume volume = loadVolume(writeVti(test::scratchDir(), c, values));
  EXPECT_EQ(volume.name, "image");
  EXPECT_EQ(volume.dims, kVtiDims);
  EXPECT_EQ(volume.spacing, glm::dvec3(0.5, 1, 2.25));
  EXPECT_EQ(volume.type(), c.type);
  if (c.format == Format::Ascii && c.type == SampleType::Float32) {
    // std::to_string prints 6 decimals (error <= 5e-7) and parsing rounds to the nearest float
    // (half an ulp, <= 4e-6 below 128): 1e-4 covers both with room.
    for (std::size_t i = 0; i < values.size(); ++i) {
      EXPECT_NEAR(volume.value(i), values[i], 1e-4) << "sample " << i;
    }
  } else {
    EXPECT_EQ(test::floatsOf(volume), values);
  }
}

std::vector<VtiCase> vtiCases() {
  std::vector<VtiCase> cases;
  for (SampleType type : kSampleTypes) {
    cases.push_back({type, Format::Ascii, false, false, false});
    for (Format format : {Format::Inline, Format::AppendedRaw, Format::AppendedBase64}) {
      for (bool compressed : {false, true}) {
        for (bool header64 : {false, true}) {
          cases.push_back({type, format, compressed, header64, false});
        }
      }
    }
    cases.push_back({type, Format::AppendedRaw, true, true, true});
    cases.push_back({type, Format::Inline, false, false, true});
    cases.push_back({type, Format::AppendedRaw, true, false, false, 7});
    for (const char* codec : {"lz4", "lzma"}) {
      cases.push_back({type, Format::AppendedRaw, true, false, false, 32, codec});
      cases.push_back({type, Format::Inline, true, true, true, 32, codec});
      cases.push_back({type, Format::AppendedBase64, true, false, false, 7, codec});
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Vti, VtiRoundTrip, ::testing::ValuesIn(vtiCases()),
                         [](const auto& info) { return caseName(info.param); });

// Int32, UInt32, Int64, UInt64 arrays are kept as float32: exact up to 2^24, the samples float32
// changes counted, the file's type reported; raw and zlib, both byte orders.
TEST(VtiReader, WideIntegersConvertToFloat32CountingRoundedSamples) {
  struct WideCase {
    const char* type;
    std::size_t size;
    std::vector<std::int64_t> values;  // UInt64 2^63 written as its bits
    std::vector<float> kept;
    std::uint64_t inexact;
  };
  const WideCase cases[] = {
      {"Int32", 4, {-5, 16777216, 16777217, 2147483647}, {-5, 16777216, 16777216, 2147483648.f}, 2},
      {"UInt32", 4, {0, 4294967295, 255, 16777215}, {0, 4294967296.f, 255, 16777215}, 1},
      {"Int64",
       8,
       {-1, std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max(),
        (std::int64_t(1) << 53) + 1},
       {-1, -9223372036854775808.f, 9223372036854775808.f, 9007199254740992.f},
       2},
      {"UInt64",
       8,
       {3, std::numeric_limits<std::int64_t>::min(), -1, 9},
       {3, 0x1p63f, 0x1p64f, 9},
       1},
  };
  for (const WideCase& c : cases) {
    for (bool compressed : {false, true}) {
      for (bool big : {false, true}) {
        SCOPED_TRACE(std::string(c.type) + (compressed ? " zlib" : " raw") +
                     (big ? " big-endian" : ""));
        const Bytes data = test::encodeIntegers(c.values, c.size, big);
        Bytes block;
        if (compressed) {
          const Bytes packed = test::deflateBytes(data, false);
          for (std::uint64_t word : {std::uint64_t(1), data.size(), data.size(), packed.size()}) {
            test::appendWord(block, word, 4, big);
          }
          block.insert(block.end(), packed.begin(), packed.end());
        } else {
          test::appendWord(block, data.size(), 4, big);
          block.insert(block.end(), data.begin(), data.end());
        }
        const auto path = test::scratchDir() / "wide.vti";
        test::writeFile(path, std::string("<VTKFile type=\"ImageData\" byte_order=\"") +
                                  (big ? "BigEndian" : "LittleEndian") + "\"" +
                                  (compressed ? " compressor=\"vtkZLibDataCompressor\"" : "") +
                                  "><ImageData WholeExtent=\"0 1 0 1 0 0\"><Piece><PointData>"
                                  "<DataArray type=\"" +
                                  c.type +
                                  "\" format=\"appended\" offset=\"0\"/></PointData></Piece>"
                                  "</ImageData><AppendedData encoding=\"raw\">_" +
                                  test::asText(block) + "</AppendedData></VTKFile>\n");
        const Volume v = loadVolume(path.string());
        EXPECT_EQ(v.type(), SampleType::Float32);
        std::string fileType = c.type;  // "int32" for "Int32"
        for (char& ch : fileType) ch = char(std::tolower(static_cast<unsigned char>(ch)));
        EXPECT_EQ(v.fileType, fileType);
        EXPECT_EQ(test::floatsOf(v), c.kept);
        EXPECT_EQ(v.inexactSamples, c.inexact);
      }
    }
  }
}

// An inline array's values are its whole character data: VTK's writer may put an
// <InformationKey> before them, and a comment may sit among them (the first text node alone
// read as "0 characters" or too few values); a value after a comment is still one too many.
TEST(VtiReader, InlineValuesAreTheArraysWholeCharacterData) {
  const auto file = [](const std::string& content) {
    const auto path = test::scratchDir() / "inline.vti";
    test::writeFile(path,
                    "<VTKFile type=\"ImageData\" byte_order=\"LittleEndian\">\n"
                    "<ImageData WholeExtent=\"0 1 0 1 0 0\" Spacing=\"1 1 1\"><Piece>"
                    "<PointData><DataArray type=\"UInt8\" Name=\"s\" format=\"ascii\">" +
                        content + "</DataArray></PointData></Piece></ImageData></VTKFile>\n");
    return path.string();
  };
  const std::string key =
      "<InformationKey name=\"L2_NORM_RANGE\" location=\"vtkDataArray\" length=\"2\">"
      "<Value index=\"0\">0</Value><Value index=\"1\">9</Value></InformationKey>\n";
  for (const std::string& content :
       {key + "1 2 3 4\n", std::string("1 2 <!-- c --> 3 4"), "1 2 3 4\n" + key}) {
    EXPECT_EQ(test::floatsOf(loadVolume(file(content))), (std::vector<float>{1, 2, 3, 4}))
        << content;
  }
  test::expectInputError([&] { loadVolume(file("1 2 3 4 <!-- c --> 5")); },
                         (test::scratchDir() / "inline.vti").string(),
                         {"holds more than the 4 values its header's sizes give"});
}

// LZ4 and xz blocks get zlib's bomb protection: a block that decompresses to more (or less)
// than its header says is refused, naming the block.
TEST(VtiReader, Lz4AndLzmaBlocksMustDecompressToTheirSize) {
  struct Lie {
    const char* codec;
    Bytes data;          // what the block really holds
    std::size_t claims;  // what the header says
    std::string message;
  };
  const Lie lies[] = {
      {"lz4", Bytes(1 << 16, 0), 8,
       "lz4 block 0 is corrupt or decompresses to more than the 8 bytes expected"},
      {"lz4", Bytes(4, 1), 8, "lz4 block 0 decompresses to 4 bytes, 8 expected"},
      {"lzma", Bytes(1 << 16, 0), 8, "lzma block 0 decompresses to more than the 8 bytes expected"},
      {"lzma", Bytes(4, 1), 8, "lzma block 0 decompresses to 4 bytes, 8 expected"},
  };
  for (const Lie& lie : lies) {
    const Bytes packed = compressVtiBlock(lie.data, lie.codec);
    Bytes block;
    for (std::uint64_t word : {std::uint64_t(1), std::uint64_t(lie.claims), std::uint64_t(0),
                               std::uint64_t(packed.size())}) {
      test::appendWord(block, word, 4, false);
    }
    block.insert(block.end(), packed.begin(), packed.end());
    const auto path = test::scratchDir() / "lie.vti";
    test::writeFile(path, "<VTKFile type=\"ImageData\" compressor=\"" +
                              vtiCompressorName(lie.codec) +
                              "\"><ImageData WholeExtent=\"0 1 0 1 0 1\"><Piece><PointData>"
                              "<DataArray type=\"UInt8\" format=\"appended\" offset=\"0\"/>"
                              "</PointData></Piece></ImageData><AppendedData encoding=\"raw\">_" +
                              test::asText(block) + "</AppendedData></VTKFile>\n");
    test::expectInputError([&] { loadVolume(path.string()); }, path.string() + ": " + lie.message,
                           {});
  }
}

}  // namespace
}  // namespace vsil
