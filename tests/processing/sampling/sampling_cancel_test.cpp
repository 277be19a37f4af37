// Cancel of every long sampling step: cancelled at its first report, each ends with Cancelled and hands
// back nothing; a SamplingSession cancelled half-way gives the next run the same result as a fresh session.
#include <gtest/gtest.h>

#include <atomic>

#include "model/error.h"
#include "processing/sampling/depth_sampler.h"
#include "processing/sampling/envelope_raster.h"
#include "processing/sampling/keyframe_sampler.h"
#include "processing/sampling/loss_refinement.h"
#include "processing/sampling/sampling_loss.h"
#include "processing/sampling/sampling_session.h"
#include "processing/util/progress.h"
#include "sampling_test_util.h"

namespace plenopath {
namespace {

// Counts the reports and cancels at the first one.
struct CancelAtFirstReport {
  std::atomic<int> reports{0};
  FunctionProgress progress{[this](double, const std::string&) {
    ++reports;
    progress.cancel();
  }};
};

struct Scene {
  FloorPlan plan = sampling_test::three_rooms();
  CameraPath path = sampling_test::three_rooms_path();
  VisibilityIndex index{plan};
};
Scene& scene() {
  static Scene s;
  return s;
}

TEST(SamplingCancel, EnvelopesAlongThePath) {
  CancelAtFirstReport c;
  EXPECT_THROW(compute_path_envelopes(scene().index, scene().path, 1, c.progress), Cancelled);
  EXPECT_EQ(c.reports.load(), 1);
}

TEST(SamplingCancel, DepthVolumesStopReading) {
  CancelAtFirstReport c;
  int reads = 0;
  PathEnvelopes envelopes;
  EXPECT_THROW(depth_volumes_along_path(
                   scene().path,
                   [&](int) {
                     ++reads;
                     return cv::Mat(32, 64, CV_32F, cv::Scalar(2.0f));
                   },
                   {}, c.progress, &envelopes),
               Cancelled);
  EXPECT_EQ(c.reports.load(), 1);
  EXPECT_EQ(reads, 1) << "the first report follows frame 0; no frame after it is read";
}

TEST(SamplingCancel, LossRefinement) {
  const PathEnvelopes envelopes = compute_path_envelopes(scene().index, scene().path);
  const EnvelopeRaster raster(envelopes);
  SamplingInputs inputs;
  inputs.path = &scene().path;
  SamplingParameters uniform;
  uniform.method = SamplingMethod::kUniform;
  uniform.count = 20;
  const Keyframes start = sample_keyframes(inputs, uniform);
  CancelAtFirstReport c;
  EXPECT_THROW(refine_keyframes_by_loss(scene().path, start, {}, raster, {}, c.progress), Cancelled);
  EXPECT_EQ(c.reports.load(), 1);
}

TEST(SamplingCancel, VisibilitySampling) {
  SamplingInputs inputs;
  inputs.path = &scene().path;
  inputs.index = &scene().index;
  CancelAtFirstReport c;
  inputs.progress = &c.progress;
  SamplingParameters parameters;
  parameters.count = 20;
  EXPECT_THROW(sample_keyframes(inputs, parameters), Cancelled);
  EXPECT_EQ(c.reports.load(), 1);
}

TEST(SamplingCancel, SessionCancelledHalfWayThenRunAgain) {
  Project project;
  project.plan = scene().plan;
  project.path = scene().path;
  project.visibility = scene().index.cells_along_path(project.path);
  SamplingRequest request;
  request.parameters.count = 20;

  SamplingSession session;
  CancelAtFirstReport c;
  EXPECT_THROW(session.run(project, request, c.progress), Cancelled);
  EXPECT_EQ(c.reports.load(), 1);
  // Cancelled later, inside the envelopes (the index is built and cached by then).
  int reports = 0;
  FunctionProgress later([&](double f, const std::string&) {
    if (++reports > 1 && f > 0.1) later.cancel();
  });
  EXPECT_THROW(session.run(project, request, later), Cancelled);

  const SamplingOutcome again = session.run(project, request);
  SamplingSession fresh;
  const SamplingOutcome truth = fresh.run(project, request);
  EXPECT_EQ(again.keyframes, truth.keyframes);
  EXPECT_DOUBLE_EQ(again.loss.geometric.mean, truth.loss.geometric.mean);
}

}  // namespace
}  // namespace plenopath
