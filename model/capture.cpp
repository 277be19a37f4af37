#include "model/capture.h"

#include <algorithm>
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
                  l.frame_names, l.frame_times_s, l.depth_folder, l.gps_track, l.gps_time_offset_s,
                  l.rig_mask, l.camera_height_m, l.stills) ==
         std::tie(r.kind, r.source, r.frame_count, r.width, r.height, r.frame_rate, r.first_frame, r.stride,
                  r.frame_names, r.frame_times_s, r.depth_folder, r.gps_track, r.gps_time_offset_s,
                  r.rig_mask, r.camera_height_m, r.stills);
}

double Capture::frame_time_s(int k) const {
  if (k >= 0 && k < static_cast<int>(frame_times_s.size())) return frame_times_s[k];
  const double rate = frame_rate > 0 ? frame_rate : 30.0;
  return (first_frame + double(k) * std::max(1, stride)) / rate;
}

int Capture::frame_index_of_kept(int k) const {
  if (kind != CaptureKind::kVideo) return k;
  return first_frame + k * std::max(1, stride);
}

int Capture::kept_of_frame_index(int index) const {
  if (index < 0) return -1;
  if (kind != CaptureKind::kVideo) return frame_count > 0 && index >= frame_count ? -1 : index;
  const int step = std::max(1, stride);
  if (index < first_frame || (index - first_frame) % step != 0) return -1;
  const int k = (index - first_frame) / step;
  return frame_count > 0 && k >= frame_count ? -1 : k;
}

double Capture::time_at_index_s(int index) const {
  const double rate = frame_rate > 0 ? frame_rate : 30.0;
  if (kind != CaptureKind::kVideo) return frame_time_s(index);
  if (frame_times_s.empty()) return index / rate;
  // The nearest kept frame at or before the index (or the first), then frame_rate on from it.
  const int step = std::max(1, stride);
  const int k = std::clamp(index >= first_frame ? (index - first_frame) / step : 0, 0,
                           static_cast<int>(frame_times_s.size()) - 1);
  return frame_times_s[k] + (index - (first_frame + k * step)) / rate;
}

}  // namespace plenopath
