// Every classic volume in ../shared/datasets loads with the right size, spacing and samples.
//
// The expected checksums were computed once, independently of vsil, with python3 and its zlib
// module on the files' voxel payloads: raw files whole; tooth.nrrd after its blank header line;
// ironProt.vtk the 68³ bytes after "LOOKUP_TABLE default\n"; the .vti files by inflating their
// appended zlib blocks (UInt64 header: #blocks, block size, last size, compressed sizes).
// "sum" is the sum of the uint8 values, "fnv" the 64-bit FNV-1a hash of the uint8 bytes.
#include <cctype>
#include <cstdint>
#include <filesystem>

#include <gtest/gtest.h>

#include "io/volume_loader.h"
#include "reference/test_support.h"

namespace vsil {
namespace {

struct Dataset {
  const char* file;
  const char* name;
  glm::ivec3 dims;
  glm::dvec3 spacing;
  std::uint64_t sum;
  std::uint64_t fnv;
};

void PrintTo(const Dataset& dataset, std::ostream* out) {
  *out << dataset.file;
}

std::uint64_t fnv1a64(const std::vector<float>& samples) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (float value : samples) {
    hash ^= std::uint8_t(value);
    hash *= 0x100000001b3ull;
  }
  return hash;
}

class ClassicDataset : public ::testing::TestWithParam<Dataset> {};

TEST_P(ClassicDataset, LoadsWithKnownSizeSpacingAndChecksum) {
  VSIL_REQUIRE_DATASETS();
  const Dataset& expected = GetParam();
  const auto path = test::datasetPath(expected.file);
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " is missing (VSIL_SHARED_DIR?)";
  const Volume volume = loadVolume(path.string());
  EXPECT_EQ(volume.name, expected.name);
  EXPECT_EQ(volume.source, path.string());
  EXPECT_EQ(volume.dims, expected.dims);
  EXPECT_EQ(volume.spacing, expected.spacing);  // exact: parsed from short decimal text
  EXPECT_EQ(volume.type, SampleType::UInt8);
  ASSERT_EQ(volume.samples.size(), volume.voxelCount());
  std::uint64_t sum = 0;
  for (float value : volume.samples) {
    ASSERT_TRUE(value >= 0.0f && value <= 255.0f && value == float(int(value))) << value;
    sum += std::uint64_t(value);
  }
  EXPECT_EQ(sum, expected.sum);
  EXPECT_EQ(fnv1a64(volume.samples), expected.fnv);
}

const Dataset kDatasets[] = {
    {"bucky_32x32x32_uint8.nhdr",
     "bucky_32x32x32_uint8",
     {32, 32, 32},
     {1, 1, 1},
     1174726,
     0x55073a879f08e1b5},
    {"hydrogen_atom_128x128x128_uint8.nhdr",
     "hydrogen_atom_128x128x128_uint8",
     {128, 128, 128},
     {1, 1, 1},
     5990975,
     0xfb63a8a44417fee8},
    {"neghip_64x64x64_uint8.nhdr",
     "neghip_64x64x64_uint8",
     {64, 64, 64},
     {1, 1, 1},
     4824177,
     0xb5fec7e00603bb50},
    {"nucleon_41x41x41_uint8.nhdr",
     "nucleon_41x41x41_uint8",
     {41, 41, 41},
     {1, 1, 1},
     2715326,
     0x48c0fbc54cbce7ab},
    {"teddybear_128x128x62_uint8.nhdr",
     "teddybear_128x128x62_uint8",
     {128, 128, 62},
     {2.8, 2.8, 5},
     54734849,
     0x375087234365eb00},
    {"tooth.nrrd", "tooth", {103, 94, 161}, {1, 1, 1}, 160814065, 0xf366aa35354c12a6},
    {"ironProt.vtk", "ironProt", {68, 68, 68}, {1, 1, 1}, 4131089, 0x246a9b3b9787c4b2},
    {"engine.vti", "engine", {256, 256, 128}, {1, 1, 1}, 187475057, 0x025df58ee211ac06},
    {"bonsai.vti", "bonsai", {256, 256, 256}, {1, 1, 1}, 230038784, 0xf4977e02015e471f},
    {"aneurism.vti", "aneurism", {256, 256, 256}, {1, 1, 1}, 17938365, 0xea40d0365da79082},
};

INSTANTIATE_TEST_SUITE_P(Datasets, ClassicDataset, ::testing::ValuesIn(kDatasets),
                         [](const auto& info) {
                           std::string name = info.param.name;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

TEST(ClassicDatasets, RawFileWithExplicitLayoutMatchesItsNrrdHeader) {
  VSIL_REQUIRE_DATASETS();
  const auto raw = test::datasetPath("nucleon_41x41x41_uint8.raw").string();
  LoadOptions options;
  options.raw = RawLayout{{41, 41, 41}, SampleType::UInt8, {1, 1, 1}, false};
  const Volume fromRaw = loadVolume(raw, options);
  const Volume fromNrrd = loadVolume(test::datasetPath("nucleon_41x41x41_uint8.nhdr").string());
  EXPECT_EQ(fromRaw.name, "nucleon_41x41x41_uint8");
  EXPECT_TRUE(fromRaw.samples == fromNrrd.samples);
}

}  // namespace
}  // namespace vsil
