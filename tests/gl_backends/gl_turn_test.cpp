// The process's GL turns (job/gl_turn.h), as the Python module takes them: 8 threads x 20
// renders over one shared RenderJob per back end and one job of each thread's own, every render
// in a turn, every fifth one uploading the volume again (as a render of a path does). Every
// image must be the one a single thread renders. Without the lock this crashed (process-wide
// GL function pointers, a context current on another thread); this is the test that runs under
// ASan (scripts/test-asan.sh), where the Python module is not built.
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "backend_support.h"
#include "io/volume_loader.h"
#include "job/gl_turn.h"
#include "job/render_job.h"

namespace vsil {
namespace {

// The back ends this build and machine give a context on; one not built is left out, one built
// but not loadable fails where VSIL_TEST_ALL_GL_BACKENDS=1 (CI).
std::vector<gl::Backend> backendsHere() {
  std::vector<gl::Backend> found;
  for (gl::Backend backend : gl::builtBackends()) {
    if (const auto why = test::missingBackend(backend)) {
      if (test::allBackendsRequired()) ADD_FAILURE() << *why;
      continue;
    }
    found.push_back(backend);
  }
  return found;
}

std::unique_ptr<RenderJob> makeJob(gl::Backend backend, const std::shared_ptr<Volume>& volume) {
  GlTurn turn(nullptr);
  gl::ContextOptions options;
  options.backend = backend;
  auto job = std::make_unique<RenderJob>(options);
  turn.setJob(job.get());
  job->setVolume(Volume::sharing(volume));
  return job;
}

RenderRequest request(int k) {
  RenderRequest r;
  r.settings.size = {40, 32};
  r.settings.camera.azimuthDeg = 15.0 * k;
  r.settings.camera.elevationDeg = 10.0;
  r.settings.options["iso"] = 0.3 + 0.1 * k;
  return r;
}

TEST(GlTurns, EightThreadsRenderingInTurnsGetTheImagesOneThreadGets) {
  const std::vector<gl::Backend> backends = backendsHere();
  ASSERT_FALSE(backends.empty()) << "no GL back end";
  auto volume = std::make_shared<Volume>(loadVolume("gen:spheres:24", {}));
  constexpr int kRequests = 5, kThreads = 8, kRenders = 20;
  std::vector<std::unique_ptr<RenderJob>> shared;
  for (gl::Backend backend : backends) shared.push_back(makeJob(backend, volume));
  std::vector<cv::Mat> expected;
  for (int k = 0; k < kRequests; ++k) {
    GlTurn turn(shared[0].get());
    expected.push_back(shared[0]->render(request(k)).image.clone());
  }

  std::mutex failuresMutex;
  std::vector<std::string> failures;
  auto work = [&](int index) {
    try {
      auto own = makeJob(backends[std::size_t(index) % backends.size()], volume);
      for (int i = 0; i < kRenders; ++i) {
        const int k = (index + i) % kRequests;
        RenderJob& job = i % 3 == 0 ? *own : *shared[std::size_t(i) % shared.size()];
        cv::Mat image;
        {
          GlTurn turn(&job);
          if (i % 5 == 1) job.setVolume(Volume::sharing(volume));
          image = job.render(request(k)).image;
        }
        if (image.size() != expected[k].size() || cv::norm(image, expected[k], cv::NORM_INF) != 0) {
          std::lock_guard lock(failuresMutex);
          failures.push_back("thread " + std::to_string(index) + " render " + std::to_string(i));
        }
      }
      GlTurn turn(nullptr);  // the job's destructor makes its context current
      own.reset();
    } catch (const std::exception& error) {
      std::lock_guard lock(failuresMutex);
      failures.push_back("thread " + std::to_string(index) + ": " + error.what());
    }
  };
  std::vector<std::thread> threads;
  for (int index = 0; index < kThreads; ++index) threads.emplace_back(work, index);
  for (std::thread& thread : threads) thread.join();
  EXPECT_TRUE(failures.empty()) << failures.size() << " failures, first: " << failures.front();
  GlTurn turn(nullptr);
  shared.clear();
}

}  // namespace
}  // namespace vsil
