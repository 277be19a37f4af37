#pragma once
// What every benchmark prints beside its figures: the commit, the load, seconds. (ARCHITECTURE.md: a figure
// comes with its commit, the load, and a ratio against a baseline measured in the same run.)
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>

namespace plenopath::bench {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// The first line a shell command prints, without its newline.
inline std::string first_line_of(const std::string& command) {
  std::string out;
  if (FILE* p = popen(command.c_str(), "r")) {
    char buf[4096];
    if (std::fgets(buf, sizeof buf, p)) out = buf;
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

inline std::string git_commit() {
  return first_line_of(std::string("git -C '") + PLENOPATH_SOURCE_DIR + "' rev-parse HEAD 2>/dev/null");
}

inline std::string load_average() {
  std::ifstream f("/proc/loadavg");
  std::string line;
  std::getline(f, line);
  return line;
}

}  // namespace plenopath::bench
