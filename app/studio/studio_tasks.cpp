#include "app/studio/studio_tasks.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "model/error.h"
#include "model/path_io.h"
#include "processing/anchors/anchor_refinement.h"
#include "processing/capture/frame_source.h"
#include "processing/capture/gps_track.h"
#include "processing/capture/stills_folder.h"
#include "processing/egomotion/egomotion.h"
#include "processing/sampling/cg_capture.h"
#include "processing/sampling/cg_project.h"
#include "processing/sampling/keyframe_sampler.h"
#include "processing/stills/still_on_plan.h"
#include "processing/stills/stills_along_pairs.h"
#include "processing/stills/stills_tracking.h"
#include "processing/visibility/visibility.h"
#include "widgets/anchor_commands.h"
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
    if (project.capture.empty()) throw Error("the project has no capture to track");
    std::shared_ptr<FrameSource> source = FrameSource::open_capture(project.capture);
    const int n = source->frame_count();
    if (n < 2) throw Error("the capture has fewer than two frames");
    const auto read = [&](int i) {
      progress.throw_if_cancelled();
      return source->read(i);
    };
    // Stills or video: as the author imported it, else judged by how well KLT follows neighbours.
    progress.checkpoint(0.0, "looking at the frames");
    const bool plain_folder = source->kind() == CaptureKind::kImageFolder && source->head_count() == 0;
    const StillsChoice choice = choose_stills(n, read, project.capture.stills, plain_folder);
    unsigned changed = widgets::kPathChanged | widgets::kVisibilityChanged;
    std::string mode;
    if (choice.stills && !project.capture.stills) {  // found out now: the stills' order and GPS too
      project.capture = stills_folder(*source, project.capture).capture;
      source = FrameSource::open_capture(project.capture);
      changed |= widgets::kCaptureChanged;
      mode = "solved as still panoramas (" + choice.reason + ")";
    }
    // With a plan, placing the path takes the last tenth of the progress.
    const bool place = !project.plan.empty();
    SubProgress tracking_progress(progress, 0.0, place ? 0.9 : 1.0);
    EgomotionResult result;
    int unconnected = 0;
    std::vector<StillsPair> pairs;  // stills: every verified pair, to place stills along them on the plan
    if (choice.stills) {
      StillsOptions options;
      if (project.capture.camera_height_m > 0) options.camera_height_m = project.capture.camera_height_m;
      options.check();
      const StillsResult stills = solve_stills(n, read, options, tracking_progress);
      unconnected = static_cast<int>(stills.unconnected.size());
      pairs = stills.pairs;
      result = tracker_result_from_stills(stills);
      if (mode.empty()) mode = "solved as still panoramas";
      mode += ": " + std::to_string(n - unconnected) + " of " + std::to_string(n) + " connected";
      if (unconnected > 0)
        mode += "; place each of the others with Process > Place still on plan (Ctrl+Shift+O) and a click";
    } else {
      EgomotionOptions options;
      options.camera_height_m = project.capture.camera_height_m;
      options.check();
      // run() gives reading and tracking the frames the first half of the progress.
      result = EgomotionTracker::run(n, read, options, tracking_progress);
    }
    // The tracker numbers frames 0..n-1 in source order; the project uses capture indices.
    std::vector<int> positions(result.path.size());
    for (int i = 0; i < static_cast<int>(positions.size()); ++i)
      positions[i] = project.capture.kind == CaptureKind::kVideo
                         ? project.capture.first_frame + i * std::max(1, project.capture.stride)
                         : i;
    for (PathFrame& f : result.path.frames)
      if (project.capture.kind == CaptureKind::kImageFolder &&
          f.index < static_cast<int>(project.capture.frame_names.size()))
        f.file = project.capture.frame_names[f.index];
    renumber_frames(&result.path, positions);
    renumber_point_frames(&result.tracked_points, positions);
    result.path.scale_source = result.scale_source;
    project.path = std::move(result.path);
    project.path_points = std::move(result.tracked_points);
    project.visibility = {};  // cells belong to the old path
    if (choice.stills) {      // every still is a keyframe
      project.keyframes = every_frame_a_keyframe(project.path);
      changed |= widgets::kKeyframesChanged;
    }
    if (!project.plan.empty()) {
      std::string summary;
      PlacementChoices choices;
      if (const std::string why = placement_precondition(project); !why.empty()) {
        summary = "tracked; not placed on the plan: " + why;
      } else {
        SubProgress placing(progress, 0.9, 1.0, "placing the path on the plan");
        try {
          choices = place_project_on_plan(project, placing, false, &summary);
          if (choice.stills) {  // the stills with a pair but no length: along it, the plan saying how far
            PairPlacementOptions pair_options;
            pair_options.fit.camera_height_m = project.capture.camera_height_m;
            PairPlacementReport along;
            SubProgress along_progress(progress, 0.97, 1.0, "stills along their pairs");
            project.path = place_stills_along_pairs(project.path, pairs, read, project.plan, pair_options,
                                                    &along, along_progress);
            if (!along.placed.empty())
              summary += "; " + std::to_string(along.placed.size()) + " still(s) placed along their pairs";
          }
        } catch (const Cancelled&) {
          throw;
        } catch (const Error& e) {  // the tracked path is still worth having, unplaced
          summary = std::string("tracked; not placed on the plan: ") + e.what();
        }
      }
      if (!mode.empty()) summary = mode + "; " + summary;
      progress.report(1.0, summary);
      if (placement) *placement = {std::move(choices), summary};
    } else if (!mode.empty()) {
      progress.report(1.0, mode);
    }
    return TaskResult{std::move(project), changed};
  };
}

