#include "processing/util/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include "model/error.h"

namespace plenopath {

namespace fs = std::filesystem;

std::string find_program(const std::string& executable, const std::string& what, const std::string& package) {
  auto runnable = [](const fs::path& p) { return access(p.c_str(), X_OK) == 0 && !fs::is_directory(p); };
  if (executable.find('/') != std::string::npos) {
    if (runnable(executable)) return fs::absolute(executable).string();
    throw Error(what + ": " + executable + " is not an executable program");
  }
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':'))
    if (!dir.empty() && runnable(fs::path(dir) / executable))
      return fs::absolute(fs::path(dir) / executable).string();
  throw Error(what + " (" + executable + ") is not installed: `sudo apt-get install " + package +
              "` (cmake/install-deps.sh installs it)");
}

std::string tail_of_file(const std::string& file, std::size_t bytes) {
  std::ifstream in(file, std::ios::binary);
  const std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return all.size() > bytes ? "..." + all.substr(all.size() - bytes) : all;
}

int run_child_process(const std::vector<std::string>& argv, const ChildProcessOptions& options,
                      Progress& progress, const std::function<bool()>& poll) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw Error(options.what + ": cannot start a process");
  if (pid == 0) {
    const int fd = open(options.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    if (chdir(options.cwd.c_str()) != 0) _exit(126);
    execv(args[0], args.data());  // argv[0] is a path (find_program): no PATH search after fork
    _exit(127);
  }
  // Whatever is thrown while it runs, the child goes.
  struct KillOnThrow {
    pid_t pid;
    bool running = true;
    ~KillOnThrow() {
      if (!running) return;
      int status = 0;
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
    }
  } child{pid};
  auto last_progress = std::chrono::steady_clock::now();
  for (;;) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) {
      child.running = false;
      if (poll) poll();
      return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    if (poll && poll()) last_progress = std::chrono::steady_clock::now();
    progress.throw_if_cancelled();
    const double idle =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - last_progress).count();
    if (idle > options.stall_s)
      throw Error(options.what + " took longer than " + std::to_string(static_cast<int>(options.stall_s)) +
                  " s" + options.stalled);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace plenopath
