#include "processing/export/keyframe_cleaner.h"

#include <opencv2/imgproc.hpp>

#include "model/error.h"
#include "processing/capture/frame_source.h"
#include "processing/cleanplate/author_edits.h"
#include "processing/cleanplate/capture_stillness.h"
#include "processing/cleanplate/rig_from_geometry.h"
#include "processing/cleanplate/rig_mask.h"
#include "rig/synthetic_camera.h"

namespace plenopath {

void KeyframeCleaning::check() const {
  if (clean_plates) {
    clean_plate.check();
    if (fill_rig) nadir.check();
  }
  if (blur_faces) face_blur.check();
}

KeyframeCleaning KeyframeCleaning::from_project(const Project& project) {
  KeyframeCleaning o;
  o.clean_plates = project.tour.export_clean_plates;
  o.clean_plate.camera_height_m = project.capture.camera_height_m;
  o.nadir.kind = project.tour.nadir_patch;
  if (o.nadir.kind == NadirPatch::kImage && !project.tour.nadir_image.empty())
    o.nadir.image = read_nadir_image(project.tour.nadir_image);
  o.blur_faces = project.tour.blur_faces;
  return o;
}

KeyframeCleaner::KeyframeCleaner(const Project& project, const KeyframeCleaning& options, Progress& progress)
    : project_(project), options_(options) {
  options_.check();
  if (project.path.empty()) throw Error("clean plates: the project has no camera path");
  frames_ = FrameSource::open_capture(project.capture);
  if (options_.clean_plates && options_.fill_rig) {
    SubProgress finding(progress, 0.0, 0.2, "finding the rig");
    rig_mask_ = rig_mask_of_capture([&](int k) { return frames_->read(k); }, frames_->frame_count(),
                                    cv::Size(frames_->width(), frames_->height()), project.capture.rig_mask,
                                    {}, finding);
    // The operator the first frames do not show as still: what stays over the capture and the geometry
    // does not explain (rig_from_geometry.h).
    SubProgress staying(progress, 0.2, 0.4, "looking for what stays in place");
    const CaptureStillness stillness =
        capture_stillness([&](int k) { return frames_->read(k); }, frames_->frame_count(), {}, staying);
    SubProgress geometry(progress, 0.4, 1.0, "finding the rig by the geometry");
    const CameraPath& path = project.path;
    rig_mask_ = rig_from_geometry(
        path,
        [&](int p) {
          const int index = path.frames[static_cast<std::size_t>(p)].index;
          if (index < 0 || index >= frames_->frame_count())
            throw Error("frame " + std::to_string(index) + " is outside the capture");
          return frames_->read(index);
        },
        [&](int p) { return static_depth(p, stillness.median.size()); }, rig_mask_, stillness, {}, geometry);
  }
  progress.report(1.0);
}

KeyframeCleaner::~KeyframeCleaner() = default;

double KeyframeCleaner::rig_pct() const {
  return rig_mask_.empty() ? 0.0 : 100.0 * cv::countNonZero(rig_mask_) / double(rig_mask_.total());
}

cv::Mat KeyframeCleaner::static_depth(int position, cv::Size size) {
  if (size.empty()) size = cv::Size(frames_->width(), frames_->height());
  const int index = project_.path.frames[static_cast<std::size_t>(position)].index;
  if (index >= 0 && index < frames_->frame_count() && frames_->has_depth(index)) {
    cv::Mat depth = frames_->read_depth(index);
    if (!depth.empty() && depth.size() != size) cv::resize(depth, depth, size, 0, 0, cv::INTER_NEAREST);
    return depth;
  }
  if (!plan_scene_) {
    SceneOptions scene;
    scene.camera_height = project_.capture.camera_height_m > 0 ? project_.capture.camera_height_m : 1.6;
    plan_scene_ = std::make_unique<SyntheticScene>(build_synthetic_scene(project_.plan, scene));
  }
  RenderOptions render;
  render.width = size.width;
  render.height = size.height;
  render.depth = true;
  return render_panorama(*plan_scene_, project_.path.frames[static_cast<std::size_t>(position)], render)
      .depth;
}

CleanedKeyframe KeyframeCleaner::clean(int frame, Progress& progress) {
  const PathFrame* pose = project_.path.find_frame(frame);
  if (!pose) throw Error("keyframe " + std::to_string(frame) + " has no pose in the path");
  if (frame < 0 || frame >= frames_->frame_count())
    throw Error("keyframe " + std::to_string(frame) + " is outside the capture (" +
                std::to_string(frames_->frame_count()) + " frames)");
  CleanedKeyframe out;
  out.original = frames_->read(frame);
  out.image = out.original;
  if (options_.clean_plates) {
    const int position = static_cast<int>(pose - project_.path.frames.data());
    SubProgress plate_progress(progress, 0.0, options_.blur_faces ? 0.9 : 1.0, "clean plate");
    out.plate = clean_plate(
        project_.path, position,
        [&](int p) {
          const int index = project_.path.frames[static_cast<std::size_t>(p)].index;
          if (index < 0 || index >= frames_->frame_count())
            throw Error("frame " + std::to_string(index) + " is outside the capture");
          return index == frame ? out.original : frames_->read(index);
        },
        [&](int p) { return static_depth(p); }, rig_mask_, options_.clean_plate, plate_progress);
    out.cleaned = true;
    out.image = out.plate.image;
    if (out.plate.unsupported_share > 0.2)
      out.warnings.push_back("keyframe " + std::to_string(frame) + ": " +
                             std::to_string(static_cast<int>(100 * out.plate.unsupported_share)) +
                             " % of what moved was seen by no neighbour and stays as it was");
    // The author's corrections (painted away or back), then the nadir patch on what is left of the rig.
    cv::Mat edits, patch_region;
    if (const CleanPlateEdit* edit = project_.tour.clean_plate_edit(frame))
      edits = read_clean_plate_edit(edit->mask, out.original.size());
    out.image = apply_clean_plate_edits(out.plate, out.original, edits, patch_region);
    if ((options_.fill_rig || !edits.empty()) && cv::countNonZero(patch_region) > 0)
      out.image = apply_nadir_patch(out.image, patch_region, options_.nadir);
  }
  if (options_.blur_faces) {
    progress.checkpoint(0.9, "blurring faces");
    FaceBlurResult blurred = blur_faces(out.image, options_.face_blur);
    out.faces = static_cast<int>(blurred.faces.size());
    out.image = blurred.image;
  }
  progress.report(1.0);
  return out;
}

}  // namespace plenopath
