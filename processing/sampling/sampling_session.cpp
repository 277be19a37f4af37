#include "processing/sampling/sampling_session.h"

#include "model/error.h"
#include "processing/capture/frame_source.h"
#include "processing/sampling/envelope_raster.h"
#include "processing/sampling/uniform_sampling.h"

namespace plenopath {

struct SamplingSession::Cache {
  // What each part was built from (compared by value: a few thousand frames compare in microseconds).
  std::vector<PlanSegment> walls;
  CameraPath envelope_path;
  std::unique_ptr<VisibilityIndex> index;
  std::unique_ptr<PathEnvelopes> envelopes;
  std::unique_ptr<EnvelopeRaster> raster;
  Capture depth_capture;
  CameraPath depth_path;
  std::vector<DepthVolume> volumes;
  PathEnvelopes depth_envelopes;
};

SamplingSession::SamplingSession() : cache_(std::make_unique<Cache>()) {}
SamplingSession::~SamplingSession() = default;

SamplingOutcome SamplingSession::run(const Project& project, const SamplingRequest& request,
                                     Progress& progress) {
  const CameraPath& path = project.path;
  if (path.empty()) throw Error("the project has no camera path yet");
  Cache& c = *cache_;
  const SamplingMethod method =
      request.sample ? request.parameters.method : request.keyframes.parameters.method;

  // The plan's visibility: index, every frame's envelope, their raster (visibility sampling, geometric loss).
  const std::vector<PlanSegment> walls = project.plan.occluder_segments();
  const bool want_envelopes =
      !walls.empty() && (request.geometric_loss || (request.sample && method == SamplingMethod::kVisibility));
  if (request.sample && method == SamplingMethod::kVisibility) {
    if (project.visibility.empty())
      throw Error("visibility sampling needs the visibility cells: run Process > Compute visibility first");
    if (walls.empty()) throw Error("visibility sampling needs a plan with walls (a layer that blocks sight)");
  }
  if (want_envelopes) {
    if (!c.index || c.walls != walls) {
      progress.checkpoint(0.0, "building the visibility index");
      c.index = std::make_unique<VisibilityIndex>(project.plan);
      c.walls = walls;
      c.envelopes.reset();
      c.raster.reset();
    }
    if (!c.envelopes || !(c.envelope_path == path)) {
      SubProgress envelopes_progress(progress, 0.05, 0.5,
                                     "envelopes of " + std::to_string(path.size()) + " frames");
      c.envelopes =
          std::make_unique<PathEnvelopes>(compute_path_envelopes(*c.index, path, 0, envelopes_progress));
      c.envelope_path = path;
      c.raster.reset();
    }
    if (!c.raster && request.sample && method == SamplingMethod::kVisibility)
      c.raster = std::make_unique<EnvelopeRaster>(*c.envelopes);
  }

  // Depth volumes along the path (depth sampling).
  if (request.sample && method == SamplingMethod::kDepth) {
    if (project.capture.empty() || project.capture.depth_folder.empty())
      throw Error("depth sampling needs depth maps: import the capture with its depth folder first");
    if (c.volumes.size() != path.size() || !(c.depth_capture == project.capture) || !(c.depth_path == path)) {
      const std::unique_ptr<FrameSource> source = FrameSource::open_capture(project.capture);
      SubProgress volumes_progress(progress, 0.0, 0.5,
                                   "depth volumes of " + std::to_string(path.size()) + " frames");
      // Into locals first: a cancel or an error half-way leaves the cache as it was.
      PathEnvelopes depth_envelopes;
      std::vector<DepthVolume> volumes = depth_volumes_along_path(
          path,
          [&](int index) {
            const int kept = project.capture.kept_of_frame_index(index);  // a capture index: the kept frame
            if (kept < 0 || kept >= source->frame_count() || !source->has_depth(kept))
              throw Error(project.capture.depth_folder + ": no depth map for frame " + std::to_string(index));
            return source->read_depth(kept);
          },
          {}, volumes_progress, &depth_envelopes);
      c.volumes = std::move(volumes);
      c.depth_envelopes = std::move(depth_envelopes);
      c.depth_capture = project.capture;
      c.depth_path = path;
    }
  }

  SamplingOutcome out;
  if (request.sample) {
    SamplingInputs inputs;
    inputs.path = &path;
    inputs.index = c.index.get();
    inputs.cells = &project.visibility;
    inputs.depth_volumes = &c.volumes;
    inputs.depth_envelopes = &c.depth_envelopes;
    inputs.envelopes = c.envelopes.get();
    inputs.raster = c.raster.get();
    SubProgress placing_progress(progress, 0.5, 0.9, "placing keyframes");
    inputs.progress = &placing_progress;
    out.keyframes = sample_keyframes(inputs, request.parameters, request.pinned);
  } else {
    out.keyframes = request.keyframes;
  }

  const SamplingStatistics stats = sampling_statistics(path, out.keyframes);
  out.loss.kept = stats.kept;
  out.loss.total = stats.total;
  out.loss.reduction_ratio = stats.ratio;
  out.loss.largest_gap_m = stats.max_gap_m;
  if (request.geometric_loss && c.envelopes && c.envelope_path == path) {
    progress.checkpoint(0.9, "geometric loss");
    out.loss.geometric = geometric_loss(path, out.keyframes, *c.envelopes);
    out.loss.has_geometric = true;
  }
  progress.report(1.0, "done");
  return out;
}

}  // namespace plenopath
