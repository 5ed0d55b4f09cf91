#pragma once
// A capture's frames written on a thread of their own (issue 39, point 4): the census, the masks'
// changes, the PNG and EXR encoding and writing, the video and the stats line of frame k run while
// the render thread draws frame k+1. Jobs run one at a time in the order submitted; at most
// `backlog` wait, so that memory stays flat when writing is the slower side.
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace tallow::app {

class FrameWriter {
 public:
  explicit FrameWriter(std::size_t backlog = 1);
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;
  /// Waits for the jobs submitted (a failure is dropped here: call finish() to see it).
  ~FrameWriter();

  /// Queues `job`, waiting while `backlog` jobs are queued already. Rethrows the first failed job's
  /// exception (the jobs after a failure are not run).
  void submit(std::function<void()> job);
  /// Waits for every job submitted; rethrows the first failure.
  void finish();
  /// Waits for every job submitted (or the first failure), rethrowing nothing: before the render
  /// thread, stopped by an error of its own, touches what the jobs use.
  void settle() noexcept;

 private:
  void run();
  void rethrowFailure();

  const std::size_t backlog_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::function<void()>> jobs_;
  bool busy_ = false;
  bool stopping_ = false;
  std::exception_ptr failure_;
  std::thread thread_;  ///< last: started when the rest is ready
};

}  // namespace tallow::app
