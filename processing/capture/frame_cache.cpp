#include "processing/capture/frame_cache.h"

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <iostream>
#include <list>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <set>
#include <thread>
#include <unordered_map>

#include "model/error.h"
#include "processing/capture/frame_source.h"

namespace plenopath {

void FrameCacheOptions::check() const {
  if (frame_bytes_bound == 0) throw Error("frame cache: frame_bytes_bound must be positive");
  if (thumbnail_bytes_bound == 0) throw Error("frame cache: thumbnail_bytes_bound must be positive");
  if (thumbnail_width < 8) throw Error("frame cache: thumbnail_width must be at least 8 pixels");
  if (prefetch_ahead < 0 || prefetch_behind < 0)
    throw Error("frame cache: prefetch_ahead and prefetch_behind must be >= 0");
}

namespace {

std::size_t bytes_of(const cv::Mat& m) { return m.total() * m.elemSize(); }

// Least-recently-used store of Mats with a byte bound. Not thread-safe by itself.
class LruStore {
 public:
  explicit LruStore(std::size_t bound) : bound_(bound) {}

  bool contains(int i) const { return entries_.count(i) != 0; }
  cv::Mat touch(int i) {
    auto it = entries_.find(i);
    if (it == entries_.end()) return {};
    order_.splice(order_.begin(), order_, it->second.position);
    return it->second.image;
  }
  cv::Mat peek(int i) const {
    auto it = entries_.find(i);
    return it == entries_.end() ? cv::Mat() : it->second.image;
  }
  // Keeps `image` as the most recently used, evicting the least recently used until it fits.
  // Returns the number of evictions; an image larger than the bound is not kept.
  long insert(int i, const cv::Mat& image) {
    const std::size_t bytes = bytes_of(image);
    if (bytes > bound_) return 0;
    erase(i);
    long evicted = 0;
    while (bytes_ + bytes > bound_ && !order_.empty()) {
      erase(order_.back());
      ++evicted;
    }
    order_.push_front(i);
    entries_[i] = Entry{image, order_.begin(), bytes};
    bytes_ += bytes;
    peak_bytes_ = std::max(peak_bytes_, bytes_);
    return evicted;
  }
  void erase(int i) {
    auto it = entries_.find(i);
    if (it == entries_.end()) return;
    bytes_ -= it->second.bytes;
    order_.erase(it->second.position);
    entries_.erase(it);
  }
  void clear() {
    entries_.clear();
    order_.clear();
    bytes_ = 0;
  }
  std::size_t bytes() const { return bytes_; }
  std::size_t peak_bytes() const { return peak_bytes_; }
  std::size_t bound() const { return bound_; }
  int size() const { return static_cast<int>(entries_.size()); }

 private:
  struct Entry {
    cv::Mat image;
    std::list<int>::iterator position;
    std::size_t bytes = 0;
  };
  std::size_t bound_;
  std::size_t bytes_ = 0;
  std::size_t peak_bytes_ = 0;
  std::list<int> order_;  // front = most recently used
  std::unordered_map<int, Entry> entries_;
};

}  // namespace

struct FrameCache::Impl {
  std::shared_ptr<FrameSource> source;
  FrameCacheOptions options;

  mutable std::mutex mutex;
  std::condition_variable work_ready;     // worker: something queued or stopping
  std::condition_variable state_changed;  // a decode finished, or the worker went idle
  LruStore frames;
  LruStore thumbnails;
  std::set<int> frames_in_flight, thumbnails_in_flight;
  std::deque<int> frame_queue, thumbnail_queue;
  bool worker_busy = false;
  bool stopping = false;
  FrameCacheStats counters;
  std::vector<std::pair<int, std::string>> failures;
  std::set<int> failed_frames;
  std::thread worker;

  Impl(std::shared_ptr<FrameSource> s, const FrameCacheOptions& o)
      : source(std::move(s)), options(o), frames(o.frame_bytes_bound), thumbnails(o.thumbnail_bytes_bound) {}

