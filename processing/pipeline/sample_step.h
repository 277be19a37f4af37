#pragma once
// Pipeline step: keyframes along the project's path (uniform, visibility or depth) and what they lose
// (processing/sampling). The studio's sampling panel and `plenopath sample` both run it; the panel keeps a
// SamplingSession between runs so that the visibility index, envelopes and depth volumes are built once.
#include "processing/pipeline/step_result.h"
#include "processing/sampling/sampling_session.h"
#include "processing/util/progress.h"

namespace plenopath::pipeline {

struct SampleStepOptions {
  // The method, its budget and rule, the pinned frames; sample = false only measures request.keyframes.
  SamplingRequest request;
  // Visibility sampling of a project without cells (a path file and a plan on the command line): compute
  // the cells along the path first instead of refusing (the studio asks the author to compute them).
  bool compute_missing_cells = false;
  // Dropped frames compared by PSNR/SSIM when the capture's frames can be read (0 = no photometric loss).
  int photometric_frames = 0;
  void check() const;  // throws Error naming the field
};

struct SampleStepResult : StepResult {
  SamplingOutcome outcome;  // the keyframes and their loss (photometric too when asked for)
};

// Still panoramas (Capture::stills): every still is a keyframe, nothing between them to leave out.
// Throws Error when the method's input is missing (visibility: cells and a plan with walls; depth: the
// capture's depth maps); Cancelled on a cancel. `session` (optional) keeps its caches between runs.
// changed: kKeyframesChanged when sampling (the project's keyframes are the outcome's), else 0.
SampleStepResult run_sample(Project project, const SampleStepOptions& options,
                            Progress& progress = null_progress(), SamplingSession* session = nullptr);

}  // namespace plenopath::pipeline
