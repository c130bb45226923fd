// VTK XML ImageData round trips: ascii, inline base64, appended raw and base64, each binary
// form with and without zlib blocks, UInt32 and UInt64 headers, both byte orders.
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
};

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
    const Bytes packed = test::deflateBytes(part, false);
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
  std::string xml = std::string("<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" ") +
                    "version=\"1.0\" byte_order=\"" + (c.bigEndian ? "BigEndian" : "LittleEndian") +
                    "\" header_type=\"" + (c.header64 ? "UInt64" : "UInt32") + "\"" +
                    (c.compressed ? " compressor=\"vtkZLibDataCompressor\"" : "") + ">\n" +
                    "  <ImageData WholeExtent=\"1 5 0 3 -1 1\" Origin=\"0 0 0\" "
                    "Spacing=\"0.5 1 2.25\">\n    <Piece Extent=\"1 5 0 3 -1 1\">\n"
                    "      <PointData Scalars=\"density\">\n"
                    "        <DataArray type=\"Float32\" Name=\"other\" format=\"ascii\">"
                    "bogus</DataArray>\n"
                    "        <DataArray type=\"" +
                    vtkTypeName(c.type) + "\" Name=\"density\" format=\"" + format +
                    "\" offset=\"0\">" + inlineText + "</DataArray>\n" +
                    "      </PointData>\n    </Piece>\n  </ImageData>\n";
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
         (c.compressed ? "_zlib" : "") + (c.header64 ? "_h64" : "_h32") +
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
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Vti, VtiRoundTrip, ::testing::ValuesIn(vtiCases()),
                         [](const auto& info) { return caseName(info.param); });

}  // namespace
}  // namespace vsil
