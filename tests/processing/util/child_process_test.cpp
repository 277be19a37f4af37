// Child processes for the renderers: the exit code comes back, output goes to the log, a stall or a cancel
// kills the child (checked by its pid being gone while its own sleep would go on), a missing program says how
// to install it. The children are the shell's own commands.
#include "processing/util/child_process.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <filesystem>
#include <fstream>

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
  // The child writes its pid, then becomes a long sleep: gone afterwards means killed, not waited for.
  const std::string pid_file = in_temp("pid").log;
  const std::vector<std::string> sleeper = {sh, "-c", "echo $$ > " + pid_file + "; exec sleep 1000"};
  ChildProcessOptions o = in_temp("stall");
  o.stall_s = 0.3;
  o.stalled = " for a test";
  const auto child_pid = [&] {
    std::ifstream in(pid_file);
    pid_t pid = 0;
    in >> pid;
    return pid;
  };
  const auto pid_written = [&] { return child_pid() > 0; };
  try {
    // Getting on until it has written its pid, stalled from then on.
    run_child_process(sleeper, o, null_progress(), [&] { return !pid_written(); });
    FAIL() << "no error for a stalled child";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Test took longer than 0 s for a test"), std::string::npos)
        << e.what();
  }
  pid_t pid = child_pid();
  ASSERT_GT(pid, 0) << "the stalled child never wrote its pid";
  EXPECT_EQ(::kill(pid, 0), -1) << "the stalled child " << pid << " is still there";
  EXPECT_EQ(errno, ESRCH);
  fs::remove(pid_file);
  // A child that gets on (poll says so) is not stalled, however long it runs in all.
  int polls = 0;
  EXPECT_EQ(run_child_process({sh, "-c", "sleep 0.6"}, o, null_progress(), [&] { return ++polls > 0; }), 0);
  EXPECT_GT(polls, 5);
  // Cancelled once the child is running: Cancelled, and the child is gone.
  FunctionProgress cancelled;
  EXPECT_THROW(run_child_process(sleeper, in_temp("cancel"), cancelled,
                                 [&] {
                                   if (pid_written()) cancelled.cancel();
                                   return true;
                                 }),
               Cancelled);
  pid = child_pid();
  ASSERT_GT(pid, 0);
  EXPECT_EQ(::kill(pid, 0), -1) << "the cancelled child " << pid << " is still there";
  EXPECT_EQ(errno, ESRCH);
  fs::remove(pid_file);
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
