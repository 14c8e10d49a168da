#pragma once
// A stage of the run loop on its own thread: tasks run one at a time in the order they were
// posted, so a stage that consumes the simulation's measurements sees them exactly as a
// sequential loop would, whatever the thread timing. The queue between the producer and the
// stage is bounded: Post() blocks while `max_pending` tasks wait, which bounds the memory a
// slow stage can hold (a task typically carries one camera frame). Inline mode runs each task
// inside Post() on the caller's thread: the sequential loop, for comparison.
//
// A task that throws stops the stage: the tasks after it are dropped, and the exception is
// rethrown on the producer's thread by the next Post(), WaitUntil() or Finish().

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace viqu::runner {

class OrderedWorker {
 public:
  // `inline_mode`: no thread; Post() runs the task at once.
  OrderedWorker(size_t max_pending, bool inline_mode);
  ~OrderedWorker();  // runs what is queued, then joins (exceptions then are swallowed: call Finish)
  OrderedWorker(const OrderedWorker&) = delete;
  OrderedWorker& operator=(const OrderedWorker&) = delete;

  // Queues `task` (blocks while the queue is full). Returns its sequence number (0, 1, ...).
  uint64_t Post(std::function<void()> task);
  // Blocks until the task with sequence number `seq` and all before it have run.
  void WaitUntil(uint64_t seq);
  // Runs everything queued, stops the thread, rethrows a task's exception.
  void Finish();

  bool inline_mode() const { return inline_; }

 private:
  void Loop();
  void RethrowLocked(std::unique_lock<std::mutex>& lock);

  const size_t max_pending_;
  const bool inline_;
  std::mutex mu_;
  std::condition_variable changed_;          // queue or progress changed
  std::deque<std::function<void()>> queue_;  // guarded by mu_
  uint64_t posted_ = 0;                      // tasks posted (guarded by mu_)
  uint64_t done_ = 0;                        // tasks run or dropped (guarded by mu_)
  bool closing_ = false;                     // no more tasks (guarded by mu_)
  std::exception_ptr error_;                 // first task failure (guarded by mu_)
  std::thread thread_;
};

}  // namespace viqu::runner
