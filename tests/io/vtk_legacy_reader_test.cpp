// Legacy VTK STRUCTURED_POINTS round trips: BINARY (big-endian) and ASCII, each scalar type,
// with and without LOOKUP_TABLE, SPACING or the old ASPECT_RATIO.
#include <gtest/gtest.h>

#include "io/volume_loader.h"
#include "io_test_files.h"
#include "reference/test_support.h"

namespace vsil {
namespace {

const glm::ivec3 kLegacyDims{5, 4, 3};

struct LegacyCase {
  SampleType type;
  const char* typeName;
  bool binary;
  bool lookupTable;
};

std::string writeLegacy(const std::filesystem::path& dir, const LegacyCase& c,
                        const std::vector<float>& values) {
  std::string text = std::string("# vtk DataFile Version 3.0\nround trip\n") +
                     (c.binary ? "BINARY" : "ASCII") +
                     "\nDATASET STRUCTURED_POINTS\nDIMENSIONS 5 4 3\nORIGIN 0 0 0\n" +
                     (c.lookupTable ? "SPACING 0.5 1 2.25\n" : "ASPECT_RATIO 0.5 1 2.25\n") +
                     "POINT_DATA 60\nSCALARS density " + c.typeName + " 1\n" +
                     (c.lookupTable ? "LOOKUP_TABLE default\n" : "");
  if (c.binary) {
    text += test::asText(test::encodeSamples(values, c.type, /*bigEndian=*/true)) + "\n";
  } else {
    for (float v : values) text += std::to_string(v) + "\n";
  }
  test::writeFile(dir / "legacy.vtk", text);
  return (dir / "legacy.vtk").string();
}

class LegacyRoundTrip : public ::testing::TestWithParam<LegacyCase> {};

TEST_P(LegacyRoundTrip, ReadsBackTheWrittenSamples) {
  const LegacyCase& c = GetParam();
  const auto values = test::testValues(kLegacyDims, c.type);
  const Volume volume = loadVolume(writeLegacy(test::scratchDir(), c, values));
  EXPECT_EQ(volume.name, "legacy");
  EXPECT_EQ(volume.dims, kLegacyDims);
  EXPECT_EQ(volume.spacing, glm::dvec3(0.5, 1, 2.25));
  EXPECT_EQ(volume.type(), c.type);
  for (std::size_t i = 0; i < values.size(); ++i) {
    // ASCII floats: 6 printed decimals and float rounding, as in vti_reader_test; else exact.
    EXPECT_NEAR(volume.value(i), values[i], c.binary ? 0.0 : 1e-4) << "sample " << i;
  }
}

std::vector<LegacyCase> legacyCases() {
  const std::pair<SampleType, const char*> types[] = {{SampleType::UInt8, "unsigned_char"},
                                                      {SampleType::Int8, "char"},
                                                      {SampleType::UInt16, "unsigned_short"},
                                                      {SampleType::Int16, "short"},
                                                      {SampleType::Float32, "float"}};
  std::vector<LegacyCase> cases;
  for (const auto& [type, name] : types) {
    for (bool binary : {true, false}) {
      for (bool table : {true, false}) cases.push_back({type, name, binary, table});
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Legacy, LegacyRoundTrip, ::testing::ValuesIn(legacyCases()),
                         [](const auto& info) {
                           return std::string(info.param.typeName) +
                                  (info.param.binary ? "_binary" : "_ascii") +
                                  (info.param.lookupTable ? "_table" : "_notable");
                         });

// VTK reads LOOKUP_TABLE as a keyword in any case after any whitespace, blank lines included;
// such a line was once taken as the first samples of a BINARY payload (every voxel shifted).
TEST(LegacyReader, ALookupTableLineInLowerCaseIndentedOrAfterABlankLineIsSkipped) {
  const auto values = test::testValues(kLegacyDims, SampleType::UInt16);
  const std::string payload =
      test::asText(test::encodeSamples(values, SampleType::UInt16, /*bigEndian=*/true));
  for (const char* table : {"lookup_table default\n", "  LOOKUP_TABLE default\n",
                            "\nLOOKUP_TABLE default\n", "\r\n \n\tLookup_Table default\r\n"}) {
    const auto path = test::scratchDir() / "table.vtk";
    test::writeFile(path, std::string("# vtk DataFile Version 3.0\ntable\nBINARY\n"
                                      "DATASET STRUCTURED_POINTS\nDIMENSIONS 5 4 3\n"
                                      "POINT_DATA 60\nSCALARS density unsigned_short 1\n") +
                              table + payload);
    const Volume volume = loadVolume(path.string());
    for (std::size_t i = 0; i < values.size(); ++i) {
      ASSERT_EQ(volume.value(i), values[i]) << "sample " << i << " after " << table;
    }
  }
}

// ASCII samples may be followed by the file's other sections (VTK reads on); a number right
// after them means DIMENSIONS is not the file's and is refused.
TEST(LegacyReader, AsciiSamplesMayBeFollowedByASectionButNotByAValue) {
  const std::string head =
      "# vtk DataFile Version 3.0\nsections\nASCII\nDATASET STRUCTURED_POINTS\n"
      "DIMENSIONS 2 2 2\nPOINT_DATA 8\nSCALARS density unsigned_char 1\n"
      "LOOKUP_TABLE default\n1 2 3 4 5 6 7 8\n";
  const auto path = test::scratchDir() / "sections.vtk";
  test::writeFile(path, head +
                            "SCALARS other float 1\nLOOKUP_TABLE default\n9 9 9 9 9 9 9 9\n"
                            "CELL_DATA 1\n");
  const Volume volume = loadVolume(path.string());
  for (std::size_t i = 0; i < 8; ++i) ASSERT_EQ(volume.value(i), float(i + 1));
  // Form feed and vertical tab separate values, as in VTK's (istream) reader.
  std::string separated = head;
  separated.replace(separated.find("1 2 3"), 5, "1\f2\v3");
  test::writeFile(path, separated);
  const Volume spaced = loadVolume(path.string());
  for (std::size_t i = 0; i < 8; ++i) ASSERT_EQ(spaced.value(i), float(i + 1));
  for (const char* extra :
       {"9\n", "-1\n", ".5\n", "+3 SCALARS\n", "nan\n", "INF\n", "nan(0x1)\n", "Infinity\n"}) {
    test::writeFile(path, head + extra);
    test::expectInputError([&] { loadVolume(path.string()); }, path.string(),
                           {"holds more than the 8 values its header's sizes give"});
  }
}

// int, unsigned_int, vtktypeint64 and vtktypeuint64 (BINARY, big-endian, and ASCII) are kept as
// float32, as the other readers keep the wide integers: exact up to 2^24, rounded ones counted.
// An unknown keyword of binary bytes is named as '?'s, the whole message valid UTF-8 (round 15:
// the line's raw bytes came first).
TEST(LegacyReader, AnUnknownKeywordOfBinaryBytesIsPrintable) {
  const auto path = test::scratchDir() / "keyword.vtk";
  test::writeFile(path,
                  "# vtk DataFile Version 3.0\nkeyword\nASCII\nDATASET STRUCTURED_POINTS\n"
                  "DIMENSIONS 2 2 2\n\xff\xfe\x80 1\n");
  test::expectInputError([&] { loadVolume(path.string()); }, path.string(),
                         {": line 6 ???: unknown keyword '??"
                          "?'"});  // (no trigraph)
}

TEST(LegacyReader, WideIntegersConvertToFloat32CountingRoundedSamples) {
  const test::WideIntegerCase cases[] = {
      {"int", "int32", 4, {-5, 16777217}, {-5, 16777216}, 1},
      {"unsigned_int", "uint32", 4, {4294967295, 7}, {0x1p32f, 7}, 1},
      {"vtktypeint64", "int64", 8, {-9, 16777216}, {-9, 16777216}, 0},
      {"vtktypeuint64", "uint64", 8, {16777219, 2}, {16777220, 2}, 1},
  };
  for (const test::WideIntegerCase& c : cases) {
    for (bool binary : {true, false}) {
      SCOPED_TRACE(std::string(c.type) + (binary ? " binary" : " ascii"));
      std::string text = std::string("# vtk DataFile Version 3.0\nwide\n") +
                         (binary ? "BINARY" : "ASCII") +
                         "\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 1 1\nPOINT_DATA 2\nSCALARS s " +
                         c.type + " 1\nLOOKUP_TABLE default\n";
      if (binary) {
        text += test::asText(test::encodeIntegers(c.values, c.size, /*bigEndian=*/true)) + "\n";
      } else {
        text += c.text("\n");
      }
      const auto path = test::scratchDir() / "wide.vtk";
      test::writeFile(path, text);
      const Volume v = loadVolume(path.string());
      test::expectWideIntegersKept(v, c);
    }
  }
}

TEST(RawReader, ReadsEachTypeInBothByteOrders) {
  for (SampleType type : kSampleTypes) {
    for (bool big : {false, true}) {
      const auto values = test::testValues(kLegacyDims, type);
      const auto path = test::scratchDir() / "samples.bin";
      test::writeFile(path, test::encodeSamples(values, type, big));
      LoadOptions options;
      options.raw = RawLayout{kLegacyDims, type, {2, 2, 3}, big};
      const Volume v = loadVolume(path.string(), options);
      EXPECT_EQ(v.name, "samples");
      EXPECT_EQ(v.type(), type);
      EXPECT_EQ(v.spacing, glm::dvec3(2, 2, 3));
      EXPECT_EQ(test::floatsOf(v), values) << sampleTypeName(type) << (big ? " big" : " little");
    }
  }
}

}  // namespace
}  // namespace vsil
