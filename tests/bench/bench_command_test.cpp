// `vsil bench` end to end, through the built binary: the JSON rows' schema and consistency, the
// self-checks, the reports, and one-line errors for bad flags. No assertion on timings: they
// depend on the machine and its load (performance is measured, never asserted).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "bench/bench_rows.h"
#include "harness/timing_stats.h"
#include "test_support.h"

namespace vsil {
namespace {

std::string datasetsDir() {
  return test::datasetPath("").parent_path().string();
}

int lineCount(const std::string& text) {
  return int(std::count(text.begin(), text.end(), '\n'));
}

// The small nk3 run of the tests below: two small datasets, 64² windows, two frames. Each test
// runs it in its own scratch folder (ctest runs the tests in parallel processes).
class Nk3Run : public ::testing::Test {
 protected:
  void SetUp() override {
    VSIL_REQUIRE_DATASETS();
    dir_ = test::scratchDir();
    result_ =
        test::runVsil("bench --table nk3 --datasets " + datasetsDir() +
                      " --only neghip,hydrogen_atom --sizes 64 --frames 2 --warmup 0 --json " +
                      (dir_ / "nk3.json").string() + " --markdown " + (dir_ / "nk3.md").string() +
                      " --plot " + (dir_ / "nk3.png").string());
  }
  std::filesystem::path dir_;
  test::CommandResult result_;
};

TEST_F(Nk3Run, SucceedsAndPrintsTheMachineAndTheTable) {
  ASSERT_EQ(result_.exitCode, 0) << result_.err;
  const std::string& out = result_.out;
  EXPECT_NE(out.find("machine: "), std::string::npos) << out;
  EXPECT_NE(out.find("LP_NUM_THREADS="), std::string::npos) << out;
  // The back end, vendor and renderer of the context the tables ran on: the one `vsil info --gl`
  // reports for the same choice ($VSIL_GL: ctest runs this once per back end).
  const auto info = test::runVsil("info --gl --json");
  ASSERT_EQ(info.exitCode, 0) << info.err;
  const auto gl = nlohmann::json::parse(info.out)["gl"];
  const std::string header =
      "GL: " + gl["backend"].get<std::string>() + " (" + gl["platform"].get<std::string>() + "), " +
      gl["vendor"].get<std::string>() + ", " + gl["renderer"].get<std::string>() + ", ";
  EXPECT_NE(out.find(header), std::string::npos) << header << " in\n" << out;
  if (const char* backend = std::getenv("VSIL_GL")) {
    EXPECT_EQ(gl["backend"], backend);
  }
  EXPECT_NE(out.find("neghip"), std::string::npos) << out;
  EXPECT_NE(out.find("hydrogen_atom"), std::string::npos) << out;
  EXPECT_EQ(out.find("bonsai"), std::string::npos) << "--only leaves bonsai out\n" << out;
  EXPECT_NE(result_.err.find("[1/2]"), std::string::npos) << "progress on stderr\n" << result_.err;
}

TEST_F(Nk3Run, JsonRowsHaveTheSchemaAndConsistentValues) {
  ASSERT_EQ(result_.exitCode, 0) << result_.err;
  const auto document = nlohmann::json::parse(test::readFileBytes(dir_ / "nk3.json"));
  for (const char* key :
       {"cpu", "hardware_threads", "gl_backend", "gl_vendor", "gl_renderer", "gl_version",
        "lp_num_threads", "vsil_version", "build_type", "date_utc"}) {
    EXPECT_TRUE(document["machine"].contains(key)) << key;
  }
  test::expectRowsRanOnTheReportedBackEnd(document);
  const auto& rows = document["rows"];
  ASSERT_TRUE(rows.is_array());
  ASSERT_EQ(rows.size(), 18u) << "2 datasets x 1 size x 3 techniques x 3 pipelines\n"
                              << rows.dump(1);
  std::map<std::string, int> perTechnique;
  std::map<std::string, int> perPipeline;
  for (const auto& row : rows) {
    SCOPED_TRACE(row.dump());
    EXPECT_EQ(row["table"], "nk3");
    const std::string dataset = row["dataset"];
    EXPECT_TRUE(dataset == "neghip" || dataset == "hydrogen_atom");
    EXPECT_EQ(row["width"], 64);
    EXPECT_EQ(row["height"], 64);
    // ra, ops, bs for the default pipeline, as before the table had pipelines; ra-tiles, ...
    // for the others.
    const std::string technique = row["technique"], pipeline = row["pipeline"];
    const std::string base = technique.substr(0, technique.find('-'));
    EXPECT_TRUE(base == "ra" || base == "ops" || base == "bs");
    EXPECT_TRUE(technique == base || technique == base + "-" + pipeline);
    ++perTechnique[technique];
    ++perPipeline[pipeline];
    EXPECT_EQ(row["frames"], 2);
    const double median = row["ms_median"], low = row["ms_min"], high = row["ms_max"];
    EXPECT_GT(low, 0.0);
    EXPECT_LE(low, median);
    EXPECT_LE(median, high);
    // fps is derived from the median alone; 1e-9 relative is double round-off.
    EXPECT_NEAR(row["fps"].get<double>(), 1000.0 / median, 1e-9 * (1000.0 / median));
    EXPECT_EQ(row["check"], "ok");
    EXPECT_GT(row["silhouette_pixels_median"].get<double>(), 0.0);
    EXPECT_TRUE(row["paper_fps"].is_null()) << "the paper has no 64² column";
  }
  EXPECT_EQ(perTechnique["ra"], 2);
  EXPECT_EQ(perTechnique["ops"], 2);
  EXPECT_EQ(perTechnique["bs"], 2);
  EXPECT_EQ(perTechnique.size(), 9u);
  for (const char* pipeline : {"fast", "paper", "tiles"}) EXPECT_EQ(perPipeline[pipeline], 6);
}

// Issue 36's ratio: per dataset and window, OPS at its default pipeline over RA at its default,
// in frame time, from the rows the table itself marks as the defaults (one pipeline per
// technique; both silhouette's and rightangle's default is tiles: technique_table_test.cpp).
TEST_F(Nk3Run, OpsDefaultOverRaDefaultComesFromTheDefaultPipelines) {
  ASSERT_EQ(result_.exitCode, 0) << result_.err;
  const auto rows = nlohmann::json::parse(test::readFileBytes(dir_ / "nk3.json"))["rows"];
  using Frames = std::vector<double>;
  std::map<std::string, std::map<std::string, Frames>> defaultMs;  // dataset -> ra/ops/bs
  std::map<std::string, std::map<std::string, Frames>> defaultCpuMs;
  std::map<std::string, std::map<std::string, std::string>> defaultPipeline;
  for (const auto& row : rows) {
    SCOPED_TRACE(row.dump());
    const std::string technique = row["technique"];
    const std::string base = technique.substr(0, technique.find('-'));
    if (!row["default_pipeline"].get<bool>()) continue;
    EXPECT_EQ(defaultMs[row["dataset"]].count(base), 0u) << "one default pipeline per technique";
    defaultMs[row["dataset"]][base] = row["ms"].get<Frames>();
    defaultCpuMs[row["dataset"]][base] = row["cpu_ms"].get<Frames>();
    EXPECT_EQ(row["ms"].size(), 2u);
    EXPECT_DOUBLE_EQ(row["ms_median"].get<double>(), bench::median(row["ms"].get<Frames>()));
    defaultPipeline[row["dataset"]][base] = row["pipeline"];
  }
  ASSERT_EQ(defaultMs.size(), 2u);
  for (const auto& [dataset, pipelines] : defaultPipeline) {
    EXPECT_EQ(pipelines.at("ra"), "tiles") << dataset;
    EXPECT_EQ(pipelines.at("ops"), "tiles") << dataset;
    EXPECT_EQ(pipelines.at("bs"), "tiles") << dataset << ": BS is OPS broadened";
  }
  for (const auto& row : rows) {
    SCOPED_TRACE(row.dump());
    // Frame by frame (the cases take turns), the median of the two turns' quotients.
    const auto& ms = defaultMs[row["dataset"]];
    const auto pairedMedian = [](const Frames& a, const Frames& b) {
      return 0.5 * (a[0] / b[0] + a[1] / b[1]);
    };
    EXPECT_NEAR(row["ops_default_over_ra_default"].get<double>(),
                pairedMedian(ms.at("ops"), ms.at("ra")), 1e-9);
    // CPU time: the same ratio, where the clock measured every frame (the process's CPU clock
    // ticks in steps that a 64² frame may fall between).
    const auto& cpu = defaultCpuMs[row["dataset"]];
    EXPECT_GE(row["cpu_ms_median"].get<double>(), 0.0);
    const auto measured = [](const Frames& f) { return f[0] > 0 && f[1] > 0; };
    if (measured(cpu.at("ra")) && measured(cpu.at("ops"))) {
      EXPECT_NEAR(row["ops_default_over_ra_default_cpu"].get<double>(),
                  pairedMedian(cpu.at("ops"), cpu.at("ra")), 1e-9);
    } else {
      EXPECT_TRUE(row["ops_default_over_ra_default_cpu"].is_null());
    }
  }
  EXPECT_NE(result_.out.find("OPS default / RA default"), std::string::npos) << result_.out;
}

// RA/OPS per pipeline (round 14: it was the ratio of the two medians, from frames of different
// turns, and disagreed with the defaults' column in the same row): the median of the turns'
// quotients, on every row of the pipeline.
TEST_F(Nk3Run, RaOverOpsIsPairedPerPipeline) {
  ASSERT_EQ(result_.exitCode, 0) << result_.err;
  const auto rows = nlohmann::json::parse(test::readFileBytes(dir_ / "nk3.json"))["rows"];
  using Frames = std::vector<double>;
  std::map<std::string, Frames> ms;  // dataset/pipeline/ra|ops|bs -> frames
  for (const auto& row : rows) {
    const std::string technique = row["technique"];  // ra, ra-paper, ops-tiles, ...
    ms[row["dataset"].get<std::string>() + "/" + row["pipeline"].get<std::string>() + "/" +
       technique.substr(0, technique.find('-'))] = row["ms"].get<Frames>();
  }
  int checked = 0;
  for (const auto& row : rows) {
    SCOPED_TRACE(row.dump());
    const std::string key =
        row["dataset"].get<std::string>() + "/" + row["pipeline"].get<std::string>() + "/";
    const Frames& ra = ms.at(key + "ra");
    const Frames& ops = ms.at(key + "ops");
    ASSERT_EQ(ra.size(), 2u);
    EXPECT_NEAR(row["ra_over_ops"].get<double>(), 0.5 * (ops[0] / ra[0] + ops[1] / ra[1]), 1e-9);
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

TEST_F(Nk3Run, WritesMarkdownAndPlot) {
  ASSERT_EQ(result_.exitCode, 0) << result_.err;
  const std::string markdown = test::readFileBytes(dir_ / "nk3.md");
  EXPECT_NE(markdown.find("| dataset |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("| neghip |"), std::string::npos) << markdown;
  const cv::Mat plot = cv::imread((dir_ / "nk3.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(plot.empty());
  EXPECT_GT(plot.cols, 100);
  EXPECT_GT(plot.rows, 100);
}

TEST(BenchCommand, SkullIsReportedMissingWithThePaperNumbers) {
  VSIL_REQUIRE_DATASETS();
  const auto dir = test::scratchDir();
  const auto result = test::runVsil("bench --table nk3 --datasets " + datasetsDir() +
                                    " --only skull --json " + (dir / "skull.json").string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("not available (no stored copy; see ../shared/datasets/README.md)"),
            std::string::npos)
      << result.out;
  const auto rows = nlohmann::json::parse(test::readFileBytes(dir / "skull.json"))["rows"];
  ASSERT_EQ(rows.size(), 18u) << "256² and 512², 3 techniques, 3 pipelines";
  for (const auto& row : rows) {
    EXPECT_EQ(row["dataset"], "skull");
    EXPECT_TRUE(row["missing"].is_string());
    EXPECT_TRUE(row["fps"].is_null());
    EXPECT_TRUE(row["paper_fps"].is_number()) << "the paper's Skull numbers are still quoted";
  }
}

// A dataset measured by default may be missing (its rows say so, the run goes on); the file of
// one --only asks for may not: exit 2 naming it, and no output file.
TEST(BenchCommand, MissingDatasetFilesAreReportedAndFatalOnlyWhenAskedFor) {
  const auto dir = test::scratchDir();  // empty folder: every dataset is missing
  const auto byDefault = test::runVsil("bench --table dv1 --datasets " + dir.string() +
                                       " --sizes 64 --frames 1 --warmup 0");
  ASSERT_EQ(byDefault.exitCode, 0) << byDefault.err;
  EXPECT_NE(byDefault.out.find("not found"), std::string::npos) << byDefault.out;

  const auto json = dir / "rows.json";
  const auto asked =
      test::runVsil("bench --table nk3 --datasets " + dir.string() +
                    " --only neghip --sizes 64 --frames 1 --warmup 0 --json " + json.string());
  EXPECT_EQ(asked.exitCode, 2) << asked.err;
  EXPECT_NE(asked.err.find("--only neghip: not found: " + (dir / "neghip").string()),
            std::string::npos)
      << asked.err;
  EXPECT_FALSE(std::filesystem::exists(json));
  EXPECT_EQ(asked.out, "") << "a failed bench prints no part of its report";
}

// Found before any frame: a dataset --only asks for whose file cannot be read (it was found
// after the others ran), and an output naming a dataset's file (after the whole run). A failed
// bench prints no table.
TEST(BenchCommand, AnUnreadableDatasetOrAnOutputNamingOneFailsBeforeAnyFrame) {
  VSIL_REQUIRE_DATASETS();
  const auto dir = test::scratchDir();
  const std::string header = "neghip_64x64x64_uint8.nhdr";
  std::filesystem::copy_file(test::datasetPath(header), dir / header);  // without its .raw
  for (const char* file :
       {"hydrogen_atom_128x128x128_uint8.nhdr", "hydrogen_atom_128x128x128_uint8.raw"}) {
    std::filesystem::copy_file(test::datasetPath(file), dir / file);  // readable, run first
  }
  const auto unreadable = test::runVsil("bench --table nk3 --datasets " + dir.string() +
                                        " --only hydrogen_atom,neghip --sizes 16 --frames 1 "
                                        "--warmup 0");
  EXPECT_EQ(unreadable.exitCode, 2) << unreadable.err;
  EXPECT_NE(unreadable.err.find("--only neghip: cannot be read: "), std::string::npos)
      << unreadable.err;
  EXPECT_EQ(unreadable.err.find("[1/"), std::string::npos) << "a frame ran: " << unreadable.err;
  EXPECT_EQ(unreadable.out, "");

  const auto datasets = test::datasetPath(header).parent_path();
  const auto named = test::runVsil("bench --table nk3 --datasets " + datasets.string() +
                                   " --only neghip --sizes 16 --frames 1 --warmup 0 --json " +
                                   (datasets / header).string());
  EXPECT_EQ(named.exitCode, 2) << named.err;
  EXPECT_NE(named.err.find("names a file this command reads"), std::string::npos) << named.err;
  EXPECT_EQ(named.err.find("[1/"), std::string::npos) << "a frame ran: " << named.err;
  EXPECT_EQ(named.out, "");
}

// A dataset file that is not the classic one (here all zeros: no surface at the table's iso)
// fails the self-checks: exit 1 once the rows are written, each failed row marked, and the
// message says so without calling it vsil's internal error.
TEST(BenchCommand, ADatasetWithoutSurfacesFailsItsSelfChecksAfterWritingTheRows) {
  const auto dir = test::scratchDir();
  std::ofstream(dir / "neghip_64x64x64_uint8.nhdr")
      << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 64 64 64\nencoding: raw\n"
         "data file: neghip_64x64x64_uint8.raw\n";
  std::ofstream(dir / "neghip_64x64x64_uint8.raw") << std::string(64 * 64 * 64, '\0');
  const auto json = dir / "rows.json";
  const auto result =
      test::runVsil("bench --table nk3 --datasets " + dir.string() +
                    " --only neghip --sizes 16 --frames 1 --warmup 0 --json " + json.string());
  EXPECT_EQ(result.exitCode, 1) << result.err;
  EXPECT_NE(result.err.find("vsil: bench: "), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("self-check(s) failed (their rows say FAILED), first: neghip"),
            std::string::npos)
      << result.err;
  EXPECT_EQ(result.err.find("internal error"), std::string::npos) << result.err;
  ASSERT_TRUE(std::filesystem::exists(json));
  EXPECT_NE(test::readFileBytes(json).find("FAILED: frame 1 has no line pixels"),
            std::string::npos);
}

// The illustrate table on the smallest dataset: RA, the plain composite, each effect, all of
// them, every row checked by the bench itself and its ratio to the right reference.
TEST(BenchCommand, IllustrateTableHasEveryCaseCheckedWithItsRatio) {
  VSIL_REQUIRE_DATASETS();
  const auto dir = test::scratchDir();
  const auto result = test::runVsil("bench --table illustrate --datasets " + datasetsDir() +
                                    " --only neghip --sizes 64 --frames 1 --warmup 1 --json " +
                                    (dir / "illustrate.json").string());
  ASSERT_EQ(result.exitCode, 0) << result.err << result.out;
  const auto document = nlohmann::json::parse(test::readFileBytes(dir / "illustrate.json"));
  std::vector<std::string> cases;
  std::map<std::string, nlohmann::json> rowOf;
  for (const auto& row : document["rows"]) {
    SCOPED_TRACE(row.dump());
    EXPECT_EQ(row["table"], "illustrate");
    EXPECT_EQ(row["dataset"], "neghip");
    EXPECT_EQ(row["check"], "ok");
    EXPECT_GT(row["fps"].get<double>(), 0.0);
    const std::string name = row["case"];
    cases.push_back(name);
    rowOf[name] = row;
  }
  // Each ratio is the frame's time over its reference's in the same turn (one frame each here).
  for (const auto& [name, row] : rowOf) {
    if (name == "ra") continue;
    SCOPED_TRACE(row.dump());
    const std::string reference = name == "plain" ? "ra" : "plain";
    EXPECT_EQ(row["ratio_to"], reference);
    ASSERT_EQ(row["ms"].size(), 1u);
    EXPECT_DOUBLE_EQ(row["ratio"].get<double>(),
                     row["ms"][0].get<double>() / rowOf[reference]["ms"][0].get<double>());
  }
  EXPECT_EQ(cases, (std::vector<std::string>{"ra", "plain", "boundary", "silhouette", "fading",
                                             "sketch", "distance", "halo", "tone", "all"}));
  test::expectRowsRanOnTheReportedBackEnd(document);
}

struct BadFlags {
  const char* name;
  const char* arguments;
  const char* mentions;  // the flag or value the one-line error must name
};

class BenchBadFlags : public ::testing::TestWithParam<BadFlags> {};

TEST_P(BenchBadFlags, ExitTwoWithOneLine) {
  const auto result = test::runVsil(std::string("bench ") + GetParam().arguments);
  EXPECT_EQ(result.exitCode, 2) << result.out << result.err;
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
  EXPECT_NE(result.err.find(GetParam().mentions), std::string::npos) << result.err;
  EXPECT_EQ(result.out, "") << "nothing runs before the flags are checked";
}

INSTANTIATE_TEST_SUITE_P(
    Flags, BenchBadFlags,
    ::testing::Values(BadFlags{"UnknownTable", "--table nk9", "nk9"},
                      BadFlags{"UnknownDataset", "--table nk3 --only bonsia", "bonsia"},
                      BadFlags{"OnlyWithoutDatasets", "--table fft --only bonsai", "--only"},
                      BadFlags{"ZeroFrames", "--frames 0", "--frames"},
                      BadFlags{"NegativeWarmup", "--warmup -1", "--warmup"},
                      BadFlags{"TinySize", "--sizes 4", "--sizes"},
                      BadFlags{"SizeNotANumber", "--sizes 256,big", "--sizes"},
                      BadFlags{"MissingDatasetsFolder", "--datasets /nonexistent/vsil",
                               "/nonexistent/vsil"},
                      BadFlags{"JsonInMissingFolder", "--json /nonexistent/vsil/x.json", "--json"},
                      BadFlags{"PlotNotPng", "--plot /tmp/x.jpg", "--plot"},
                      BadFlags{"JsonIsAFolder", "--table fft --json /tmp", "is a folder"},
                      BadFlags{"DatasetsIsAFile", "--datasets /etc/hostname", "is not a folder"},
                      BadFlags{"JsonAndMarkdownOneFile",
                               "--table fft --json /tmp/vsil-j.json --markdown /tmp/./vsil-j.json",
                               "names the same file as --json"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace vsil
