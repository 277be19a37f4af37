#pragma once
// What was shot: a folder of equirectangular frames or a video, optional depth maps and GPS track.
#include <string>
#include <vector>

namespace plenopath {

enum class CaptureKind { kNone, kImageFolder, kVideo };
const char* to_string(CaptureKind kind);
CaptureKind capture_kind_from_string(const std::string& text);  // throws Error on an unknown name

struct GpsSample {
  double time_s = 0.0;  // seconds since the track's epoch (UTC)
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double altitude_m = 0.0;
};
bool operator==(const GpsSample& l, const GpsSample& r);

struct Capture {
  CaptureKind kind = CaptureKind::kNone;
  std::string source;  // folder or video file; absolute in memory, relative to the project on disk
  int frame_count = 0;
  int width = 0;
  int height = 0;
  double frame_rate = 30.0;              // frames per second, for playback and GPS matching
  int first_frame = 0;                   // video: first decoded frame number
  int stride = 1;                        // video/folder: keep every stride-th frame
  std::vector<std::string> frame_names;  // image folder: file names relative to source, in capture order
  // Video with a variable frame rate: each kept frame's presentation time, seconds after the video's frame 0
  // (kept frame k is video frame first_frame + k * stride). Empty when the frames are evenly spaced at
  // frame_rate, as nearly all are.
  std::vector<double> frame_times_s;
  std::string depth_folder;          // optional; depth maps matched to frames by name
  std::vector<GpsSample> gps_track;  // optional
  double gps_time_offset_s = 0.0;    // capture time of frame 0 in the GPS track's clock
  double camera_height_m = 0.0;      // 0 = unknown
  // Optional: an image of the frames' size, black where the rig (trolley, operator, tripod) covers every
  // frame, white elsewhere (as `track --mask`); the tracker's own estimate is used when it is empty.
  std::string rig_mask;
  // Still panoramas shot from a tripod metres apart (issue 20): solved by the stills pipeline, not tracked
  // as video. Set when the author imports them as stills, or when tracking finds the folder is stills.
  bool stills = false;

  bool empty() const { return kind == CaptureKind::kNone; }
  // Seconds from the source's frame 0 to kept frame k: its stored time, else (first_frame + k * stride) /
  // frame_rate.
  double frame_time_s(int k) const;
  // The same at a path frame's index (PathFrame::index: a video's frame number; an image folder's position
  // in the capture): a video frame between kept ones, or outside them, is placed at frame_rate from the
  // nearest kept frame.
  double time_at_index_s(int index) const;
  // The one mapping between kept frames (0..frame_count-1, what FrameSource::read takes) and capture
  // indices (PathFrame::index, anchors, keyframes, hotspots): a video's kept frame k is its frame number
  // first_frame + k * stride; an image folder's (and a generated capture's) kept frame k is index k.
  int frame_index_of_kept(int k) const;
  // The inverse: the kept frame at capture index `index`, or -1 when no kept frame has it (a video frame
  // between strides or before first_frame, or an index beyond frame_count when frame_count is known).
  int kept_of_frame_index(int index) const;
};
bool operator==(const Capture& l, const Capture& r);

}  // namespace plenopath
