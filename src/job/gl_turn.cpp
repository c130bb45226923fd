#include "job/gl_turn.h"

namespace vsil {
namespace {

std::mutex& processGlMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

GlTurn::GlTurn(RenderJob* job) : job_(job), lock_(processGlMutex()) {}

GlTurn::~GlTurn() {
  if (job_) job_->context().releaseCurrent();
}

}  // namespace vsil
