#include "runner/ordered_worker.h"

#include <utility>

namespace viqu::runner {

OrderedWorker::OrderedWorker(size_t max_pending, bool inline_mode)
    : max_pending_(max_pending < 1 ? 1 : max_pending), inline_(inline_mode) {
  if (!inline_) thread_ = std::thread([this] { Loop(); });
}

OrderedWorker::~OrderedWorker() {
  try {
    Finish();
  } catch (...) {
    // The owner did not call Finish(): a failure is already on its way up (or it chose not to
    // look); a destructor must not throw.
  }
}

void OrderedWorker::RethrowLocked(std::unique_lock<std::mutex>& lock) {
  if (!error_) return;
  std::exception_ptr e = error_;
  lock.unlock();
  std::rethrow_exception(e);
}

uint64_t OrderedWorker::Post(std::function<void()> task) {
  if (inline_) {
    const uint64_t seq = posted_++;
    if (error_) std::rethrow_exception(error_);
    try {
      task();
    } catch (...) {
      error_ = std::current_exception();
      throw;
    }
    ++done_;
    return seq;
  }
  std::unique_lock<std::mutex> lock(mu_);
  changed_.wait(lock, [&] { return error_ || queue_.size() < max_pending_; });
  RethrowLocked(lock);
  queue_.push_back(std::move(task));
  const uint64_t seq = posted_++;
  changed_.notify_all();
  return seq;
}

void OrderedWorker::WaitUntil(uint64_t seq) {
  if (inline_) {
    if (error_) std::rethrow_exception(error_);
    return;
  }
  std::unique_lock<std::mutex> lock(mu_);
  changed_.wait(lock, [&] { return error_ || done_ > seq; });
  RethrowLocked(lock);
}

void OrderedWorker::Finish() {
  if (inline_) {
    if (error_) std::rethrow_exception(error_);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mu_);
    closing_ = true;
    changed_.notify_all();
  }
  if (thread_.joinable()) thread_.join();
  std::unique_lock<std::mutex> lock(mu_);
  RethrowLocked(lock);
}

void OrderedWorker::Loop() {
  std::unique_lock<std::mutex> lock(mu_);
  while (true) {
    changed_.wait(lock, [&] { return closing_ || !queue_.empty(); });
    if (queue_.empty()) return;  // closing and nothing left
    std::function<void()> task = std::move(queue_.front());
    queue_.pop_front();
    changed_.notify_all();  // room in the queue
    if (error_) {
      ++done_;  // dropped: an earlier task failed
      continue;
    }
    lock.unlock();
    std::exception_ptr failure;
    try {
      task();
    } catch (...) {
      failure = std::current_exception();
    }
    task = nullptr;  // free what the task held (a frame) before taking the next
    lock.lock();
    if (failure && !error_) error_ = failure;
    ++done_;
    changed_.notify_all();
  }
}

}  // namespace viqu::runner
