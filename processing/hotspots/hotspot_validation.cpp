#include "processing/hotspots/hotspot_validation.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <regex>
#include <set>

#include "model/error.h"
#include "processing/hotspots/hotspot_geometry.h"
#include "processing/hotspots/hotspot_placement.h"

namespace plenopath {
namespace {

namespace fs = std::filesystem;

std::string lower_extension(const std::string& file) {
  std::string ext = fs::path(file).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string format_metres(double m) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f m", m);
  return text;
}

// Why `file` cannot be used as media of `expected` type ("" = usable). Decoding checks are optional.
std::string media_problem(const std::string& file, const std::string& expected, bool decode) {
  if (file.empty()) return "no media file is chosen";
  std::error_code ec;
  if (!fs::exists(file, ec)) return "media file not found: " + file;
  if (!fs::is_regular_file(file, ec)) return "media is not a file: " + file;
  const std::string type = media_type_of(file);
  if (type.empty()) return "media has an unknown file type: " + file;
  if (!expected.empty() && type != expected &&
      !(expected == "visual" && (type == "image" || type == "video")))
    return "media is " + std::string(type == "image" ? "an " : "a ") + type + " file where " +
           (expected == "visual" ? std::string("an image or a video")
                                 : (expected == "image" ? "an " : "a ") + expected) +
           " is needed: " + file;
  std::ifstream in(file, std::ios::binary);
  if (!in || in.peek() == std::ifstream::traits_type::eof())
    return "media file is empty or unreadable: " + file;
  if (!decode) return "";
  if (type == "image") {
    if (cv::imread(file, cv::IMREAD_REDUCED_COLOR_8).empty()) return "media image cannot be decoded: " + file;
  } else if (type == "video") {
    cv::VideoCapture video(file, cv::CAP_FFMPEG);  // FFmpeg only: no GStreamer noise
    cv::Mat first;
    if (!video.isOpened() || !video.read(first) || first.empty())
      return "media video cannot be decoded: " + file;
  }
  return "";
}

void add(std::vector<HotspotWarning>& out, const Hotspot& h, const std::string& field,
         const std::string& message) {
  out.push_back(
      {h.id, field,
       "hotspot '" + h.id + "' (" + (h.title.empty() ? std::string("untitled") : h.title) + "): " + message});
}

const PathFrame* frame_with_index(const CameraPath& path, int index) {
  for (const PathFrame& f : path.frames)
    if (f.index == index) return &f;
  return nullptr;
}

// The 3-D corners must be one plane and agree with the corners marked in the authoring frame.
void check_geometry(const Hotspot& h, const Project& project, const HotspotValidationOptions& options,
                    std::vector<HotspotWarning>& out) {
  if (h.world_corners.empty()) return;
  if (h.world_corners.size() < 3) {
    add(out, h, "world_corners", "has fewer than three 3-D corners");
    return;
  }
  if (h.kind == HotspotKind::kMovieTexture && h.world_corners.size() != 4)
    add(out, h, "world_corners",
        "a movie texture needs four corners, it has " + std::to_string(h.world_corners.size()));
  Plane3 plane;
  try {
    plane = fit_plane(h.world_corners);
  } catch (const Error& e) {
    add(out, h, "world_corners", e.what());
    return;
  }
  if (plane.rms_m > options.max_planarity_m)
    add(out, h, "world_corners",
        "its 3-D corners are not on one plane (rms " + format_metres(plane.rms_m) + " off the best plane)");
  const PathFrame* pose = frame_with_index(project.path, h.frame);
  if (!pose || h.image_corners.size() != h.world_corners.size()) return;
  const double camera_height = camera_height_or_default(project.capture.camera_height_m);
  LiftedQuad marks, stored;
  stored.corners = h.world_corners;
  try {
    for (const auto& c : h.image_corners)
      marks.corners.push_back(point_on_quad_plane(h.world_corners, {c.x(), c.y()}, *pose, camera_height));
  } catch (const Error& e) {
    add(out, h, "world_corners",
        "its corners marked in frame " + std::to_string(h.frame) + " do not meet its 3-D plane (" + e.what() +
            ")");
    return;
  }
  const double off = quad_consistency_m(marks, stored);
  if (off > options.max_inconsistency_m)
    add(out, h, "world_corners",
        "the quad is not consistent with one plane across frames: its corners marked in frame " +
            std::to_string(h.frame) + " land " + format_metres(off) + " from its 3-D corners");
}

}  // namespace

void HotspotValidationOptions::check() const {
  if (!(max_planarity_m > 0)) throw Error("hotspot validation: max planarity must be > 0");
  if (!(max_inconsistency_m > 0)) throw Error("hotspot validation: max inconsistency must be > 0");
}

std::string media_type_of(const std::string& file) {
  static const std::set<std::string> images{".png",  ".jpg", ".jpeg", ".bmp",
                                            ".webp", ".gif", ".tif",  ".tiff"};
  static const std::set<std::string> videos{".mp4", ".m4v", ".mov", ".mkv", ".avi", ".webm", ".ogv"};
  static const std::set<std::string> sounds{".mp3", ".wav", ".ogg", ".oga", ".m4a", ".aac", ".flac"};
  const std::string ext = lower_extension(file);
  if (images.count(ext)) return "image";
  if (videos.count(ext)) return "video";
  if (sounds.count(ext)) return "audio";
  return "";
}

bool text_has_markup(const std::string& text) {
  // A tag (<b>, </p>, <img ...>, <!-- -->) or a character entity (&amp; &#60; &#x3c;).
  static const std::regex markup(
      R"(<\s*/?\s*[A-Za-z!][^>]*>|&(#[0-9]+|#[xX][0-9A-Fa-f]+|[A-Za-z][A-Za-z0-9]*);)");
  return std::regex_search(text, markup);
}

std::vector<HotspotWarning> validate_hotspot(const Hotspot& h, const Project& project,
                                             const HotspotValidationOptions& options) {
  options.check();
  std::vector<HotspotWarning> out;
  if (h.kind == HotspotKind::kMovieTexture) {
    const std::string problem = media_problem(h.media, "visual", options.decode_media);
    if (!problem.empty()) add(out, h, "media", problem);
    if (h.image_corners.size() != 4 && h.world_corners.size() != 4)
      add(out, h, "image_corners", "a movie texture needs a quad of four corners");
  } else if (!h.media.empty()) {
    const std::string problem = media_problem(h.media, "visual", options.decode_media);
    if (!problem.empty()) add(out, h, "media", problem);
  }
  if (h.image_corners.size() < 3 && h.world_corners.size() < 3)
    add(out, h, "image_corners", "has no region (fewer than three corners)");
  if (!project.path.empty() && !frame_with_index(project.path, h.frame))
    add(out, h, "frame", "its authoring frame " + std::to_string(h.frame) + " is not on the camera path");
  check_geometry(h, project, options, out);

  if (text_has_markup(h.title))
    add(out, h, "title", "the title contains markup; it is shown as plain text, not interpreted");

  if (h.kind == HotspotKind::kEvent) {
    if (h.trigger == HotspotTrigger::kProximity && !(h.trigger_distance_m > 0))
      add(out, h, "trigger_distance_m", "a proximity trigger needs a distance > 0");
    const std::string& t = h.action_target;
    switch (h.action) {
      case HotspotAction::kSwapImage: {
        // An image, or a video standing for an image sequence (`plenopath encode-video` makes one from
        // frames).
        const std::string problem = media_problem(t, "visual", options.decode_media);
        if (!problem.empty()) add(out, h, "action_target", "swap image: " + problem);
        break;
      }
      case HotspotAction::kPlayVideo:
        // A movie texture's own video plays in place; otherwise the target is the video.
        if (!(t.empty() && media_type_of(h.media) == "video")) {
          const std::string problem = media_problem(t, "video", options.decode_media);
          if (!problem.empty()) add(out, h, "action_target", "play video: " + problem);
        }
        break;
      case HotspotAction::kPlaySound: {
        const std::string problem = media_problem(t, "audio", false);
        if (!problem.empty()) add(out, h, "action_target", "play sound: " + problem);
        break;
      }
      case HotspotAction::kJump: {
        static const std::regex number(R"(\s*[0-9]+\s*)");
        static const std::regex url(R"(https?://\S+)", std::regex::icase);
        if (std::regex_match(t, number)) {
          if (!project.path.empty() && !frame_with_index(project.path, std::stoi(t)))
            add(out, h, "action_target", "jump: frame " + t + " is not on the camera path");
        } else if (!std::regex_match(t, url)) {
          add(out, h, "action_target",
              "jump: the target must be a frame number or another tour's http(s) address");
        }
        break;
      }
      case HotspotAction::kOpenUrl: {
        static const std::regex url(R"(https?://\S+)", std::regex::icase);
        if (!std::regex_match(t, url))
          add(out, h, "action_target", "open URL: only http and https links open: '" + t + "'");
        break;
      }
      case HotspotAction::kShowText:
        if (t.empty()) add(out, h, "action_target", "show text: the text is empty");
        if (text_has_markup(t))
          add(out, h, "action_target",
              "the text contains markup; it is shown as plain text, not interpreted");
        break;
      case HotspotAction::kNone:
        add(out, h, "action", "an event hotspot without an action does nothing");
        break;
    }
  }
  return out;
}

std::vector<HotspotWarning> validate_hotspots(const Project& project,
                                              const HotspotValidationOptions& options) {
  options.check();
  std::vector<HotspotWarning> out;
  std::set<std::string> seen;
  for (const Hotspot& h : project.hotspots) {
    if (h.id.empty())
      add(out, h, "id", "has no id");
    else if (!seen.insert(h.id).second)
      add(out, h, "id", "its id is used by another hotspot");
    for (auto& w : validate_hotspot(h, project, options)) out.push_back(std::move(w));
  }
  return out;
}

}  // namespace plenopath
