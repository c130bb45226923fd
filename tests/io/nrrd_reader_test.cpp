// NRRD round trips: files written here (every type, raw and gzip, attached and detached, both
// byte orders) read back exactly, and header variants (aliases, space directions, byte skip).
#include <gtest/gtest.h>

#include "io/volume_loader.h"
#include "io_test_files.h"
#include "reference/test_support.h"

namespace vsil {
namespace {

using test::Bytes;

const glm::ivec3 kDims{5, 4, 3};

struct NrrdCase {
  SampleType type;
  const char* typeName;  // as written in the header (NRRD spelling or alias)
  bool gzip;
  bool detached;
  bool bigEndian;
};

std::string caseName(const NrrdCase& c) {
  return std::string(sampleTypeName(c.type)) + (c.gzip ? "_gzip" : "_raw") +
         (c.detached ? "_detached" : "_attached") + (c.bigEndian ? "_big" : "_little");
}

// Writes the case's file(s) into `dir` and returns the path to load.
std::string writeNrrd(const std::filesystem::path& dir, const NrrdCase& c, const Bytes& samples) {
  const Bytes payload = c.gzip ? test::deflateBytes(samples, true) : samples;
  std::string header = "NRRD0004\n# written by nrrd_reader_test\ntype: " + std::string(c.typeName) +
                       "\ndimension: 3\nsizes: 5 4 3\nspacings: 0.5 1 2.25\nendian: " +
                       (c.bigEndian ? "big" : "little") +
                       "\nencoding: " + (c.gzip ? "gzip" : "raw") + "\n";
  if (c.detached) {
    header += "data file: payload.bin\n";
    test::writeFile(dir / "volume.nhdr", header);
    test::writeFile(dir / "payload.bin", payload);
    return (dir / "volume.nhdr").string();
  }
  test::writeFile(dir / "volume.nrrd", header + "\n" + test::asText(payload));
  return (dir / "volume.nrrd").string();
}

class NrrdRoundTrip : public ::testing::TestWithParam<NrrdCase> {};

TEST_P(NrrdRoundTrip, ReadsBackTheWrittenSamples) {
  const NrrdCase& c = GetParam();
  const auto values = test::testValues(kDims, c.type);
  const std::string path =
      writeNrrd(test::scratchDir(), c, test::encodeSamples(values, c.type, c.bigEndian));
  const Volume volume = loadVolume(path);
  EXPECT_EQ(volume.name, "volume");
  EXPECT_EQ(volume.dims, kDims);
  EXPECT_EQ(volume.spacing, glm::dvec3(0.5, 1, 2.25));
  EXPECT_EQ(volume.type(), c.type);
  EXPECT_EQ(test::floatsOf(volume),
            values);  // exact: every test value is representable in its type
}

std::vector<NrrdCase> allCases() {
  const std::pair<SampleType, const char*> types[] = {{SampleType::UInt8, "uint8"},
                                                      {SampleType::Int8, "int8"},
                                                      {SampleType::UInt16, "uint16"},
                                                      {SampleType::Int16, "int16"},
                                                      {SampleType::Float32, "float"}};
  std::vector<NrrdCase> cases;
  for (const auto& [type, name] : types) {
    for (bool gzip : {false, true}) {
      for (bool detached : {false, true}) {
        for (bool big : {false, true}) cases.push_back({type, name, gzip, detached, big});
      }
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Nrrd, NrrdRoundTrip, ::testing::ValuesIn(allCases()),
                         [](const auto& info) { return caseName(info.param); });

Volume loadAttached(const std::string& headerFields, const Bytes& payload) {
  const auto path = test::scratchDir() / "v.nrrd";
  test::writeFile(
      path, "NRRD0005\ndimension: 3\nsizes: 2 2 1\n" + headerFields + "\n" + test::asText(payload));
  return loadVolume(path.string());
}

TEST(NrrdReader, AcceptsTypeAliases) {
  const std::pair<const char*, SampleType> aliases[] = {{"uchar", SampleType::UInt8},
                                                        {"unsigned char", SampleType::UInt8},
                                                        {"uint8_t", SampleType::UInt8},
                                                        {"ushort", SampleType::UInt16},
                                                        {"unsigned short int", SampleType::UInt16},
                                                        {"short", SampleType::Int16},
                                                        {"int16_t", SampleType::Int16},
                                                        {"float", SampleType::Float32}};
  for (const auto& [alias, type] : aliases) {
    const std::vector<float> values{1, 2, 3, 4};
    const Volume v =
        loadAttached(std::string("type: ") + alias + "\nendian: little\nencoding: raw\n",
                     test::encodeSamples(values, type, false));
    EXPECT_EQ(v.type(), type) << alias;
    EXPECT_EQ(test::floatsOf(v), values) << alias;
  }
}

// int8 is kept as int8 (it loaded as int16 before samples kept their file's type); float64 is
// kept as float32, the values that float32 rounds counted.
TEST(NrrdReader, Int8StaysInt8AndDoubleLoadsAsFloat32) {
  const Volume int8 = loadAttached("type: signed char\nencoding: raw\n", {0x00, 0x7f, 0x80, 0xff});
  EXPECT_EQ(int8.type(), SampleType::Int8);
  EXPECT_EQ(int8.fileType, "");
  EXPECT_EQ(test::floatsOf(int8), (std::vector<float>{0, 127, -128, -1}));

  Bytes doubles;
  for (double d : {0.5, -2.0, 1e10, 0.1}) {
    std::uint64_t bits;
    std::memcpy(&bits, &d, 8);
    test::appendWord(doubles, bits, 8, false);
  }
  const Volume f64 = loadAttached("type: double\nendian: little\nencoding: raw\n", doubles);
  EXPECT_EQ(f64.type(), SampleType::Float32);
  EXPECT_EQ(test::floatsOf(f64), (std::vector<float>{0.5f, -2.0f, 1e10f, 0.1f}));
  EXPECT_EQ(f64.fileType, "float64");
  EXPECT_EQ(f64.inexactSamples, 1u);  // 0.1; the others are exact in float32
}

// The 32- and 64-bit integers (NRRD's int, uint, longlong, ulonglong and their aliases), raw
// in either byte order, gzip and ascii, are kept as float32 as the other readers keep them:
// exact up to 2^24, the samples float32 changes counted, the file's type reported.
TEST(NrrdReader, WideIntegersConvertToFloat32CountingRoundedSamples) {
  const test::WideIntegerCase cases[] = {
      {"int",
       "int32",
       4,
       {-5, 16777216, 16777217, 2147483647},
       {-5, 16777216, 16777216, 0x1p31f},
       2},
      {"unsigned int", "uint32", 4, {0, 4294967295, 255, 16777215}, {0, 0x1p32f, 255, 16777215}, 1},
      {"longlong", "int64", 8, {-1, -7, 16777217, 3}, {-1, -7, 16777216, 3}, 1},
      {"uint64_t", "uint64", 8, {3, 9, 16777218, 0}, {3, 9, 16777218, 0}, 0},
  };
  for (const test::WideIntegerCase& c : cases) {
    for (const char* encoding : {"raw", "gzip", "ascii"}) {
      for (bool big : {false, true}) {
        SCOPED_TRACE(std::string(c.type) + " " + encoding + (big ? " big-endian" : ""));
        const Bytes data = test::encodeIntegers(c.values, c.size, big);
        Bytes payload = data;
        if (std::string(encoding) == "gzip") payload = test::deflateBytes(data, true);
        if (std::string(encoding) == "ascii") {
          const std::string text = c.text(" ");
          payload = Bytes(text.begin(), text.end());
        }
        const Volume v =
            loadAttached(std::string("type: ") + c.type + "\nendian: " + (big ? "big" : "little") +
                             "\nencoding: " + encoding + "\n",
                         payload);
        test::expectWideIntegersKept(v, c);
      }
    }
  }
}

TEST(NrrdReader, SpacingIsTheLengthOfEachSpaceDirection) {
  const Volume v = loadAttached(
      "type: uint8\nencoding: raw\nspace: right-anterior-superior\n"
      "space directions: (0.5,0,0) (0,3,4) (0,0,-2)\n",
      {1, 2, 3, 4});
  // 3-4-5 triangle: exact in double.
  EXPECT_EQ(v.spacing, glm::dvec3(0.5, 5.0, 2.0));
}

// An anatomical space with space directions places the volume (recorded, not applied): each
// index axis named by the direction it runs most along; other spaces place nothing.
TEST(NrrdReader, AnAnatomicalSpaceIsRecordedAsThePlacement) {
  const Volume v = loadAttached(
      "type: uint8\nencoding: raw\nspace: left-posterior-superior\n"
      "space directions: (0,0.5,0) (-2,0,0.1) (0,0,3)\nspace origin: (10,-20,30.5)\n",
      {1, 2, 3, 4});
  ASSERT_EQ(v.orientations.size(), 1u);
  const Orientation& o = v.orientations.front();
  EXPECT_EQ(o.name, "space");
  EXPECT_EQ(o.space, "LPS");
  EXPECT_EQ(o.axes, "PRS");  // +i along +y (Posterior), +j along -x (Right), +k Superior
  EXPECT_EQ(o.worldFromIndex * glm::dvec4(1, 1, 1, 1), glm::dvec4(8, -19.5, 33.6, 1));
  // The short name with time, and RAS: the same letters mean the same directions.
  const Volume ras = loadAttached(
      "type: uint8\nencoding: raw\nspace: RAST\nspace directions: (1,0,0) (0,0,-1) (0,1,0)\n",
      {1, 2, 3, 4});
  ASSERT_EQ(ras.orientations.size(), 1u);
  EXPECT_EQ(ras.orientations.front().axes, "RIA");
  // A placement's origin must be a point.
  const auto path = (test::scratchDir() / "v.nrrd").string();
  test::expectInputError(
      [&] {
        loadAttached(
            "type: uint8\nencoding: raw\nspace: LPS\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n"
            "space origin: (nan,0,0)\n",
            {1, 2, 3, 4});
      },
      path, {"space origin '(nan,0,0)' is not finite"});
  for (const char* none : {"space: scanner-xyz\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n",
                           "space: left-posterior-superior\nspacings: 1 1 1\n", ""}) {
    EXPECT_TRUE(loadAttached(std::string("type: uint8\nencoding: raw\n") + none, {1, 2, 3, 4})
                    .orientations.empty())
        << none;
  }
}

// What the format allows for the axes reads: spatial kinds, and one unit, quoted, for all three
// (units may hold blanks).
TEST(NrrdReader, SpatialKindsAndOneQuotedUnitRead) {
  const Volume v = loadAttached(
      "type: uint8\nencoding: raw\nkinds: domain space ???\nspace dimension: 3\n"
      "space units: \"milli meter\" \"milli meter\"  \"milli meter\"\n",
      {1, 2, 3, 4});
  EXPECT_EQ(test::floatsOf(v), (std::vector<float>{1, 2, 3, 4}));
}

TEST(NrrdReader, AsciiEncodingAndByteSkip) {
  const Volume text = loadAttached("type: short\nencoding: ascii\n",
                                   test::Bytes{'1', ' ', '-', '2', '\n', '3', ' ', '4'});
  EXPECT_EQ(test::floatsOf(text), (std::vector<float>{1, -2, 3, 4}));
  const Volume skipped =
      loadAttached("type: uint8\nencoding: raw\nbyte skip: 3\n", {9, 9, 9, 1, 2, 3, 4});
  EXPECT_EQ(test::floatsOf(skipped), (std::vector<float>{1, 2, 3, 4}));
  const Volume fromEnd =
      loadAttached("type: uint8\nencoding: raw\nbyte skip: -1\n", {9, 9, 1, 2, 3, 4});
  EXPECT_EQ(test::floatsOf(fromEnd), (std::vector<float>{1, 2, 3, 4}));
}

// A gzip payload of several members (`cat a.gz b.gz`) is read whole, as gzip reads it; padding
// may follow the last member, anything else may not.
TEST(NrrdReader, GzipPayloadOfSeveralMembers) {
  test::Bytes twoMembers = test::deflateBytes({1, 2}, true);
  const test::Bytes second = test::deflateBytes({3, 4}, true);
  twoMembers.insert(twoMembers.end(), second.begin(), second.end());
  EXPECT_EQ(test::floatsOf(loadAttached("type: uint8\nencoding: gzip\n", twoMembers)),
            (std::vector<float>{1, 2, 3, 4}));
  test::Bytes padded = twoMembers;
  padded.insert(padded.end(), {0, 0, '\n'});
  EXPECT_EQ(test::floatsOf(loadAttached("type: uint8\nencoding: gzip\n", padded)),
            (std::vector<float>{1, 2, 3, 4}));
  test::Bytes paddedBetween = test::deflateBytes({1, 2}, true);
  paddedBetween.insert(paddedBetween.end(), {0, 0, 0});
  paddedBetween.insert(paddedBetween.end(), second.begin(), second.end());
  EXPECT_EQ(test::floatsOf(loadAttached("type: uint8\nencoding: gzip\n", paddedBetween)),
            (std::vector<float>{1, 2, 3, 4}))
      << "NUL padding between members";
  for (const test::Bytes& after : {test::Bytes{'J', 'U', 'N', 'K'}, test::Bytes{0x1f, 'X', 'Y'}}) {
    test::Bytes junk = twoMembers;
    junk.insert(junk.end(), after.begin(), after.end());
    test::expectInputError([&] { loadAttached("type: uint8\nencoding: gzip\n", junk); },
                           (test::scratchDir() / "v.nrrd").string(),
                           {"is followed by bytes that are not part of it"});
  }
  test::Bytes junk = twoMembers;
  junk.insert(junk.end(), {'J', 'U', 'N', 'K'});
  test::expectInputError([&] { loadAttached("type: uint8\nencoding: gzip\n", junk); },
                         (test::scratchDir() / "v.nrrd").string(),
                         {"is followed by bytes that are not part of it"});
  const test::Bytes oneMore = test::deflateBytes({5}, true);
  test::Bytes tooLong = twoMembers;
  tooLong.insert(tooLong.end(), oneMore.begin(), oneMore.end());
  test::expectInputError([&] { loadAttached("type: uint8\nencoding: gzip\n", tooLong); },
                         (test::scratchDir() / "v.nrrd").string(),
                         {"inflates to more than the 4 bytes expected"});
}

TEST(NrrdReader, CrLfHeadersAndKeyValuePairs) {
  const auto path = test::scratchDir() / "crlf.nrrd";
  test::writeFile(path, std::string("NRRD0004\r\ntype: uint8\r\nmodality:=CT\r\ndimension: 3\r\n"
                                    "sizes: 2 1 1\r\nencoding: raw\r\n\r\n") +
                            "\x05\x06");
  EXPECT_EQ(test::floatsOf(loadVolume(path.string())), (std::vector<float>{5, 6}));
}

}  // namespace
}  // namespace vsil
