#pragma once
// The studio's background tasks: each wraps a processing step as a TaskFunction (snapshot in, changed
// project out) so it runs on a worker with progress and cancel, and lands as one undo step.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>

#include "app/studio/placement.h"
#include "processing/visibility/shared_visibility_index.h"
#include "widgets/capture_import_dialog.h"
#include "widgets/cg_scene_dialog.h"
#include "widgets/task_runner.h"

namespace plenopath::studio {

// Scans the folder or video and sets the project's capture (keeps GPS data already there).
widgets::TaskFunction import_capture_task(const widgets::CaptureImportChoices& choices);
// Process > Render CG scene: the author's POV-Ray scene rendered along the project's path or the typed
// waypoints (processing/sampling/cg_capture.h), every frame or online; the frames written become the
// project's capture and their true poses its path (scale from the ground truth).
widgets::TaskFunction render_cg_scene_task(const widgets::CgSceneChoices& choices);
// The camera path from the capture's frames alone (processing/egomotion): progress and cancel reach Ceres
// through the tracker's callback. Scale from the capture's camera height when known. The tracker's points
// are kept with the path (Project::path_points); when the project has a plan the path is then placed on it
// by itself (placement.h), and `placement` (optional) gets what registration found.
widgets::TaskFunction track_path_task(std::shared_ptr<PlacementOutcome> placement = nullptr);
// Process > Place path on plan: the path placed on the plan by its tracked points (placement.h); fails with
// the reason when no piece fits. `placement` gets the candidates.
widgets::TaskFunction place_path_on_plan_task(std::shared_ptr<PlacementOutcome> placement,
                                              std::shared_ptr<const SharedVisibilityIndex> index = nullptr);
// Process > Place still on plan: the still at capture index `frame` placed from the author's click (plan
// metres), with the heading near `heading_hint_deg` when given; its piece moves with it, the visibility
// cells go. `summary` receives the placement's sentence.
widgets::TaskFunction place_still_task(int frame, Eigen::Vector2d click,
                                       std::optional<double> heading_hint_deg,
                                       std::shared_ptr<std::string> summary);
// `index` (the tasks that compute visibility): the document's shared index of the plan
// (ProjectDocument::visibility_index()), or null to build one on the worker.
// Visibility events, cells and critical lines along the path (processing/visibility/visibility.h).
widgets::TaskFunction compute_visibility_task(std::shared_ptr<const SharedVisibilityIndex> index = nullptr);
// The path refined with the anchors as priors (Ceres pose graph with a drift model, plus the capture's GPS
// fixes as weak priors when there are any; processing/anchors/anchor_refinement.h). Progress per solver
// iteration; cancel stops the solver and changes nothing.
widgets::TaskFunction refine_with_anchors_task(std::shared_ptr<const SharedVisibilityIndex> index = nullptr);
// File > Export tour: the packaged walkthrough at `output` (a folder, or a .zip) with the project's tour
// settings (processing/pipeline/export_step.h). Changes nothing in the document.
widgets::TaskFunction export_tour_task(const std::string& output);

}  // namespace plenopath::studio
