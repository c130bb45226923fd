// Choosing the GL back end: --gl and --gl-device, $VSIL_GL, auto's order, what `vsil info --gl`
// reports, and the one-line errors (exit 1, nothing written) when a choice cannot give a 4.5 core
// context. The failures are real ones made on this machine: glvnd with no EGL driver
// (__EGL_VENDOR_LIBRARY_FILENAMES naming none), Mesa's softpipe (GALLIUM_DRIVER=softpipe: a
// driver with OpenGL 3.3 and no 4.5 core), an EGL device that does not exist.
#include <algorithm>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "backend_support.h"
#include "core/error.h"
#include "generators/generators.h"
#include "slicing/gl.h"
#include "slicing/gl_backends/backend.h"
#include "slicing/gl_context.h"
#include "slicing/gl_loader.h"
#include "slicing/renderer.h"
#include "test_support.h"

namespace vsil {
namespace {

int lineCount(const std::string& text) {
  return int(std::count(text.begin(), text.end(), '\n'));
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// `vsil info --gl ... --json`'s "gl" object; fails the test on a non-zero exit.
nlohmann::json glInfo(const std::string& flags) {
  const auto result = test::runVsil("info " + flags + " --json");
  EXPECT_EQ(result.exitCode, 0) << flags << ": " << result.err;
  if (result.exitCode != 0) return {};
  return nlohmann::json::parse(result.out)["gl"];
}

// A small render into `dir` with `flags`; the caller checks the result.
test::CommandResult renderInto(const std::filesystem::path& dir, const std::string& flags) {
  return test::runVsil("render gen:sphere:24 --size 40x40 " + flags + " --out " +
                       (dir / "out.png").string() + " --meta-out " + (dir / "meta.json").string());
}

// The contract of a back end that cannot be had: exit 1, one line on stderr starting with
// `start`, nothing on stdout, no file (not even a temporary) in `dir`.
void expectUnavailable(const test::CommandResult& result, const std::filesystem::path& dir,
                       const std::string& start) {
  EXPECT_EQ(result.exitCode, 1) << result.err;
  EXPECT_EQ(lineCount(result.err), 1) << result.err;
  EXPECT_EQ(result.err.rfind("vsil: " + start, 0), 0u) << result.err;
  EXPECT_TRUE(result.out.empty()) << result.out;
  EXPECT_TRUE(std::filesystem::is_empty(dir)) << "nothing written into " << dir;
}

class GlChoice : public ::testing::Test {
 protected:
  // The choices come from the flags in these tests, not from the caller's environment.
  test::ScopedEnvironment noBackend_{"VSIL_GL", nullptr}, noDevice_{"VSIL_GL_DEVICE", nullptr};
};

TEST_F(GlChoice, InfoReportsTheBackEndAskedFor) {
  for (gl::Backend backend : {gl::Backend::Osmesa, gl::Backend::Egl}) {
    VSIL_REQUIRE_GL_BACKEND(backend);
    const std::string name = gl::backendName(backend);
    const nlohmann::json info = glInfo("--gl " + name);
    EXPECT_EQ(info["backend"], name);
    EXPECT_EQ(info["platform"].get<std::string>().rfind(name, 0), 0u) << info;
    EXPECT_EQ(info["version"].get<std::string>().rfind("4.5", 0), 0u) << info;
    EXPECT_FALSE(info["vendor"].get<std::string>().empty()) << info;
    EXPECT_FALSE(info["renderer"].get<std::string>().empty()) << info;
    EXPECT_EQ(info["built"], nlohmann::json({"osmesa", "egl"}));
  }
  // The text form names the back end, vendor, renderer and version too.
  const auto text = test::runVsil("info --gl egl");
  ASSERT_EQ(text.exitCode, 0) << text.err;
  for (const char* key : {"gl        egl (egl ", "vendor    ", "renderer  ", "version   4.5"}) {
    EXPECT_TRUE(contains(text.out, key)) << key << " in\n" << text.out;
  }
}

TEST_F(GlChoice, EglDevicesAreListedAndPickedByNumber) {
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Egl);
  const nlohmann::json info = glInfo("--gl egl");
  ASSERT_FALSE(info["egl_devices"].empty()) << info;  // Mesa's software device at least
  for (std::size_t n = 0; n < info["egl_devices"].size(); ++n) {
    const nlohmann::json device = glInfo("--gl egl --gl-device " + std::to_string(n));
    EXPECT_EQ(device["egl_device"], int(n)) << device;
    EXPECT_EQ(device["platform"].get<std::string>().rfind("egl device " + std::to_string(n), 0), 0u)
        << device;
  }
}

TEST_F(GlChoice, AutoPrefersAGpuThenOsmesaThenEglOnLlvmpipe) {
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Osmesa);
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Egl);
  const nlohmann::json info = glInfo("--gl");  // a bare --gl: $VSIL_GL (unset here), else auto
  if (test::hardwareEglDevice()) {
    EXPECT_EQ(info["backend"], "egl") << info;
    EXPECT_TRUE(contains(info["platform"], "egl device")) << info;
  } else {
    EXPECT_EQ(info["backend"], "osmesa") << info;
  }
  // Without any EGL driver, auto still finds OSMesa; without OSMesa too, nothing is left.
  const auto noDriver = test::scratchDir() / "no-such-vendor.json";
  const test::ScopedEnvironment noEgl("__EGL_VENDOR_LIBRARY_FILENAMES", noDriver.c_str());
  EXPECT_EQ(glInfo("--gl auto")["backend"], "osmesa");
  const test::ScopedEnvironment softpipe("GALLIUM_DRIVER", "softpipe");
  const auto dir = test::scratchDir();
  const auto result = renderInto(dir, "--gl auto");
  expectUnavailable(result, dir, "--gl auto: no back end gave an OpenGL 4.5 core context (");
  EXPECT_TRUE(contains(result.err, "no other --gl choice works here")) << result.err;
}

