#include "processing/pipeline/track_step.h"

#include <memory>

#include "model/error.h"
#include "processing/capture/frame_source.h"
#include "processing/capture/stills_folder.h"
#include "processing/egomotion/tracking_health.h"
#include "processing/sampling/keyframe_sampler.h"

namespace plenopath::pipeline {

void TrackStepOptions::check() const {
  egomotion.check();
  stills.check();
  place.check();
}

TrackStepResult run_track(Project project, const TrackStepOptions& options, Progress& progress) {
  options.check();
  if (project.capture.empty()) throw Error("the project has no capture to track");
  std::shared_ptr<FrameSource> source = FrameSource::open_capture(project.capture);
  const int n = source->frame_count();
  if (n < 2) throw Error("the capture has fewer than two frames");
  const auto read = [&](int kept) {
    progress.throw_if_cancelled();
    return source->read(kept);
  };
  // Registration and the stills' fits name frames by capture index.
  const auto read_index = [&](int index) { return read(project.capture.kept_of_frame_index(index)); };
  TrackStepResult out;
  // Stills or video: as the author imported it, else judged by how well KLT follows neighbours.
  progress.checkpoint(0.0, "looking at the frames");
  const bool plain_folder = source->kind() == CaptureKind::kImageFolder && source->head_count() == 0;
  if (options.force_stills && !plain_folder)
    throw Error(project.capture.source +
                ": not a folder of panoramas (a video or a rig capture is tracked, not solved as stills)");
  out.choice = choose_stills(n, read, project.capture.stills || options.force_stills, plain_folder,
                             options.auto_stills);
  out.changed = kPathChanged | kVisibilityChanged;
  std::string mode;
  if (out.choice.stills && !project.capture.stills) {  // found out now: the stills' order and GPS too
    out.order = stills_folder(*source, project.capture);
    project.capture = out.order->capture;
    source = FrameSource::open_capture(project.capture);
    out.changed |= kCaptureChanged;
    mode = "solved as still panoramas (" + out.choice.reason + ")";
  }
  // With a plan, placing the path takes the last tenth of the progress.
  const bool place = options.place_on_plan && !project.plan.empty();
  const double tracked_at = place ? 0.9 : options.refine_with_anchors ? 0.95 : 1.0;
  SubProgress tracking_progress(progress, 0.0, tracked_at);
  EgomotionResult& result = out.tracking;
  if (out.choice.stills) {
    StillsOptions stills_options = options.stills;
    if (project.capture.camera_height_m > 0) stills_options.camera_height_m = project.capture.camera_height_m;
    stills_options.check();
    out.stills = solve_stills(n, read, stills_options, tracking_progress);
    const int unconnected = static_cast<int>(out.stills->unconnected.size());
    result = tracker_result_from_stills(*out.stills);
    out.stills->path = {};
    out.stills->points.clear();
    if (mode.empty()) mode = "solved as still panoramas";
    mode += ": " + std::to_string(n - unconnected) + " of " + std::to_string(n) + " connected";
    if (unconnected > 0)
      mode += "; place each of the others with Process > Place still on plan (Ctrl+Shift+O) and a click";
  } else {
    EgomotionOptions egomotion = options.egomotion;
    if (!(egomotion.camera_height_m > 0)) egomotion.camera_height_m = project.capture.camera_height_m;
    egomotion.check();
    // run() gives reading and tracking the frames the first half of the progress.
    result = EgomotionTracker::run(n, read, egomotion, tracking_progress);
  }
  // The tracker numbers frames 0..n-1 in source order (kept frames); the project uses capture indices.
  std::vector<int> positions(result.path.size());
  for (int i = 0; i < static_cast<int>(positions.size()); ++i)
    positions[i] = project.capture.frame_index_of_kept(i);
  for (PathFrame& f : result.path.frames)
    if (project.capture.kind == CaptureKind::kImageFolder && f.index >= 0 &&
        f.index < static_cast<int>(project.capture.frame_names.size()))
      f.file = project.capture.frame_names[static_cast<std::size_t>(f.index)];
  renumber_frames(&result.path, positions);
  renumber_point_frames(&result.tracked_points, positions);
  result.path.scale_source = result.scale_source;
  project.path = std::move(result.path);
  project.path_points = std::move(result.tracked_points);
  result.path = {};
  result.tracked_points.clear();
  project.visibility = {};  // cells belong to the old path
  if (out.choice.stills) {  // every still is a keyframe
    project.keyframes = every_frame_a_keyframe(project.path);
    out.changed |= kKeyframesChanged;
  }
  if (!out.choice.stills) {
    // A path mostly bridged is still the author's to anchor, but it must be said to be a guess.
    const TrackingHealth health = assess_tracking(project.path);
    if (!health.reliable) mode = (mode.empty() ? "" : mode + "; ") + "warning: " + health.warning;
  }
  std::string summary = mode;
  if (place) {
    const auto join = [&](const std::string& line) { summary = mode.empty() ? line : mode + "; " + line; };
    if (const std::string why = placement_precondition(project, options.place.camera_height_m);
        !why.empty()) {
      out.placement_error = why;
      join("tracked; not placed on the plan: " + why);
    } else {
      // No stage name of its own: "registration: ...", "refinement on the walls: ..." say what it does.
      SubProgress placing(progress, 0.9, out.choice.stills ? 0.97 : 1.0);
      try {
        PlaceStepResult placed = run_place_on_plan(project, options.place, placing);
        project = std::move(placed.project);
        placed.project = {};
        std::string line = placed.summary;
        if (out.choice.stills) {
          // The stills registration left off the plan: next to their neighbours in capture order, then
          // along pairs that have a direction but no length, the plan saying how far; again next to their
          // neighbours, from the stills the pairs placed. A group without metric scale is taken as stills
          // of their own first.
          const double height = options.place.camera_height_m > 0 ? options.place.camera_height_m
                                                                  : project.capture.camera_height_m;
          split_unscaled_groups(&project.path, &project.path_points);
          CaptureOrderPlacementOptions order_options;
          order_options.fit.camera_height_m = height;
          PairPlacementOptions pair_options;
          pair_options.fit.camera_height_m = height;
          SubProgress order_progress(progress, 0.97, 0.98, "stills next to their neighbours");
          project.path = place_stills_by_capture_order(project.path, out.stills->pairs, read_index,
                                                       project.plan, &project.path_points, order_options,
                                                       &out.capture_order, order_progress);
          SubProgress along_progress(progress, 0.98, 0.99, "stills along their pairs");
          project.path =
              place_stills_along_pairs(project.path, out.stills->pairs, read_index, project.plan,
                                       &project.path_points, pair_options, &out.along_pairs, along_progress);
          if (!out.along_pairs.placed.empty()) {
            SubProgress again(progress, 0.99, 1.0, "stills next to their neighbours");
            project.path =
                place_stills_by_capture_order(project.path, out.stills->pairs, read_index, project.plan,
                                              &project.path_points, order_options, &out.capture_order, again);
          }
          if (!out.capture_order.placed.empty())
            line += "; " + std::to_string(out.capture_order.placed.size()) +
                    " still(s) placed next to their neighbours in capture order";
          if (!out.along_pairs.placed.empty())
            line +=
                "; " + std::to_string(out.along_pairs.placed.size()) + " still(s) placed along their pairs";
        }
        out.placement = std::move(placed);
        join(line);
      } catch (const Cancelled&) {
        throw;
      } catch (const Error& e) {  // the tracked path is still worth having, unplaced
        out.placement_error = e.what();
        join(std::string("tracked; not placed on the plan: ") + e.what());
      }
    }
  }
  if (options.refine_with_anchors && !project.anchors.empty()) {
    SubProgress anchor_progress(progress, place ? 0.98 : 0.95, 1.0, "refinement with the anchors");
    project.path = refine_path_with_anchors(project.path, project.anchors, {}, &out.anchors, anchor_progress);
    // Two anchors or more fix the scale too.
    if (project.anchors.size() >= 2) project.path.scale_source = result.scale_source = "anchors";
  }
  if (!summary.empty()) progress.report(1.0, summary);
  out.summary = summary.empty() ? "tracked " + std::to_string(project.path.size()) + " frames" : summary;
  out.project = std::move(project);
  return out;
}

}  // namespace plenopath::pipeline
