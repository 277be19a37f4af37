#pragma once
// Test videos made by the ffmpeg command line (Debian's ffmpeg, installed by cmake/install-deps.sh): frames
// that show their own number (capture_test_util.h) piped in as raw BGR, encoded with the codec options
// given. Made once per build directory and kept there (tests/video_cache), so reruns are fast. Tests that
// need ffmpeg or ffprobe fail - never skip - when they are missing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace plenopath::test {

inline bool have_tool(const std::string& tool, const std::string& version_option = "-version") {
  return std::system((tool + " " + version_option + " > /dev/null 2>&1").c_str()) == 0;
}

// Fails the test (fatal for the caller: check HasFatalFailure) unless ffmpeg and ffprobe run.
inline void require_ffmpeg() {
  ASSERT_TRUE(have_tool("ffmpeg")) << "ffmpeg is needed to make the test videos (cmake/install-deps.sh)";
  ASSERT_TRUE(have_tool("ffprobe")) << "ffprobe is needed to check the test videos (cmake/install-deps.sh)";
}

// Runs a shell command and returns its standard output; fails the test when it exits non-zero.
inline std::string command_output(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) {
    ADD_FAILURE() << "cannot run " << command;
    return out;
  }
  char buffer[65536];
  std::size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  const int rc = pclose(pipe);
  EXPECT_EQ(rc, 0) << command;
  return out;
}

// The video `name` in the build's cache, made by
//   ffmpeg -f rawvideo -pix_fmt bgr24 -s WxH -r <input_rate> -i - <options> FILE
// from frame(0..count-1) when it is not there yet. The name should change whenever the options do.
inline std::string cached_test_video(const std::string& name, int count, const std::string& input_rate,
                                     const std::string& options, const std::function<cv::Mat(int)>& frame) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(PLENOPATH_BINARY_DIR) / "tests" / "video_cache";
  const fs::path path = dir / name;
  std::error_code ec;
  if (fs::exists(path, ec)) return path.string();
  fs::create_directories(dir, ec);
  // Written beside, then renamed: tests running in parallel never see half a file.
  const fs::path part = dir / ("part" + std::to_string(getpid()) + "_" + name);
  const cv::Mat first = frame(0);
  const std::string command = "ffmpeg -v error -y -f rawvideo -pix_fmt bgr24 -s " +
                              std::to_string(first.cols) + "x" + std::to_string(first.rows) + " -r " +
                              input_rate + " -i - " + options + " '" + part.string() + "'";
  FILE* pipe = popen(command.c_str(), "w");
  if (!pipe) {
    ADD_FAILURE() << "cannot run " << command;
    return path.string();
  }
  for (int k = 0; k < count; ++k) {
    const cv::Mat f = k == 0 ? first : frame(k);
    EXPECT_TRUE(f.isContinuous() && f.type() == CV_8UC3 && f.size() == first.size());
    std::fwrite(f.data, 1, f.total() * f.elemSize(), pipe);
  }
  const int rc = pclose(pipe);
  EXPECT_EQ(rc, 0) << command;
  fs::rename(part, path, ec);
  EXPECT_FALSE(ec) << "cannot move " << part << " to " << path << ": " << ec.message();
  return path.string();
}

// Each frame's presentation time in seconds as ffprobe reports it (6 decimals), in presentation order.
inline std::vector<double> ffprobe_frame_times(const std::string& video) {
  const std::string text = command_output(
      "ffprobe -v error -select_streams v:0 -show_entries frame=pts_time -of csv=p=0 '" + video + "'");
  std::vector<double> times;
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(at, end - at);
    if (!line.empty()) times.push_back(std::stod(line));
    at = end + 1;
  }
  return times;
}

}  // namespace plenopath::test
