// `vsil info` through the built binary: a dataset in text and JSON, and an error's exit status.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "reference/test_support.h"

namespace vsil {
namespace {

TEST(InfoCommand, DescribesADataset) {
  VSIL_REQUIRE_DATASETS();
  const auto path = test::datasetPath("bucky_32x32x32_uint8.nhdr").string();
  const auto result = test::runVsil("info '" + path + "'");
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.err, "");
  EXPECT_NE(result.out.find("32 x 32 x 32 (32768 samples)"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("type      uint8"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("histogram"), std::string::npos) << result.out;
}

TEST(InfoCommand, JsonAgreesWithTheDatasetChecksum) {
  VSIL_REQUIRE_DATASETS();
  const auto path = test::datasetPath("bucky_32x32x32_uint8.nhdr").string();
  const auto result = test::runVsil("info --json '" + path + "'");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto json = nlohmann::json::parse(result.out);
  EXPECT_EQ(json["name"], "bucky_32x32x32_uint8");
  EXPECT_EQ(json["dims"], nlohmann::json({32, 32, 32}));
  EXPECT_EQ(json["type"], "uint8");
  // The sum of the samples (1174726, see dataset_loading_test) over 32768 samples; the mean is
  // accumulated in double, exact for integer sums this small.
  EXPECT_DOUBLE_EQ(json["mean"].get<double>(), 1174726.0 / 32768.0);
  std::size_t counted = 0;
  for (const auto& count : json["histogram"]["counts"]) counted += count.get<std::size_t>();
  EXPECT_EQ(counted, 32768u);
}

// The iso value `info` reports is the one a render without --iso uses (Otsu's threshold).
// A file name that is not UTF-8 (Linux names are bytes): the JSON vsil writes about it, info's
// and --meta-out's, holds U+FFFD for the byte (JSON must be UTF-8); it once failed with
// nlohmann's "invalid UTF-8 byte" after the render, exit 1.
TEST(InfoCommand, ANameThatIsNotUtf8IsWrittenWithAReplacementCharacter) {
  const auto dir = test::scratchDir();
  const std::string name = "bad\xffname.nrrd";
  std::ofstream(dir / name, std::ios::binary)
      << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n"
      << std::string(8, '\x40');
  const std::string path = (dir / name).string();
  const auto info = test::runVsil("info --json '" + path + "'");
  ASSERT_EQ(info.exitCode, 0) << info.err;
  EXPECT_EQ(nlohmann::json::parse(info.out)["source"].get<std::string>(),
            (dir / "bad\xef\xbf\xbdname.nrrd").string());
  const auto meta = dir / "meta.json";
  const auto render =
      test::runVsil("render '" + path + "' --size 16x16 --out '" + (dir / "x.png").string() +
                    "' --meta-out '" + meta.string() + "'");
  ASSERT_EQ(render.exitCode, 0) << render.err;
  const auto document = nlohmann::json::parse(test::readFileBytes(meta));
  EXPECT_NE(document.dump().find("bad\xef\xbf\xbdname.nrrd"), std::string::npos);
}

TEST(InfoCommand, DefaultIsoIsWhatARenderUses) {
  VSIL_REQUIRE_DATASETS();
  const auto path = test::datasetPath("bucky_32x32x32_uint8.nhdr").string();
  const auto info = test::runVsil("info --json '" + path + "'");
  ASSERT_EQ(info.exitCode, 0) << info.err;
  const double iso = nlohmann::json::parse(info.out)["default_iso"].get<double>();
  const auto meta = test::scratchDir() / "default_iso_meta.json";
  const auto render = test::runVsil("render '" + path + "' --size 32x32 --out '" +
                                    (test::scratchDir() / "default_iso.png").string() +
                                    "' --meta-out '" + meta.string() + "'");
  ASSERT_EQ(render.exitCode, 0) << render.err;
  const auto parameters = nlohmann::json::parse(test::readFileBytes(meta))["parameters"];
  EXPECT_FLOAT_EQ(float(parameters["iso"].get<double>()), float(iso));
  const auto range = nlohmann::json::parse(info.out);
  EXPECT_GT(iso, range["min"].get<double>());
  EXPECT_LT(iso, range["max"].get<double>());
}

TEST(InfoCommand, RawLayoutFlagsAndGenerators) {
  VSIL_REQUIRE_DATASETS();
  const auto raw = test::datasetPath("nucleon_41x41x41_uint8.raw").string();
  const auto result = test::runVsil("info '" + raw + "' --dims 41x41x41 --type uint8 --json");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(nlohmann::json::parse(result.out)["samples"], 68921);
  const auto generated = test::runVsil("info gen:torus:16");
  EXPECT_EQ(generated.exitCode, 0) << generated.err;
  EXPECT_NE(generated.out.find("float32"), std::string::npos);
}

// Float samples spanning more than FLT_MAX (max − min overflows in float): every sample lands
// in the histogram, the lowest in the first bin and the highest in the last.
TEST(InfoCommand, AValueRangeWiderThanAFloatHolds) {
  const float samples[8] = {1.8e38f, -1.8e38f, 0, 0, 0, 0, 0, 0};
  const auto raw = test::scratchDir() / "wide_range.raw";
  std::ofstream(raw, std::ios::binary)
      .write(reinterpret_cast<const char*>(samples), sizeof samples);
  const auto result =
      test::runVsil("info '" + raw.string() + "' --dims 2x2x2 --type float32 --json");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto counts = nlohmann::json::parse(result.out)["histogram"]["counts"];
  ASSERT_GE(counts.size(), 2u);
  EXPECT_EQ(counts.front().get<int>(), 1);
  EXPECT_EQ(counts.back().get<int>(), 1);
  std::size_t counted = 0;
  for (const auto& count : counts) counted += count.get<std::size_t>();
  EXPECT_EQ(counted, 8u);
}

// A file name with a newline and an escape sequence: the text report shows them as '?', one
// line per field, as errors do (the JSON report escapes them).
TEST(InfoCommand, ControlBytesInANameDoNotReachTheTerminal) {
  const float samples[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  const auto raw = test::scratchDir() / "a\x1b[31mb\nc.raw";
  std::ofstream(raw, std::ios::binary)
      .write(reinterpret_cast<const char*>(samples), sizeof samples);
  const auto result = test::runVsil("info '" + raw.string() + "' --dims 2x2x2 --type float32");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out.find('\x1b'), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("a?[31mb?c.raw\n"), std::string::npos) << result.out;
}

TEST(InfoCommand, BadInputExitsTwoWithOneLineNamingTheFile) {
  const auto path = (test::scratchDir() / "absent.nrrd").string();
  const auto result = test::runVsil("info '" + path + "'");
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(result.out, "");
  EXPECT_EQ(result.err, "vsil: " + path + ": no such file\n");
}

TEST(InfoCommand, MaxMemoryRefusesLargeVolumes) {
  VSIL_REQUIRE_DATASETS();
  // bonsai: 256³ uint8 samples = 16 MiB in memory, plus info's counts for the percentiles
  // (512 KiB), over a 16 MiB limit; the message names the options that read less.
  const auto path = test::datasetPath("bonsai.vti").string();
  const auto result = test::runVsil("info --max-memory 16 '" + path + "'");
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(result.out, "");
  EXPECT_EQ(result.err, "vsil: " + path +
                            ": reading 256x256x256 uint8 samples needs 17 MiB, over the "
                            "--max-memory limit of 16 MiB; read less with --crop "
                            "X0:X1,Y0:Y1,Z0:Z1 or --stride N, or raise --max-memory\n");
  const auto flags = test::runVsil("info '" + path + "' --dims 4x4 --type uint8");
  EXPECT_EQ(flags.exitCode, 2);
  EXPECT_NE(flags.err.find("--dims '4x4'"), std::string::npos) << flags.err;
}

}  // namespace
}  // namespace vsil
