// The described frames kept on disk come back exactly as they went in, found by their capture frame.
#include "processing/egomotion/descriptor_store.h"

#include <gtest/gtest.h>

#include <random>

#include "model/error.h"

namespace plenopath {
namespace {

FrameDescriptors random_frame(int frame, int rows, std::mt19937& rng) {
  FrameDescriptors d;
  d.frame = frame;
  if (rows == 0) return d;
  d.descriptors.create(rows, 32, CV_8U);
  cv::randu(d.descriptors, 0, 256);
  std::uniform_int_distribution<int> track(0, 1 << 30);
  for (int r = 0; r < rows; ++r) d.tracks.push_back(track(rng));
  return d;
}

TEST(DescriptorStore, GivesBackWhatWasStoredByFrame) {
  std::mt19937 rng(3);
  cv::theRNG().state = 5;
  DescriptorStore store;
  std::vector<FrameDescriptors> stored;
  const int rows[] = {700, 0, 1, 350, 64};
  for (int k = 0; k < 5; ++k) {
    stored.push_back(random_frame(3 * k + (k == 1 ? 1 : 0), rows[k], rng));
    store.add(stored.back());
  }
  EXPECT_TRUE(store.on_disk());  // /tmp is writable here
  ASSERT_EQ(store.size(), 5);
  EXPECT_EQ(store.last_frame(), 12);
  EXPECT_EQ(store.find(4), 1);
  EXPECT_EQ(store.find(5), -1);
  EXPECT_EQ(store.find(100), -1);
  EXPECT_FALSE(store.has_descriptors(1));
  // Read back in an order other than written (loop closure jumps about).
  for (int k : {3, 0, 4, 1, 2, 0}) {
    const FrameDescriptors back = store.load(k);
    EXPECT_EQ(back.frame, stored[k].frame);
    EXPECT_EQ(back.tracks, stored[k].tracks);
    ASSERT_EQ(back.descriptors.rows, stored[k].descriptors.rows);
    if (rows[k] > 0) {
      EXPECT_EQ(back.descriptors.type(), CV_8U);
      EXPECT_EQ(cv::norm(back.descriptors, stored[k].descriptors, cv::NORM_L1), 0.0);
    }
  }
}

TEST(DescriptorStore, RefusesRowsWithoutTheirTracks) {
  std::mt19937 rng(1);
  FrameDescriptors d = random_frame(0, 10, rng);
  d.tracks.pop_back();
  DescriptorStore store;
  EXPECT_THROW(store.add(d), Error);
  EXPECT_EQ(store.size(), 0);
}

}  // namespace
}  // namespace plenopath
