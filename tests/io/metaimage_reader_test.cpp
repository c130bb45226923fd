// MetaImage (.mhd, .mha): the committed fixtures of tests/io/metaimage/ (every element type,
// detached raw and zlib, attached, both byte orders, HeaderSize, ASCII; make_fixtures.py writes
// them and the values a reader must find), files written here for the header variants, and the
// errors for what vsil refuses.
#include <cstdint>

#include <gtest/gtest.h>

#include "io/volume_loader.h"
#include "io_test_files.h"
#include "reference/test_support.h"

namespace vsil {
namespace {

namespace fs = std::filesystem;
using test::Bytes;

const fs::path kMetaImageFixtures = fs::path(VSIL_SOURCE_DIR) / "tests" / "io" / "metaimage";

std::vector<test::FixtureExpectation> metaImageFixtures() {
  return test::readFixtureManifest(kMetaImageFixtures / "fixtures.txt");
}

class MetaImageFixtureRead : public ::testing::TestWithParam<test::FixtureExpectation> {};

TEST_P(MetaImageFixtureRead, FindsTheWrittenSamples) {
  test::expectFixtureRead(loadVolume((kMetaImageFixtures / GetParam().file).string()), GetParam());
}

INSTANTIATE_TEST_SUITE_P(Fixtures, MetaImageFixtureRead, ::testing::ValuesIn(metaImageFixtures()),
                         [](const auto& info) { return test::fixtureTestName(info.param.file); });

TEST(MetaImageReader, EveryFixtureIsListed) {
  EXPECT_EQ(metaImageFixtures().size(), 20u);  // 12 element types and 8 layouts
}

// An .mha with `fields` before ElementDataFile = LOCAL and `payload` after it.
std::string writeMha(const std::string& fields, const Bytes& payload) {
  const auto path = test::scratchDir() / "v.mha";
  test::writeFile(path, "ObjectType = Image\nNDims = 3\nDimSize = 2 2 1\n" + fields +
                            "ElementDataFile = LOCAL\n" + test::asText(payload));
  return path.string();
}

// 32-bit integers: exact up to 2^24, the others counted; the file's type is reported.
TEST(MetaImageReader, WideIntegersConvertToFloat32CountingRoundedSamples) {
  const Volume v =
      loadVolume(writeMha("ElementType = MET_INT\n",
                          test::encodeIntegers({-16777216, 16777217, 2147483647, 7}, 4, false)));
  EXPECT_EQ(v.type(), SampleType::Float32);
  EXPECT_EQ(v.fileType, "int32");
  EXPECT_EQ(test::floatsOf(v), (std::vector<float>{-16777216.f, 16777216.f, 2147483648.f, 7.f}));
  EXPECT_EQ(v.inexactSamples, 2u);  // 2^24 + 1 and 2^31 - 1
}

TEST(MetaImageReader, KeyCaseAndSpacesAreFree) {
  const auto path = test::scratchDir() / "v.mha";
  test::writeFile(path,
                  "objecttype=Image\r\n  NDims =3\nDimSize= 2 1 1\nElementSpacing = 2 3 4\n"
                  "AnatomicalOrientation = RAI\nElementType = MET_UCHAR\nElementDataFile=local\n"
                  "\x05\x06");
  const Volume v = loadVolume(path.string());
  EXPECT_EQ(v.spacing, glm::dvec3(2, 3, 4));
  EXPECT_EQ(test::floatsOf(v), (std::vector<float>{5, 6}));
}

TEST(MetaImageReader, RefusesWhatItDoesNotRead) {
  const Bytes four(4, 1);
  auto refuses = [&](const std::string& fields, const std::string& message) {
    const std::string path = writeMha(fields, four);
    test::expectInputError([&] { loadVolume(path); }, path + ": " + message, {});
  };
  refuses("ElementType = MET_UCHAR\nElementNumberOfChannels = 3\n",
          "ElementNumberOfChannels '3' is not supported: vsil reads scalar volumes (1 channel)");
  refuses("ElementType = MET_UCHAR_ARRAY\n", "ElementType 'MET_UCHAR_ARRAY' is not supported");
  refuses("ElementType = MET_UCHAR\nBinaryData = maybe\n",
          "BinaryData 'maybe' is neither True nor False");
  refuses("ElementType = MET_UCHAR\nHeaderSize = 5\n",
          "HeaderSize 5 passes the end of the data after the header (4 bytes)");
  refuses("ElementType = MET_USHORT\n",
          "data after the header holds 4 bytes, 8 expected (2x2x1 uint16)");
  refuses("ElementType = MET_UCHAR\nCompressedData = True\nCompressedDataSize = 40\n",
          "CompressedDataSize 40 passes the end of the data after the header (4 bytes)");

  const auto dir = test::scratchDir();
  test::writeFile(dir / "flat.mha",
                  "NDims = 2\nDimSize = 2 2\nElementType = MET_UCHAR\n"
                  "ElementDataFile = LOCAL\n\x01\x02\x03\x04");
  test::expectInputError([&] { loadVolume((dir / "flat.mha").string()); },
                         (dir / "flat.mha").string() +
                             ": NDims '2' is not supported: vsil reads 3D volumes (NDims = 3)",
                         {});
  for (const std::string dataFile : {"LIST", "slice%03d.raw 1 10 1"}) {
    test::writeFile(dir / "many.mhd",
                    "NDims = 3\nDimSize = 2 2 1\nElementType = MET_UCHAR\n"
                    "ElementDataFile = " +
                        dataFile + "\n");
    test::expectInputError([&] { loadVolume((dir / "many.mhd").string()); },
                           (dir / "many.mhd").string() + ": ElementDataFile", {"not supported"});
  }
  test::writeFile(
      dir / "nodata.mhd",
      "NDims = 3\nDimSize = 2 2 1\nElementType = MET_UCHAR\nElementDataFile = gone.raw\n");
  test::expectInputError(
      [&] { loadVolume((dir / "nodata.mhd").string()); },
      (dir / "nodata.mhd").string() + ": data file 'gone.raw': ", {"gone.raw: no such file"});
  test::writeFile(dir / "text.mha", "not a header\n");
  test::expectInputError([&] { loadVolume((dir / "text.mha").string()); },
                         (dir / "text.mha").string() + ": header line 1 'not a header' is not", {});
}

TEST(MetaImageReader, CompressedPayloadsMustInflateToTheirSize) {
  const Bytes zeros(1 << 16, 0);
  const std::string bomb = writeMha("ElementType = MET_UCHAR\nCompressedData = True\n",
                                    test::deflateBytes(zeros, false));
  test::expectInputError([&] { loadVolume(bomb); },
                         bomb +
                             ": zlib data after the header inflates to more than the 4 bytes "
                             "expected",
                         {});
  const std::string shortStream = writeMha("ElementType = MET_UCHAR\nCompressedData = True\n",
                                           test::deflateBytes(Bytes(3, 7), false));
  test::expectInputError([&] { loadVolume(shortStream); },
                         shortStream +
                             ": zlib data after the header inflates to 3 bytes, 4 "
                             "expected",
                         {});
  // gzip streams are read too (some writers use them).
  const Volume gzip = loadVolume(writeMha("ElementType = MET_UCHAR\nCompressedData = True\n",
                                          test::deflateBytes(Bytes{1, 2, 3, 4}, true)));
  EXPECT_EQ(test::floatsOf(gzip), (std::vector<float>{1, 2, 3, 4}));
}

TEST(MetaImageReader, LimitsAreCheckedBeforeTheDataFileIsOpened) {
  const auto dir = test::scratchDir();
  test::writeFile(dir / "big.mhd",
                  "NDims = 3\nDimSize = 1024 1024 1024\nElementType = MET_INT\n"
                  "ElementDataFile = absent.raw\n");
  LoadOptions options;
  options.limits.maxBytes = std::size_t(100) << 20;
  test::expectInputError([&] { loadVolume((dir / "big.mhd").string(), options); },
                         (dir / "big.mhd").string() + ": reading 1024x1024x1024 float32 samples",
                         {"--max-memory"});
}

}  // namespace
}  // namespace vsil
