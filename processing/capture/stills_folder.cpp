#include "processing/capture/stills_folder.h"

#include <algorithm>
#include <filesystem>
#include <numeric>

#include "processing/capture/frame_source.h"
#include "processing/capture/photo_metadata.h"

namespace plenopath {

StillsFolder stills_folder(const FrameSource& source, const Capture& capture_in) {
  StillsFolder out;
  out.capture = capture_from_frame_source(source, capture_in);
  const int n = source.frame_count();
  if (source.kind() != CaptureKind::kImageFolder || n == 0) {
    out.order = "as the source gives them";
    return out;
  }
  std::vector<PhotoMetadata> meta(static_cast<std::size_t>(n));
  int timed = 0;
  for (int i = 0; i < n; ++i) {
    const std::string name = source.frame_name(i);
    meta[i] = read_photo_metadata((std::filesystem::path(source.source()) / name).string());
    timed += meta[i].capture_time_s.has_value();
    out.stills_with_gps += meta[i].has_gps();
    for (const std::string& note : meta[i].notes) out.notes.push_back(name + ": " + note);
    if (const std::string partial = meta[i].partial_reason(); !partial.empty())
      out.notes.push_back(name + ": " + partial + " (the stills pipeline expects the full sphere)");
  }
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  out.ordered_by_time = timed == n;
  if (out.ordered_by_time) {
    // Stable: equal times (burst shots, a camera that writes whole seconds) keep the names' order.
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return *meta[a].capture_time_s < *meta[b].capture_time_s; });
    out.order = "by EXIF DateTimeOriginal";
  } else if (timed == 0) {
    out.order = "by file name: no still has an EXIF DateTimeOriginal";
  } else {
    out.order = "by file name: " + std::to_string(n - timed) + " of " + std::to_string(n) +
                " stills have no EXIF DateTimeOriginal";
  }
  Capture& c = out.capture;
  c.stills = true;
  std::vector<std::string> names;
  for (int i : order) names.push_back(source.frame_name(i));
  c.frame_names = names;
  c.frame_times_s.clear();
  const double first_time = out.ordered_by_time ? *meta[order.front()].capture_time_s : 0.0;
  if (out.ordered_by_time)
    for (int i : order) {
      double t = *meta[i].capture_time_s - first_time;
      // Projects keep times strictly increasing; cameras that write whole seconds repeat them.
      if (!c.frame_times_s.empty() && !(t > c.frame_times_s.back())) t = c.frame_times_s.back() + 1e-3;
      c.frame_times_s.push_back(t);
    }
  if (out.stills_with_gps > 0) {
    c.gps_track.clear();
    c.gps_time_offset_s = first_time;
    for (int k = 0; k < n; ++k) {
      const PhotoMetadata& m = meta[order[k]];
      if (!m.has_gps()) continue;
      GpsSample s;
      s.time_s = first_time + c.frame_time_s(k);
      s.latitude_deg = *m.latitude_deg;
      s.longitude_deg = *m.longitude_deg;
      s.altitude_m = m.altitude_m;
      c.gps_track.push_back(s);
    }
  }
  return out;
}

}  // namespace plenopath
