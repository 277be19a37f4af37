#pragma once
// One background thread running jobs in the order they were queued, with a bounded queue: a producer
// (`render` encoding frame i while frame i + 1 renders) runs at most `capacity` jobs ahead of the writer
// and never holds more than capacity + 1 of its buffers in the writer's hands.
#include <functional>
#include <memory>

namespace plenopath {

class BackgroundQueue {
 public:
  // capacity >= 1: how many jobs may wait (besides the one running) before submit() blocks.
  explicit BackgroundQueue(int capacity = 2);
  // Waits for the queued jobs, dropping their errors (call finish() to see them).
  ~BackgroundQueue();
  BackgroundQueue(const BackgroundQueue&) = delete;
  BackgroundQueue& operator=(const BackgroundQueue&) = delete;

  // Queues `job`, blocking while `capacity` jobs wait. When submit() returns, every job queued more than
  // `capacity` submissions before this one has run and been destroyed (so has whatever it captured).
  // Rethrows the first exception a job threw (once the queue is drained); after one, the jobs still
  // queued are skipped.
  void submit(std::function<void()> job);
  // Waits until every queued job has run; rethrows the first exception a job threw.
  void finish();
  int capacity() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace plenopath
