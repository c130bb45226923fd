// --crop and --stride in every reader: a volume read with a region holds exactly the samples
// lo + i·stride of the whole volume (checked against a whole read), its spacing grows by the
// stride, and Volume::subset says what was read. Binary payloads decode only what is kept.
#include <cmath>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>

#include "generators/generators.h"
#include "io/volume_loader.h"
#include "io_test_files.h"
#include "reference/test_support.h"

namespace vsil {
namespace {

using test::Bytes;

constexpr glm::ivec3 kFileDims{23, 17, 11};

enum class FileFormat {
  Raw,
  NrrdRaw,
  NrrdGzip,
  NrrdAscii,
  VtiAppendedRaw,
  VtiAppendedZlib,
  VtiAppendedZlibOddBlocks,
  VtiInlineBase64Zlib,
  VtiAscii,
  VtkBinary,
  VtkAscii,
  MetaImageRaw,
  MetaImageZlib,
  MetaImageBigEndianDetached,
  VtiAppendedLz4,
  VtiAppendedLzma
};

const char* formatName(FileFormat f) {
  static const char* names[] = {"Raw",
                                "NrrdRaw",
                                "NrrdGzip",
                                "NrrdAscii",
                                "VtiAppendedRaw",
                                "VtiAppendedZlib",
                                "VtiOddZlib",
                                "VtiInlineBase64",
                                "VtiAscii",
                                "VtkBinary",
                                "VtkAscii",
                                "MetaImageRaw",
                                "MetaImageZlib",
                                "MetaImageMsbDetached",
                                "VtiAppendedLz4",
                                "VtiAppendedLzma"};
  return names[int(f)];
}

std::string asciiValues(const std::vector<float>& values) {
  std::string text;
  for (float v : values) text += std::to_string(v) + " ";
  return text + "\n";
}

// VTK's zlib block layout (UInt32 header): [#blocks][block size][last size][sizes...] data.
// VTK's compressed block layout, each block compressed by `compress` (zlib by default).
Bytes zlibBlocks(
    const Bytes& data, std::size_t blockSize,
    Bytes (*compress)(const Bytes&) = [](const Bytes& b) { return test::deflateBytes(b, false); }) {
  std::vector<Bytes> blocks;
  for (std::size_t at = 0; at < data.size(); at += blockSize) {
    blocks.push_back(
        compress(Bytes(data.begin() + std::ptrdiff_t(at),
                       data.begin() + std::ptrdiff_t(std::min(data.size(), at + blockSize)))));
  }
  Bytes out;
  test::appendWord(out, blocks.size(), 4, false);
  test::appendWord(out, blockSize, 4, false);
  test::appendWord(out, data.size() % blockSize, 4, false);
  for (const Bytes& b : blocks) test::appendWord(out, b.size(), 4, false);
  for (const Bytes& b : blocks) out.insert(out.end(), b.begin(), b.end());
  return out;
}

// Writes `values` (uint16 samples, spacing 0.5 1 2) in `format`; returns the path and how
// loadVolume must be told to read it.
std::pair<std::string, LoadOptions> writeVolume(FileFormat format,
                                                const std::vector<float>& values) {
  const auto dir = test::scratchDir();
  const Bytes little = test::encodeSamples(values, SampleType::UInt16, false);
  const std::string dims = std::to_string(kFileDims.x) + " " + std::to_string(kFileDims.y) + " " +
                           std::to_string(kFileDims.z);
  LoadOptions options;
  auto nrrd = [&](const std::string& encoding, const std::string& payload) {
    const auto path = dir / "v.nrrd";
    test::writeFile(path, "NRRD0004\ntype: uint16\ndimension: 3\nsizes: " + dims +
                              "\nspacings: 0.5 1 2\nendian: little\nencoding: " + encoding +
                              "\n\n" + payload);
    return path.string();
  };
  auto vti = [&](const std::string& attributes, const std::string& array,
                 const std::string& appended) {
    const auto path = dir / "v.vti";
    test::writeFile(path,
                    "<VTKFile type=\"ImageData\" byte_order=\"LittleEndian\" "
                    "header_type=\"UInt32\"" +
                        attributes + "><ImageData WholeExtent=\"0 " +
                        std::to_string(kFileDims.x - 1) + " 0 " + std::to_string(kFileDims.y - 1) +
                        " 0 " + std::to_string(kFileDims.z - 1) +
                        "\" Spacing=\"0.5 1 2\"><Piece><PointData>" + array +
                        "</PointData></Piece></ImageData>" + appended + "</VTKFile>\n");
    return path.string();
  };
  const std::string zlib = " compressor=\"vtkZLibDataCompressor\"";
  const std::string appendedArray =
      "<DataArray type=\"UInt16\" Name=\"v\" format=\"appended\" offset=\"0\"/>";
  switch (format) {
    case FileFormat::Raw: {
      const auto path = dir / "v.raw";
      test::writeFile(path, little);
      options.raw = RawLayout{kFileDims, SampleType::UInt16, {0.5, 1, 2}, false};
      return {path.string(), options};
    }
    case FileFormat::NrrdRaw:
      return {nrrd("raw", test::asText(little)), options};
    case FileFormat::NrrdGzip:
      return {nrrd("gzip", test::asText(test::deflateBytes(little, true))), options};
    case FileFormat::NrrdAscii:
      return {nrrd("ascii", asciiValues(values)), options};
    case FileFormat::VtiAppendedRaw: {
      Bytes block;
      test::appendWord(block, little.size(), 4, false);
      block.insert(block.end(), little.begin(), little.end());
      return {vti("", appendedArray,
                  "<AppendedData encoding=\"raw\">_" + test::asText(block) + "</AppendedData>"),
              options};
    }
    case FileFormat::VtiAppendedZlib:
    case FileFormat::VtiAppendedZlibOddBlocks: {
      // 512-byte blocks: 16 of them, inflated on every core; 1001 bytes: blocks that start
      // within a uint16 sample, read in order.
      const std::size_t blockSize = format == FileFormat::VtiAppendedZlib ? 512 : 1001;
      return {vti(zlib, appendedArray,
                  "<AppendedData encoding=\"raw\">_" + test::asText(zlibBlocks(little, blockSize)) +
                      "</AppendedData>"),
              options};
    }
    case FileFormat::VtiAppendedLz4:
    case FileFormat::VtiAppendedLzma: {
      const bool lz4 = format == FileFormat::VtiAppendedLz4;
      return {vti(lz4 ? " compressor=\"vtkLZ4DataCompressor\""
                      : " compressor=\"vtkLZMADataCompressor\"",
                  appendedArray,
                  "<AppendedData encoding=\"raw\">_" +
                      test::asText(zlibBlocks(little, 600, lz4 ? test::lz4Bytes : test::xzBytes)) +
                      "</AppendedData>"),
              options};
    }
    case FileFormat::VtiInlineBase64Zlib: {
      // VTK encodes the header and the data separately.
      const Bytes blocks = zlibBlocks(little, 700);
      const std::size_t headerBytes = 4 * (3 + (little.size() + 699) / 700);
      const std::string text =
          test::encodeBase64(Bytes(blocks.begin(), blocks.begin() + std::ptrdiff_t(headerBytes))) +
          test::encodeBase64(Bytes(blocks.begin() + std::ptrdiff_t(headerBytes), blocks.end()));
      return {
          vti(zlib,
              "<DataArray type=\"UInt16\" Name=\"v\" format=\"binary\">" + text + "</DataArray>",
              ""),
          options};
    }
    case FileFormat::VtiAscii:
      return {vti("",
                  "<DataArray type=\"UInt16\" Name=\"v\" format=\"ascii\">" + asciiValues(values) +
                      "</DataArray>",
                  ""),
              options};
    case FileFormat::VtkBinary:
    case FileFormat::VtkAscii: {
      const bool binary = format == FileFormat::VtkBinary;
      const auto path = dir / "v.vtk";
      test::writeFile(
          path, std::string("# vtk DataFile Version 3.0\ncropped\n") +
                    (binary ? "BINARY" : "ASCII") + "\nDATASET STRUCTURED_POINTS\nDIMENSIONS " +
                    dims + "\nSPACING 0.5 1 2\nPOINT_DATA " + std::to_string(values.size()) +
                    "\nSCALARS v unsigned_short\nLOOKUP_TABLE default\n" +
                    (binary ? test::asText(test::encodeSamples(values, SampleType::UInt16, true))
                            : asciiValues(values)));
      return {path.string(), options};
    }
    case FileFormat::MetaImageRaw:
    case FileFormat::MetaImageZlib:
    case FileFormat::MetaImageBigEndianDetached: {
      const bool zlib = format == FileFormat::MetaImageZlib;
      const bool big = format == FileFormat::MetaImageBigEndianDetached;
      const std::string header =
          "ObjectType = Image\nNDims = 3\nDimSize = " + dims +
          "\nElementSpacing = 0.5 1 2\nElementType = MET_USHORT\nBinaryDataByteOrderMSB = " +
          (big ? "True" : "False") + "\nCompressedData = " + (zlib ? "True" : "False") +
          "\nElementDataFile = ";
      if (big) {
        test::writeFile(dir / "v.raw", test::encodeSamples(values, SampleType::UInt16, true));
        test::writeFile(dir / "v.mhd", header + "v.raw\n");
        return {(dir / "v.mhd").string(), options};
      }
      test::writeFile(
          dir / "v.mha",
          header + "LOCAL\n" + test::asText(zlib ? test::deflateBytes(little, false) : little));
      return {(dir / "v.mha").string(), options};
    }
  }
  return {};
}

ReadRegion regionOf(const std::string& crop, int stride) {
  ReadRegion region;
  region.stride = stride;
  if (crop.empty()) return region;
  region.cropText = crop;
  std::array<ReadRegion::Range, 3> ranges;
  int axis = 0;
  std::size_t at = 0;
  while (axis < 3) {
    const std::size_t comma = std::min(crop.find(',', at), crop.size());
    const std::string range = crop.substr(at, comma - at);
    const std::size_t colon = range.find(':');
    const std::string begin = range.substr(0, colon), end = range.substr(colon + 1);
    if (!begin.empty()) ranges[std::size_t(axis)].begin = std::stoi(begin);
    if (!end.empty()) ranges[std::size_t(axis)].end = std::stoi(end);
    at = comma + 1;
    ++axis;
  }
  region.crop = ranges;
  return region;
}

struct Region {
  const char* crop;
  int stride;
};
const Region kRegions[] = {
    {"", 2},      {"3:20,2:,:9", 1}, {"1:22,0:17,2:11", 3}, {"22:23,5:6,:", 1},
    {":,:,:", 1}, {"4:5,:,10:", 4},  {"0:2,16:,1:3", 7},
};

class CropStrideRead : public ::testing::TestWithParam<FileFormat> {};

TEST_P(CropStrideRead, KeepsExactlyTheSubsetOfTheWholeVolume) {
  std::vector<float> values(std::size_t(kFileDims.x) * kFileDims.y * kFileDims.z);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = float((i * 7919) % 65536);
  const auto [path, options] = writeVolume(GetParam(), values);
  const Volume whole = loadVolume(path, options);
  ASSERT_EQ(test::floatsOf(whole), values);
  EXPECT_FALSE(whole.subset);

  for (const Region& r : kRegions) {
    SCOPED_TRACE(std::string("--crop '") + r.crop + "' --stride " + std::to_string(r.stride));
    LoadOptions cropped = options;
    cropped.region = regionOf(r.crop, r.stride);
    const Volume volume = loadVolume(path, cropped);
    const VolumeSubset subset = resolveRegion(path, kFileDims, cropped.region);
    EXPECT_EQ(volume.type(), SampleType::UInt16);
    ASSERT_EQ(volume.dims, subset.dims());
    EXPECT_EQ(volume.spacing, glm::dvec3(0.5, 1, 2) * double(r.stride));
    ASSERT_EQ(volume.subset.has_value(), !subset.whole());
    if (volume.subset) {
      EXPECT_EQ(volume.subset->lo, subset.lo);
      EXPECT_EQ(volume.subset->hi, subset.hi);
      EXPECT_EQ(volume.subset->stride, r.stride);
      EXPECT_EQ(volume.subset->fileDims, kFileDims);
    }
    for (int z = 0; z < volume.dims.z; ++z) {
      for (int y = 0; y < volume.dims.y; ++y) {
        for (int x = 0; x < volume.dims.x; ++x) {
          const glm::ivec3 file = subset.lo + glm::ivec3(x, y, z) * r.stride;
          ASSERT_EQ(volume.at(x, y, z), whole.at(file.x, file.y, file.z))
              << "kept " << x << "," << y << "," << z;
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(EveryReader, CropStrideRead,
                         ::testing::Values(FileFormat::Raw, FileFormat::NrrdRaw,
                                           FileFormat::NrrdGzip, FileFormat::NrrdAscii,
                                           FileFormat::VtiAppendedRaw, FileFormat::VtiAppendedZlib,
                                           FileFormat::VtiAppendedZlibOddBlocks,
                                           FileFormat::VtiInlineBase64Zlib, FileFormat::VtiAscii,
                                           FileFormat::VtkBinary, FileFormat::VtkAscii,
                                           FileFormat::MetaImageRaw, FileFormat::MetaImageZlib,
                                           FileFormat::MetaImageBigEndianDetached,
                                           FileFormat::VtiAppendedLz4, FileFormat::VtiAppendedLzma),
                         [](const auto& info) { return std::string(formatName(info.param)); });

// Float samples are checked for NaN as they are decoded: a NaN outside the crop is never
// decoded (raw: never even read), so the cropped read succeeds where the whole read fails.
TEST(CropStrideRead, SamplesOutsideTheCropAreNotDecoded) {
  const glm::ivec3 dims(8, 6, 5);
  std::vector<float> values(std::size_t(dims.x) * dims.y * dims.z, 1.0f);
  const std::size_t nanAt = std::size_t((4 * dims.y + 3) * dims.x + 7);  // (7, 3, 4)
  Bytes bytes = test::encodeSamples(values, SampleType::Float32, false);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&bytes[nanAt * 4], &nan, 4);
  const auto dir = test::scratchDir();
  const std::string raw = (dir / "nan.raw").string();
  test::writeFile(raw, bytes);
  const std::string gzip = (dir / "nan.nrrd").string();
  test::writeFile(gzip,
                  "NRRD0004\ntype: float\ndimension: 3\nsizes: 8 6 5\nendian: little\n"
                  "encoding: gzip\n\n" +
                      test::asText(test::deflateBytes(bytes, true)));
  for (const std::string& path : {raw, gzip}) {
    LoadOptions options;
    if (path == raw) options.raw = RawLayout{dims, SampleType::Float32, {1, 1, 1}, false};
    test::expectInputError([&] { loadVolume(path, options); },
                           path + ": sample " + std::to_string(nanAt) + " is NaN", {});
    options.region = regionOf("0:7,:,:", 1);  // x = 7 left out
    const Volume cropped = loadVolume(path, options);
    EXPECT_EQ(cropped.dims, glm::ivec3(7, 6, 5));
    options.region = regionOf("", 2);  // x = 0, 2, 4, 6
    EXPECT_EQ(loadVolume(path, options).dims, glm::ivec3(4, 3, 3));
  }
}

TEST(CropStrideRead, GeneratorsComputeOnlyTheKeptSamples) {
  const Volume whole = generateVolume("blobs:30");
  ReadRegion region = regionOf("5:29,:,3:", 2);
  const Volume part = generateVolume("blobs:30", {}, region);
  EXPECT_EQ(part.dims, glm::ivec3(12, 15, 14));
  EXPECT_EQ(part.spacing, glm::dvec3(2.0));
  ASSERT_TRUE(part.subset);
  for (int z = 0; z < part.dims.z; ++z) {
    for (int y = 0; y < part.dims.y; ++y) {
      for (int x = 0; x < part.dims.x; ++x) {
        ASSERT_EQ(part.at(x, y, z), whole.at(5 + 2 * x, 2 * y, 3 + 2 * z));
      }
    }
  }
}

}  // namespace
}  // namespace vsil
