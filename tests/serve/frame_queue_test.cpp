// LatestOnlyQueue: one task at a time; a task not yet started is dropped for a newer one.
#include <chrono>
#include <future>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

#include "serve/frame_queue.h"

namespace vsil::serve {
namespace {

// Bounded waits: a broken queue fails the test instead of hanging it.
template <typename Predicate>
bool eventually(Predicate done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

TEST(LatestOnlyQueue, ATaskNotStartedIsReplacedByTheNewerOne) {
  LatestOnlyQueue queue;
  std::thread worker([&] { queue.workerLoop(); });
  std::promise<void> gate;
  std::shared_future<void> open = gate.get_future().share();
  std::atomic<bool> firstRunning = false, secondRan = false, thirdRan = false;

  auto first = std::async(std::launch::async, [&] {
    return queue.run([&] {
      firstRunning = true;
      open.wait();
    });
  });
  ASSERT_TRUE(eventually([&] { return firstRunning.load(); }));
  auto second =
      std::async(std::launch::async, [&] { return queue.run([&] { secondRan = true; }); });
  ASSERT_TRUE(eventually([&] { return queue.taskWaiting(); }));
  auto third = std::async(std::launch::async, [&] { return queue.run([&] { thirdRan = true; }); });

  EXPECT_FALSE(second.get());  // replaced while the first ran: it answers at once
  gate.set_value();
  EXPECT_TRUE(first.get());
  EXPECT_TRUE(third.get());
  EXPECT_FALSE(secondRan);
  EXPECT_TRUE(thirdRan);
  queue.close();
  worker.join();
}

TEST(LatestOnlyQueue, ATaskThrowsToItsCallerAndTheWorkerGoesOn) {
  LatestOnlyQueue queue;
  std::thread worker([&] { queue.workerLoop(); });
  EXPECT_THROW(queue.run([] { throw std::runtime_error("bad frame"); }), std::runtime_error);
  int ran = 0;
  EXPECT_TRUE(queue.run([&] { ++ran; }));
  EXPECT_EQ(ran, 1);
  queue.close();
  worker.join();
  EXPECT_FALSE(queue.run([&] { ++ran; }));  // closed: nothing runs
  EXPECT_EQ(ran, 1);
}

}  // namespace
}  // namespace vsil::serve
