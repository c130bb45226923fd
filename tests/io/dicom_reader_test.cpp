// DICOM series (folders of slices): the committed fixtures of tests/io/dicom/, written by
// pydicom and gdcmconv (make_fixtures.py: uncompressed, RLE, lossless JPEG, JPEG-LS, an oblique
// series, two series in one folder, a missing slice). File names are shuffled and Instance
// Numbers run against the slice order, so only sorting by position along the normal reads
// them right; the manifest holds the values computed with numpy, not vsil.
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "io/volume_loader.h"
#include "io_test_files.h"
#include "reference/test_support.h"

namespace vsil {
namespace {

namespace fs = std::filesystem;

const fs::path kDicomFixtures = fs::path(VSIL_SOURCE_DIR) / "tests" / "io" / "dicom";

struct DicomFixture {
  std::string folder;
  std::string series;  // "" for the folder's default
  glm::ivec3 dims{0};
  glm::dvec3 spacing{0.0};
  double sum = 0, first = 0, last = 0;
  std::string axes;
  glm::dvec3 origin{0.0};
};

std::vector<DicomFixture> dicomFixtures() {
  std::ifstream in(kDicomFixtures / "fixtures.txt");
  std::vector<DicomFixture> fixtures;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    DicomFixture f;
    fields >> f.folder >> f.dims.x >> f.dims.y >> f.dims.z >> f.spacing.x >> f.spacing.y >>
        f.spacing.z >> f.sum >> f.first >> f.last >> f.axes >> f.origin.x >> f.origin.y >>
        f.origin.z;
    if (const std::size_t colon = f.folder.find(':'); colon != std::string::npos) {
      f.series = f.folder.substr(colon + 1);
      f.folder.resize(colon);
    }
    fixtures.push_back(f);
  }
  return fixtures;
}

class DicomFixtureRead : public ::testing::TestWithParam<DicomFixture> {};

// A fresh copy of the ct_series fixture in the scratch folder `name`, to damage.
fs::path copyOfCtSeries(const std::string& name) {
  const fs::path folder = test::scratchDir() / name;
  fs::remove_all(folder);
  fs::create_directories(folder);
  for (const auto& entry : fs::directory_iterator(kDicomFixtures / "ct_series")) {
    fs::copy_file(entry.path(), folder / entry.path().filename());
  }
  return folder;
}

TEST_P(DicomFixtureRead, ReadsTheSeriesInSlicePositionOrder) {
  const DicomFixture& f = GetParam();
  LoadOptions options;
  options.series = f.series;
  const Volume volume = loadVolume((kDicomFixtures / f.folder).string(), options);
  EXPECT_EQ(volume.dims, f.dims);
  EXPECT_NEAR(volume.spacing.x, f.spacing.x, 1e-9);
  EXPECT_NEAR(volume.spacing.y, f.spacing.y, 1e-9);
  EXPECT_NEAR(volume.spacing.z, f.spacing.z, 1e-6);
  EXPECT_EQ(volume.type(), SampleType::Float32);  // rescaled to Hounsfield units
  ASSERT_TRUE(volume.rescale);
  EXPECT_TRUE(volume.format.starts_with("DICOM series (CT, ")) << volume.format;
  double sum = 0;
  for (std::size_t i = 0; i < volume.sampleCount(); ++i) sum += double(volume.value(i));
  EXPECT_EQ(sum, f.sum);
  EXPECT_EQ(double(volume.value(0)), f.first);
  EXPECT_EQ(double(volume.value(volume.sampleCount() - 1)), f.last);
  ASSERT_EQ(volume.orientations.size(), 1u);
  const Orientation& patient = volume.orientations[0];
  EXPECT_EQ(patient.space, "LPS");
  EXPECT_EQ(patient.axes, f.axes);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(patient.worldFromIndex[3][i], f.origin[i], 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Fixtures, DicomFixtureRead, ::testing::ValuesIn(dicomFixtures()),
                         [](const auto& info) {
                           return info.param.series.empty() ? info.param.folder
                                                            : info.param.folder + "_chosen";
                         });

// Whether the DICOM plugin (and with it GDCM) is mapped into this process. The plugin, not
// GDCM itself: a test binary may map GDCM through another library (the sanitizer build keeps
// OpenCV's imgcodecs, whose GDAL needs GDCM); tests/gl_backends/linkage_test.cpp checks that
// `vsil` itself maps no GDCM before a DICOM file.
bool dicomPluginLoaded() {
  std::ifstream maps("/proc/self/maps");
  const std::string text((std::istreambuf_iterator<char>(maps)), std::istreambuf_iterator<char>());
  return text.find("libvsil_dicom") != std::string::npos;
}

// The DICOM plugin (io/dicom_plugin.h) loads at the first DICOM file, not before: a process
// reading other files never loads it. In a child process, so that the tests before it in this
// one (a DICOM read loads the plugin for good) do not matter; the child's exit status holds one
// bit per check.
TEST(DicomReader, ThePluginLoadsAtTheFirstDicomFileOnly) {
  const fs::path nrrd = test::scratchDir() / "small.nrrd";
  test::writeFile(nrrd,
                  "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n"
                  "abcdefgh");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    int failed = dicomPluginLoaded() ? 1 : 0;
    try {
      loadVolume(nrrd.string());
      loadVolume("gen:sphere:8");
      if (dicomPluginLoaded()) failed |= 2;
      if (loadVolume((kDicomFixtures / "ct_rle").string()).dims.z < 2) failed |= 8;
      if (!dicomPluginLoaded()) failed |= 4;
    } catch (...) {
      failed |= 16;
    }
    ::_exit(failed);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "the child did not exit";
  const int failed = WEXITSTATUS(status);
  EXPECT_FALSE(failed & 1) << "the DICOM plugin is loaded before any volume is read";
  EXPECT_FALSE(failed & 2) << "reading a NRRD file and a generated volume loaded the DICOM plugin";
  EXPECT_FALSE(failed & 4) << "reading a DICOM series did not load the DICOM plugin";
  EXPECT_FALSE(failed & 8) << "the DICOM series read wrong";
  EXPECT_FALSE(failed & 16) << "a read threw";
}

TEST(DicomReader, EveryFixtureIsListed) {
  EXPECT_EQ(dicomFixtures().size(), 7u);
}

TEST(DicomReader, TheCompressedSeriesDecodeToTheUncompressedOne) {
  const Volume plain = loadVolume((kDicomFixtures / "ct_series").string());
  for (const char* folder : {"ct_rle", "ct_jpeg", "ct_jpegls"}) {
    const Volume compressed = loadVolume((kDicomFixtures / folder).string());
    EXPECT_EQ(test::floatsOf(compressed), test::floatsOf(plain)) << folder;
  }
  EXPECT_NE(loadVolume((kDicomFixtures / "ct_jpegls").string()).format.find("JPEG-LS"),
            std::string::npos);
}

TEST(DicomReader, ASliceFileStandsForItsSeries) {
  const fs::path folder = kDicomFixtures / "two_series";
  const Volume all = loadVolume(folder.string());
  ASSERT_EQ(all.warnings.size(), 1u);
  EXPECT_NE(all.warnings[0].find("2 series; reading"), std::string::npos) << all.warnings[0];
  EXPECT_NE(all.warnings[0].find("--series"), std::string::npos);
  // IM0007 is one of the small series' slices (make_fixtures.py numbers them from 6).
  const Volume small = loadVolume((folder / "IM0007").string());
  EXPECT_EQ(small.dims.z, 3);
  EXPECT_TRUE(small.warnings.size() == 1u);  // the other series is still named
  // Named relative to the working folder, as a user in that folder types it.
  const fs::path before = fs::current_path();
  fs::current_path(folder);
  const Volume relative = loadVolume("IM0007");
  fs::current_path(before);
  EXPECT_EQ(test::floatsOf(relative), test::floatsOf(small));
}

TEST(DicomReader, CropAndStrideDecodeOnlyTheKeptSlices) {
  const std::string folder = (kDicomFixtures / "ct_jpegls").string();
  const Volume whole = loadVolume(folder);
  LoadOptions options;
  options.region.crop = {ReadRegion::Range{1, 4}, ReadRegion::Range{0, 3}, ReadRegion::Range{1, 5}};
  options.region.cropText = "1:4,0:3,1:5";
  options.region.stride = 2;
  const Volume part = loadVolume(folder, options);
  ASSERT_EQ(part.dims, glm::ivec3(2, 2, 2));
  for (int z = 0; z < 2; ++z) {
    for (int y = 0; y < 2; ++y) {
      for (int x = 0; x < 2; ++x) {
        EXPECT_EQ(part.value(part.index(x, y, z)),
                  whole.value(whole.index(1 + 2 * x, 2 * y, 1 + 2 * z)));
      }
    }
  }
  const glm::dvec4 kept = part.orientations[0].worldFromIndex * glm::dvec4(1, 1, 1, 1);
  const glm::dvec4 file = whole.orientations[0].worldFromIndex * glm::dvec4(3, 2, 3, 1);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(kept[i], file[i], 1e-9);
}

TEST(DicomReader, RefusesWhatItCannotReadRight) {
  const std::string missing = (kDicomFixtures / "missing_slice").string();
  test::expectInputError([&] { loadVolume(missing); },
                         missing + ": slices are unevenly spaced: 5 between positions 105 and 110",
                         {"a missing slice?"});
  const std::string none = (kDicomFixtures / "no_dicom").string();
  test::expectInputError([&] { loadVolume(none); },
                         none + ": holds no DICOM image slices (1 file looked at)", {});
  LoadOptions options;
  options.series = "1.2.3";
  const std::string two = (kDicomFixtures / "two_series").string();
  test::expectInputError([&] { loadVolume(two, options); },
                         two + ": has no series '1.2.3' (series: ", {});
  // A slice cut short: GDCM cannot read it, and the message names it.
  const fs::path cut = copyOfCtSeries("cut");
  fs::resize_file(cut / "IM0002", fs::file_size(cut / "IM0002") - 10);
  test::expectInputError([&] { loadVolume(cut.string()); }, cut.string() + ": ", {"IM0002"});
}

// A series folder may hold more than slices: every slice is read whatever else it holds and in
// whatever order the folder lists it (gdcm::Directory stopped listing at a FIFO or a link to
// nothing, so the slices listed after one were lost). A FIFO (never opened: a read would wait
// for a writer), a link to nothing and a loop of links are left out with a warning, each saying
// which it is; a subfolder and hidden
// files quietly; a link to a slice is read as the slice.
TEST(DicomReader, EverySliceIsReadWhateverElseTheFolderHolds) {
  const fs::path folder = copyOfCtSeries("mixed");
  const fs::path moved = folder.parent_path() / "mixed_IM0002";
  fs::remove(moved);
  fs::rename(folder / "IM0002", moved);
  fs::create_symlink(moved, folder / "IM0002");
  for (const std::string name : {"a", "m", "z"}) {  // among the slices in any listing order
    ASSERT_EQ(::mkfifo((folder / (name + "_fifo")).c_str(), 0600), 0);
    fs::create_symlink(folder / "nowhere", folder / (name + "_link"));
  }
  fs::create_symlink("m_loop", folder / "m_loop");
  fs::create_directory(folder / "sub");
  fs::copy_file(kDicomFixtures / "ct_series" / "IM0000", folder / "sub" / "IM0000");
  test::writeFile(folder / ".hidden", "not DICOM");

  const Volume plain = loadVolume((kDicomFixtures / "ct_series").string());
  for (const bool inChild : {true, false}) {
    LoadOptions options;
    options.dicomInChildProcess = inChild;
    const Volume volume = loadVolume(folder.string(), options);
    EXPECT_EQ(volume.dims, plain.dims);
    volume.visit([&](auto samples) {
      plain.visit([&](auto plainSamples) {
        ASSERT_EQ(samples.size_bytes(), plainSamples.size_bytes());
        EXPECT_EQ(std::memcmp(samples.data(), plainSamples.data(), samples.size_bytes()), 0);
      });
    });
    std::vector<std::string> expected;
    for (const std::string name : {"a", "m", "z"}) {
      expected.push_back(folder.string() + ": left out '" + name + "_fifo': not a regular file");
      expected.push_back(folder.string() + ": left out '" + name + "_link': a link to nothing");
    }
    expected.push_back(folder.string() + ": left out 'm_loop': Too many levels of symbolic links");
    std::sort(expected.begin(), expected.end());
    std::vector<std::string> warnings = volume.warnings;
    std::sort(warnings.begin(), warnings.end());
    EXPECT_EQ(warnings, expected);
  }
}

// GDCM allocates what a data element declares before reading it: a file whose element claims
// more than the file holds is left out of its folder's scan (a warning names it and the
// element) and refused when named, before GDCM sees it.
TEST(DicomReader, AnElementLongerThanItsFileKeepsGdcmAway) {
  const fs::path folder = copyOfCtSeries("overlong");
  std::ifstream in(kDicomFixtures / "ct_series" / "IM0000", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Image Position (Patient): explicit VR "DS" with a 2-byte length, made 0xf0f0 (61680).
  const std::size_t position = bytes.find(std::string{'\x20', '\0', '\x32', '\0', 'D', 'S'});
  ASSERT_NE(position, std::string::npos);
  bytes[position + 6] = bytes[position + 7] = char(0xf0);
  const fs::path bad = folder / "bad.dcm";
  std::ofstream(bad, std::ios::binary) << bytes;

  const Volume volume = loadVolume(folder.string());
  EXPECT_EQ(volume.dims, glm::ivec3(4, 3, 5)) << "the good slices, read as before";
  ASSERT_EQ(volume.warnings.size(), 1u);
  EXPECT_NE(volume.warnings[0].find("left out 'bad.dcm': its data element (0020,0032) at byte " +
                                    std::to_string(position) + " declares 61680 bytes"),
            std::string::npos)
      << volume.warnings[0];
  test::expectInputError([&] { loadVolume(bad.string()); },
                         bad.string() + ": its data element (0020,0032) at byte " +
                             std::to_string(position) + " declares 61680 bytes",
                         {"are left in the file (a malformed or truncated DICOM file)"});
}

// GDCM reads in a child process (io/dicom_child.h): every field of the volume, its samples and
// the progress calls come across as a read in the process itself gives them. Every fixture,
// a crop with a stride (Volume::subset), two series in a folder (a warning) and a rescaled,
// oblique series (orientations).
TEST(DicomReader, TheChildProcessGivesWhatAReadInTheProcessGives) {
  struct Case {
    std::string path;
    LoadOptions options;
  };
  std::vector<Case> cases;
  for (const DicomFixture& fixture : dicomFixtures()) {
    Case c{(kDicomFixtures / fixture.folder).string(), {}};
    c.options.series = fixture.series;
    cases.push_back(c);
  }
  Case cropped{(kDicomFixtures / "ct_oblique").string(), {}};
  cropped.options.region.crop = {ReadRegion::Range{1, 4}, ReadRegion::Range{0, 3},
                                 ReadRegion::Range{1, 4}};
  cropped.options.region.cropText = "1:4,0:3,1:4";
  cropped.options.region.stride = 2;
  cases.push_back(cropped);
  cases.push_back({(kDicomFixtures / "two_series").string(), {}});

  using Calls = std::vector<std::pair<std::uint64_t, std::uint64_t>>;
  for (Case& c : cases) {
    SCOPED_TRACE(c.path);
    Calls childCalls, ownCalls;
    LoadOptions inChild = c.options, inProcess = c.options;
    inChild.progress = [&](std::uint64_t done, std::uint64_t all) {
      childCalls.emplace_back(done, all);
    };
    inProcess.progress = [&](std::uint64_t done, std::uint64_t all) {
      ownCalls.emplace_back(done, all);
    };
    inProcess.dicomInChildProcess = false;
    const Volume child = loadVolume(c.path, inChild);
    const Volume own = loadVolume(c.path, inProcess);
    EXPECT_EQ(child.name, own.name);
    EXPECT_EQ(child.source, own.source);
    EXPECT_EQ(child.dims, own.dims);
    EXPECT_EQ(child.spacing, own.spacing);
    EXPECT_EQ(child.fileType, own.fileType);
    EXPECT_EQ(child.inexactSamples, own.inexactSamples);
    ASSERT_EQ(child.rescale.has_value(), own.rescale.has_value());
    if (own.rescale) {
      EXPECT_EQ(child.rescale->slope, own.rescale->slope);
      EXPECT_EQ(child.rescale->intercept, own.rescale->intercept);
    }
    ASSERT_EQ(child.subset.has_value(), own.subset.has_value());
    if (own.subset) {
      EXPECT_EQ(child.subset->cropText(), own.subset->cropText());
      EXPECT_EQ(child.subset->stride, own.subset->stride);
    }
    EXPECT_EQ(child.format, own.format);
    EXPECT_EQ(child.warnings, own.warnings);
    ASSERT_EQ(child.orientations.size(), own.orientations.size());
    for (std::size_t i = 0; i < own.orientations.size(); ++i) {
      EXPECT_EQ(child.orientations[i].name, own.orientations[i].name);
      EXPECT_EQ(child.orientations[i].space, own.orientations[i].space);
      EXPECT_EQ(child.orientations[i].worldFromIndex, own.orientations[i].worldFromIndex);
      EXPECT_EQ(child.orientations[i].axes, own.orientations[i].axes);
    }
    EXPECT_EQ(child.type(), own.type());
    EXPECT_FALSE(child.borrowsSamples());
    EXPECT_EQ(child.sampleBytes(), own.sampleBytes());
    child.visit([&](auto samples) {
      own.visit([&](auto ownSamples) {
        ASSERT_EQ(samples.size_bytes(), ownSamples.size_bytes());
        EXPECT_EQ(std::memcmp(samples.data(), ownSamples.data(), samples.size_bytes()), 0);
      });
    });
    EXPECT_FALSE(ownCalls.empty());
    EXPECT_EQ(childCalls, ownCalls);
  }
  // What a read throws comes across as it is.
  LoadOptions options;
  options.series = "1.2.3";
  const std::string two = (kDicomFixtures / "two_series").string();
  test::expectInputError([&] { loadVolume(two, options); },
                         two + ": has no series '1.2.3' (series: ", {});
}

// A volume is named after its series' folder however the folder or a slice in it is written; a
// hidden slice file is left out of its folder's scan, but read when named itself.
TEST(DicomReader, TheVolumeIsNamedAfterItsFolder) {
  const fs::path folder = copyOfCtSeries("named");
  for (const std::string& path :
       {folder.string(), folder.string() + "/", folder.string() + "/.",
        (folder / "IM0001").string(), folder.string() + "/sub/../IM0001"}) {
    SCOPED_TRACE(path);
    fs::create_directories(folder / "sub");
    EXPECT_EQ(loadVolume(path).name, "named");
  }
  fs::rename(folder / "IM0003", folder / ".IM0003");  // the last slice
  EXPECT_EQ(loadVolume(folder.string()).dims.z, 4) << "the hidden slice is not scanned";
  EXPECT_EQ(loadVolume((folder / ".IM0003").string()).dims.z, 5) << "unless it is named";
}

// A series of `slices` copies of ct_series' first slice, 2.5 apart, in the scratch folder `name`
// (the position's text rewritten in place: "-12.0\\", y and the height fill its 16 bytes); y
// of slice i is `y(i)`, 4 characters ("30.5").
fs::path longCtSeries(
    const std::string& name, int slices,
    const std::function<std::string(int)>& y = [](int) { return "30.5"; }) {
  const fs::path folder = test::scratchDir() / name;
  fs::remove_all(folder);
  fs::create_directories(folder);
  std::ifstream in(kDicomFixtures / "ct_series" / "IM0000", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t value = bytes.find("-12.0\\30.5\\105.0 ");
  EXPECT_NE(value, std::string::npos);
  for (int i = 0; i < slices && value != std::string::npos; ++i) {
    std::string position =
        "-12.0\\" + y(i) + "\\" + std::to_string(100 + 5 * i / 2) + (i % 2 ? ".5" : ".0");
    position.resize(16, ' ');
    bytes.replace(value, 16, position);
    std::ofstream(folder / ("IM" + std::to_string(i)), std::ios::binary) << bytes;
  }
  return folder;
}

// Slices shifted in-plane from one to the next (a gantry tilt: 1 per 2.5 along y, 21.8 degrees)
// are read as a straight stack, with a warning; the patient placement keeps the files' step.
// Shifts that are not equal steps (a series put together wrongly, one jump) are said as such;
// shifts within half a pixel (0.25 here) are not said.
TEST(DicomReader, SlicesShiftedInPlaneAreSaidAndTheTiltKeptInThePlacement) {
  const Volume tilted = loadVolume(
      longCtSeries("tilted", 4, [](int i) { return std::to_string(30 + i) + ".5"; }).string());
  ASSERT_EQ(tilted.warnings.size(), 1u);
  EXPECT_NE(tilted.warnings[0].find(
                "slices shift in-plane by 1 per slice (a gantry tilt of 21.8 degrees): read as a "
                "straight stack"),
            std::string::npos)
      << tilted.warnings[0];
  const glm::dvec4 step = tilted.orientations[0].worldFromIndex * glm::dvec4(0, 0, 1, 0);
  EXPECT_NEAR(step.y, 1.0, 1e-9);
  EXPECT_NEAR(step.z, 2.5, 1e-9);

  const Volume jumbled = loadVolume(
      longCtSeries("jumbled", 4, [](int i) { return i % 2 ? "33.5" : "30.5"; }).string());
  ASSERT_EQ(jumbled.warnings.size(), 1u);
  EXPECT_NE(jumbled.warnings[0].find(
                "slices lie shifted in-plane, up to 3 from the first and not in steps"),
            std::string::npos)
      << jumbled.warnings[0];

  // One jump (a patient's or table's movement) keeps every slice within half a pixel of the
  // line of equal steps, its steps unequal: not a tilt (round 13 read it as one).
  const Volume jump =
      loadVolume(longCtSeries("jump", 4, [](int i) { return i < 2 ? "30.5" : "31.1"; }).string());
  ASSERT_EQ(jump.warnings.size(), 1u);
  EXPECT_NE(jump.warnings[0].find("slices lie shifted in-plane, up to 0.6 from the first and not "
                                  "in steps"),
            std::string::npos)
      << jump.warnings[0];
  EXPECT_NEAR((jump.orientations[0].worldFromIndex * glm::dvec4(0, 0, 1, 0)).y, 0.0, 1e-9);

  const Volume within = loadVolume(
      longCtSeries("within", 4, [](int i) { return i == 2 ? "30.7" : "30.5"; }).string());
  EXPECT_TRUE(within.warnings.empty()) << within.warnings[0];
  EXPECT_NEAR((within.orientations[0].worldFromIndex * glm::dvec4(0, 0, 1, 0)).y, 0.0, 1e-9);
}

// What the descriptors of process `pid` point at ("pipe:[123]", "/tmp/x", ...); empty when it
// has ended (a zombie lists none).
std::vector<std::string> descriptorTargets(pid_t pid) {
  std::vector<std::string> targets;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator("/proc/" + std::to_string(pid) + "/fd", error)) {
    const fs::path target = fs::read_symlink(entry.path(), error);
    if (!error) targets.push_back(target.string());
  }
  return targets;
}

// The processes whose parent is this one.
std::vector<pid_t> childProcesses() {
  std::vector<pid_t> children;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(entry.path() / "stat");
    std::string line;
    if (!std::getline(stat, line) || line.rfind(')') == std::string::npos) continue;
    std::istringstream fields(line.substr(line.rfind(')') + 1));  // after "pid (name)"
    char state;
    pid_t parent = 0;
    fields >> state >> parent;
    if (parent == ::getpid()) children.push_back(std::stoi(name));
  }
  return children;
}

// The fork copies every descriptor of the caller, among them the pipe of a DICOM read another
// thread has under way: held open in this read's child, that read would wait for this one to
// end before it saw the end of its own pipe. The child closes all but stdio and its own two.
TEST(DicomReader, TheChildHoldsNoneOfTheCallersDescriptors) {
  int foreign[2];  // stands for another read's pipe, open at the fork
  ASSERT_EQ(::pipe(foreign), 0);
  const std::string foreignPipe = fs::read_symlink("/proc/self/fd/" + std::to_string(foreign[1]));
  const std::string path = longCtSeries("long", 300).string();
  int liveChildrenSeen = 0;
  // The child is seen at its first progress call, with most slices still to read; one that has
  // ended by then all the same (a loaded machine) lists nothing, so the read is tried again.
  for (int attempt = 0; attempt < 20 && liveChildrenSeen == 0; ++attempt) {
    LoadOptions options;
    options.progress = [&, first = true](std::uint64_t, std::uint64_t) mutable {
      if (!std::exchange(first, false)) return;
      for (const pid_t child : childProcesses()) {
        ::kill(child, SIGSTOP);  // it stays as it is while its descriptors are read
        const std::vector<std::string> targets = descriptorTargets(child);
        ::kill(child, SIGCONT);
        if (targets.empty()) continue;
        ++liveChildrenSeen;
        for (const std::string& target : targets) EXPECT_NE(target, foreignPipe);
      }
    };
    EXPECT_EQ(loadVolume(path, options).dims.z, 300);
  }
  EXPECT_GT(liveChildrenSeen, 0);
  ::close(foreign[0]);
  ::close(foreign[1]);
}

TEST(DicomReader, LimitsAreCheckedBeforeAnySliceIsDecoded) {
  LoadOptions options;
  options.limits.maxBytes = 100;  // the 4x3x5 float32 series needs 240 bytes of samples
  const std::string folder = (kDicomFixtures / "ct_series").string();
  test::expectInputError([&] { loadVolume(folder, options); },
                         folder + ": reading 4x3x5 float32 samples", {"--max-memory"});
}

}  // namespace
}  // namespace vsil
