// assess_tracking: counts of hand-set flags, and the warning only past the bridged share.
#include "processing/egomotion/tracking_health.h"

#include <gtest/gtest.h>

namespace plenopath {
namespace {

CameraPath path_with_flags(int frames, int bridged, int moving) {
  CameraPath path;
  for (int i = 0; i < frames; ++i) {
    PathFrame f;
    f.index = i;
    if (i < bridged) f.flags |= kFrameBridged;
    if (i >= frames - moving) f.flags |= kFrameMovingObjects;
    path.frames.push_back(f);
  }
  return path;
}

TEST(TrackingHealth, AFewBridgedFramesAreNoWarning) {
  // The gap walk's 10 frames inside a wall among 266: 4 %.
  const TrackingHealth h = assess_tracking(path_with_flags(266, 10, 3));
  EXPECT_EQ(h.frames, 266);
  EXPECT_EQ(h.bridged, 10);
  EXPECT_EQ(h.moving_objects, 3);
  EXPECT_TRUE(h.reliable);
  EXPECT_TRUE(h.warning.empty());
  EXPECT_TRUE(assess_tracking(CameraPath{}).reliable);
}

TEST(TrackingHealth, AMostlyBridgedPathIsSaidToBeAGuess) {
  // The POV-Ray trolley corridor as tracked: 165 of 382 frames bridged, 176 with moving objects.
  CameraPath path = path_with_flags(382, 165, 176);
  const TrackingHealth h = assess_tracking(path);
  EXPECT_FALSE(h.reliable);
  EXPECT_EQ(h.bridged, 165);
  EXPECT_EQ(h.moving_objects, 176);
  EXPECT_NE(h.warning.find("165 of 382 frames (43 %)"), std::string::npos) << h.warning;
  EXPECT_NE(h.warning.find("--level"), std::string::npos) << h.warning;
  // Bridged alone: no word about a rocking camera.
  const TrackingHealth bridged_only = assess_tracking(path_with_flags(100, 30, 0));
  EXPECT_FALSE(bridged_only.reliable);
  EXPECT_EQ(bridged_only.warning.find("--level"), std::string::npos) << bridged_only.warning;
  // The threshold is the caller's.
  EXPECT_TRUE(assess_tracking(path, 0.5).reliable);
}

}  // namespace
}  // namespace plenopath
