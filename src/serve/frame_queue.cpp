#include "serve/frame_queue.h"

namespace vsil::serve {

bool LatestOnlyQueue::run(std::function<void()> task) {
  auto slot = std::make_shared<Slot>();
  slot->task = std::move(task);
  std::unique_lock lock(mutex_);
  if (closed_) return false;
  if (waiting_) waiting_->state = State::Dropped;
  waiting_ = slot;
  changed_.notify_all();
  changed_.wait(lock, [&] { return slot->state == State::Done || slot->state == State::Dropped; });
  if (slot->state == State::Dropped) return false;
  if (slot->error) std::rethrow_exception(slot->error);
  return true;
}

void LatestOnlyQueue::workerLoop() {
  std::unique_lock lock(mutex_);
  while (true) {
    changed_.wait(lock, [&] { return closed_ || waiting_ != nullptr; });
    if (closed_) return;
    std::shared_ptr<Slot> slot = std::move(waiting_);
    waiting_ = nullptr;
    slot->state = State::Running;
    lock.unlock();
    try {
      slot->task();
    } catch (...) {
      slot->error = std::current_exception();
    }
    lock.lock();
    slot->state = State::Done;
    changed_.notify_all();
  }
}

bool LatestOnlyQueue::taskWaiting() {
  std::lock_guard lock(mutex_);
  return waiting_ != nullptr;
}

void LatestOnlyQueue::close() {
  std::lock_guard lock(mutex_);
  closed_ = true;
  if (waiting_) waiting_->state = State::Dropped;
  waiting_ = nullptr;
  changed_.notify_all();
}

}  // namespace vsil::serve
