#include "processing/capture/video_encode.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <opencv2/videoio.hpp>

#include "model/error.h"
#include "processing/capture/frame_source.h"

namespace plenopath {

void VideoEncodeOptions::check() const {
  if (codec != "h264" && codec != "hevc" && codec != "mp4v" && codec != "mjpg")
    throw Error("video encoding: unknown codec '" + codec + "' (expected h264, hevc, mp4v or mjpg)");
  if (!(frame_rate >= 0.0) || frame_rate > 1000.0)
    throw Error("video encoding: frame_rate must be in 0..1000");
}

VideoEncodeResult encode_video(FrameSource& source, const std::string& file,
                               const VideoEncodeOptions& options, Progress& progress) {
  options.check();
  std::string ext = std::filesystem::path(file).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool mp4_family = ext == ".mp4" || ext == ".mov" || ext == ".m4v";
  // MP4/MOV want the ISO names (avc1, hev1); Matroska and AVI take the FFmpeg codec tags.
  std::string fourcc = "avc1";
  if (options.codec == "h264")
    fourcc = mp4_family ? "avc1" : "H264";
  else if (options.codec == "hevc")
    fourcc = mp4_family ? "hev1" : "HEVC";
  else if (options.codec == "mp4v")
    fourcc = "mp4v";
  else
    fourcc = "MJPG";
  const double rate = options.frame_rate > 0.0 ? options.frame_rate : source.frame_rate();
  cv::VideoWriter writer;
  try {
    writer.open(file, cv::CAP_FFMPEG, cv::VideoWriter::fourcc(fourcc[0], fourcc[1], fourcc[2], fourcc[3]),
                rate, cv::Size(source.width(), source.height()));
  } catch (const cv::Exception& e) {
    throw file_error(file, "cannot write video: " + std::string(e.what()));
  }
  if (!writer.isOpened())
    throw file_error(file, "cannot write a " + options.codec + " video in this container (" + fourcc +
                               " through FFmpeg); try .mp4 or .mkv, or another codec");
  VideoEncodeResult result;
  result.fourcc = fourcc;
  const int n = source.frame_count();
  try {
    for (int i = 0; i < n; ++i) {
      progress.checkpoint(static_cast<double>(i) / std::max(1, n),
                          "frame " + std::to_string(i + 1) + " of " + std::to_string(n));
      cv::Mat frame;
      try {
        frame = source.read(i);
      } catch (const Error&) {
        ++result.frames_failed;  // one bad frame does not end the video
        continue;
      }
      writer.write(frame);
      ++result.frames_written;
    }
  } catch (const Cancelled&) {
    // No partial video is left behind.
    writer.release();
    std::error_code ec;
    std::filesystem::remove(file, ec);
    throw;
  }
  writer.release();
  progress.report(1.0, std::to_string(result.frames_written) + " frames written");
  return result;
}

}  // namespace plenopath
