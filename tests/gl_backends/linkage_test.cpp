// The decision that one binary runs where either GL library is installed: `vsil` needs neither
// libOSMesa nor libEGL (nor any libGL) to start; slicing/gl_backends/ opens them with dlopen.
#include <cstdio>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "test_support.h"

namespace vsil {
namespace {

// The DT_NEEDED libraries of `binary`, as `readelf -d` prints them.
std::string neededLibraries(const std::string& binary) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(("readelf -d " + binary).c_str(), "r"), pclose);
  std::string needed;
  char line[512];
  while (pipe && std::fgets(line, sizeof line, pipe.get())) {
    if (std::string(line).find("(NEEDED)") != std::string::npos) needed += line;
  }
  return needed;
}

TEST(Linkage, VsilStartsWithoutAnyGlLibrary) {
  const std::string needed = neededLibraries(test::vsilBinary().string());
  ASSERT_NE(needed.find("libc.so"), std::string::npos) << "readelf listed nothing:\n" << needed;
  for (const char* library : {"libOSMesa", "libEGL", "libGL", "libOpenGL", "libglapi"}) {
    EXPECT_EQ(needed.find(library), std::string::npos) << library << " in\n" << needed;
  }
}

}  // namespace
}  // namespace vsil
