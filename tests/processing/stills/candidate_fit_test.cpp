// What the stills see picks the right placement among registration's candidates: three stills rendered by
// the studio's renderer at known poses in the office sample, given in a frame of their own (turned and
// shifted); registration's candidates are the true similarity and two wrong ones (the group shifted 3 m,
// and turned half round), the wrong ones listed first. The re-ranking must put the true one first.
#include "processing/stills/candidate_fit.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "model/error.h"
#include "tests/processing/stills/rendered_stills.h"

namespace plenopath {
namespace {

TEST(CandidateFit, TheStillsPickTheTruePlacementOverRepeatedOnes) {
  const FloorPlan plan = make_office_sample_plan();
  const std::vector<Eigen::Vector3d> truth = {{2.6, 9.4, 0.3}, {4.6, 9.6, 2.0}, {3.0, 12.0, -1.2}};
  const std::vector<cv::Mat> stills = test::render_stills_at(plan, truth);
  // The group's own frame: plan = true_transform.apply(own).
  Similarity2 true_transform;
  true_transform.rotation = 0.7;
  true_transform.translation = {3.0, 10.0};
  CameraPath path;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    PathFrame f = test::frame_at(static_cast<int>(i), truth[i]);
    const Eigen::Rotation2Dd back(-true_transform.rotation);
    const Eigen::Vector2d own = back * (f.position() - true_transform.translation);
    f.x = own.x();
    f.y = own.y();
    f.heading = truth[i].z() - true_transform.rotation;
    path.frames.push_back(f);
  }
  Similarity2 shifted = true_transform;
  shifted.translation += Eigen::Vector2d(3.0, 0.0);
  Similarity2 turned = true_transform;
  turned.rotation += M_PI;
  RegistrationResult result;
  PieceRegistration piece;
  piece.ok = true;
  for (const Similarity2& t : {shifted, turned, true_transform}) {
    RegistrationCandidate c;
    c.transform = t;
    piece.candidates.push_back(c);
  }
  result.pieces.push_back(piece);

  const CandidateFitReport report = rerank_by_still_fit(
      &result, path, [&](int i) { return stills[static_cast<std::size_t>(i)]; }, plan);
  ASSERT_EQ(report.pieces_scored, 1);
  EXPECT_EQ(report.pieces_reordered, 1);
  const Similarity2& first = result.pieces[0].candidates[0].transform;
  EXPECT_NEAR(first.rotation, true_transform.rotation, 1e-12);
  EXPECT_NEAR((first.translation - true_transform.translation).norm(), 0.0, 1e-12);
  ASSERT_EQ(report.fits_px[0].size(), 3u);
  std::printf("fits: %.2f (true) %.2f %.2f px\n", report.fits_px[0][0], report.fits_px[0][1],
              report.fits_px[0][2]);
  EXPECT_LT(1.5 * report.fits_px[0][0], report.fits_px[0][1]);
  EXPECT_NE(result.pieces[0].message.find("chosen by what the stills see"), std::string::npos);

  // Already first: left alone.
  const CandidateFitReport again = rerank_by_still_fit(
      &result, path, [&](int i) { return stills[static_cast<std::size_t>(i)]; }, plan);
  EXPECT_EQ(again.pieces_reordered, 0);

  // Where no candidate fits well enough, the piece is not placed, and says why.
  CandidateFitOptions strict;
  strict.max_fit_px = 0.5 * report.fits_px[0][0];
  const CandidateFitReport refused = rerank_by_still_fit(
      &result, path, [&](int i) { return stills[static_cast<std::size_t>(i)]; }, plan, strict);
  EXPECT_EQ(refused.pieces_refused, 1);
  EXPECT_FALSE(result.pieces[0].ok);
  EXPECT_NE(result.pieces[0].message.find("what its stills see does not"), std::string::npos);
}

TEST(CandidateFit, BadOptionsAreRefused) {
  CandidateFitOptions options;
  options.max_candidates = 0;
  EXPECT_THROW(options.check(), Error);
}

}  // namespace
}  // namespace plenopath
