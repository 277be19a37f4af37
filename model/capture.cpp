#include "model/capture.h"

#include <tuple>

#include "model/error.h"

namespace plenopath {

const char* to_string(CaptureKind kind) {
  switch (kind) {
    case CaptureKind::kNone:
      return "none";
    case CaptureKind::kImageFolder:
      return "image_folder";
    case CaptureKind::kVideo:
      return "video";
  }
  return "none";
}

CaptureKind capture_kind_from_string(const std::string& text) {
  if (text == "none") return CaptureKind::kNone;
  if (text == "image_folder") return CaptureKind::kImageFolder;
  if (text == "video") return CaptureKind::kVideo;
  throw Error("unknown capture kind '" + text + "' (expected none, image_folder or video)");
}

bool operator==(const GpsSample& l, const GpsSample& r) {
  return std::tie(l.time_s, l.latitude_deg, l.longitude_deg, l.altitude_m) ==
         std::tie(r.time_s, r.latitude_deg, r.longitude_deg, r.altitude_m);
}

bool operator==(const Capture& l, const Capture& r) {
  return std::tie(l.kind, l.source, l.frame_count, l.width, l.height, l.frame_rate, l.first_frame, l.stride,
                  l.frame_names, l.depth_folder, l.gps_track, l.gps_time_offset_s, l.camera_height_m) ==
         std::tie(r.kind, r.source, r.frame_count, r.width, r.height, r.frame_rate, r.first_frame, r.stride,
                  r.frame_names, r.depth_folder, r.gps_track, r.gps_time_offset_s, r.camera_height_m);
}

}  // namespace plenopath
