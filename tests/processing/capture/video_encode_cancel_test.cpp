// encode_video reports per frame; cancelled, it ends with Cancelled and leaves no unfinished video behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>

#include "processing/capture/frame_source.h"
#include "processing/capture/video_encode.h"
#include "processing/util/progress.h"

namespace plenopath {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("plenopath_encode_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

std::unique_ptr<FrameSource> colour_ramp(int frames, std::atomic<int>* generated) {
  return FrameSource::from_generator(frames, 64, 32, 10.0, [generated](int k) {
    ++*generated;
    return cv::Mat(32, 64, CV_8UC3, cv::Scalar(8 * k, 60, 250 - 8 * k));
  });
}

TEST(VideoEncode, ReportsEveryFrameUpToTheEnd) {
  TempDir dir;
  std::atomic<int> generated{0};
  const auto source = colour_ramp(20, &generated);
  int reports = 0;
  double last = -1;
  FunctionProgress progress([&](double f, const std::string&) {
    ++reports;
    EXPECT_GE(f, last);
    last = f;
  });
  VideoEncodeOptions options;
  options.codec = "mjpg";
  const std::string file = (dir.path / "ramp.avi").string();
  const VideoEncodeResult r = encode_video(*source, file, options, progress);
  EXPECT_EQ(r.frames_written, 20);
  EXPECT_EQ(reports, 21);  // one before each frame, one at the end
  EXPECT_DOUBLE_EQ(last, 1.0);
  EXPECT_TRUE(fs::exists(file));
}

TEST(VideoEncode, CancelAfterTheFirstReportLeavesNoFile) {
  TempDir dir;
  std::atomic<int> generated{0};
  const auto source = colour_ramp(20, &generated);
  int reports = 0;
  FunctionProgress progress([&](double, const std::string&) {
    ++reports;
    progress.cancel();
  });
  VideoEncodeOptions options;
  options.codec = "mjpg";
  const std::string file = (dir.path / "cancelled.avi").string();
  EXPECT_THROW(encode_video(*source, file, options, progress), Cancelled);
  EXPECT_EQ(reports, 1);
  EXPECT_EQ(generated.load(), 0) << "the first report comes before frame 0 is read";
  EXPECT_FALSE(fs::exists(file));
}

}  // namespace
}  // namespace plenopath
