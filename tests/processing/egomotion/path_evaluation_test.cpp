// Path scoring: hand-built paths with known similarity, noise, and a mirrored path that must score badly.
#include "processing/egomotion/path_evaluation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "model/error.h"

namespace plenopath {
namespace {

CameraPath l_shaped_path() {
  CameraPath p;
  for (int i = 0; i < 40; ++i) {
    PathFrame f;
    f.index = i;
    if (i < 20) {
      f.x = 0.2 * i;
      f.y = 0.0;
      f.heading = 0.0;
    } else {
      f.x = 3.8;
      f.y = 0.2 * (i - 19);
      f.heading = M_PI / 2;
    }
    p.frames.push_back(f);
  }
  return p;
}

TEST(PathEvaluation, SimilarityTransformedPathScoresPerfect) {
  const CameraPath truth = l_shaped_path();
  CameraPath est = truth;
  const double rot = 0.7, scale = 2.5;
  for (PathFrame& f : est.frames) {
    const double x = f.x, y = f.y;
    f.x = scale * (std::cos(rot) * x - std::sin(rot) * y) + 10;
    f.y = scale * (std::sin(rot) * x + std::cos(rot) * y) - 4;
    f.heading = wrap_angle(f.heading + rot);
  }
  const PathErrors e = evaluate_path(est, truth);
  EXPECT_EQ(e.frames_matched, 40);
  EXPECT_NEAR(e.ate_rms_m, 0.0, 1e-9);
  EXPECT_NEAR(e.rot_rms_deg, 0.0, 1e-9);
  EXPECT_NEAR(e.scale, 1.0 / scale, 1e-9);
  EXPECT_NEAR(e.truth_length_m, 0.2 * 19 + 0.2 * 20, 1e-9);
}

TEST(PathEvaluation, KnownOffsetGivesKnownAte) {
  const CameraPath truth = l_shaped_path();
  CameraPath est = truth;
  // Alternate +-d perpendicular... use a pattern whose mean and rotation are zero: +d, -d along z-order
  // pairs.
  for (size_t i = 0; i < est.frames.size(); ++i) est.frames[i].heading += (i % 2 ? 0.01 : -0.01);
  const PathErrors e = evaluate_path(est, truth);
  EXPECT_NEAR(e.rot_rms_deg, 0.01 * 180 / M_PI, 1e-6);
}

TEST(PathEvaluation, MirroredPathScoresWrong) {
  const CameraPath truth = l_shaped_path();
  CameraPath est = truth;
  for (PathFrame& f : est.frames) {
    f.y = -f.y;
    f.heading = -f.heading;
  }
  const PathErrors e = evaluate_path(est, truth);
  EXPECT_GT(e.ate_pct, 5.0);
  EXPECT_GT(e.rot_rms_deg, 20.0);
}

TEST(PathEvaluation, TooFewMatchesIsAnError) {
  CameraPath truth = l_shaped_path();
  CameraPath est;
  est.frames.push_back(truth.frames[0]);
  EXPECT_THROW(evaluate_path(est, truth), Error);
}

}  // namespace
}  // namespace plenopath