widgets::TaskFunction place_path_on_plan_task(std::shared_ptr<PlacementOutcome> placement) {
  return [placement](Project project, Progress& progress) {
    std::string summary;
    progress.checkpoint(0.0, "placing " + std::to_string(project.path.size()) + " frames on the plan");
    PlacementChoices choices = place_project_on_plan(project, progress, true, &summary);
    progress.report(1.0, summary);
    if (placement) *placement = {std::move(choices), summary};
    return TaskResult{std::move(project), widgets::kPathChanged | widgets::kVisibilityChanged};
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

widgets::TaskFunction compute_visibility_task() {
  return [](Project project, Progress& progress) {
    if (project.plan.occluder_segments().empty())
      throw Error("the plan has no occluder layer: mark the walls' layer as blocking sight first");
    if (project.path.size() < 2) throw Error("the project has no camera path yet");
    progress.checkpoint(0.1, "building the visibility index");
    const VisibilityIndex index(project.plan);
    progress.checkpoint(0.3, "events and cells along " + std::to_string(project.path.size()) + " frames");
    // Cancel reaches inside: the visibility workers stop at their next report.
    SubProgress cells_progress(progress, 0.3, 1.0);
    project.visibility = index.cells_along_path(project.path, cells_progress);
    progress.report(1.0);
    return TaskResult{std::move(project), widgets::kVisibilityChanged};
  };
}

widgets::TaskFunction refine_with_anchors_task() {
  return [](Project project, Progress& progress) {
    if (project.path.empty()) throw Error("the project has no camera path to refine");
    const std::vector<GpsPrior> gps = gps_priors_for_path(project);
    if (project.anchors.empty() && gps.size() < 2)
      throw Error("no anchors: Ctrl + drag a frame on the map to where it really was first");
    AnchorRefinementOptions options;
    AnchorRefinementReport report;
    progress.checkpoint(0.02, "refining " + std::to_string(project.path.size()) + " frames with " +
                                  std::to_string(project.anchors.size()) + " anchors");
    SubProgress solver_progress(progress, 0.02, 0.99, "refinement");
    project.path =
        refine_path_with_anchors(project.path, project.anchors, options, &report, solver_progress, gps);
    project.path.scale_source = project.anchors.empty() ? "gps" : "anchors";
    double worst = 0.0;
    for (const AnchorResidual& r : report.residuals) worst = std::max(worst, r.distance_m);
    char done[160];
    std::snprintf(done, sizeof done, "refined in %d iterations; largest anchor residual %.3f m",
                  report.iterations, worst);
    progress.report(1.0, done);
    unsigned changed = widgets::kPathChanged;
    if (std::optional<VisibilityCells> cells = widgets::cells_following_path(project, project.path)) {
      project.visibility = std::move(*cells);
      changed |= widgets::kVisibilityChanged;
    }
    return TaskResult{std::move(project), changed};
  };
}

}  // namespace plenopath::studio
