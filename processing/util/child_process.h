#pragma once
// Renderers run as child processes (POV-Ray, Blender): found on PATH, run in a folder with their output
// to a log, polled so that a cancel or a stall kills them. One implementation for every renderer.
#include <functional>
#include <string>
#include <vector>

#include "processing/util/progress.h"

namespace plenopath {

// The program to run: `executable` itself when it holds a '/', else the first match on PATH. Throws Error
// naming `what` ("POV-Ray") and how to install it (`package`, a Debian package) when it is not there.
std::string find_program(const std::string& executable, const std::string& what, const std::string& package);

// The last `bytes` of a text file ("..." before them when cut); empty when it cannot be read.
std::string tail_of_file(const std::string& file, std::size_t bytes);

struct ChildProcessOptions {
  std::string cwd;         // the folder it runs in
  std::string log;         // its standard output and error go here
  double stall_s = 900.0;  // killed when `poll` reports no progress for this long
  std::string what;        // names it in errors ("POV-Ray", "Blender")
  std::string stalled;     // ends the stall's message (" for a pass")
};

// Runs argv (argv[0] a path: find_program) and waits for it, calling `poll` about every 20 ms while it runs
// (and once after it ended): poll returns whether the child got on since the last call (a frame written).
// A cancel or a stall kills the child, then throws Cancelled or Error; so does anything `poll` throws.
// Returns the exit code (-1 when it did not exit normally). Between fork and exec only async-signal-safe
// calls: the studio calls this from worker threads.
int run_child_process(const std::vector<std::string>& argv, const ChildProcessOptions& options,
                      Progress& progress, const std::function<bool()>& poll = {});

}  // namespace plenopath
