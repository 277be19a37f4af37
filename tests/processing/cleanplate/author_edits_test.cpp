// The author's clean-plate edits against hand-made plates: painted back is the original, painted away is
// the consensus where some frame saw the scene and the nadir patch's region elsewhere.
#include "processing/cleanplate/author_edits.h"

#include <gtest/gtest.h>

#include "model/error.h"
#include "model/tour_settings.h"

namespace plenopath {
namespace {

TEST(CleanPlateEdits, AwayTakesTheConsensusBackTakesTheOriginal) {
  const cv::Size size(40, 20);
  CleanPlate plate;
  plate.image = cv::Mat(size, CV_8UC3, cv::Scalar::all(100));
  plate.consensus = cv::Mat(size, CV_8UC3, cv::Scalar::all(200));
  plate.support = cv::Mat::zeros(size, CV_8U);
  plate.support.colRange(0, 20).setTo(3);  // the left half was seen by three frames
  plate.rig_filled = cv::Mat::zeros(size, CV_8U);
  plate.rig_unfilled = cv::Mat::zeros(size, CV_8U);
  plate.rig_unfilled.rowRange(16, 20).setTo(255);  // the nadir rows: nothing saw behind the rig
  const cv::Mat original(size, CV_8UC3, cv::Scalar::all(50));
  cv::Mat edits = cv::Mat::zeros(size, CV_8U);
  edits(cv::Rect(0, 0, 5, 5)).setTo(kCleanPlateKeep);     // back, top left
  edits(cv::Rect(10, 5, 5, 5)).setTo(kCleanPlateRemove);  // away where seen
  edits(cv::Rect(30, 5, 5, 5)).setTo(kCleanPlateRemove);  // away where nothing saw
  edits(cv::Rect(0, 16, 8, 4)).setTo(kCleanPlateKeep);    // the rig kept at the left of the nadir rows
  cv::Mat patch;
  const cv::Mat out = apply_clean_plate_edits(plate, original, edits, patch);
  EXPECT_EQ(out.at<cv::Vec3b>(2, 2)[0], 50);
  EXPECT_EQ(out.at<cv::Vec3b>(7, 12)[0], 200);
  EXPECT_EQ(out.at<cv::Vec3b>(7, 32)[0], 100);  // nothing to take: left for the patch
  EXPECT_EQ(patch.at<std::uint8_t>(7, 32), 255);
  EXPECT_EQ(out.at<cv::Vec3b>(12, 25)[0], 100);  // not painted: the plate as it was
  EXPECT_EQ(patch.at<std::uint8_t>(18, 3), 0);   // painted back: no patch
  EXPECT_EQ(out.at<cv::Vec3b>(18, 3)[0], 50);
  EXPECT_EQ(patch.at<std::uint8_t>(18, 20), 255);
  EXPECT_EQ(cv::countNonZero(patch), 25 + (40 - 8) * 4);
  // No edits: the plate, and the rig nothing saw for the patch.
  const cv::Mat unchanged = apply_clean_plate_edits(plate, original, {}, patch);
  EXPECT_EQ(cv::countNonZero(patch), 40 * 4);
  EXPECT_EQ(unchanged.at<cv::Vec3b>(2, 2)[0], 100);
  EXPECT_THROW(apply_clean_plate_edits(plate, original, cv::Mat::zeros(5, 5, CV_8U), patch), Error);
  EXPECT_THROW(read_clean_plate_edit("/nonexistent/edit.png", size), Error);
}

}  // namespace
}  // namespace plenopath