TEST_F(GlChoice, EnvironmentChoosesWhenNoFlagDoes) {
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Osmesa);
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Egl);
  for (const char* backend : {"osmesa", "egl"}) {
    const test::ScopedEnvironment choice("VSIL_GL", backend);
    EXPECT_EQ(glInfo("--gl")["backend"], backend);
    const auto dir = test::scratchDir();
    ASSERT_EQ(renderInto(dir, "").exitCode, 0);
    EXPECT_EQ(nlohmann::json::parse(test::readFileBytes(dir / "meta.json"))["gl"]["backend"],
              backend);
  }
  const test::ScopedEnvironment choice("VSIL_GL", "egl");
  EXPECT_EQ(glInfo("--gl osmesa")["backend"], "osmesa") << "the flag wins over the environment";
  const test::ScopedEnvironment device("VSIL_GL_DEVICE", "0");
  EXPECT_EQ(glInfo("--gl")["egl_device"], 0);
}

TEST_F(GlChoice, EglWithoutADriverNamesWhatIsMissingAndOsmesa) {
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Osmesa);
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Egl);
  // glvnd's libEGL with no vendor library: no device platform, no surfaceless platform.
  const auto noDriver = test::scratchDir() / "no-such-vendor.json";
  const test::ScopedEnvironment noEgl("__EGL_VENDOR_LIBRARY_FILENAMES", noDriver.c_str());
  const auto dir = test::scratchDir();
  const auto result = renderInto(dir, "--gl egl");
  expectUnavailable(result, dir, "--gl egl: no EGL device or surfaceless platform");
  EXPECT_TRUE(contains(result.err, "EGL_MESA_platform_surfaceless")) << result.err;
  EXPECT_TRUE(result.err.ends_with("; try --gl osmesa\n")) << result.err;
}

TEST_F(GlChoice, DriverWithoutCore45IsNamedForEachBackEnd) {
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Osmesa);
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Egl);
  const std::optional<int> software = test::softwareEglDevice();
  ASSERT_TRUE(software) << "Mesa's software EGL device (libegl-mesa0)";
  // Mesa's softpipe offers OpenGL 3.3 only, for OSMesa and EGL's software device alike.
  const test::ScopedEnvironment softpipe("GALLIUM_DRIVER", "softpipe");
  const auto dir = test::scratchDir();
  const auto osmesa = renderInto(dir, "--gl osmesa");
  expectUnavailable(osmesa, dir, "--gl osmesa: no OSMesa OpenGL 4.5 core context (");
  const auto device = renderInto(dir, "--gl egl --gl-device " + std::to_string(*software));
  expectUnavailable(device, dir, "--gl-device " + std::to_string(*software) + ": device ");
  EXPECT_TRUE(contains(device.err, "no OpenGL 4.5 core context")) << device.err;
}

TEST_F(GlChoice, AnEglDeviceThatDoesNotExist) {
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Osmesa);
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Egl);
  const auto dir = test::scratchDir();
  const auto result = renderInto(dir, "--gl egl --gl-device 99");
  expectUnavailable(result, dir, "--gl-device 99: there is no EGL device 99 (found ");
  EXPECT_TRUE(contains(result.err, "; try --gl egl without --gl-device, or --gl osmesa\n"))
      << result.err;
}

