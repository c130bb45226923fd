// Renderers made and destroyed over and over (as a benchmark or a batch job does) leak neither
// GL objects nor memory. GL objects: after the cycles, no more textures, framebuffers, buffers,
// vertex arrays, programs or shaders are alive than before them. Memory: the
// resident set after warm-up grows by less than a few MiB over many more cycles.
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>

#include <gtest/gtest.h>

#include "frame_compare.h"
#include "generators/generators.h"
#include "reference/gl_harness.h"
#include "slicing/gl.h"
#include "slicing/gl_context.h"
#include "slicing/renderer.h"
#include "slicing/technique_table.h"

namespace vsil {
namespace {

using test::GlTest;

std::size_t residentBytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * std::size_t(::sysconf(_SC_PAGESIZE));
}

// How many objects of each kind are alive among the names handed out so far. Mesa (22.3 here)
// does not reuse deleted names, it counts up; so "names are reused" cannot be the test. Instead
// every name up to a freshly generated one is asked whether it is still an object.
struct LiveObjects {
  int textures = 0, framebuffers = 0, buffers = 0, vertexArrays = 0, programsAndShaders = 0;
  GLuint highestName = 0;
  bool operator==(const LiveObjects&) const = default;
};

LiveObjects liveObjects() {
  GLuint texture = 0, framebuffer = 0, buffer = 0, vertexArray = 0;
  glGenTextures(1, &texture);
  glGenFramebuffers(1, &framebuffer);
  glGenBuffers(1, &buffer);
  glGenVertexArrays(1, &vertexArray);
  const GLuint program = glCreateProgram();
  glDeleteTextures(1, &texture);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteBuffers(1, &buffer);
  glDeleteVertexArrays(1, &vertexArray);
  glDeleteProgram(program);
  LiveObjects live;
  for (GLuint name = 1; name < texture; ++name) live.textures += glIsTexture(name);
  for (GLuint name = 1; name < framebuffer; ++name) live.framebuffers += glIsFramebuffer(name);
  for (GLuint name = 1; name < buffer; ++name) live.buffers += glIsBuffer(name);
  for (GLuint name = 1; name < vertexArray; ++name) live.vertexArrays += glIsVertexArray(name);
  for (GLuint name = 1; name < program; ++name) {
    live.programsAndShaders += glIsProgram(name) || glIsShader(name);
  }
  live.highestName = std::max({texture, framebuffer, buffer, vertexArray, program});
  return live;
}

void renderCycle(const Volume& volume) {
  Renderer renderer(test::sharedGlContext());
  renderer.setVolume(volume);
  for (const auto& technique : techniqueTable()) {
    RenderSettings settings;
    settings.technique = technique.name;
    settings.options = test::isoOptions(technique, 0.5);
    settings.size = {256, 192};
    renderer.render(settings);
  }
}

TEST_F(GlTest, RenderersLeakNoGlObjectsAndNoMemory) {
  const Volume volume = generateVolume("sphere:32");
  renderCycle(volume);  // first use: shaders compiled, Mesa's caches filled
  const LiveObjects before = liveObjects();

#if defined(__SANITIZE_ADDRESS__)
  // The resident set is not measured under ASan (below): a few cycles show leaked GL objects,
  // and LeakSanitizer the rest.
  constexpr int kWarmUp = 2, kCycles = 8;
#else
  constexpr int kWarmUp = 5, kCycles = 40;
#endif
  for (int i = 0; i < kWarmUp; ++i) renderCycle(volume);
  // Allocators settle over the first cycles; a leak keeps growing. So the growth is measured
  // over the second half of the cycles only.
  for (int i = 0; i < kCycles / 2; ++i) renderCycle(volume);
  const std::size_t residentBefore = residentBytes();
  for (int i = kCycles / 2; i < kCycles; ++i) renderCycle(volume);
  const std::size_t residentAfter = residentBytes();
  LiveObjects after = liveObjects();

  // Every object a cycle made was deleted: as many live objects as before the cycles (a leak
  // of k objects per cycle would add k·45), though far more names were handed out.
  EXPECT_GT(after.highestName, before.highestName + kCycles) << "the cycles made no objects?";
  EXPECT_EQ(after.textures, before.textures);
  EXPECT_EQ(after.framebuffers, before.framebuffers);
  EXPECT_EQ(after.buffers, before.buffers);
  EXPECT_EQ(after.vertexArrays, before.vertexArrays);
  EXPECT_EQ(after.programsAndShaders, before.programsAndShaders);

  // Each cycle makes ~1.6 MiB of render targets (two RGBA32F 256x192 and more) and a 128 KiB
  // texture: leaking one frame's objects per cycle would add > 30 MiB over 20 cycles. 4 MiB is
  // allocator noise (seen up to 4.4 MiB over 40 cycles from the first, on a loaded machine).
#if defined(__SANITIZE_ADDRESS__)
  // ASan keeps freed memory in quarantine (256 MiB), so the resident set grows by design;
  // LeakSanitizer checks for leaks at exit instead.
  (void)residentBefore;
  (void)residentAfter;
#else
  const auto mebibytes = [](std::size_t from, std::size_t to) {
    return (double(to) - double(from)) / (1 << 20);
  };
  double growthMiB = mebibytes(residentBefore, residentAfter);
  if (growthMiB >= 4.0) {
    // A one-off step (seen: 6.1 MiB under ctest -j2, the same build passing alone) does not
    // come again; a leak grows by as much over the next cycles.
    for (int i = 0; i < kCycles / 2; ++i) renderCycle(volume);
    const double again = mebibytes(residentAfter, residentBytes());
    std::cout << "[ info ] resident set grew by " << growthMiB << " MiB, then by " << again
              << " MiB over " << kCycles / 2 << " more cycles\n";
    growthMiB = std::min(growthMiB, again);
  }
  EXPECT_LT(growthMiB, 4.0) << "resident set grew by 4 MiB or more over " << kCycles / 2
                            << " cycles, twice running";
#endif
}

// Two renderers on two contexts (two vsil.Renderer in one Python process): the one destroyed
// while the other's context is current deletes its own objects, not the other's of the same
// names, and the other renders on.
TEST_F(GlTest, ARendererDestroyedUnderAnotherContextLeavesThatOnesObjects) {
  const Volume volume = generateVolume("spheres:48");
  RenderSettings settings;
  settings.technique = "silhouette";
  settings.options = test::isoOptions(findTechnique("silhouette"), 0.5);
  settings.size = {64, 48};
  Renderer staying(test::sharedGlContext());
  staying.setVolume(volume);
  const RenderResult before = staying.render(settings);
  {
    gl::GlContext otherContext(gl::contextOptionsFromEnvironment());
    auto leaving = std::make_unique<Renderer>(otherContext);
    leaving->setVolume(volume);
    leaving->render(settings);
    test::sharedGlContext().makeCurrent();  // as the other vsil.Renderer's next call would
    leaving.reset();
    test::sharedGlContext().makeCurrent();
  }
  const RenderResult after = staying.render(settings);
  EXPECT_EQ(cv::norm(before.frame.state, after.frame.state, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::countNonZero(after.frame.state), 100);
}

}  // namespace
}  // namespace vsil
