// Bad input gets one-line InputErrors that start with the file's path and say what is wrong:
// truncated and oversized payloads, absurd sizes, broken headers, non-finite samples,
// decompression bombs, missing files, directories, empty files.
#include <unistd.h>

#include <limits>

#include <gtest/gtest.h>

#include "io/volume_loader.h"
#include "io_test_files.h"
#include "reference/test_support.h"

namespace vsil {
namespace {

using test::Bytes;
using test::expectInputError;

// Writes `name` with `text` into a fresh scratch folder and returns its path.
std::string scratchFile(const std::string& name, std::string_view text) {
  const auto path = test::scratchDir() / name;
  test::writeFile(path, text);
  return path.string();
}

std::string nrrdHeader(const std::string& fields) {
  return "NRRD0004\n" + fields + "\n";
}

TEST(InputErrors, DetachedDataFileTooShortSaysBothSizes) {
  const auto dir = test::scratchDir();
  test::writeFile(dir / "x.nhdr", nrrdHeader("type: uint8\ndimension: 3\nsizes: 128 128 128\n"
                                             "encoding: raw\ndata file: x.raw"));
  test::writeFile(dir / "x.raw", Bytes(1000));
  const std::string path = (dir / "x.nhdr").string();
  expectInputError([&] { loadVolume(path); },
                   path +
                       ": data file 'x.raw' holds 1000 bytes, 2097152 expected "
                       "(128x128x128 uint8)",
                   {});
}

TEST(InputErrors, AttachedPayloadTruncatedOrTooLong) {
  const std::string header = nrrdHeader(
                                 "type: uint16\ndimension: 3\nsizes: 4 4 4\n"
                                 "endian: little\nencoding: raw") +
                             "\n";
  const std::string shortPath = scratchFile("short.nrrd", header + std::string(100, 'a'));
  expectInputError([&] { loadVolume(shortPath); }, shortPath + ": ",
                   {"holds 100 bytes, 128 expected (4x4x4 uint16)"});
  const std::string longPath = scratchFile("long.nrrd", header + std::string(129, 'a'));
  expectInputError([&] { loadVolume(longPath); }, longPath + ": ", {"holds 129 bytes, 128"});
}

TEST(InputErrors, RawFileOfTheWrongSize) {
  const std::string path = scratchFile("v.raw", std::string(999, '\0'));
  LoadOptions options;
  options.raw = RawLayout{{10, 10, 10}, SampleType::UInt16, {1, 1, 1}, false};
  expectInputError([&] { loadVolume(path, options); }, path + ": ",
                   {"999 bytes", "2000 expected", "10x10x10 uint16"});
}

TEST(InputErrors, AbsurdDimensionsAreRefusedBeforeAllocating) {
  const std::string nrrd =
      scratchFile("huge.nrrd", nrrdHeader("type: uint8\ndimension: 3\nsizes: 100000 100000 100000\n"
                                          "encoding: raw") +
                                   "\nxx");
  expectInputError([&] { loadVolume(nrrd); }, nrrd + ": ", {"100000", "limit"});

  const std::string vti =
      scratchFile("huge.vti",
                  "<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 99999 0 99999 0 99999\">"
                  "<Piece><PointData><DataArray type=\"UInt8\" format=\"ascii\">1</DataArray>"
                  "</PointData></Piece></ImageData></VTKFile>");
  expectInputError([&] { loadVolume(vti); }, vti + ": ", {"100000", "limit"});

  const std::string vtk = scratchFile("huge.vtk",
                                      "# vtk DataFile Version 3.0\nt\nBINARY\n"
                                      "DATASET STRUCTURED_POINTS\n"
                                      "DIMENSIONS 100000 100000 100000\n"
                                      "POINT_DATA 1\nSCALARS s float\nxxxx");
  expectInputError([&] { loadVolume(vtk); }, vtk + ": ", {"100000", "limit"});

  // With the per-axis limit lifted, the byte count (2^93 bytes) must not overflow unnoticed.
  LoadOptions options;
  options.limits.maxDimension = std::numeric_limits<int>::max();
  options.raw = RawLayout{{2147483647, 2147483647, 2147483647}, SampleType::Float32, {1, 1, 1}};
  const std::string raw = scratchFile("huge.raw", "x");
  expectInputError([&] { loadVolume(raw, options); }, raw + ": ", {"memory limit"});

  // Beyond int: the number itself is out of range.
  const std::string wide = scratchFile(
      "wide.nrrd", nrrdHeader("type: uint8\ndimension: 3\nsizes: 1 1 99999999999999999999\n"
                              "encoding: raw") +
                       "\nx");
  expectInputError([&] { loadVolume(wide); }, wide + ": ", {"sizes", "out of range"});
}

TEST(InputErrors, BadNrrdHeaders) {
  struct Case {
    const char* header;
    const char* says;
  };
  const Case cases[] = {
      {"type: uint8\ndimension: 3\nsizes: 2 2 2\n", "required field 'encoding'"},
      {"dimension: 3\nsizes: 2 2 2\nencoding: raw\n", "required field 'type'"},
      {"type: uint8\ndimension: 2\nsizes: 2 2\nencoding: raw\n", "dimension '2' is not supported"},
      {"type: uint8\ndimension: 3\nsizes: 2 x2 2\nencoding: raw\n", "sizes value 'x2' is not an"},
      {"type: uint8\ndimension: 3\nsizes: 2 2\nencoding: raw\n", "sizes needs 3 values, found 2"},
      {"type: uint8\ndimension: three\nsizes: 2 2 2\nencoding: raw\n", "dimension value 'three'"},
      {"type: block\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n", "type 'block' is not supported"},
      {"type: uint16\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n", "'endian', required"},
      {"type: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: bzip2\n", "encoding 'bzip2'"},
      {"type: uint8\ndimension: 3\nsizes: 2 2 2\nspacings: 1 -1 1\nencoding: raw\n",
       "spacings -1 along y is not a positive"},
      {"type: uint8\ndimension: 3\nsizes: 2 2 2\nspacings: 1 0 1\nencoding: raw\n",
       "is not a positive"},
      {"type: uint8\ndimension: 3\nsizes: 2 2 2\nspacings: 1 nan 1\nencoding: raw\n",
       "is not a positive"},
      {"type: uint8\ndimension: 3\nsizes: 2 2 2\nspace directions: (1,0,0) none (0,0,1)\n"
       "encoding: raw\n",
       "'none' for a spatial axis"},
      {"type: uint8\nthis line is junk\n", "header line 3 'this line is junk' is neither"},
  };
  for (const Case& c : cases) {
    const std::string path = scratchFile("bad.nrrd", nrrdHeader(c.header) + std::string(8, 'x'));
    expectInputError([&] { loadVolume(path); }, path + ": ", {c.says});
  }
  const std::string notNrrd = scratchFile("plain.nrrd", "hello\n");
  expectInputError([&] { loadVolume(notNrrd); }, notNrrd + ": ", {"is not a NRRD file"});
}

TEST(InputErrors, UnknownTypesInEveryFormat) {
  const std::string vti =
      scratchFile("t.vti",
                  "<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 0 0 0 0 0\"><Piece>"
                  "<PointData><DataArray type=\"Bit\" format=\"ascii\">1</DataArray></PointData>"
                  "</Piece></ImageData></VTKFile>");
  expectInputError([&] { loadVolume(vti); }, vti + ": ", {"type 'Bit' is not supported"});
  const std::string vtk = scratchFile("t.vtk",
                                      "# vtk DataFile Version 3.0\nt\nASCII\n"
                                      "DATASET STRUCTURED_POINTS\nDIMENSIONS 1 1 1\n"
                                      "POINT_DATA 1\nSCALARS s long\n1\n");
  expectInputError([&] { loadVolume(vtk); }, vtk + ": ", {"SCALARS type 'long' is not supported"});
}

TEST(InputErrors, NonFiniteFloatsNameTheFirstBadSample) {
  std::vector<float> values(8, 1.0f);
  values[5] = std::numeric_limits<float>::quiet_NaN();
  values[6] = std::numeric_limits<float>::infinity();
  const std::string nan = scratchFile(
      "nan.nrrd", nrrdHeader("type: float\ndimension: 3\nsizes: 2 2 2\nendian: big\n"
                             "encoding: raw") +
                      "\n" + test::asText(test::encodeSamples(values, SampleType::Float32, true)));
  expectInputError([&] { loadVolume(nan); }, nan + ": ", {"sample 5 is NaN"});

  const std::string inf =
      scratchFile("inf.vti",
                  "<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 2 0 0 0 0\"><Piece>"
                  "<PointData><DataArray type=\"Float32\" format=\"ascii\">1 -inf 2</DataArray>"
                  "</PointData></Piece></ImageData></VTKFile>");
  expectInputError([&] { loadVolume(inf); }, inf + ": ", {"sample 1 is infinite"});

  const std::string big =
      scratchFile("big.vtk",
                  "# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\n"
                  "DIMENSIONS 2 1 1\nPOINT_DATA 2\nSCALARS s double\n0 1e300\n");
  expectInputError([&] { loadVolume(big); }, big + ": ", {"sample 1", "float32 range"});

  const std::string ascii =
      scratchFile("a.vtk",
                  "# vtk DataFile Version 3.0\nt\nASCII\nDATASET STRUCTURED_POINTS\n"
                  "DIMENSIONS 3 1 1\nPOINT_DATA 3\nSCALARS s unsigned_char\n1 256 2\n");
  expectInputError([&] { loadVolume(ascii); }, ascii + ": ", {"sample 1 '256' is not a uint8"});
}

TEST(InputErrors, GzipBombsStopAtTheExpectedSize) {
  const std::string header = nrrdHeader("type: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: gzip");
  // 1 MiB of zeros packs into ~1 KiB: small enough to be read, then stopped by the inflater.
  const Bytes bomb = test::deflateBytes(Bytes(1 << 20), true);
  const std::string small = scratchFile("bomb.nrrd", header + "\n" + test::asText(bomb));
  expectInputError([&] { loadVolume(small); }, small + ": ",
                   {"inflates to more than the 64 bytes expected"});
  // 64 MiB of zeros packs into ~64 KiB: stopped alike, at the first byte beyond the samples
  // (the payload's size is not bounded before: padding may follow a stream, round 13).
  const Bytes bigBomb = test::deflateBytes(Bytes(64 << 20), true);
  const std::string large = scratchFile("bigbomb.nrrd", header + "\n" + test::asText(bigBomb));
  expectInputError([&] { loadVolume(large); }, large + ": ",
                   {"inflates to more than the 64 bytes expected"});
  // 10240 NUL bytes of padding after a 64-byte stream (gzip and Python read it): read.
  const std::string padded = scratchFile(
      "padded.nrrd", header + "\n" + test::asText(test::deflateBytes(Bytes(64, 3), true)) +
                         std::string(10240, '\0'));
  EXPECT_EQ(loadVolume(padded).dims, glm::ivec3(4));
  // A blank between two members ends the stream (gzip refuses it too): said.
  const std::string blank = scratchFile(
      "blank.nrrd", header + "\n" + test::asText(test::deflateBytes(Bytes(10, 3), true)) + "\n" +
                        test::asText(test::deflateBytes(Bytes(54, 3), true)));
  expectInputError([&] { loadVolume(blank); }, blank + ": ",
                   {"inflates to 10 bytes, 64 expected (bytes follow its end that are not another "
                    "gzip member)"});
  // Too little, corrupt, or not gzip at all.
  const Bytes few = test::deflateBytes(Bytes(10), true);
  const std::string shortPath = scratchFile("few.nrrd", header + "\n" + test::asText(few));
  expectInputError([&] { loadVolume(shortPath); }, shortPath + ": ",
                   {"inflates to 10 bytes, 64 expected"});
  Bytes cut = test::deflateBytes(Bytes(64, 7), true);
  cut.resize(cut.size() / 2);
  const std::string cutPath = scratchFile("cut.nrrd", header + "\n" + test::asText(cut));
  expectInputError([&] { loadVolume(cutPath); }, cutPath + ": ", {"truncated"});
  const std::string junk = scratchFile("junk.nrrd", header + "\n" + std::string(64, 'j'));
  expectInputError([&] { loadVolume(junk); }, junk + ": ", {"corrupt"});
}

TEST(InputErrors, TinyFilesClaimingHugeVolumesAllocateNothing) {
  // 1024³ samples from a few bytes: refused by size checks before any sample buffer exists.
  const std::string gz =
      scratchFile("tiny.nrrd", nrrdHeader("type: uint8\ndimension: 3\nsizes: 1024 1024 1024\n"
                                          "encoding: gzip") +
                                   "\n" + test::asText(test::deflateBytes({1}, true)));
  expectInputError([&] { loadVolume(gz); }, gz + ": ", {"cannot inflate to the 1073741824 bytes"});
  const std::string ascii =
      scratchFile("tiny.vti",
                  "<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 1023 0 1023 0 1023\">"
                  "<Piece><PointData><DataArray type=\"UInt8\" format=\"ascii\">1 2 3</DataArray>"
                  "</PointData></Piece></ImageData></VTKFile>");
  expectInputError([&] { loadVolume(ascii); }, ascii + ": ", {"too few for 1073741824 values"});
  Bytes header;
  for (std::uint64_t word : {1ull, 1ull << 30, 0ull, 8ull})
    test::appendWord(header, word, 8, false);
  const std::string zlib =
      scratchFile("tiny64.vti",
                  "<VTKFile type=\"ImageData\" header_type=\"UInt64\" "
                  "compressor=\"vtkZLibDataCompressor\"><ImageData WholeExtent=\"0 1023 0 1023 "
                  "0 1023\"><Piece><PointData><DataArray type=\"UInt8\" format=\"appended\" "
                  "offset=\"0\"/></PointData></Piece></ImageData><AppendedData>_" +
                      test::asText(header) + "12345678</AppendedData></VTKFile>");
  expectInputError([&] { loadVolume(zlib); }, zlib + ": ", {"cannot inflate"});
}

TEST(InputErrors, ZlibBlockBombInVti) {
  // The block table claims one 8-byte block; the block inflates to 1 MiB.
  const Bytes packed = test::deflateBytes(Bytes(1 << 20), false);
  Bytes block;
  for (std::uint64_t word :
       {std::uint64_t(1), std::uint64_t(8), std::uint64_t(0), std::uint64_t(packed.size())}) {
    test::appendWord(block, word, 4, false);
  }
  block.insert(block.end(), packed.begin(), packed.end());
  const std::string path =
      scratchFile("bomb.vti",
                  "<VTKFile type=\"ImageData\" compressor=\"vtkZLibDataCompressor\">"
                  "<ImageData WholeExtent=\"0 1 0 1 0 1\"><Piece><PointData>"
                  "<DataArray type=\"UInt8\" format=\"appended\" offset=\"0\"/></PointData>"
                  "</Piece></ImageData><AppendedData encoding=\"raw\">_" +
                      test::asText(block) + "</AppendedData></VTKFile>");
  expectInputError([&] { loadVolume(path); }, path + ": ",
                   {"zlib block 0 inflates to more than the 8 bytes expected"});
}

// The zlib blocks of a VTI are inflated on every core at once; whatever the threads meet, the
// error is the one reading block by block meets first: the lowest broken block's.
TEST(InputErrors, ParallelZlibBlocksReportTheFirstBrokenBlock) {
  // 32 blocks of 64 bytes (uint8 samples, 8x16x16).
  const std::size_t blockSize = 64, blocks = 32;
  std::vector<Bytes> packed;
  for (std::size_t b = 0; b < blocks; ++b)
    packed.push_back(test::deflateBytes(Bytes(blockSize, std::uint8_t(b)), false));
  auto file = [&](const std::vector<Bytes>& data, std::size_t claimedLastBlock) {
    Bytes block;
    for (std::uint64_t word : {std::uint64_t(blocks), std::uint64_t(blockSize), std::uint64_t(0)}) {
      test::appendWord(block, word, 4, false);
    }
    for (std::size_t b = 0; b < blocks; ++b) {
      test::appendWord(block, b + 1 == blocks ? claimedLastBlock : data[b].size(), 4, false);
    }
    for (const Bytes& d : data) block.insert(block.end(), d.begin(), d.end());
    return scratchFile("blocks.vti",
                       "<VTKFile type=\"ImageData\" header_type=\"UInt32\" "
                       "compressor=\"vtkZLibDataCompressor\"><ImageData WholeExtent=\"0 7 0 15 0 "
                       "15\"><Piece><PointData><DataArray type=\"UInt8\" format=\"appended\" "
                       "offset=\"0\"/></PointData></Piece></ImageData><AppendedData "
                       "encoding=\"raw\">_" +
                           test::asText(block));
  };
  std::vector<Bytes> data = packed;
  const std::string good = file(data, data.back().size());
  const Volume volume = loadVolume(good);
  for (std::size_t b = 0; b < blocks; ++b) ASSERT_EQ(volume.value(b * blockSize + 5), float(b));
  // Corrupt blocks 29, 17 and 6 (in that order: the lowest is not the first one written).
  for (std::size_t b : {29u, 17u, 6u}) {
    data[b][data[b].size() / 2] ^= 0xff;
    data[b][2] ^= 0x55;
  }
  for (int run = 0; run < 5; ++run) {
    const std::string path = file(data, data.back().size());
    expectInputError([&] { loadVolume(path); }, path + ": zlib block 6 ", {});
  }
  // A last block claiming more bytes than the file holds: reported after the blocks before it.
  const std::string truncated = file(packed, packed.back().size() + 1000);
  expectInputError([&] { loadVolume(truncated); }, truncated + ": zlib block 31 is truncated", {});
  data = packed;
  data[3][2] ^= 0x55;
  const std::string both = file(data, data.back().size() + 1000);
  expectInputError([&] { loadVolume(both); }, both + ": zlib block 3 ", {});
}

TEST(InputErrors, BrokenVtiFiles) {
  const std::string head =
      "<VTKFile type=\"ImageData\" header_type=\"UInt32\">"
      "<ImageData WholeExtent=\"0 1 0 1 0 1\"><Piece><PointData>";
  const std::string tail = "</PointData></Piece></ImageData>";
  struct Case {
    std::string body;
    const char* says;
  };
  const Case cases[] = {
      {"<VTKFile type=\"ImageData\"><ImageData", "is not valid XML"},
      {"<VTKFile type=\"PolyData\"/>", "only ImageData"},
      {head + "</PointData></Piece></ImageData></VTKFile>", "has no <DataArray>"},
      {head + "<DataArray type=\"UInt8\" format=\"ascii\">1    2    3    </DataArray>" + tail +
           "</VTKFile>",
       "holds 3 values, 8 expected"},
      {head + "<DataArray type=\"UInt8\" format=\"binary\">CAAAAA==AQID</DataArray>" + tail +
           "</VTKFile>",
       "DataArray holds 3 bytes, 8 expected"},
      {head + "<DataArray type=\"UInt8\" format=\"binary\">AQ!D</DataArray>" + tail + "</VTKFile>",
       "invalid character"},
      {head + "<DataArray type=\"UInt8\" format=\"appended\" offset=\"999\"/>" + tail +
           "<AppendedData encoding=\"raw\">_abc</AppendedData></VTKFile>",
       "offset 999 lies outside"},
      {head + "<DataArray type=\"UInt8\" format=\"appended\" offset=\"0\"/>" + tail + "</VTKFile>",
       "has no <AppendedData>"},
      {head + "<DataArray type=\"UInt8\" format=\"appended\" offset=\"0\"/>" + tail +
           "<AppendedData encoding=\"raw\">_ab",  // the file ends inside the header
       "block header is truncated"},
      {head + "<DataArray type=\"UInt8\" NumberOfComponents=\"3\" format=\"ascii\">1</DataArray>" +
           tail + "</VTKFile>",
       "only scalar"},
  };
  for (const Case& c : cases) {
    const std::string path = scratchFile("broken.vti", c.body);
    expectInputError([&] { loadVolume(path); }, path + ": ", {c.says});
  }
}

TEST(InputErrors, BrokenLegacyVtkFiles) {
  const std::string head = "# vtk DataFile Version 3.0\ntitle\nBINARY\nDATASET STRUCTURED_POINTS\n";
  struct Case {
    std::string body;
    const char* says;
  };
  const Case cases[] = {
      {"hello\n", "is not a legacy VTK file"},
      {head + "DIMENSIONS 2 2 2\nPOINT_DATA 8\nSCALARS s unsigned_char\nLOOKUP_TABLE default\n"
              "abc",
       "payload holds 3 bytes, 8 expected (2x2x2 uint8)"},
      {head + "DIMENSIONS 2 2 2\nPOINT_DATA 9\nSCALARS s unsigned_char\nabcdefghi",
       "POINT_DATA 9 differs from 8"},
      {"# vtk DataFile Version 3.0\nt\nBINARY\nDATASET POLYDATA\n", "STRUCTURED_POINTS only"},
      {head + "DIMENSIONS 2 2\n", "DIMENSIONS needs 3 values"},
      {head + "DIMENSIONS 2 2 2\nSPACING 1 1 0\n", "is not a positive"},
      {head + "DIMENSIONS 2 2 2\n", "header ends before the SCALARS data"},
  };
  for (const Case& c : cases) {
    const std::string path = scratchFile("broken.vtk", c.body);
    expectInputError([&] { loadVolume(path); }, path + ": ", {c.says});
  }
}

TEST(InputErrors, MissingDataFileNamesHeaderAndDataFile) {
  const std::string path =
      scratchFile("m.nhdr", nrrdHeader("type: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n"
                                       "data file: missing.raw"));
  expectInputError([&] { loadVolume(path); },
                   path + ": data file 'missing.raw': ", {"missing.raw: no such file"});
}

TEST(InputErrors, MissingFilesDirectoriesEmptyAndUnreadableFiles) {
  const auto dir = test::scratchDir();
  const std::string missing = (dir / "nothing.vti").string();
  expectInputError([&] { loadVolume(missing); }, missing + ": no such file", {});
  const std::string missingUnknown = (dir / "nothing.xyz").string();
  expectInputError([&] { loadVolume(missingUnknown); }, missingUnknown + ": no such file", {});

  std::filesystem::create_directories(dir / "folder.nrrd");
  const std::string folder = (dir / "folder.nrrd").string();
  expectInputError([&] { loadVolume(folder); }, folder + ": is a directory", {});
  // A folder without an extension is read as a DICOM series.
  expectInputError([&] { loadVolume(dir.string()); },
                   dir.string() + ": is a folder without files (a DICOM series", {});

  for (const char* name : {"empty.nrrd", "empty.vti", "empty.vtk"}) {
    const std::string empty = (dir / name).string();
    test::writeFile(empty, "");
    expectInputError([&] { loadVolume(empty); }, empty + ": file is empty", {});
  }

  const std::string locked = (dir / "locked.nrrd").string();
  test::writeFile(locked, "NRRD0004\n");
  std::filesystem::permissions(locked, std::filesystem::perms::none);
  if (::geteuid() != 0) {  // root reads anything
    expectInputError([&] { loadVolume(locked); }, locked + ": cannot be opened", {});
  }
}

TEST(InputErrors, UnknownExtensionListsTheFormats) {
  const std::string path = scratchFile("volume.dat", "1234");
  expectInputError([&] { loadVolume(path); }, path + ": unknown volume format '.dat'",
                   {".nrrd, .nhdr, .vti, .vtk", "--dims and --type"});
}

}  // namespace
}  // namespace vsil
