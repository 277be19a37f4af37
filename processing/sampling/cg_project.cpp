#include "processing/sampling/cg_project.h"

#include <filesystem>
#include <memory>

#include "model/error.h"
#include "processing/capture/frame_source.h"

namespace plenopath {

void land_cg_capture(Project& project, const CgCaptureResult& rendered, const CgCaptureOptions& options,
                     const std::string& out_dir) {
  namespace fs = std::filesystem;
  FrameSourceOptions source_options;
  const std::string folder = (fs::path(out_dir) / "frames").string();
  if (rendered.depth) source_options.depth_folder = (fs::path(out_dir) / "depth").string();
  const std::unique_ptr<FrameSource> source = FrameSource::open(folder, source_options);
  Capture capture = capture_from_frame_source(*source, Capture{});
  capture.camera_height_m = rendered.camera_height_m;
  // The path in the capture's numbering: frame k of the folder is the k-th frame written.
  CameraPath path = rendered.path;
  if (static_cast<int>(path.size()) != source->frame_count())
    throw Error(out_dir + ": " + std::to_string(source->frame_count()) + " frames in the folder for " +
                std::to_string(path.size()) + " rendered (the folder held other frames before?)");
  for (std::size_t k = 0; k < path.frames.size(); ++k) {
    path.frames[k].index = static_cast<int>(k);
    if (k < capture.frame_names.size()) path.frames[k].file = capture.frame_names[k];
  }
  if (options.section_plan) project.plan = rendered.section_plan;
  project.capture = std::move(capture);
  project.path = std::move(path);
  project.path_points = {};
  project.visibility = {};
  project.keyframes = {};
  // Online, the frames written are the keyframes the sampler chose: they stay keyframes, in its progressive
  // order, numbered as the capture's frames (the k-th frame written is the k-th keyframe).
  if (!rendered.online_keyframes.empty() &&
      rendered.online_keyframes.indices.size() == project.path.frames.size()) {
    Keyframes keyframes = rendered.online_keyframes;
    for (std::size_t k = 0; k < keyframes.indices.size(); ++k) keyframes.indices[k] = static_cast<int>(k);
    keyframes.pinned.clear();
    project.keyframes = std::move(keyframes);
  }
}

}  // namespace plenopath
