#include "app/cli/console_progress.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <utility>

namespace plenopath::cli {

namespace {

std::atomic<bool> g_interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the SIGINT handler needs a lock-free flag");

extern "C" void on_sigint(int) { g_interrupted.store(true); }

}  // namespace

void install_interrupt_handler() {
  struct sigaction action {};
  action.sa_handler = on_sigint;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;  // the second Ctrl+C: the default action (end the program)
  sigaction(SIGINT, &action, nullptr);
}

bool interrupted() { return g_interrupted.load(); }

ConsoleProgress::ConsoleProgress(std::string what, bool quiet)
    : what_(std::move(what)), quiet_(quiet), tty_(isatty(2) != 0), start_(std::chrono::steady_clock::now()) {}

ConsoleProgress::~ConsoleProgress() { finish(); }

void ConsoleProgress::print(const std::string& line) {
  if (tty_) {
    std::cerr << "\r" << line << "\033[K" << std::flush;
    open_line_ = true;
  } else {
    std::cerr << line << "\n" << std::flush;
  }
}

void ConsoleProgress::report(double fraction, const std::string& stage) {
  if (quiet_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (!stage.empty()) stage_ = stage;
  const double f = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
  const int percent = static_cast<int>(std::floor(100 * f));
  const int tenth = percent / 10;
  // On a terminal every whole percent; in a log a line per tenth and per stage.
  const bool changed = stage_ != last_stage_;
  if (!tty_ && !changed && tenth == last_tenth_) return;
  last_tenth_ = tenth;
  last_stage_ = stage_;
  print(what_ + ": " + (stage_.empty() ? "" : stage_ + " ") + std::to_string(percent) + "%");
}

void ConsoleProgress::frames(int done, int total) {
  if (!quiet_) {
    std::lock_guard<std::mutex> lock(mutex_);
    const int tenth = total > 0 ? done * 10 / total : 10;
    if (tty_ || tenth != last_tenth_) {
      last_tenth_ = tenth;
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
      char line[200];
      std::snprintf(line, sizeof line, "%s: %d/%d frames, %.1f frames/s", what_.c_str(), done, total,
                    s > 0 ? done / s : 0.0);
      print(line);
    }
  }
  throw_if_cancelled();
}

void ConsoleProgress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (open_line_) std::cerr << "\n" << std::flush;
  open_line_ = false;
}

}  // namespace plenopath::cli
