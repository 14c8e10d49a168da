#include "sim/image_write_queue.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "common/errors.h"

namespace viqu::sim {

ImageWriteQueue::ImageWriteQueue(size_t max_pending)
    : max_pending_(max_pending == 0 ? 1 : max_pending), worker_([this] { Work(); }) {}

ImageWriteQueue::~ImageWriteQueue() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    jobs_.clear();
  }
  changed_.notify_all();
  worker_.join();
}

void ImageWriteQueue::ThrowIfFailed() {
  if (!error_.empty()) throw RunError(error_);
}

void ImageWriteQueue::Push(std::string path, cv::Mat image, PngContent content) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return jobs_.size() < max_pending_ || !error_.empty(); });
  ThrowIfFailed();
  jobs_.push_back(Job{std::move(path), std::move(image), content});
  changed_.notify_all();
}

void ImageWriteQueue::Drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return (jobs_.empty() && !busy_) || !error_.empty(); });
  ThrowIfFailed();
}

void ImageWriteQueue::Work() {
  // Lowest priority for this thread only (a failure leaves it at the default: nothing else
  // depends on it).
  setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 19);
  PngEncoder encoder;  // its buffers serve every image of the queue
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    changed_.wait(lock, [this] { return stop_ || !jobs_.empty(); });
    if (stop_) return;
    Job job = std::move(jobs_.front());
    jobs_.pop_front();
    busy_ = true;
    changed_.notify_all();
    lock.unlock();
    std::string failure;
    try {
      failure = WritePng(job.path, job.image, job.content, &encoder);
    } catch (const std::exception& e) {
      failure = "cannot write " + job.path + ": " + e.what();
    }
    lock.lock();
    busy_ = false;
    if (!failure.empty() && error_.empty()) error_ = failure;
    changed_.notify_all();
  }
}

}  // namespace viqu::sim
