#pragma once
// One render at a time, on the thread that owns the GL context, and only the latest view: a task
// that has not started when a newer one arrives is dropped ("superseded"), so a drag that sends
// many views renders the last one next instead of every one in turn. At most one task waits and
// one runs: the queue is bounded by construction.
#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>

namespace vsil::serve {

class LatestOnlyQueue {
 public:
  // Runs `task` on the worker (the thread in workerLoop) and returns true when it ran (its
  // exception rethrown here), false when a newer submission replaced it before it started or the
  // queue closed. Blocks the caller until then.
  bool run(std::function<void()> task);

  // The worker: runs the submitted tasks one by one until close().
  void workerLoop();
  // Whether a task waits for the worker (for tests).
  bool taskWaiting();
  // Wakes every waiter (their tasks not started: false) and ends workerLoop after its task.
  void close();

 private:
  enum class State { Waiting, Running, Done, Dropped };
  struct Slot {
    std::function<void()> task;
    State state = State::Waiting;
    std::exception_ptr error;
  };

  std::mutex mutex_;
  std::condition_variable changed_;
  std::shared_ptr<Slot> waiting_;  // the one task not yet started
  bool closed_ = false;
};

}  // namespace vsil::serve
