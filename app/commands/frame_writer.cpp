#include "app/commands/frame_writer.h"

namespace tallow::app {

FrameWriter::FrameWriter(std::size_t backlog) : backlog_(backlog == 0 ? 1 : backlog), thread_([this] { run(); }) {}

FrameWriter::~FrameWriter() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void FrameWriter::rethrowFailure() {
  if (failure_) std::rethrow_exception(failure_);
}

void FrameWriter::submit(std::function<void()> job) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return failure_ || jobs_.size() < backlog_; });
  rethrowFailure();
  jobs_.push_back(std::move(job));
  lock.unlock();
  changed_.notify_all();
}

void FrameWriter::finish() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return failure_ || (jobs_.empty() && !busy_); });
  rethrowFailure();
}

void FrameWriter::settle() noexcept {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return failure_ || (jobs_.empty() && !busy_); });
  // After a failure the job that failed has ended and no other runs.
  changed_.wait(lock, [&] { return !busy_; });
}

void FrameWriter::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return stopping_ || !jobs_.empty(); });
    if (jobs_.empty()) return;  // stopping, nothing left
    std::function<void()> job = std::move(jobs_.front());
    jobs_.pop_front();
    busy_ = true;
    lock.unlock();
    changed_.notify_all();  // room in the queue
    std::exception_ptr failed;
    try {
      job();
    } catch (...) {
      failed = std::current_exception();
    }
    lock.lock();
    busy_ = false;
    if (failed && !failure_) {
      failure_ = failed;
      jobs_.clear();  // nothing after a failure is written
    }
    changed_.notify_all();
  }
}

}  // namespace tallow::app