  void record_failure(int i, const std::string& message) {  // mutex held
    ++counters.failed;
    if (failed_frames.insert(i).second && failures.size() < 10000) failures.emplace_back(i, message);
  }

  // How many full frames fit under the bound; prefetching more would only evict what it just decoded.
  int frames_that_fit() const {
    const std::size_t frame_bytes = std::size_t(source->width()) * source->height() * 3;
    return frame_bytes == 0 ? 0 : static_cast<int>(options.frame_bytes_bound / frame_bytes);
  }

  cv::Mat make_thumbnail(int i) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      cv::Mat full = frames.peek(i);
      if (!full.empty()) {
        cv::Mat small;
        const int w = std::min(options.thumbnail_width, full.cols);
        const int h = std::max(1, static_cast<int>(double(full.rows) * w / full.cols + 0.5));
        cv::resize(full, small, cv::Size(w, h), 0, 0, cv::INTER_AREA);
        return small;
      }
    }
    return source->read_thumbnail(i, options.thumbnail_width);
  }

  void run_worker() {
    std::unique_lock<std::mutex> lock(mutex);
    while (true) {
      work_ready.wait(lock, [&] { return stopping || !frame_queue.empty() || !thumbnail_queue.empty(); });
      if (stopping) break;
      const bool is_frame = !frame_queue.empty();
      const int i = is_frame ? frame_queue.front() : thumbnail_queue.front();
      (is_frame ? frame_queue : thumbnail_queue).pop_front();
      std::set<int>& in_flight = is_frame ? frames_in_flight : thumbnails_in_flight;
      LruStore& store = is_frame ? frames : thumbnails;
      if (store.contains(i) || in_flight.count(i) || failed_frames.count(i)) continue;
      in_flight.insert(i);
      worker_busy = true;
      lock.unlock();
      cv::Mat image;
      std::string error;
      try {
        image = is_frame ? source->read(i) : make_thumbnail(i);
      } catch (const std::exception& e) {
        error = e.what();
      } catch (...) {
        error = "unknown error while decoding frame " + std::to_string(i);
      }
      lock.lock();
      in_flight.erase(i);
      worker_busy = false;
      if (!error.empty()) {
        record_failure(i, error);
      } else if (!stopping) {
        counters.evictions += store.insert(i, image);
        if (is_frame) ++counters.prefetched;
      }
      image.release();
      state_changed.notify_all();
    }
    worker_busy = false;
    state_changed.notify_all();
  }

  void worker_main() {
    // Top-level catch: an exception must never escape a thread (it would terminate the editor).
    try {
      run_worker();
    } catch (const std::exception& e) {
      std::cerr << "frame cache: prefetch worker stopped: " << e.what() << "\n";
    } catch (...) {
      std::cerr << "frame cache: prefetch worker stopped by an unknown error\n";
    }
    std::lock_guard<std::mutex> lock(mutex);
    frame_queue.clear();
    thumbnail_queue.clear();
    worker_busy = false;
    state_changed.notify_all();
  }

  // Gets frame i from `store`, decoding it here if needed (waits if the worker is decoding it already).
  cv::Mat get_from(int i, bool is_frame) {
    if (i < 0 || i >= source->frame_count())
      throw Error(source->source() + ": frame index " + std::to_string(i) + " is out of range (0.." +
                  std::to_string(source->frame_count() - 1) + ")");
    LruStore& store = is_frame ? frames : thumbnails;
    std::set<int>& in_flight = is_frame ? frames_in_flight : thumbnails_in_flight;
    {
      std::unique_lock<std::mutex> lock(mutex);
      state_changed.wait(lock, [&] { return in_flight.count(i) == 0; });
      cv::Mat hit = store.touch(i);
      if (!hit.empty()) {
        if (is_frame) ++counters.hits;
        return hit;
      }
      if (is_frame) ++counters.misses;
      in_flight.insert(i);
    }
    cv::Mat image;
    try {
      image = is_frame ? source->read(i) : make_thumbnail(i);
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex);
      in_flight.erase(i);
      record_failure(i, e.what());
      state_changed.notify_all();
      throw;
    }
    std::lock_guard<std::mutex> lock(mutex);
    in_flight.erase(i);
    failed_frames.erase(i);
    counters.evictions += store.insert(i, image);
    state_changed.notify_all();
    return image;
  }
};

