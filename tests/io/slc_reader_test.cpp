// VolVis SLC: files written here (both compressions, runs of both kinds, slices with and
// without the closing 0), the classic NegHip against the raw copy made from it independently
// (the datasets' README), and malformed files refused in one line naming the problem.
#include <gtest/gtest.h>

#include "io/volume_loader.h"
#include "io_test_files.h"
#include "reference/test_support.h"

namespace vsil {
namespace {

// An SLC of 3 x 2 x `slices.size()` samples with a 2 x 1 icon; each slice's stored bytes as given,
// after "N X" when run-length coded (`sizeLine` between N and its bytes), alone when not (as
// vtkSLCReader reads them). `header` goes before the magic number's line ends.
std::string writeSlc(const std::string& name, int compression,
                     const std::vector<test::Bytes>& slices, const std::string& sizes = "3 2",
                     const std::string& sizeLine = " X", const std::string& header = "") {
  std::string text = "11111" + header + "\n" + sizes + " " + std::to_string(slices.size()) +
                     " 8\n0.5 1.000000 2.25\n1 6 0 " + std::to_string(compression) + "\n2 1 X" +
                     std::string(6, '\x7f');
  for (const test::Bytes& slice : slices) {
    if (compression != 0) text += std::to_string(slice.size()) + sizeLine;
    text += test::asText(slice);
  }
  const auto path = test::scratchDir() / name;
  test::writeFile(path, text);
  return path.string();
}

TEST(SlcReader, ReadsRawAndRunLengthSlices) {
  const Volume raw =
      loadVolume(writeSlc("raw.slc", 0, {{1, 2, 3, 4, 5, 6}, {7, 8, 9, 10, 11, 12}}));
  EXPECT_EQ(raw.dims, glm::ivec3(3, 2, 2));
  EXPECT_EQ(raw.spacing, glm::dvec3(0.5, 1, 2.25));
  EXPECT_EQ(raw.format, "VolVis SLC");
  EXPECT_EQ(test::floatsOf(raw), (std::vector<float>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}));
  // Slice 0: 3 repeated 9s, then 3 literal bytes, then the closing 0; slice 1: 6 repeated 200s
  // and no closing 0.
  const Volume rle =
      loadVolume(writeSlc("rle.slc", 1, {{0x03, 9, 0x83, 1, 2, 3, 0x00}, {0x06, 200}}));
  EXPECT_EQ(test::floatsOf(rle),
            (std::vector<float>{9, 9, 9, 1, 2, 3, 200, 200, 200, 200, 200, 200}));
  // As fscanf reads "%d X": the X right after the count; a header of 5000 blanks more
  // (whitespace to fscanf).
  const Volume tight = loadVolume(writeSlc("tight.slc", 1, {{0x06, 5}, {0x06, 6}}, "3 2", "X"));
  EXPECT_EQ(test::floatsOf(tight), (std::vector<float>{5, 5, 5, 5, 5, 5, 6, 6, 6, 6, 6, 6}));
  const Volume longHeader = loadVolume(
      writeSlc("long_header.slc", 0, {{1, 2, 3, 4, 5, 6}}, "3 2", " X", std::string(5000, ' ')));
  EXPECT_EQ(test::floatsOf(longHeader), (std::vector<float>{1, 2, 3, 4, 5, 6}));
}

TEST(SlcReader, NegHipIsTheRawCopyWithItsBorder) {
  VSIL_REQUIRE_DATASETS();
  const Volume slc = loadVolume(test::datasetPath("neghip.slc").string());
  const Volume raw = loadVolume(test::datasetPath("neghip_64x64x64_uint8.nhdr").string());
  ASSERT_EQ(slc.dims, glm::ivec3(66));
  for (int z = 0; z < 64; ++z) {
    for (int y = 0; y < 64; ++y) {
      for (int x = 0; x < 64; ++x) {
        ASSERT_EQ(slc.at(x + 1, y + 1, z + 1), raw.at(x, y, z)) << x << " " << y << " " << z;
      }
    }
  }
}

TEST(SlcReader, MalformedFilesAreRefusedNamingTheProblem) {
  struct Bad {
    std::string name;
    int compression;
    std::vector<test::Bytes> slices;
    std::string message;
  };
  const std::vector<Bad> cases = {
      {"overrun.slc", 1, {{0x07, 1}}, "slice 0: decodes to more than the 6 samples of a slice"},
      {"short.slc", 1, {{0x02, 1, 0x00}}, "slice 0: decodes to 2 samples, 6 expected"},
      {"cut_run.slc", 1, {{0x84, 1, 2}}, "slice 0: ends inside a run"},
      {"raw_size.slc", 0, {{1, 2, 3}}, "slice 0 needs 6 bytes, the file holds 3 more"},
      {"compression.slc", 2, {{1, 2, 3, 4, 5, 6}}, "compression 2 is neither 0 (none) nor 1"},
  };
  for (const Bad& bad : cases) {
    const std::string path = writeSlc(bad.name, bad.compression, bad.slices);
    test::expectInputError([&] { loadVolume(path); }, path, {bad.message});
  }
  const std::string bits = writeSlc("bits.slc", 0, {{1, 2, 3, 4, 5, 6}}, "3 2");
  std::string text = test::readFileBytes(bits);
  text.replace(text.find(" 8\n"), 3, " 16\n");
  test::writeFile(bits, text);
  test::expectInputError([&] { loadVolume(bits); }, bits, {"16 bits per voxel: only 8 are read"});
  const std::string trailing = writeSlc("trailing.slc", 0, {{1, 2, 3, 4, 5, 6}});
  test::writeFile(trailing, test::readFileBytes(trailing) + "junk");
  test::expectInputError([&] { loadVolume(trailing); }, trailing,
                         {"holds bytes after its last slice"});
  const std::string cut = writeSlc("cut.slc", 0, {{1, 2, 3, 4, 5, 6}, {1, 2, 3, 4, 5, 6}});
  const std::string whole = test::readFileBytes(cut);
  test::writeFile(cut, whole.substr(0, whole.size() - 2));
  test::expectInputError([&] { loadVolume(cut); }, cut, {"slice 1 needs 6 bytes"});
  // A run-length slice without its "N X" line: said so, without echoing the binary bytes.
  const std::string noSize = writeSlc("no_size.slc", 1, {{0x86, 1, 2, 3, 4, 5, 6}}, "3 2", "");
  std::string bytes = test::readFileBytes(noSize);
  bytes.erase(bytes.size() - 8, 1);  // the "7" of the size line
  test::writeFile(noSize, bytes);
  test::expectInputError([&] { loadVolume(noSize); }, noSize,
                         {"slice 0's size is not a number (\"N X\" expected)"});
  const std::string longHeader =
      writeSlc("longer.slc", 0, {{1, 2, 3, 4, 5, 6}}, "3 2", " X", std::string(70000, ' '));
  test::expectInputError([&] { loadVolume(longHeader); }, longHeader,
                         {"header runs past its first 65536 bytes"});
  // A header whose last number read before the sizes are known (the third spacing) ends
  // exactly at the part's end is read.
  const std::string upTo = "\n3 2 1 8\n0.5 1.000000 2.25";
  const std::string fits = writeSlc("fits.slc", 0, {{1, 2, 3, 4, 5, 6}}, "3 2", " X",
                                    std::string(65536 - 5 - upTo.size(), ' '));
  ASSERT_EQ(test::readFileBytes(fits).find("2.25") + 4, 65536u);
  EXPECT_EQ(loadVolume(fits).dims, glm::ivec3(3, 2, 1));
}

}  // namespace
}  // namespace vsil
