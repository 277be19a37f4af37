// Every pipeline step (processing/pipeline) reports through its Progress and, cancelled at its first report,
// ends with Cancelled and changes nothing: the caller's project is as it was (issue 17). A cancel later in
// the work ends the same way. No timing is asserted.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "model/error.h"
#include "processing/capture/frame_source.h"
#include "processing/pipeline/export_step.h"
#include "processing/pipeline/place_step.h"
#include "processing/pipeline/refine_step.h"
#include "processing/pipeline/sample_step.h"
#include "processing/pipeline/track_step.h"
#include "processing/pipeline/visibility_step.h"

namespace plenopath::pipeline {
namespace {

namespace fs = std::filesystem;

// Two rooms, 10 m x 6 m each, joined by a door in the middle wall: walls that block sight.
FloorPlan two_rooms() {
  FloorPlan plan;
  plan.layers = {{"WALLS", 7, true, true, 0}};
  const auto wall = [&](double x0, double y0, double x1, double y1) {
    plan.segments.push_back({{x0, y0}, {x1, y1}, "WALLS", true});
  };
  wall(0, 0, 20, 0);
  wall(20, 0, 20, 6);
  wall(20, 6, 0, 6);
  wall(0, 6, 0, 0);
  wall(10, 0, 10, 2.5);
  wall(10, 3.5, 10, 6);
  return plan;
}

// A walk along the two rooms through the door, one frame every 0.25 m.
CameraPath walk(int frames) {
  CameraPath path;
  for (int i = 0; i < frames; ++i) {
    PathFrame f;
    f.index = i;
    f.x = 1.0 + 18.0 * i / (frames - 1);
    f.y = 3.0;
    path.frames.push_back(f);
  }
  path.scale_source = "ground_truth";
  return path;
}

// A project every step can start on: plan, path, anchors, keyframes, a capture of `frames` noise images.
Project sample_project(const fs::path& dir, int frames) {
  Project p;
  p.plan = two_rooms();
  p.path = walk(frames);
  fs::create_directories(dir);
  cv::RNG rng(17);
  for (int i = 0; i < frames; ++i) {
    cv::Mat image(64, 128, CV_8UC3);
    rng.fill(image, cv::RNG::UNIFORM, 0, 255);
    char name[32];
    std::snprintf(name, sizeof name, "f%03d.png", i);
    cv::imwrite((dir / name).string(), image);
  }
  FrameSourceOptions options;
  options.require_2to1 = true;
  const auto source = FrameSource::open(dir.string(), options);
  p.capture = capture_from_frame_source(*source);
  p.capture.camera_height_m = 1.6;
  for (PathFrame& f : p.path.frames) f.file = p.capture.frame_names[static_cast<std::size_t>(f.index)];
  p.anchors = {{0, {1.2, 3.1}, std::nullopt}, {frames - 1, {18.8, 2.9}, std::nullopt}};
  for (int i = 0; i < frames; ++i) p.path_points.push_back({{1.0 + 0.5 * i, 3.0, 0.5}, 0, 3, i});
  p.keyframes.indices = {0, frames / 2, frames - 1};
  p.keyframes.rank = {0, 1, 2};
  return p;
}

class PipelineCancel : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("plenopath_pipeline_cancel_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    project_ = sample_project(dir_ / "frames", 12);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `step` on a copy of the project with a Progress that cancels at report number `at` (1 = the
  // first); expects Cancelled, and the project as it was.
  void expect_cancelled_at(int at, const std::function<void(Project, Progress&)>& step) {
    const Project before = project_;
    int reports = 0;
    FunctionProgress* self = nullptr;
    FunctionProgress progress([&](double fraction, const std::string&) {
      EXPECT_GE(fraction, 0.0);
      EXPECT_LE(fraction, 1.0);
      if (++reports == at) self->cancel();
    });
    self = &progress;
    EXPECT_THROW(step(project_, progress), Cancelled);
    // At the first report the step stops there; later, workers already running may report once more.
    if (at == 1) {
      EXPECT_EQ(reports, 1) << "the step went on reporting after it was cancelled";
    }
    EXPECT_GE(reports, at);
    EXPECT_TRUE(project_ == before) << "a cancelled step changed its caller's project";
  }

  // Reports of a run that is not cancelled.
  template <typename Result>
  int reports_of(const std::function<Result(Project, Progress&)>& step, Result* result) {
    int reports = 0;
    double last = -1;
    FunctionProgress progress([&](double fraction, const std::string&) {
      ++reports;
      last = fraction;
    });
    *result = step(project_, progress);
    EXPECT_DOUBLE_EQ(last, 1.0) << "the last report is not the end";
    return reports;
  }

  fs::path dir_;
  Project project_;
};

TEST_F(PipelineCancel, Track) {
  expect_cancelled_at(1, [](Project p, Progress& progress) { run_track(std::move(p), {}, progress); });
}

TEST_F(PipelineCancel, PlaceOnPlan) {
  expect_cancelled_at(1,
                      [](Project p, Progress& progress) { run_place_on_plan(std::move(p), {}, progress); });
}

TEST_F(PipelineCancel, Visibility) {
  expect_cancelled_at(1, [](Project p, Progress& progress) { run_visibility(std::move(p), {}, progress); });
  // Later, inside the cells' computation, it ends the same way.
  expect_cancelled_at(3, [](Project p, Progress& progress) { run_visibility(std::move(p), {}, progress); });
  StepResult done;
  EXPECT_GT(
      reports_of<StepResult>(
          [](Project p, Progress& progress) { return run_visibility(std::move(p), {}, progress); }, &done),
      2);
  EXPECT_FALSE(done.project.visibility.empty());
  EXPECT_EQ(done.changed, unsigned(kVisibilityChanged));
}

TEST_F(PipelineCancel, Sample) {
  SampleStepOptions options;
  options.request.parameters.method = SamplingMethod::kUniform;
  options.request.parameters.ratio = 4.0;
  expect_cancelled_at(1, [&](Project p, Progress& progress) { run_sample(std::move(p), options, progress); });
  expect_cancelled_at(2, [&](Project p, Progress& progress) { run_sample(std::move(p), options, progress); });
  SampleStepResult done;
  reports_of<SampleStepResult>(
      [&](Project p, Progress& progress) { return run_sample(std::move(p), options, progress); }, &done);
  EXPECT_EQ(done.project.keyframes, done.outcome.keyframes);
  EXPECT_EQ(done.changed, unsigned(kKeyframesChanged));
}

TEST_F(PipelineCancel, Refine) {
  expect_cancelled_at(1, [](Project p, Progress& progress) { run_refine(std::move(p), {}, progress); });
  expect_cancelled_at(2, [](Project p, Progress& progress) { run_refine(std::move(p), {}, progress); });
}

TEST_F(PipelineCancel, Export) {
  ExportStepOptions options;
  options.tour = TourExportOptions::from_project(project_, (dir_ / "tour").string());
  expect_cancelled_at(1, [&](Project p, Progress& progress) { run_export(std::move(p), options, progress); });
  EXPECT_FALSE(fs::exists(dir_ / "tour")) << "a cancelled export left its output";
}

// check() names the field it refuses (model/option_check.h).
TEST(PipelineOptions, CheckNamesTheField) {
  const auto message = [](const std::function<void()>& check) {
    try {
      check();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  PlaceStepOptions place;
  place.camera_height_m = -1;
  EXPECT_NE(message([&] { place.check(); }).find("PlaceStepOptions.camera_height_m"), std::string::npos);
  SampleStepOptions sample;
  sample.photometric_frames = -2;
  EXPECT_NE(message([&] { sample.check(); }).find("SampleStepOptions.photometric_frames"), std::string::npos);
  ExportStepOptions exported;
  EXPECT_NE(message([&] { exported.check(); }).find("ExportStepOptions.tour.output"), std::string::npos);
  TrackStepOptions track;
  track.egomotion.keyframe_parallax_deg = -1;
  EXPECT_NE(message([&] { track.check(); }).find("keyframe_parallax_deg"), std::string::npos);
}

}  // namespace
}  // namespace plenopath::pipeline
