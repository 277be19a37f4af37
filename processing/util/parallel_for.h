#pragma once
// Runs body(i) for i in [0, n) on `threads` std::threads (0 = hardware concurrency, 1 = the calling thread),
// joined before returning; after the first exception no new i starts, and that exception is rethrown.
// Own threads, not OpenCV's pool: CGAL keeps thread-local state, which must die with threads that end
// before the program does.
#include <functional>

namespace plenopath {

void parallel_for_each(int n, int threads, const std::function<void(int)>& body);

// The thread count `threads` asks for: itself if > 0, else the hardware concurrency (at least 1).
int resolve_thread_count(int threads);

}  // namespace plenopath
