#include "app/studio/studio_tasks.h"

#include "model/error.h"
#include "processing/frame_source.h"
#include "processing/visibility.h"
#include "widgets/project_document.h"

namespace plenopath::studio {

using widgets::TaskProgress;
using widgets::TaskResult;

widgets::TaskFunction import_capture_task(const widgets::CaptureImportChoices& choices) {
  return [choices](Project project, TaskProgress& progress) {
    progress.report(0.05, "scanning " + choices.source);
    choices.options.check();
    const std::unique_ptr<FrameSource> source = FrameSource::open(choices.source, choices.options);
    progress.throw_if_cancelled();
    project.capture = capture_from_frame_source(*source, project.capture);
    if (choices.camera_height_m > 0) project.capture.camera_height_m = choices.camera_height_m;
    progress.report(1.0, std::to_string(source->frame_count()) + " frames");
    return TaskResult{std::move(project), widgets::kCaptureChanged};
  };
}

widgets::TaskFunction compute_visibility_task() {
  return [](Project project, TaskProgress& progress) {
    if (project.plan.occluder_segments().empty())
      throw Error("the plan has no occluder layer: mark the walls' layer as blocking sight first");
    if (project.path.size() < 2) throw Error("the project has no camera path yet");
    progress.report(0.1, "building the visibility index");
    const VisibilityIndex index(project.plan);
    progress.throw_if_cancelled();
    progress.report(0.3, "events and cells along " + std::to_string(project.path.size()) + " frames");
    project.visibility = index.cells_along_path(project.path);
    progress.report(1.0);
    return TaskResult{std::move(project), widgets::kVisibilityChanged};
  };
}

}  // namespace plenopath::studio
