// The decision that one binary runs where either GL library is installed: `vsil` needs neither
// libOSMesa nor libEGL (nor any libGL) to start; slicing/gl_backends/ opens them with dlopen.
// Likewise GDCM, whose libraries cost 20 ms at every start: it comes with the DICOM plugin at
// the first DICOM file (src/io/dicom_plugin.h).
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "test_support.h"

namespace vsil {
namespace {

// The lines of `command`'s output that contain `marker`.
std::string linesContaining(const std::string& command, const std::string& marker) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::string lines;
  char line[1024];
  while (pipe && std::fgets(line, sizeof line, pipe.get())) {
    if (std::string(line).find(marker) != std::string::npos) lines += line;
  }
  return lines;
}

// The DT_NEEDED libraries of `binary`, as `readelf -d` prints them.
std::string neededLibraries(const std::string& binary) {
  return linesContaining("readelf -d " + binary, "(NEEDED)");
}

TEST(Linkage, VsilStartsWithoutAnyGlLibrary) {
  const std::string needed = neededLibraries(test::vsilBinary().string());
  ASSERT_NE(needed.find("libc.so"), std::string::npos) << "readelf listed nothing:\n" << needed;
  for (const char* library : {"libOSMesa", "libEGL", "libGL", "libOpenGL", "libglapi"}) {
    EXPECT_EQ(needed.find(library), std::string::npos) << library << " in\n" << needed;
  }
}

// The shared objects the dynamic loader opens for `vsil info input`, as LD_DEBUG=files lists
// them (one "file=NAME [0];  needed by ..." or "... dynamically loaded by ..." line each).
std::string librariesLoadedFor(const std::string& input) {
  return linesContaining(
      "LD_DEBUG=files " + test::vsilBinary().string() + " info '" + input + "' 2>&1 >/dev/null",
      "file=");
}

TEST(Linkage, VsilLoadsGdcmAtTheFirstDicomFileOnly) {
  const auto nrrd = test::scratchDir() / "small.nrrd";
  std::ofstream(nrrd) << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n"
                      << "abcdefgh";
  for (const std::string& input : {nrrd.string(), std::string("gen:sphere:8")}) {
    const std::string loaded = librariesLoadedFor(input);
    ASSERT_NE(loaded.find("libc.so"), std::string::npos) << "LD_DEBUG listed nothing:\n" << loaded;
    EXPECT_EQ(loaded.find("libgdcm"), std::string::npos) << "vsil info " << input << ":\n"
                                                         << loaded;
    EXPECT_EQ(loaded.find("libvsil_dicom"), std::string::npos) << "vsil info " << input;
  }
  const std::string dicom =
      librariesLoadedFor(std::string(VSIL_SOURCE_DIR) + "/tests/io/dicom/ct_rle");
  EXPECT_NE(dicom.find("libvsil_dicom"), std::string::npos) << "a DICOM series:\n" << dicom;
  EXPECT_NE(dicom.find("libgdcmMSFF"), std::string::npos) << "a DICOM series:\n" << dicom;
}

}  // namespace
}  // namespace vsil
