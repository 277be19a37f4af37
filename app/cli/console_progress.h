#pragma once
// The command line's Progress (processing/util/progress.h): "track: refinement 40%" on stderr (rewritten in
// place on a terminal, else a line per tenth and per stage), and Ctrl+C as the cancel flag. main() installs
// the SIGINT handler; a cancelled command ends with "cancelled" and exit code 130 (kExitCancelled).
#include <chrono>
#include <mutex>
#include <string>

#include "processing/util/progress.h"

namespace plenopath::cli {

// SIGINT sets the flag every ConsoleProgress reads; the handler resets itself, so a second Ctrl+C ends the
// program at once (for a step that does not poll).
void install_interrupt_handler();
bool interrupted();

class ConsoleProgress final : public Progress {
 public:
  // what: the command's name ("track"); quiet: report nothing (Ctrl+C still cancels).
  explicit ConsoleProgress(std::string what, bool quiet = false);
  ~ConsoleProgress() override;
  ConsoleProgress(const ConsoleProgress&) = delete;
  ConsoleProgress& operator=(const ConsoleProgress&) = delete;

  void report(double fraction, const std::string& stage = {}) override;
  bool is_cancelled() const override { return interrupted(); }

  // A loop over frames: "render: 12/300 frames, 8.1 frames/s"; throws Cancelled after Ctrl+C.
  void frames(int done, int total);
  // Ends a line rewritten in place (called by the destructor too).
  void finish();

 private:
  void print(const std::string& line);  // holds mutex_

  std::string what_;
  bool quiet_, tty_;
  std::mutex mutex_;
  std::string stage_;
  int last_tenth_ = -1;
  std::string last_stage_;
  bool open_line_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace plenopath::cli