// A device chosen by $VSIL_GL_DEVICE is named as the user set it, with the way out.
TEST_F(GlChoice, AnEglDeviceFromTheEnvironmentIsNamedSo) {
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Osmesa);
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Egl);
  const test::ScopedEnvironment device("VSIL_GL_DEVICE", "99");
  const auto dir = test::scratchDir();
  const auto result = renderInto(dir, "");
  expectUnavailable(result, dir, "VSIL_GL_DEVICE=99: there is no EGL device 99 (found ");
  EXPECT_TRUE(contains(result.err, "; try --gl egl with VSIL_GL_DEVICE unset, or --gl osmesa\n"))
      << result.err;
  const test::ScopedEnvironment osmesa("VSIL_GL", "osmesa");
  const auto both = renderInto(dir, "");
  EXPECT_EQ(both.exitCode, 2);
  EXPECT_EQ(both.err,
            "vsil: VSIL_GL_DEVICE=99 picks an EGL device: it goes with --gl egl or auto, not "
            "VSIL_GL=osmesa\n");
}

TEST_F(GlChoice, BadChoicesAreBadInput) {
  const auto dir = test::scratchDir();
  for (const char* flags : {"--gl vulkan", "--gl osmesa --gl-device 0", "--gl-device -1"}) {
    const auto result = renderInto(dir, flags);
    EXPECT_EQ(result.exitCode, 2) << flags << ": " << result.err;
    EXPECT_EQ(lineCount(result.err), 1) << result.err;
  }
  const test::ScopedEnvironment bad("VSIL_GL", "vulkan");
  const auto result = renderInto(dir, "");
  EXPECT_EQ(result.exitCode, 2) << result.err;
  EXPECT_EQ(result.err, "vsil: VSIL_GL 'vulkan': expected auto, osmesa or egl\n");
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

// In one process: contexts of both back ends, and two on one EGL display.

// The state image of a small sphere, rendered with `context`.
cv::Mat1b sphereState(gl::GlContext& context) {
  context.makeCurrent();
  Renderer renderer(context);
  const Volume volume = generateVolume("sphere:24");  // alive while rendered (setVolume)
  renderer.setVolume(volume);
  RenderSettings settings;
  settings.size = {40, 40};
  return renderer.render(settings).frame.state.clone();
}

TEST(GlContextInProcess, TwoEglContextsShareOneDisplay) {
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Egl);
  // Both on the same display: EGL does not count eglInitialize, so the first context's end must
  // not terminate the display under the second.
  auto first = std::make_unique<gl::GlContext>(gl::ContextOptions{gl::Backend::Egl, 0});
  gl::GlContext second({gl::Backend::Egl, 0});
  const cv::Mat1b before = sphereState(*first);
  EXPECT_GT(cv::countNonZero(before), 50);
  first.reset();
  const cv::Mat1b after = sphereState(second);
  EXPECT_EQ(cv::countNonZero(before != after), 0);
}

TEST(GlContextInProcess, AMissingExtensionIsNamedWithTheOtherBackEnd) {
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Osmesa);
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Egl);
  gl::GlContext context({gl::Backend::Osmesa, std::nullopt});
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  ASSERT_GT(count, 0);
  const std::string present = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, 0));
  EXPECT_NO_THROW(context.requireExtensions({present}, "--technique test"));
  try {
    context.requireExtensions({present, "GL_VSIL_no_such_extension"}, "--technique test");
    FAIL() << "no error for a missing extension";
  } catch (const UnavailableError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("--technique test needs GL_VSIL_no_such_extension, which llvmpipe", 0),
              0u)
        << message;
    EXPECT_TRUE(contains(message, "(--gl osmesa, osmesa) lacks; try --gl egl")) << message;
  }
  // Trying EGL for the message made its context current for a moment: this one still renders.
  EXPECT_GT(cv::countNonZero(sphereState(context)), 50);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// GlContext reaches Mesa's surfaceless platform only where the device platform fails; here it
// does not, so the platform is made directly through the back end, as GlContext would.
TEST(GlContextInProcess, MesaSurfacelessPlatformGivesA45CoreContext) {
  VSIL_REQUIRE_GL_BACKEND(gl::Backend::Egl);
  const auto context = gl::backends::createEglSurfacelessContext();
  context->makeCurrent();
  std::vector<std::string> missing;
  const gl::EntryPoints gl = gl::loadEntryPoints(context->getProcAddress(), missing);
  EXPECT_TRUE(missing.empty()) << missing.front();
  GLint major = 0, minor = 0, profile = 0;
  gl.glGetIntegerv(GL_MAJOR_VERSION, &major);
  gl.glGetIntegerv(GL_MINOR_VERSION, &minor);
  gl.glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_GE(major * 10 + minor, 45);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  EXPECT_EQ(gl.glGetError(), GLenum(GL_NO_ERROR));
}

}  // namespace
}  // namespace vsil
