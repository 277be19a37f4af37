#pragma once
// Decoded frames kept in memory under a byte bound, so a 100 000-frame capture opens and scrubs without
// loading it: an LRU of full frames, a second LRU of timeline thumbnails, and a background worker that
// decodes the frames around the play head before they are asked for.
//
// Bytes counted are the pixel bytes of the Mats the cache holds. A Mat handed out by get() shares its pixels
// with the cache: treat it as read-only (clone() before drawing on it); if the caller keeps it after
// eviction, that memory is the caller's, not the cache's. Frames being decoded (at most one per calling
// thread plus one on the worker) are not counted either. glibc keeps freed large blocks unless
// mallopt(M_MMAP_THRESHOLD, 1 << 20) is set at start-up (see tests/bench/bench_frame_cache.cpp).
// All public functions are thread-safe. The destructor cancels prefetching and joins the worker.
#include <cstddef>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace plenopath {

class FrameSource;

struct FrameCacheOptions {
  std::size_t frame_bytes_bound = std::size_t(512) << 20;     // full frames held at most (bytes)
  std::size_t thumbnail_bytes_bound = std::size_t(64) << 20;  // thumbnails held at most (bytes)
  int thumbnail_width = 256;                                  // thumbnails are at most this wide (pixels)
  int prefetch_ahead = 6;           // frames decoded ahead of the play head, in the scrub direction
  int prefetch_behind = 1;          // and behind it
  bool background_prefetch = true;  // false: no worker thread; prefetch() does nothing
  void check() const;               // throws Error saying which field is wrong
};

struct FrameCacheStats {
  std::size_t frame_bytes = 0;       // bytes of full frames held now
  std::size_t peak_frame_bytes = 0;  // most ever held at once
  std::size_t thumbnail_bytes = 0;
  std::size_t peak_thumbnail_bytes = 0;
  int frames_held = 0;
  int thumbnails_held = 0;
  long hits = 0;        // get() answered from memory
  long misses = 0;      // get() had to decode
  long evictions = 0;   // full frames dropped to stay under the bound
  long prefetched = 0;  // frames decoded by the worker
  long failed = 0;      // frames that could not be decoded (see failures())
};

class FrameCache {
 public:
  FrameCache(std::shared_ptr<FrameSource> source, const FrameCacheOptions& options = {});
  ~FrameCache();
  FrameCache(const FrameCache&) = delete;
  FrameCache& operator=(const FrameCache&) = delete;

  // The full frame i (CV_8UC3), from memory or decoded now; it becomes the most recently used.
  // Throws Error naming the frame when it cannot be decoded. A frame larger than the whole bound is
  // returned but not kept.
  cv::Mat get(int i);
  // The frame if it is in memory, else an empty Mat (never decodes; for drawing while scrubbing).
  cv::Mat peek(int i);
  bool contains(int i) const;

  // A thumbnail for the timeline, at most options.thumbnail_width wide; decoded at reduced size.
  // Throws Error like get().
  cv::Mat thumbnail(int i);

  // Tells the worker where the play head is and which way it moves (+1 forward, -1 backward). Frames
  // already queued that are no longer near the play head are dropped from the queue.
  void prefetch(int play_head, int direction = +1);
  // Asks the worker to make thumbnails for frames first, first+step, ... <= last (the timeline's visible
  // range), after the frames near the play head. Replaces the previous thumbnail request.
  void prefetch_thumbnails(int first, int last, int step = 1);
  // Blocks until the worker has nothing queued (for tests and benchmarks).
  void wait_for_prefetch();

  // Drops everything held (e.g. after the source changed on disk).
  void clear();

  FrameCacheStats stats() const;
  // Frames that failed to decode (in get(), thumbnail() or the worker) with the error message.
  std::vector<std::pair<int, std::string>> failures() const;
  const FrameCacheOptions& options() const;
  const FrameSource& source() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace plenopath
