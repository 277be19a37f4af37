// Child processes for the renderers: the exit code comes back, output goes to the log, a stall or a cancel
// kills the child (checked by the time it takes against the child's own sleep), a missing program says how
// to install it. The children are the shell's own commands.
#include "processing/util/child_process.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>

#include "model/error.h"

namespace plenopath {
namespace {

namespace fs = std::filesystem;

ChildProcessOptions in_temp(const std::string& name) {
  ChildProcessOptions o;
  o.cwd = fs::temp_directory_path().string();
  o.log = (fs::temp_directory_path() / ("plenopath_child_" + name + std::to_string(::getpid()))).string();
  o.what = "Test";
  return o;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

TEST(ChildProcess, ExitCodeAndLog) {
  const std::string sh = find_program("sh", "sh", "dash");
  ChildProcessOptions o = in_temp("exit");
  EXPECT_EQ(run_child_process({sh, "-c", "echo hello from $(pwd); exit 3"}, o, null_progress()), 3);
  EXPECT_EQ(tail_of_file(o.log, 1000), "hello from " + fs::temp_directory_path().string() + "\n");
  EXPECT_EQ(tail_of_file(o.log, 4), "...tmp\n");  // the last four bytes: "tmp\n"
  fs::remove(o.log);
}

TEST(ChildProcess, AStallOrACancelKillsTheChild) {
  const std::string sh = find_program("sh", "sh", "dash");
  ChildProcessOptions o = in_temp("stall");
  o.stall_s = 0.3;
  o.stalled = " for a test";
  auto t0 = std::chrono::steady_clock::now();
  try {
    run_child_process({sh, "-c", "sleep 20"}, o, null_progress());
    FAIL() << "no error for a stalled child";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Test took longer than 0 s for a test"), std::string::npos)
        << e.what();
  }
  EXPECT_LT(seconds_since(t0), 10.0);  // killed, not waited for
  // A child that gets on (poll says so) is not stalled, however long it runs in all.
  int polls = 0;
  EXPECT_EQ(run_child_process({sh, "-c", "sleep 0.6"}, o, null_progress(), [&] { return ++polls > 0; }), 0);
  EXPECT_GT(polls, 5);
  FunctionProgress cancelled;
  cancelled.cancel();
  t0 = std::chrono::steady_clock::now();
  EXPECT_THROW(run_child_process({sh, "-c", "sleep 20"}, in_temp("cancel"), cancelled), Cancelled);
  EXPECT_LT(seconds_since(t0), 10.0);
  fs::remove(o.log);
  fs::remove(in_temp("cancel").log);
}

TEST(ChildProcess, AMissingProgramSaysHowToInstallIt) {
  try {
    find_program("no-such-renderer-program", "Renderer", "renderer-package");
    FAIL() << "found a program that is not there";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("`sudo apt-get install renderer-package`"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(find_program("/no/such/path/prog", "Renderer", "renderer-package"), Error);
}

}  // namespace
}  // namespace plenopath
