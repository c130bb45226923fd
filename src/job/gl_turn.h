#pragma once
// Turns on the process's GL: GL state is process-wide (the function pointers of slicing/gl.h;
// a context current on one thread only), so a caller that lets several threads render in one
// process (the Python module: any thread may call any Renderer, of either back end) does every
// GL call — making a RenderJob, uploads, renders, destroying it — inside a turn, under one lock.
// A turn ends by releasing its job's context, so that the next turn may make any context
// current on any thread.
//
//   { GlTurn turn(&job); job.setVolume(...); output = job.render(request); }
//   { GlTurn turn(nullptr); auto job = std::make_unique<RenderJob>(gl); turn.setJob(job.get()); }
//
// tests/gl_backends/gl_turn_test.cpp drives it from 8 threads on every back end (under ASan in
// CI, where the Python module is not built).
#include <mutex>

#include "job/render_job.h"

namespace vsil {

class GlTurn {
 public:
  // Waits for the process's GL lock.
  explicit GlTurn(RenderJob* job);
  // Releases `job`'s context (if any), then the lock.
  ~GlTurn();
  GlTurn(const GlTurn&) = delete;
  GlTurn& operator=(const GlTurn&) = delete;
  // The job whose context the turn ends by releasing (one made during the turn).
  void setJob(RenderJob* job) { job_ = job; }

 private:
  RenderJob* job_;
  std::unique_lock<std::mutex> lock_;
};

}  // namespace vsil
