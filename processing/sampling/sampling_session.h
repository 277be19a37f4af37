#pragma once
// Resampling one project again and again (the studio's sampling panel): keeps what the samplers and the
// loss measures need between runs - the visibility index, every frame's envelope and their raster, the
// depth volumes - and rebuilds a part only when the plan, path or capture it came from changed.
// Qt-free; the studio runs it on a worker thread, one run at a time (a session is not thread-safe).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "model/project.h"
#include "processing/sampling/keyframe_sampler.h"
#include "processing/sampling/sampling_loss.h"

namespace plenopath {

struct SamplingRequest {
  SamplingParameters parameters;  // the method and, for visibility, the rule
  std::vector<int> pinned;
  bool sample = true;          // false: only measure the loss of `keyframes`
  Keyframes keyframes;         // measured when sample is false
  bool geometric_loss = true;  // measure it (needs a plan with walls)
};

struct SamplingOutcome {
  Keyframes keyframes;
  SamplingLoss loss;
};

class SamplingSession {
 public:
  SamplingSession();
  ~SamplingSession();
  SamplingSession(const SamplingSession&) = delete;
  SamplingSession& operator=(const SamplingSession&) = delete;

  // Throws plenopath::Error when the method's input is missing (visibility: the project's visibility cells
  // and a plan with walls; depth: the capture's depth maps) or the budget cannot be met. `progress` gets
  // the fraction done and what is being done; a cancel ends the run with Cancelled and leaves the session's
  // caches consistent (a part cancelled half-way is rebuilt by the next run).
  SamplingOutcome run(const Project& project, const SamplingRequest& request,
                      Progress& progress = null_progress());

 private:
  struct Cache;
  std::unique_ptr<Cache> cache_;
};

}  // namespace plenopath
