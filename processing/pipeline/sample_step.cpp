#include "processing/pipeline/sample_step.h"

#include <cstdio>
#include <memory>

#include "model/error.h"
#include "model/option_check.h"
#include "processing/capture/frame_source.h"
#include "processing/sampling/keyframe_sampler.h"
#include "processing/sampling/sampling_loss.h"
#include "processing/sampling/uniform_sampling.h"
#include "processing/visibility/visibility.h"

namespace plenopath::pipeline {

void SampleStepOptions::check() const {
  require_option(photometric_frames >= 0, "SampleStepOptions.photometric_frames", "must be >= 0",
                 photometric_frames);
}

SampleStepResult run_sample(Project project, const SampleStepOptions& options, Progress& progress,
                            SamplingSession* session) {
  options.check();
  const SamplingRequest& request = options.request;
  progress.checkpoint(0.0, request.sample ? "sampling keyframes" : "measuring the keyframes' loss");
  if (project.path.empty()) throw Error("the project has no camera path yet");
  SampleStepResult out;
  const double photometric_share = options.photometric_frames > 0 ? 0.2 : 0.0;
  const bool stills = request.sample && project.capture.stills;
  SamplingSession own;
  SamplingSession& used = session ? *session : own;
  if (stills) {  // the loss of every frame kept: measured, not sampled
    SamplingRequest every = request;
    every.sample = false;
    every.keyframes = every_frame_a_keyframe(project.path);
    SubProgress measuring(progress, 0.0, 1.0 - photometric_share);
    out.outcome = used.run(project, every, measuring);
  } else {
    double begin = 0.0;
    if (request.sample && request.parameters.method == SamplingMethod::kVisibility &&
        project.visibility.empty() && options.compute_missing_cells &&
        !project.plan.occluder_segments().empty()) {
      SubProgress cells_progress(progress, 0.0, 0.3, "visibility cells");
      project.visibility = VisibilityIndex(project.plan).cells_along_path(project.path, cells_progress);
      begin = 0.3;
    }
    SubProgress sampling(progress, begin, 1.0 - photometric_share);
    out.outcome = used.run(project, request, sampling);
  }
  if (options.photometric_frames > 0 && !project.capture.empty()) {
    progress.checkpoint(1.0 - photometric_share, "photometric loss");
    const std::unique_ptr<FrameSource> source = FrameSource::open_capture(project.capture);
    PhotometricOptions photometric;
    photometric.max_frames = options.photometric_frames;
    out.outcome.loss.photometric = photometric_loss(
        project.path, out.outcome.keyframes,
        [&](int index) {
          const int kept = project.capture.kept_of_frame_index(index);
          if (kept < 0 || kept >= source->frame_count())
            throw Error(source->source() + ": the path's frame " + std::to_string(index) +
                        " is not in the capture (" + std::to_string(source->frame_count()) + " frames)");
          progress.throw_if_cancelled();
          return source->read(kept);
        },
        photometric);
    out.outcome.loss.has_photometric = true;
  }
  char line[160];
  std::snprintf(line, sizeof line, "%d of %d frames kept (%.1f : 1), largest gap %.2f m",
                out.outcome.loss.kept, out.outcome.loss.total, out.outcome.loss.reduction_ratio,
                out.outcome.loss.largest_gap_m);
  out.summary = stills ? std::string("still panoramas: every still is a keyframe; ") + line : line;
  if (request.sample) {
    project.keyframes = out.outcome.keyframes;
    out.changed = kKeyframesChanged;
  }
  progress.report(1.0, out.summary);
  out.project = std::move(project);
  return out;
}

}  // namespace plenopath::pipeline
