// `plenopath capture-info DIR|VIDEO [--first N] [--last N] [--stride S] [--depth DIR] [--gps FILE] [--json]`:
// what a capture holds before it is imported: frames, size, rate, skipped frames with reasons, depth and
// GPS matches; for videos whether the frame rate varies and what the file says about its 360° projection
// and initial orientation. A folder holding rig.json and one folder per head is a multi-head capture.
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "model/error.h"
#include "processing/capture/frame_source.h"
#include "processing/capture/gps_track.h"
#include "processing/capture/spherical_video.h"

namespace plenopath::cli {
namespace {

struct Options {
  std::string source;
  int first = 0;
  int last = -1;
  int stride = 1;
  double rate = 30.0;
  std::string depth;
  std::string gpx;
  double gps_offset_s = 0.0;
  int stitch_width = 2048;
  bool any_aspect = false;
  bool verify = false;
  bool json = false;
};

// The file's 360° metadata; a malformed box is reported, not fatal (the frames may still be fine).
nlohmann::json spherical_summary(const std::string& video) {
  SphericalVideoInfo info;
  try {
    info = read_spherical_video_info(video);
  } catch (const Error& e) {
    return {{"error", e.what()}};
  }
  nlohmann::json s = {{"metadata", info.metadata},
                      {"projection", to_string(info.projection)},
                      {"equirectangular", info.equirectangular()}};
  if (info.spherical) {
    s["stereo"] = to_string(info.stereo);
    s["yaw_deg"] = info.yaw_deg;
    s["pitch_deg"] = info.pitch_deg;
    s["roll_deg"] = info.roll_deg;
    s["crop"] = {{"top", info.crop_top},
                 {"bottom", info.crop_bottom},
                 {"left", info.crop_left},
                 {"right", info.crop_right}};
    s["software"] = info.software;
  }
  return s;
}

nlohmann::json summarize(const Options& o) {
  FrameSourceOptions options;
  options.first_frame = o.first;
  options.last_frame = o.last;
  options.stride = o.stride;
  options.folder_frame_rate = o.rate;
  options.depth_folder = o.depth;
  options.require_2to1 = !o.any_aspect;
  options.verify_by_decoding = o.verify;
  options.stitch_width = o.stitch_width;
  const std::unique_ptr<FrameSource> source = FrameSource::open(o.source, options);
  const int n = source->frame_count();

  nlohmann::json skipped = nlohmann::json::array();
  for (const SkippedFrame& s : source->skipped())
    skipped.push_back({{"number", s.number}, {"name", s.name}, {"reason", s.reason}});
  nlohmann::json summary = {{"source", o.source},
                            {"kind", to_string(source->kind())},
                            {"frames", n},
                            {"size", {source->width(), source->height()}},
                            {"frame_rate", source->frame_rate()},
                            {"first_frame", o.first},
                            {"stride", o.stride},
                            {"duration_s", n > 0 ? source->timestamp_s(n - 1) - source->timestamp_s(0) : 0.0},
                            {"first_name", source->frame_name(0)},
                            {"last_name", source->frame_name(n - 1)},
                            {"heads", source->head_count()},
                            {"skipped", skipped}};
  if (source->kind() == CaptureKind::kVideo) {
    summary["variable_frame_rate"] = !capture_from_frame_source(*source).frame_times_s.empty();
    summary["spherical"] = spherical_summary(o.source);
  }
  if (!o.depth.empty())
    summary["depth"] = {{"folder", o.depth},
                        {"matched", source->depth_match_count()},
                        {"unmatched", n - source->depth_match_count()}};
  if (!o.gpx.empty()) {
    const GpsTrack track = read_gps_track(o.gpx);
    std::vector<double> times(n);
    for (int i = 0; i < n; ++i) times[i] = source->timestamp_s(i);
    GpsMatchOptions match;
    match.time_offset_s = o.gps_offset_s;
    const std::vector<FrameGps> matched = match_gps_to_frames(track.samples, times, match);
    int count = 0;
    for (const FrameGps& m : matched) count += m.valid;
    summary["gps"] = {{"file", o.gpx},
                      {"samples", track.samples.size()},
                      {"samples_without_time", track.samples_without_time},
                      {"duration_s", track.samples.back().time_s},
                      {"time_offset_s", o.gps_offset_s},
                      {"frames_matched", count},
                      {"frames_unmatched", n - count},
                      {"notes", track.notes}};
  }
  return summary;
}

void print_text(const nlohmann::json& s) {
  std::cout << std::fixed << std::setprecision(3);
  std::cout << "Capture   " << s["source"].get<std::string>() << " (" << s["kind"].get<std::string>()
            << ")\n";
  std::cout << "Frames    " << s["frames"] << " of " << s["size"][0] << "x" << s["size"][1] << " at "
            << s["frame_rate"].get<double>() << " fps, " << s["duration_s"].get<double>() << " s ("
            << s["first_name"].get<std::string>() << " .. " << s["last_name"].get<std::string>() << ")\n";
  if (s.value("variable_frame_rate", false))
    std::cout << "          variable frame rate: times from the video's time stamps\n";
  if (s.contains("spherical")) {
    const nlohmann::json& v = s["spherical"];
    if (v.contains("error"))
      std::cout << "360       metadata unreadable: " << v["error"].get<std::string>() << "\n";
    else if (v["metadata"].get<std::string>().empty())
      std::cout << "360       no spherical metadata in the file\n";
    else
      std::cout << "360       " << v["projection"].get<std::string>() << ", "
                << v["stereo"].get<std::string>() << " (" << v["metadata"].get<std::string>()
                << "); initial view yaw " << v["yaw_deg"].get<double>() << "°, pitch "
                << v["pitch_deg"].get<double>() << "°, roll " << v["roll_deg"].get<double>() << "°\n";
  }
  if (s["heads"].get<int>() > 0) std::cout << "Heads     " << s["heads"] << " (stitched on the fly)\n";
  std::cout << "Skipped   " << s["skipped"].size() << "\n";
  for (const auto& k : s["skipped"])
    std::cout << "          " << k["name"].get<std::string>() << ": " << k["reason"].get<std::string>()
              << "\n";
  if (s.contains("depth"))
    std::cout << "Depth     " << s["depth"]["matched"] << " frames matched, " << s["depth"]["unmatched"]
              << " without\n";
  if (s.contains("gps"))
    std::cout << "GPS       " << s["gps"]["samples"] << " samples over "
              << s["gps"]["duration_s"].get<double>() << " s; " << s["gps"]["frames_matched"]
              << " frames matched, " << s["gps"]["frames_unmatched"] << " not\n";
}

}  // namespace

Command add_capture_info_command(CLI::App& parent) {
  auto o = std::make_shared<Options>();
  CLI::App* sub =
      parent.add_subcommand("capture-info", "Inspect a capture (image folder or 360 video) before import");
  sub->add_option("source", o->source, "Folder of equirectangular frames, or a video file")->required();
  sub->add_option("--first", o->first, "First frame kept (video frame number or position in the folder)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--last", o->last, "Last frame kept, inclusive (-1 = to the end)");
  sub->add_option("--stride", o->stride, "Keep every S-th frame")->check(CLI::PositiveNumber);
  sub->add_option("--rate", o->rate, "Frames per second of an image folder (default 30)")
      ->check(CLI::PositiveNumber);
  sub->add_option("--depth", o->depth, "Folder of depth maps matched to frames by name");
  sub->add_option("--gps,--gpx", o->gpx, "GPS track (GPX, NMEA 0183 or GeoJSON) matched to frames by time");
  sub->add_option("--gps-offset", o->gps_offset_s,
                  "Seconds on the GPS clock at the capture's first frame time");
  sub->add_option("--stitch-width", o->stitch_width,
                  "Multi-head captures (a folder with rig.json): panorama width")
      ->check(CLI::Range(8, 32768));
  sub->add_flag("--any-aspect", o->any_aspect, "Accept frames that are not 2:1");
  sub->add_flag("--verify", o->verify, "Decode every image while scanning (slow, finds all corrupt frames)");
  sub->add_flag("--json", o->json, "Machine-readable output");
  return {sub, [o]() {
            const nlohmann::json summary = summarize(*o);
            if (o->json)
              std::cout << summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
            else
              print_text(summary);
            return kExitOk;
          }};
}

}  // namespace plenopath::cli
