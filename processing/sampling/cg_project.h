#pragma once
// A rendered CG capture landing in a project (issue 23): the frames the render wrote become the project's
// capture, their true poses its path (numbered as the capture's frames), and what was computed from the
// old path (the tracker's points, visibility cells, keyframes) goes. With CgCaptureOptions::section_plan the
// scene cut at eye height becomes the project's plan. Online, the frames written are the sampler's
// keyframes and stay the project's keyframes, so the tour can be exported at once. The studio's Process >
// Render CG scene and `plenopath render-scene --project` both call it, so both make the same project.
#include <string>

#include "model/project.h"
#include "processing/sampling/cg_capture.h"

namespace plenopath {

// `out_dir` is the folder render_cg_capture wrote `rendered` into; depth maps are taken from it when the
// render made them. Throws Error when the folder's frames are not the ones rendered (it held others before).
void land_cg_capture(Project& project, const CgCaptureResult& rendered, const CgCaptureOptions& options,
                     const std::string& out_dir);

}  // namespace plenopath
