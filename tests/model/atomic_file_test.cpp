#include "model/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/error.h"

namespace plenopath {
namespace {
namespace fs = std::filesystem;

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("plenopath_atomic_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  static std::string read(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  static unsigned mode_of(const std::string& path) {
    struct stat st {};
    EXPECT_EQ(::stat(path.c_str(), &st), 0) << path;
    return st.st_mode & 07777;
  }
  void touch(const std::string& name) const { std::ofstream(file(name)) << "stale"; }
  fs::path dir_;
};

// A pid no process has: a child that has exited and been reaped.
pid_t pid_of_an_ended_process() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

TEST_F(AtomicFileTest, ExistingFileKeepsItsMode) {
  write_file_atomically(file("t.json"), "one", false);
  ASSERT_EQ(::chmod(file("t.json").c_str(), 0640), 0);
  write_file_atomically(file("t.json"), "two", true);
  EXPECT_EQ(read(file("t.json")), "two");
  EXPECT_EQ(mode_of(file("t.json")), 0640u);
  ASSERT_EQ(::chmod(file("t.json").c_str(), 0600), 0);
  write_file_atomically(file("t.json"), "three", false);
  EXPECT_EQ(mode_of(file("t.json")), 0600u);
}

TEST_F(AtomicFileTest, NewFileGetsWhatTheUmaskAllows) {
  const mode_t old_mask = ::umask(022);
  write_file_atomically(file("a.json"), "a", false);
  ::umask(077);
  write_file_atomically(file("b.json"), "b", false);
  ::umask(old_mask);
  EXPECT_EQ(mode_of(file("a.json")), 0644u);
  EXPECT_EQ(mode_of(file("b.json")), 0600u);
}

TEST_F(AtomicFileTest, SymlinkIsFollowedAndStays) {
  fs::create_directories(dir_ / "real");
  write_file_atomically(file("real/t.json"), "one", false);
  fs::create_symlink(fs::path("real") / "t.json", dir_ / "link.json");
  write_file_atomically(file("link.json"), "two", true);
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir_ / "link.json"))) << "the link was replaced by a file";
  EXPECT_EQ(read(file("real/t.json")), "two");
  EXPECT_EQ(read(file("real/t.json.bak")), "one") << "the backup sits beside the file it backs up";
  EXPECT_FALSE(fs::exists(dir_ / "link.json.bak"));
  EXPECT_EQ(resolve_symlinks(file("link.json")), (dir_ / "real" / "t.json").string());
  EXPECT_EQ(resolve_symlinks(file("real/t.json")), file("real/t.json"));
}

TEST_F(AtomicFileTest, ChainOfLinksAndDanglingLinkReachTheTarget) {
  fs::create_symlink("middle.json", dir_ / "first.json");
  fs::create_symlink("target.json", dir_ / "middle.json");  // target.json does not exist yet
  write_file_atomically(file("first.json"), "made", false);
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir_ / "first.json")));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir_ / "middle.json")));
  EXPECT_EQ(read(file("target.json")), "made");
}

TEST_F(AtomicFileTest, SymlinkLoopIsAnErrorNamingTheFile) {
  fs::create_symlink("b.json", dir_ / "a.json");
  fs::create_symlink("a.json", dir_ / "b.json");
  try {
    write_file_atomically(file("a.json"), "x", false);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("symbolic links"), std::string::npos) << e.what();
  }
}

TEST_F(AtomicFileTest, TemporariesOfKilledSavesAreRemovedOnTheNextSave) {
  const pid_t gone = pid_of_an_ended_process();
  const std::string dead = ".t.json.tmp" + std::to_string(gone) + "-123";
  const std::string alive = ".t.json.tmp" + std::to_string(::getpid()) + "-77";  // a save in flight
  touch(dead);
  touch(alive);
  touch(".t.json.tmp4242");  // old-style name, two hours old: no save takes that long
  fs::last_write_time(file(".t.json.tmp4242"), fs::file_time_type::clock::now() - std::chrono::hours(2));
  touch(".t.json.tmp999");      // old-style, fresh: may be in flight
  touch(".other.json.tmp1-1");  // another file's temporary
  touch(".t.json.tmpnotes");    // not a temporary name at all

  write_file_atomically(file("t.json"), "saved", false);
  EXPECT_FALSE(fs::exists(file(dead)));
  EXPECT_FALSE(fs::exists(file(".t.json.tmp4242")));
  EXPECT_TRUE(fs::exists(file(alive)));
  EXPECT_TRUE(fs::exists(file(".t.json.tmp999")));
  EXPECT_TRUE(fs::exists(file(".other.json.tmp1-1")));
  EXPECT_TRUE(fs::exists(file(".t.json.tmpnotes")));
  EXPECT_EQ(read(file("t.json")), "saved");
}

TEST_F(AtomicFileTest, KilledSaveLeavesTheOldFileWhole) {
  // A child saves a large file and is killed with SIGKILL part-way; the file is the old one or the new one,
  // never a mix, and the next save leaves no temporary behind.
  write_file_atomically(file("t.json"), "old", false);
  const std::string big(64 << 20, 'n');
  for (int attempt = 0; attempt < 3; ++attempt) {
    const pid_t child = ::fork();
    if (child == 0) {
      write_file_atomically(file("t.json"), big, false);
      ::_exit(0);
    }
    ::usleep(static_cast<useconds_t>(2000 + 4000 * attempt));
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    const auto size = fs::file_size(file("t.json"));
    EXPECT_TRUE(size == 3 || size == big.size()) << size;
  }
  write_file_atomically(file("t.json"), "final", false);
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir_)) entries += e.path().filename() != "t.json";
  EXPECT_EQ(entries, 0) << "temporaries left behind";
  EXPECT_EQ(read(file("t.json")), "final");
}

}  // namespace
}  // namespace plenopath
