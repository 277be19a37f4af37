// Videos (FrameSource's video backend): frame-exact reads through VideoDecoder, each kept frame's own time
// stamp (right for variable frame rates), and the frames a stream promised but does not hold.
#include <cmath>
#include <filesystem>
#include <mutex>

#include "model/error.h"
#include "processing/capture/frame_source.h"
#include "processing/capture/frame_source_internal.h"
#include "processing/capture/video_decoder.h"

namespace fs = std::filesystem;

namespace plenopath::frame_source_detail {
namespace {

struct VideoBackend : Backend {
  const FrameSource::Impl* impl = nullptr;
  std::mutex mutex;
  std::unique_ptr<VideoDecoder> decoder;  // frame-exact: decodes on when reading in order, else seeks

  cv::Mat read(int i) override {
    const long long raw = impl->numbers[i];
    cv::Mat frame;
    {
      std::lock_guard<std::mutex> lock(mutex);
      frame = decoder->read(static_cast<int>(raw));
    }
    if (frame.cols != impl->width || frame.rows != impl->height)
      throw file_error(impl->source, "frame " + std::to_string(raw) + " is " + std::to_string(frame.cols) +
                                         "x" + std::to_string(frame.rows) + ", expected " +
                                         std::to_string(impl->width) + "x" + std::to_string(impl->height));
    return frame;
  }
};

}  // namespace

std::unique_ptr<FrameSource::Impl> open_video(const std::string& path, const FrameSourceOptions& options) {
  auto impl = std::make_unique<FrameSource::Impl>();
  impl->kind = CaptureKind::kVideo;
  impl->source = path;
  impl->options = options;
  auto backend = std::make_unique<VideoBackend>();
  backend->impl = impl.get();
  backend->decoder = std::make_unique<VideoDecoder>(path);  // throws Error naming the file
  VideoDecoder& decoder = *backend->decoder;
  double fps = decoder.frame_rate();
  if (!(fps > 0.0) || !std::isfinite(fps) || fps > 1000.0) fps = 30.0;
  impl->frame_rate = fps;

  // The first frame tells the true size (and that the stream decodes at all); the last that the packets
  // keep their promise. If either fails, only decoding every frame tells which frames there are.
  const auto decodes = [&](int frame) {
    try {
      return decoder.read(frame);
    } catch (const Error&) {
      return cv::Mat();
    }
  };
  const long long packet_count = decoder.frame_count();
  cv::Mat first = packet_count > 0 ? decodes(0) : cv::Mat();
  if (packet_count > 0 &&
      (first.empty() || (packet_count > 1 && decodes(decoder.frame_count() - 1).empty()))) {
    decoder.index_by_decoding();
    first = decoder.frame_count() > 0 ? decodes(0) : cv::Mat();
  }
  if (first.empty()) throw file_error(path, "video has no decodable frame");
  impl->width = first.cols;
  impl->height = first.rows;
  const long long count = decoder.frame_count();
  const long long promised =
      std::max(packet_count, decoder.packets_end_early() ? decoder.container_frame_count() : 0);
  if (count < promised)
    impl->skipped.push_back({static_cast<int>(count), "frame " + std::to_string(count),
                             "missing: the stream ends after " + std::to_string(count) +
                                 " frames though the container says " + std::to_string(promised)});
  check_aspect(impl->width, impl->height, options.require_2to1, path);

  const long long last =
      options.last_frame < 0 ? count - 1 : std::min<long long>(options.last_frame, count - 1);
  if (options.first_frame > last)
    throw file_error(path, "first frame " + std::to_string(options.first_frame) + " is beyond the video's " +
                               std::to_string(count) + " frames");
  for (long long raw = options.first_frame; raw <= last; raw += options.stride) {
    impl->names.push_back("frame " + std::to_string(raw));
    impl->numbers.push_back(raw);
    impl->timestamps.push_back(
        decoder.time_s(static_cast<int>(raw)));  // the frame's own PTS: right for variable rates
  }
  impl->backend = std::move(backend);
  return impl;
}

bool looks_like_video(const std::string& path) {
  const std::string e = lower(fs::path(path).extension().string());
  return e == ".mp4" || e == ".mov" || e == ".mkv" || e == ".avi" || e == ".m4v" || e == ".webm" ||
         e == ".insv";
}

}  // namespace plenopath::frame_source_detail
