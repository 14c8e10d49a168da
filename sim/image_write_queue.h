#pragma once
// Encodes and writes images on a background thread, so that a recording run renders the next
// frame while the last one is compressed. Bounded: Push blocks while `max_pending` images wait.
//
// The thread runs at the lowest scheduling priority (nice 19; on Linux the nice value is per
// thread): the simulation and estimator stages pace a run, and on a machine with fewer cores
// than busy threads an encoder at their priority takes their time (walking_people with
// --record, 2 cores: wall time 0.98x with it lowered, 4 pairs). It works in their gaps instead,
// and the default queue of 40 images (ten frames of a recording: about 30 MB at 640x480)
// carries it over their busy stretches.
#include <condition_variable>
#include <deque>
#include <mutex>
#include <string>
#include <thread>

#include <opencv2/core/mat.hpp>

#include "sim/png_writer.h"

namespace viqu::sim {

class ImageWriteQueue {
 public:
  explicit ImageWriteQueue(size_t max_pending = 40);
  // Stops the worker; images still waiting are dropped (the caller discards a partial dataset).
  ~ImageWriteQueue();
  ImageWriteQueue(const ImageWriteQueue&) = delete;
  ImageWriteQueue& operator=(const ImageWriteQueue&) = delete;

  // Queues `image` (which must not be modified afterwards by the caller: pass a copy or a Mat
  // that is not reused) for WritePng(path, image, content) (sim/png_writer.h: RGB byte order for
  // colour). Throws viqu::RunError if an earlier write failed.
  void Push(std::string path, cv::Mat image, PngContent content);

  // Waits until every queued image is written; throws viqu::RunError naming the first failure.
  void Drain();

 private:
  struct Job {
    std::string path;
    cv::Mat image;
    PngContent content;
  };
  void Work();
  void ThrowIfFailed();  // with mutex_ held

  size_t max_pending_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> jobs_;
  bool busy_ = false;     // the worker is writing a job it has taken off the queue
  bool stop_ = false;
  std::string error_;     // first failure, empty if none
  std::thread worker_;
};

}  // namespace viqu::sim
