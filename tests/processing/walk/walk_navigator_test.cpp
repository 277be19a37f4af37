#include "processing/walk/walk_navigator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "model/error.h"

namespace plenopath {
namespace {

// An L-shaped path: 0..10 m east along y = 0, then 0..5 m north along x = 10; a frame every metre.
CameraPath l_path() {
  CameraPath p;
  int index = 0;
  for (int i = 0; i <= 10; ++i) p.frames.push_back({index++, "", double(i), 0.0, 0.0, 1.0, 0, ""});
  for (int j = 1; j <= 5; ++j) p.frames.push_back({index++, "", 10.0, double(j), M_PI / 2, 1.0, 0, ""});
  return p;
}

Keyframes keys(std::vector<int> indices) {
  Keyframes k;
  k.indices = std::move(indices);
  return k;
}

void settle(WalkNavigator& w) {
  for (int i = 0; i < 200 && w.advance(0.05); ++i) {
  }
}

TEST(WalkNavigator, GeometryOfThePath) {
  WalkNavigator w(l_path(), keys({0, 5, 10, 15}));
  EXPECT_DOUBLE_EQ(w.path_length(), 15.0);
  EXPECT_LT((w.position_at(12.5) - Eigen::Vector2d(10, 2.5)).norm(), 1e-12);
  EXPECT_LT((w.position_at(-3) - Eigen::Vector2d(0, 0)).norm(), 1e-12);
  EXPECT_LT((w.tangent_at(3.2) - Eigen::Vector2d(1, 0)).norm(), 1e-12);
  EXPECT_LT((w.tangent_at(11.0) - Eigen::Vector2d(0, 1)).norm(), 1e-12);
  EXPECT_NEAR(w.nearest_s({4.3, -2.0}), 4.3, 1e-12);
  EXPECT_NEAR(w.nearest_s({12.0, 3.0}), 13.0, 1e-12);
  ASSERT_EQ(w.keyframes().size(), 4u);
  EXPECT_EQ(w.nearest_keyframe(7.4), 1);  // s = 5 is nearer than s = 10
  EXPECT_EQ(w.nearest_keyframe(7.6), 2);
}

TEST(WalkNavigator, ForwardIsWhereTheViewerLooks) {
  WalkNavigator w(l_path(), keys({0, 5, 10, 15}));
  EXPECT_EQ(w.current_keyframe(), 0);
  EXPECT_TRUE(w.step(+1));  // looking east along the path
  settle(w);
  EXPECT_EQ(w.current_keyframe(), 1);
  EXPECT_DOUBLE_EQ(w.s(), 5.0);
  w.set_yaw(M_PI);  // turn round: forward now walks back along the path
  EXPECT_TRUE(w.step(+1));
  settle(w);
  EXPECT_EQ(w.current_keyframe(), 0);
  EXPECT_FALSE(w.step(+1));  // nothing further back
  EXPECT_TRUE(w.step(-1));   // backing up (still looking west) goes east
  settle(w);
  EXPECT_EQ(w.current_keyframe(), 1);
}

TEST(WalkNavigator, CrossFadesWhenTheKeyframeChanges) {
  WalkNavigator w(l_path(), keys({0, 5}));
  EXPECT_DOUBLE_EQ(w.fade(), 1.0);
  w.walk_to(5.0);
  bool switched = false;
  while (w.advance(0.02)) {
    if (w.current_keyframe() == 1 && !switched) {
      switched = true;
      EXPECT_LT(w.fade(), 1.0);
      EXPECT_EQ(w.previous_keyframe(), 0);
    }
  }
  EXPECT_TRUE(switched);
  EXPECT_DOUBLE_EQ(w.fade(), 1.0);
  EXPECT_FALSE(w.moving());
}

TEST(WalkNavigator, MapClickAndJump) {
  WalkNavigator w(l_path(), keys({0, 5, 10, 15}));
  w.walk_to(w.nearest_s({10.5, 4.9}));
  settle(w);
  EXPECT_EQ(w.current_keyframe(), 3);
  w.jump_to(0.4);
  EXPECT_EQ(w.current_keyframe(), 0);
  EXPECT_FALSE(w.moving());
}

TEST(WalkNavigator, RejectsUnusableInput) {
  EXPECT_THROW(WalkNavigator(CameraPath{}, keys({0})), Error);
  EXPECT_THROW(WalkNavigator(l_path(), keys({})), Error);
  EXPECT_THROW(WalkNavigator(l_path(), keys({99})), Error);
  WalkOptions bad;
  bad.speed_m_per_s = 0;
  EXPECT_THROW(WalkNavigator(l_path(), keys({0}), bad), Error);
  // A path whose frames all sit at one point (the trolley never moved) still walks without dividing by 0.
  CameraPath still;
  still.frames = {{0, "", 1.0, 1.0, 0.3, 1.0, 0, ""}, {1, "", 1.0, 1.0, 0.3, 1.0, 0, ""}};
  WalkNavigator w(still, keys({0, 1}));
  EXPECT_TRUE(std::isfinite(w.tangent_at(0.0).x()));
  EXPECT_FALSE(w.step(+1));
}

}  // namespace
}  // namespace plenopath
