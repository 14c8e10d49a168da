// The estimator stage's executor (runner/ordered_worker.h): order, the bound on waiting tasks,
// waiting for a given task, failures carried to the producer, and the inline (sequential) mode.
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "runner/ordered_worker.h"

namespace viqu::runner {
namespace {

TEST(OrderedWorker, RunsTasksInPostingOrderOnAnotherThread) {
  for (bool inline_mode : {false, true}) {
    std::vector<int> seen;  // only the worker writes it until Finish()
    std::thread::id worker_thread;
    OrderedWorker w(3, inline_mode);
    for (int i = 0; i < 1000; ++i) {
      EXPECT_EQ(w.Post([&seen, &worker_thread, i] {
        seen.push_back(i);
        worker_thread = std::this_thread::get_id();
      }),
                static_cast<uint64_t>(i));
    }
    w.Finish();
    ASSERT_EQ(seen.size(), 1000u);
    for (int i = 0; i < 1000; ++i) EXPECT_EQ(seen[i], i);
    EXPECT_EQ(worker_thread == std::this_thread::get_id(), inline_mode);
  }
}

TEST(OrderedWorker, PostBlocksWhileTheQueueIsFull) {
  std::atomic<bool> release{false};
  std::atomic<int> started{0};
  OrderedWorker w(2, false);
  w.Post([&] {
    ++started;
    while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  });
  while (started == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  // One task runs; two may wait; the fourth post must block until the first finishes.
  w.Post([] {});
  w.Post([] {});
  std::atomic<bool> fourth_posted{false};
  std::thread producer([&] {
    w.Post([] {});
    fourth_posted = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_FALSE(fourth_posted);
  release = true;
  producer.join();
  EXPECT_TRUE(fourth_posted);
  w.Finish();
}

TEST(OrderedWorker, WaitUntilSeesEveryEarlierTaskDone) {
  std::atomic<int> done{0};
  OrderedWorker w(8, false);
  uint64_t seq = 0;
  for (int i = 0; i < 20; ++i) {
    seq = w.Post([&] {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      ++done;
    });
    w.WaitUntil(seq);
    EXPECT_EQ(done.load(), i + 1);
  }
  w.Finish();
}

TEST(OrderedWorker, AFailureStopsTheStageAndReachesTheProducer) {
  for (bool inline_mode : {false, true}) {
    std::atomic<int> ran_after{0};
    OrderedWorker w(4, inline_mode);
    bool thrown = false;
    try {
      w.Post([] { throw std::runtime_error("frame 3: bad image"); });
      for (int i = 0; i < 10; ++i) w.Post([&] { ++ran_after; });
      w.Finish();
    } catch (const std::runtime_error& e) {
      thrown = true;
      EXPECT_STREQ(e.what(), "frame 3: bad image");
    }
    EXPECT_TRUE(thrown) << inline_mode;
    EXPECT_EQ(ran_after.load(), 0) << inline_mode;  // nothing after the failed task runs
    EXPECT_THROW(w.Finish(), std::runtime_error);    // and the failure stays
  }
}

}  // namespace
}  // namespace viqu::runner
