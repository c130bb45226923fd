// The GL loader (slicing/gl_loader.h): the list of functions vsil calls pairs each name with its
// own <GL/glcorearb.h> type, every listed function is looked up through the back end's
// get-proc-address, the ones that come back null are named, and a current context leaves every
// pointer filled.
#include <algorithm>
#include <cctype>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "reference/gl_harness.h"
#include "slicing/gl_loader.h"

namespace vsil {
namespace {

TEST(GlLoader, EachNameHasItsOwnGlcorearbType) {
  const auto names = gl::entryPointNames();
  ASSERT_GT(names.size(), 50u);
  std::set<std::string> seen;
  std::string previous;
  for (const auto& [name, type] : names) {
    std::string expected = "PFN" + std::string(name) + "PROC";
    std::transform(expected.begin(), expected.end(), expected.begin(),
                   [](unsigned char c) { return char(std::toupper(c)); });
    EXPECT_EQ(std::string(type), expected) << name;
    EXPECT_TRUE(seen.insert(name).second) << name << " listed twice";
    EXPECT_LT(previous, std::string(name)) << "slicing/gl_functions.h is sorted";
    previous = name;
  }
}

// A get-proc-address that knows every function but one.
gl::GlProc allButGetError(const char* name) {
  static int anything = 0;
  if (std::string(name) == "glGetError") return nullptr;
  return reinterpret_cast<gl::GlProc>(&anything);
}

TEST(GlLoader, LooksUpEveryFunctionAndNamesTheMissing) {
  std::vector<std::string> missing;
  const gl::EntryPoints entryPoints = gl::loadEntryPoints(allButGetError, missing);
  EXPECT_EQ(missing, std::vector<std::string>{"glGetError"});
  EXPECT_EQ(entryPoints.glGetError, nullptr);
  EXPECT_NE(entryPoints.glDrawArrays, nullptr);
  EXPECT_NE(entryPoints.glTexImage3D, nullptr);
}

using GlLoaderInContext = test::GlTest;

TEST_F(GlLoaderInContext, TheCurrentContextFilledEveryPointer) {
  int filled = 0;  // of the pointers call sites use (slicing/gl.h), after SetUp's makeCurrent
#define VSIL_GL_CHECK_FILLED(name, type) filled += (name != nullptr);
  VSIL_GL_FUNCTIONS(VSIL_GL_CHECK_FILLED)
#undef VSIL_GL_CHECK_FILLED
  EXPECT_EQ(filled, int(gl::entryPointNames().size()));
  EXPECT_NE(glGetString(GL_VERSION), nullptr);
}

}  // namespace
}  // namespace vsil
