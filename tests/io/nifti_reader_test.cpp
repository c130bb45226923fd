// NIfTI (.nii, .nii.gz, .hdr/.img): the committed fixtures of tests/io/nifti/, written by
// nibabel (make_fixtures.py: every integer and float datatype, NIfTI-1 and NIfTI-2, gzip, header
// and image pairs, both byte orders, scl_slope/scl_inter) with the values a reader must find,
// the orientations recorded, --crop/--stride through gzip, and the errors for hostile headers.
#include <cstdint>
#include <cstring>

#include <gtest/gtest.h>

#include "io/volume_loader.h"
#include "io_test_files.h"
#include "reference/test_support.h"

namespace vsil {
namespace {

namespace fs = std::filesystem;
using test::Bytes;

const fs::path kNiftiFixtures = fs::path(VSIL_SOURCE_DIR) / "tests" / "io" / "nifti";

// fixtures.txt's lines end with the format vsil names (spaces as _) and the sform's axes.
std::vector<test::FixtureExpectation> niftiFixtures() {
  return test::readFixtureManifest(kNiftiFixtures / "fixtures.txt");
}

class NiftiFixtureRead : public ::testing::TestWithParam<test::FixtureExpectation> {};

TEST_P(NiftiFixtureRead, FindsTheWrittenSamplesAndPlacement) {
  const test::FixtureExpectation& f = GetParam();
  ASSERT_EQ(f.rest.size(), 2u);
  std::string format = f.rest[0];
  for (char& c : format) c = c == '_' ? ' ' : c;
  const std::string& axes = f.rest[1];
  const Volume volume = loadVolume((kNiftiFixtures / f.file).string());
  test::expectFixtureRead(volume, f);
  EXPECT_EQ(volume.warnings.size(), f.inexact ? 1u : 0u);
  EXPECT_EQ(volume.format, format);
  // nibabel wrote the same affine as qform (scanner) and sform (MNI): x flipped, origin 10,-20,30.
  ASSERT_EQ(volume.orientations.size(), 2u);
  EXPECT_EQ(volume.orientations[0].name, "qform");
  EXPECT_EQ(volume.orientations[1].name, "sform");
  EXPECT_EQ(volume.orientations[1].space, "MNI_152");
  for (const Orientation& o : volume.orientations) {
    EXPECT_EQ(o.axes, axes) << o.name;
    const glm::dvec4 corner = o.worldFromIndex * glm::dvec4(1, 2, 1, 1);
    EXPECT_NEAR(corner.x, 10 - 0.5, 1e-6) << o.name;
    EXPECT_NEAR(corner.y, -20 + 2.5, 1e-6) << o.name;
    EXPECT_NEAR(corner.z, 30 + 2, 1e-6) << o.name;
  }
}

INSTANTIATE_TEST_SUITE_P(Fixtures, NiftiFixtureRead, ::testing::ValuesIn(niftiFixtures()),
                         [](const auto& info) { return test::fixtureTestName(info.param.file); });

TEST(NiftiReader, EveryFixtureIsListed) {
  EXPECT_EQ(niftiFixtures().size(), 19u);  // 10 datatypes and 9 layouts
}

// A .hdr whose image was gzipped on its own (.img.gz beside it) reads as its .img would.
TEST(NiftiReader, AHeaderBesideAGzippedImageReadsItsSamples) {
  const fs::path dir = test::scratchDir();
  fs::copy_file(kNiftiFixtures / "uint8_pair.hdr", dir / "pair.hdr");
  const std::string image = test::readFileBytes(kNiftiFixtures / "uint8_pair.img");
  test::writeFile(dir / "pair.img.gz",
                  test::deflateBytes(test::Bytes(image.begin(), image.end()), true));
  const Volume plain = loadVolume((kNiftiFixtures / "uint8_pair.hdr").string());
  const Volume gzipped = loadVolume((dir / "pair.hdr").string());
  EXPECT_EQ(gzipped.format, "NIfTI-1 (.hdr/.img, gzip)");
  EXPECT_EQ(gzipped.dims, plain.dims);
  EXPECT_EQ(test::floatsOf(gzipped), test::floatsOf(plain));
}

TEST(NiftiReader, RescaleIsRecordedAndAppliedInDouble) {
  const Volume ct = loadVolume((kNiftiFixtures / "uint16_rescaled.nii").string());
  ASSERT_TRUE(ct.rescale);
  EXPECT_EQ(ct.rescale->slope, 1.0);
  EXPECT_EQ(ct.rescale->intercept, -1024.0);
  EXPECT_EQ(ct.type(), SampleType::Float32);
  const Volume plain = loadVolume((kNiftiFixtures / "uint16.nii").string());
  EXPECT_FALSE(plain.rescale);
  for (std::size_t i = 0; i < ct.sampleCount(); ++i) {
    ASSERT_EQ(double(ct.value(i)), double(plain.value(i)) - 1024.0) << i;
  }
}

// --crop and --stride keep the same samples from a gzip stream, an uncompressed file and a
// header/image pair; the orientation follows the kept samples' first index.
TEST(NiftiReader, CropAndStrideKeepTheSubsetFromEveryLayout) {
  for (const char* file : {"int16.nii", "int16_gzip.nii.gz", "int16_nifti2.nii"}) {
    const std::string path = (kNiftiFixtures / file).string();
    const Volume whole = loadVolume(path);
    LoadOptions options;
    options.region.crop = {ReadRegion::Range{1, 4}, ReadRegion::Range{0, 3},
                           ReadRegion::Range{1, 2}};
    options.region.cropText = "1:4,0:3,1:2";
    options.region.stride = 2;
    const Volume part = loadVolume(path, options);
    ASSERT_EQ(part.dims, glm::ivec3(2, 2, 1)) << file;
    for (int y = 0; y < 2; ++y) {
      for (int x = 0; x < 2; ++x) {
        EXPECT_EQ(part.value(part.index(x, y, 0)), whole.value(whole.index(1 + 2 * x, 2 * y, 1)))
            << file << " " << x << "," << y;
      }
    }
    ASSERT_EQ(part.orientations.size(), 2u);
    const glm::dvec4 kept = part.orientations[1].worldFromIndex * glm::dvec4(1, 1, 0, 1);
    const glm::dvec4 file_ = whole.orientations[1].worldFromIndex * glm::dvec4(3, 2, 1, 1);
    EXPECT_EQ(kept, file_) << file;
  }
}

// A header written here with its fields changed; `data` after vox_offset 352.
std::string writeNifti(const std::string& name, const std::function<void(Bytes&)>& change,
                       const Bytes& data) {
  Bytes bytes(352, 0);
  auto put = [&](std::size_t at, const void* value, std::size_t size) {
    std::memcpy(bytes.data() + at, value, size);
  };
  const std::int32_t sizeofHdr = 348;
  put(0, &sizeofHdr, 4);
  const std::int16_t dim[8] = {3, 2, 2, 1, 1, 1, 1, 1};
  put(40, dim, sizeof dim);
  const std::int16_t datatype[2] = {2, 8};  // UINT8, 8 bits
  put(70, datatype, sizeof datatype);
  const float pixdim[8] = {1, 1, 1, 1, 0, 0, 0, 0};
  put(76, pixdim, sizeof pixdim);
  const float voxOffset = 352;
  put(108, &voxOffset, 4);
  put(344, "n+1\0", 4);
  change(bytes);
  bytes.insert(bytes.end(), data.begin(), data.end());
  const auto path = test::scratchDir() / name;
  test::writeFile(path, bytes);
  return path.string();
}

TEST(NiftiReader, AHeaderWrittenByHandReadsAndHostileOnesAreRefused) {
  const Bytes four{1, 2, 3, 4};
  const Volume v = loadVolume(writeNifti(
      "ok.nii", [](Bytes&) {}, four));
  EXPECT_EQ(test::floatsOf(v), (std::vector<float>{1, 2, 3, 4}));
  EXPECT_EQ(v.format, "NIfTI-1 (.nii)");
  EXPECT_TRUE(v.orientations.empty());  // qform_code and sform_code 0: no placement stated

  auto refuses = [&](const std::function<void(Bytes&)>& change, const Bytes& data,
                     const std::string& message) {
    const std::string path = writeNifti("bad.nii", change, data);
    test::expectInputError([&] { loadVolume(path); }, path + ": " + message, {});
  };
  auto setShort = [](std::size_t at, std::int16_t value) {
    return [=](Bytes& b) { std::memcpy(b.data() + at, &value, 2); };
  };
  refuses([](Bytes&) {}, Bytes{1, 2},
          "its data holds 2 bytes after offset 352, 4 expected (2x2x1 uint8)");
  refuses(setShort(42, 0), four, "dim[1] 0 is not a positive size");
  refuses(setShort(40, 9), four, "dim[0] 9 is not a dimension count (1..7)");
  refuses(
      [](Bytes& b) {
        const std::int16_t dim[5] = {4, 2, 2, 1, 3};
        std::memcpy(b.data() + 40, dim, sizeof dim);
      },
      Bytes(12, 0), "holds 3 volumes along dim[4] (a 4D or 5D image)");
  refuses(setShort(70, 128), Bytes(12, 0), "datatype 128 (RGB24) is not supported");
  // nifticlib reads a spacing of 0 or NaN as 1; vsil says so.
  const Volume noSpacing = loadVolume(writeNifti(
      "nan.nii",
      [](Bytes& b) {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        std::memcpy(b.data() + 80, &nan, 4);
      },
      four));
  EXPECT_EQ(noSpacing.spacing, glm::dvec3(1.0));
  ASSERT_EQ(noSpacing.warnings.size(), 1u);
  EXPECT_NE(noSpacing.warnings[0].find("pixdim[1] nan is no spacing; read as 1"), std::string::npos)
      << noSpacing.warnings[0];
  refuses(
      [](Bytes& b) {
        const float far = 1e12f;
        std::memcpy(b.data() + 108, &far, 4);
      },
      four, "vox_offset 999999995904 is beyond 64 MiB: not the header of an image");
  const auto text = test::scratchDir() / "text.nii";
  test::writeFile(text, std::string(400, 'x'));
  test::expectInputError([&] { loadVolume(text.string()); },
                         text.string() + ": is not a NIfTI-1 or NIfTI-2 file", {});
}

TEST(NiftiReader, LimitsAreCheckedBeforeTheDataAreRead) {
  const std::string path = writeNifti(
      "big.nii",
      [](Bytes& b) {
        const std::int16_t dim[4] = {3, 1024, 1024, 1024};
        std::memcpy(b.data() + 40, dim, sizeof dim);
        const std::int16_t datatype[2] = {8, 32};  // INT32
        std::memcpy(b.data() + 70, datatype, sizeof datatype);
      },
      Bytes(4, 0));
  LoadOptions options;
  options.limits.maxBytes = std::size_t(100) << 20;
  test::expectInputError([&] { loadVolume(path, options); },
                         path + ": reading 1024x1024x1024 float32 samples", {"--max-memory"});
}

}  // namespace
}  // namespace vsil
