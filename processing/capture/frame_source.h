#pragma once
// Where a capture's frames come from: a folder of equirectangular images, a video file, or a generator
// (synthetic captures, multi-head stitching). One class with a private backend; all backends give the same
// view: frames 0..frame_count()-1 in capture order, BGR 8-bit, each with a name and a time stamp.
//
// Opening scans cheaply (file names, image headers, the container's frame count) and never aborts on a bad
// frame: corrupt or missing frames are left out of the index and listed by skipped(). read() of a frame that
// only turns out bad when decoded throws plenopath::Error naming the file or frame.
//
// Thread safety: read(), read_thumbnail() and read_depth() may be called from several threads at once
// (the frame cache prefetches on a worker); the video backend serialises decoding internally.
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "model/capture.h"

namespace plenopath {

struct FrameSourceOptions {
  int first_frame = 0;       // first frame kept: video frame number, or position in the sorted file list
  int last_frame = -1;       // last frame kept (inclusive); -1 = up to the end
  int stride = 1;            // keep every stride-th frame from first_frame on
  bool require_2to1 = true;  // refuse frames that are not equirectangular 2:1 (width == 2 * height)
  double folder_frame_rate = 30.0;  // image folders: frames per second, for time stamps and GPS matching
  std::string depth_folder;         // optional: depth maps matched to frames by name (see read_depth)
  bool verify_by_decoding = false;  // image folders: decode every frame while scanning (slow, thorough);
                                    // otherwise only headers, sizes and JPEG end markers are checked
  int stitch_width = 2048;  // multi-head captures: width of the stitched panorama (height = width / 2)
  void check() const;       // throws Error saying which field is wrong
};

// A frame left out of the capture while scanning, and why.
struct SkippedFrame {
  int number = -1;     // video frame number, or the frame's number in the folder's numbering (-1 unknown)
  std::string name;    // file name (image folder) or "frame N" (video)
  std::string reason;  // e.g. "corrupt JPEG (no end-of-image marker)", "missing (gap in numbering)"
};

class FrameSource {
 public:
  // Opens an image folder (JPEG, PNG, TIFF, EXR; natural sort of file names, so frame10 follows frame9) or
  // a video file (MP4, MOV, MKV, AVI through FFmpeg: frame-exact, see video_decoder.h). Throws Error naming
  // the path when it does not exist, holds no usable frame, or the frames are not 2:1 (if
  // options.require_2to1).
  static std::unique_ptr<FrameSource> open(const std::string& folder_or_video,
                                           const FrameSourceOptions& options = {});
  // A multi-head capture: one image folder per head (in the rig file's head order) and the rig calibration
  // (rig/multi_head_rig.h); frames are stitched to stitch_width x stitch_width/2 on the fly. A head's frames
  // are matched to head 0's by the number in their names (else by file stem); frames some head lacks are
  // skipped and listed. Range and stride apply to head 0's sorted frames. open() does this by itself for a
  // folder holding kRigFileName and one sub-folder per head named after the head (or head0, head1, ...).
  static std::unique_ptr<FrameSource> open_multi_head(const std::string& rig_file,
                                                      const std::vector<std::string>& head_folders,
                                                      const FrameSourceOptions& options = {});
  static constexpr const char* kRigFileName = "rig.json";
  // Re-opens what a project's Capture describes (image folders use capture.frame_names as listed).
  static std::unique_ptr<FrameSource> open_capture(const Capture& capture);
  // Frames made on demand by `generate(i)` (must return width x height CV_8UC3 and be thread-safe):
  // synthetic captures, stitched multi-head rigs, benchmarks.
  static std::unique_ptr<FrameSource> from_generator(int frame_count, int width, int height,
                                                     double frame_rate, std::function<cv::Mat(int)> generate,
                                                     const std::string& description = "generated");

  ~FrameSource();
  FrameSource(const FrameSource&) = delete;
  FrameSource& operator=(const FrameSource&) = delete;

  CaptureKind kind() const;           // kImageFolder, kVideo, or kNone for generators
  const std::string& source() const;  // the folder or video path as given
  int frame_count() const;
  int width() const;
  int height() const;
  double frame_rate() const;  // frames per second of the kept frames' source (before stride)
  const FrameSourceOptions& options() const;
  int head_count() const;  // multi-head captures: number of heads; 0 otherwise

  std::string frame_name(int i) const;  // file name relative to the folder, or "frame N" for videos
  int frame_number(int i) const;        // video frame number, or the number in the file name (-1 if none)
  double timestamp_s(int i) const;      // seconds from the source's frame 0 (video: the frame's own time
                                        // stamp, so variable frame rates are right; folders: number / rate)

  cv::Mat read(int i);  // full frame, CV_8UC3 BGR; throws Error naming the file/frame
  // A small frame no wider than max_width (JPEG decodes at reduced size, so this is fast), CV_8UC3.
  cv::Mat read_thumbnail(int i, int max_width);

  std::vector<SkippedFrame> skipped() const;

  // Depth maps (options.depth_folder): a depth file matches a frame when its stem equals the frame's stem,
  // or when the number in its name equals frame_number(i). 16-bit PNG in millimetres (0 = no hit) or 32-bit
  // float EXR in metres, same size as the frame.
  bool has_depth(int i) const;
  int depth_match_count() const;
  std::string depth_name(int i) const;  // matched depth file name, "" if none
  cv::Mat read_depth(int i);            // CV_32F metres, 0 = no hit; throws Error if none or unreadable

  struct Impl;

 private:
  explicit FrameSource(std::unique_ptr<Impl> impl);
  static std::unique_ptr<FrameSource> open_multi_head_folder(const std::string& capture_folder,
                                                             const FrameSourceOptions& options,
                                                             const std::vector<std::string>* given_names);
  std::unique_ptr<Impl> impl_;
};

// A project's Capture for this source: kind, source, frame counts, size, rate, first frame, stride,
// frame names (image folders), frame times (videos whose frames are not evenly spaced at the rate), depth
// folder. GPS fields are left as they are in `capture_in`.
Capture capture_from_frame_source(const FrameSource& source, Capture capture_in = {});

// Natural order of file names: digit runs compare as numbers ("frame9" < "frame10"), the rest
// case-insensitively; ties broken by plain comparison so the order is total.
bool natural_less(const std::string& a, const std::string& b);

}  // namespace plenopath