FrameCache::FrameCache(std::shared_ptr<FrameSource> source, const FrameCacheOptions& options) {
  if (!source) throw Error("frame cache: no frame source");
  options.check();
  impl_ = std::make_unique<Impl>(std::move(source), options);
  if (options.background_prefetch) impl_->worker = std::thread([this] { impl_->worker_main(); });
}

FrameCache::~FrameCache() {
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->stopping = true;
    impl_->frame_queue.clear();
    impl_->thumbnail_queue.clear();
  }
  impl_->work_ready.notify_all();
  if (impl_->worker.joinable()) impl_->worker.join();
}

cv::Mat FrameCache::get(int i) { return impl_->get_from(i, true); }

cv::Mat FrameCache::peek(int i) {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->frames.peek(i);
}

bool FrameCache::contains(int i) const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->frames.contains(i);
}

cv::Mat FrameCache::thumbnail(int i) { return impl_->get_from(i, false); }

void FrameCache::prefetch(int play_head, int direction) {
  if (!impl_->options.background_prefetch) return;
  const int n = impl_->source->frame_count();
  const int dir = direction < 0 ? -1 : 1;
  // Never queue more than fits beside the play-head frame, or prefetching evicts its own work.
  const int room = std::max(0, impl_->frames_that_fit() - 1);
  const int ahead = std::min(impl_->options.prefetch_ahead, room);
  const int behind = std::min(impl_->options.prefetch_behind, std::max(0, room - ahead));
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->frame_queue.clear();
  auto queue = [&](int i) {
    if (i >= 0 && i < n && !impl_->frames.contains(i) && !impl_->failed_frames.count(i))
      impl_->frame_queue.push_back(i);
  };
  for (int k = 1; k <= ahead; ++k) queue(play_head + dir * k);
  for (int k = 1; k <= behind; ++k) queue(play_head - dir * k);
  impl_->work_ready.notify_all();
}

void FrameCache::prefetch_thumbnails(int first, int last, int step) {
  if (!impl_->options.background_prefetch) return;
  const int n = impl_->source->frame_count();
  step = std::max(1, step);
  first = std::max(0, first);
  last = std::min(n - 1, last);
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->thumbnail_queue.clear();
  for (int i = first; i <= last; i += step)
    if (!impl_->thumbnails.contains(i) && !impl_->failed_frames.count(i)) impl_->thumbnail_queue.push_back(i);
  impl_->work_ready.notify_all();
}

void FrameCache::wait_for_prefetch() {
  std::unique_lock<std::mutex> lock(impl_->mutex);
  if (!impl_->worker.joinable()) return;
  impl_->state_changed.wait(lock, [&] {
    return impl_->stopping ||
           (impl_->frame_queue.empty() && impl_->thumbnail_queue.empty() && !impl_->worker_busy);
  });
}

void FrameCache::clear() {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->frames.clear();
  impl_->thumbnails.clear();
  impl_->frame_queue.clear();
  impl_->thumbnail_queue.clear();
  impl_->failed_frames.clear();
}

FrameCacheStats FrameCache::stats() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  FrameCacheStats s = impl_->counters;
  s.frame_bytes = impl_->frames.bytes();
  s.peak_frame_bytes = impl_->frames.peak_bytes();
  s.thumbnail_bytes = impl_->thumbnails.bytes();
  s.peak_thumbnail_bytes = impl_->thumbnails.peak_bytes();
  s.frames_held = impl_->frames.size();
  s.thumbnails_held = impl_->thumbnails.size();
  return s;
}

std::vector<std::pair<int, std::string>> FrameCache::failures() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->failures;
}

const FrameCacheOptions& FrameCache::options() const { return impl_->options; }
const FrameSource& FrameCache::source() const { return *impl_->source; }

}  // namespace plenopath
