#include "processing/util/background_queue.h"

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

namespace plenopath {

struct BackgroundQueue::Impl {
  int capacity = 2;
  std::mutex mutex;
  std::condition_variable changed;  // a job queued, a job done, or stopping
  std::deque<std::function<void()>> waiting;
  bool running = false;  // the worker holds a job
  bool stopping = false;
  std::exception_ptr error;
  std::thread worker;

  void worker_main() {
    std::unique_lock<std::mutex> lock(mutex);
    while (true) {
      changed.wait(lock, [&] { return stopping || !waiting.empty(); });
      if (waiting.empty()) return;  // stopping with nothing left
      std::function<void()> job = std::move(waiting.front());
      waiting.pop_front();
      running = true;
      const bool skip = static_cast<bool>(error);
      lock.unlock();
      std::exception_ptr failure;
      if (!skip) {
        try {
          job();
        } catch (...) {
          failure = std::current_exception();
        }
      }
      job = nullptr;  // release what the job captured before anyone is told it is done
      lock.lock();
      if (failure && !error) error = failure;
      running = false;
      changed.notify_all();
    }
  }

  void rethrow_locked() {
    if (!error) return;
    std::exception_ptr e = error;
    error = nullptr;
    std::rethrow_exception(e);
  }
};

BackgroundQueue::BackgroundQueue(int capacity) : impl_(std::make_unique<Impl>()) {
  impl_->capacity = std::max(1, capacity);
  impl_->worker = std::thread([this] { impl_->worker_main(); });
}

BackgroundQueue::~BackgroundQueue() {
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->stopping = true;
  }
  impl_->changed.notify_all();
  impl_->worker.join();
}

void BackgroundQueue::submit(std::function<void()> job) {
  std::unique_lock<std::mutex> lock(impl_->mutex);
  impl_->changed.wait(lock, [&] {
    return static_cast<int>(impl_->waiting.size()) < impl_->capacity || static_cast<bool>(impl_->error);
  });
  if (impl_->error) {
    impl_->changed.wait(lock, [&] { return impl_->waiting.empty() && !impl_->running; });
    impl_->rethrow_locked();
  }
  impl_->waiting.push_back(std::move(job));
  impl_->changed.notify_all();
}

void BackgroundQueue::finish() {
  std::unique_lock<std::mutex> lock(impl_->mutex);
  impl_->changed.wait(lock, [&] { return impl_->waiting.empty() && !impl_->running; });
  impl_->rethrow_locked();
}

int BackgroundQueue::capacity() const { return impl_->capacity; }

}  // namespace plenopath
