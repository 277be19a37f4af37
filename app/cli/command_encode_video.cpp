// `plenopath encode-video DIR|VIDEO --out FILE [--codec h264|hevc|mp4v|mjpg] [--fps F] [--first N] [--last N]
// [--stride S] [--json]`: writes a capture's frames as a video (e.g. rendered frames -> the MP4 a 360° camera
// would have produced).
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "app/cli/console_progress.h"
#include "processing/capture/frame_source.h"
#include "processing/capture/video_encode.h"

namespace plenopath::cli {

Command add_encode_video_command(CLI::App& parent) {
  struct Options {
    std::string source, out;
    VideoEncodeOptions encode;
    int first = 0, last = -1, stride = 1;
    double rate = 30.0;
    bool any_aspect = false, json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub =
      parent.add_subcommand("encode-video", "Write a capture's frames (image folder or video) as a video");
  sub->add_option("source", o->source, "Folder of frames (natural sort order), multi-head folder, or video")
      ->required();
  sub->add_option("--out", o->out, "Video file to write (.mp4, .mkv, .mov, .avi)")->required();
  sub->add_option("--codec", o->encode.codec, "h264 (default), hevc, mp4v or mjpg")
      ->check(CLI::IsMember({"h264", "hevc", "mp4v", "mjpg"}));
  sub->add_option("--fps", o->encode.frame_rate, "Frames per second of the video (default: the source's)")
      ->check(CLI::Range(0.0, 1000.0));
  sub->add_option("--rate", o->rate, "Frames per second of an image folder (default 30)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--first", o->first, "First frame kept")->check(CLI::NonNegativeNumber);
  sub->add_option("--last", o->last, "Last frame kept, inclusive (-1 = to the end)");
  sub->add_option("--stride", o->stride, "Keep every S-th frame")->check(CLI::PositiveNumber);
  sub->add_flag("--any-aspect", o->any_aspect, "Accept frames that are not 2:1");
  sub->add_flag("--json", o->json, "Machine-readable output");
  return {sub, [o]() {
            FrameSourceOptions options;
            options.first_frame = o->first;
            options.last_frame = o->last;
            options.stride = o->stride;
            options.folder_frame_rate = o->rate;
            options.require_2to1 = !o->any_aspect;
            const std::unique_ptr<FrameSource> source = FrameSource::open(o->source, options);
            ConsoleProgress progress("encode-video");
            const VideoEncodeResult r = encode_video(*source, o->out, o->encode, progress);
            progress.finish();
            const nlohmann::json summary = {{"out", o->out},
                                            {"codec", o->encode.codec},
                                            {"fourcc", r.fourcc},
                                            {"frames_written", r.frames_written},
                                            {"frames_failed", r.frames_failed},
                                            {"size", {source->width(), source->height()}}};
            if (o->json)
              std::cout << summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
            else
              std::cout << "Wrote " << r.frames_written << " frames to " << o->out << " (" << r.fourcc << ")"
                        << (r.frames_failed
                                ? ", " + std::to_string(r.frames_failed) + " unreadable frames left out"
                                : "")
                        << "\n";
            return kExitOk;
          }};
}

}  // namespace plenopath::cli
