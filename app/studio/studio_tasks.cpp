#include "app/studio/studio_tasks.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "model/error.h"
#include "model/path_io.h"
#include "processing/capture/frame_source.h"
#include "processing/capture/gps_track.h"
#include "processing/capture/stills_folder.h"
#include "processing/pipeline/export_step.h"
#include "processing/pipeline/refine_step.h"
#include "processing/pipeline/track_step.h"
#include "processing/pipeline/visibility_step.h"
#include "processing/sampling/cg_capture.h"
#include "processing/sampling/cg_project.h"
#include "processing/stills/still_on_plan.h"
#include "widgets/project_document.h"

namespace plenopath::studio {

using widgets::TaskResult;

widgets::TaskFunction import_capture_task(const widgets::CaptureImportChoices& choices) {
  return [choices](Project project, Progress& progress) {
    progress.checkpoint(0.05, "scanning " + choices.source);
    choices.options.check();
    const std::unique_ptr<FrameSource> source = FrameSource::open(choices.source, choices.options);
    progress.checkpoint(0.9, "listing " + std::to_string(source->frame_count()) + " frames");
    const bool same_source = project.capture.source == source->source();
    std::string stills_summary;
    if (choices.stills) {
      if (source->kind() != CaptureKind::kImageFolder || source->head_count() > 0)
        throw Error(choices.source +
                    ": still panoramas are a folder of images (a video or a rig capture is "
                    "imported without \"still panoramas\")");
      progress.checkpoint(0.5, "reading the stills' metadata");
      Capture before = project.capture;
      if (!same_source) before.gps_track.clear();
      const StillsFolder folder = stills_folder(*source, before);
      project.capture = folder.capture;
      stills_summary = " still panoramas, ordered " + folder.order;
      if (folder.stills_with_gps > 0)
        stills_summary += ", " + std::to_string(folder.stills_with_gps) + " with a GPS position";
      if (!folder.notes.empty())
        stills_summary +=
            "; " + std::to_string(folder.notes.size()) + " note(s), the first: " + folder.notes.front();
    } else {
      project.capture = capture_from_frame_source(*source, project.capture);
      project.capture.stills = false;
      if (!same_source) project.capture.gps_track.clear();  // another capture's track would be wrong
    }
    if (choices.camera_height_m > 0) project.capture.camera_height_m = choices.camera_height_m;
    std::string gps_summary;
    if (!choices.gps_file.empty()) {
      progress.checkpoint(0.95, "reading the GPS track " + choices.gps_file);
      const GpsTrack track = read_gps_track(choices.gps_file);
      project.capture.gps_track = track.samples;
      project.capture.gps_time_offset_s = choices.gps_time_offset_s;
      gps_summary = ", " + std::to_string(track.samples.size()) + " GPS points";
      for (const std::string& note : track.notes) gps_summary += " (" + note + ")";
    }
    progress.report(1.0, std::to_string(source->frame_count()) +
                             (choices.stills ? stills_summary : std::string(" frames")) + gps_summary);
    return TaskResult{std::move(project), widgets::kCaptureChanged};
  };
}

widgets::TaskFunction render_cg_scene_task(const widgets::CgSceneChoices& choices) {
  return [choices](Project project, Progress& progress) {
    const CameraPath along = choices.use_project_path     ? project.path
                             : !choices.path_file.empty() ? read_path_file(choices.path_file)
                                                          : walk_waypoints(choices.waypoints, choices.step_m);
    if (along.empty())
      throw Error("there is no path to render along: track or import one, or type waypoints");
    require_placed(along, "render CG scene");  // an unplaced piece has no plan positions to render at
    SubProgress rendering(progress, 0.0, 0.95, "rendering " + choices.scene);
    const CgCaptureResult rendered =
        render_cg_capture(choices.scene, along, choices.options, choices.out_dir, rendering);
    progress.checkpoint(0.96, "scanning " + choices.out_dir);
    land_cg_capture(project, rendered, choices.options, choices.out_dir);
    progress.report(1.0, std::to_string(rendered.full_frames) + " of " +
                             std::to_string(rendered.path_frames) + " frames rendered at full size into " +
                             choices.out_dir);
    return TaskResult{std::move(project), widgets::kCaptureChanged | widgets::kPathChanged |
                                              widgets::kVisibilityChanged | widgets::kKeyframesChanged |
                                              (choices.options.section_plan ? widgets::kPlanChanged : 0u)};
  };
}

widgets::TaskFunction track_path_task(std::shared_ptr<PlacementOutcome> placement) {
  return [placement](Project project, Progress& progress) {
    const bool has_plan = !project.plan.empty();
    pipeline::TrackStepResult result = pipeline::run_track(std::move(project), {}, progress);
    // The summary reaches the status bar with or without a plan: it says when the path is mostly a guess.
    if (placement)
      *placement = {has_plan && result.placement ? std::move(result.placement->choices) : PlacementChoices{},
                    result.summary};
    return TaskResult{std::move(result.project), result.changed};
  };
}

widgets::TaskFunction place_path_on_plan_task(std::shared_ptr<PlacementOutcome> placement,
                                              std::shared_ptr<const SharedVisibilityIndex> index) {
  return [placement, index](Project project, Progress& progress) {
    pipeline::PlaceStepOptions options;
    options.visibility_index = index;
    pipeline::PlaceStepResult result = pipeline::run_place_on_plan(std::move(project), options, progress);
    if (placement) *placement = {std::move(result.choices), result.summary};
    return TaskResult{std::move(result.project), result.changed};
  };
}

widgets::TaskFunction place_still_task(int frame, Eigen::Vector2d click,
                                       std::optional<double> heading_hint_deg,
                                       std::shared_ptr<std::string> summary) {
  return [=](Project project, Progress& progress) {
    if (project.plan.empty()) throw Error("the project has no plan to place the still on");
    if (!project.path.find_frame(frame)) throw Error("the path has no frame " + std::to_string(frame));
    if (project.capture.kind != CaptureKind::kImageFolder)
      throw Error("stills are placed from a folder of images; this capture is a video");
    if (!(project.capture.camera_height_m > 0))
      throw Error("the camera height is unknown: set it in File > Import still panoramas");
    progress.checkpoint(0.01, "reading the still");
    const auto source = FrameSource::open_capture(project.capture);
    if (frame >= source->frame_count())
      throw Error("frame " + std::to_string(frame) + " is beyond the capture");
    StillOnPlanOptions options;
    options.camera_height_m = project.capture.camera_height_m;
    options.heading_hint_deg = heading_hint_deg;
    SubProgress placing(progress, 0.02, 0.98);
    const StillPlacement placed =
        place_still_on_plan(source->read(frame), project.plan, click, options, placing);
    project.path = path_with_still_placed(project.path, frame, placed);
    project.visibility = {};  // cells belong to the old path
    const std::string text = source->frame_name(frame) + ": " + placed.summary;
    if (summary) *summary = text;
    progress.report(1.0, text);
    return TaskResult{std::move(project), widgets::kPathChanged | widgets::kVisibilityChanged};
  };
}

widgets::TaskFunction compute_visibility_task(std::shared_ptr<const SharedVisibilityIndex> index) {
  return [index](Project project, Progress& progress) {
    pipeline::VisibilityStepOptions options;
    options.visibility_index = index;
    pipeline::StepResult result = pipeline::run_visibility(std::move(project), options, progress);
    return TaskResult{std::move(result.project), result.changed};
  };
}

widgets::TaskFunction refine_with_anchors_task(std::shared_ptr<const SharedVisibilityIndex> index) {
  return [index](Project project, Progress& progress) {
    pipeline::RefineStepOptions options;
    options.visibility_index = index;
    pipeline::RefineStepResult result = pipeline::run_refine(std::move(project), options, progress);
    return TaskResult{std::move(result.project), result.changed};
  };
}

widgets::TaskFunction export_tour_task(const std::string& output) {
  return [output](Project project, Progress& progress) {
    pipeline::ExportStepOptions options;
    options.tour = TourExportOptions::from_project(project, output);
    pipeline::ExportStepResult result = pipeline::run_export(std::move(project), options, progress);
    return TaskResult{std::move(result.project), result.changed};
  };
}

}  // namespace plenopath::studio
