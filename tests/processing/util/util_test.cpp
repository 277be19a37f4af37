#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <opencv2/core.hpp>
#include <random>
#include <stdexcept>
#include <vector>

#include "model/error.h"
#include "processing/util/grey_image.h"
#include "processing/util/parallel_for.h"
#include "processing/util/statistics.h"

namespace plenopath {
namespace {

TEST(Statistics, MedianAndPercentileAgreeWithAFullSort) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5, 5);
  for (int n : {1, 2, 3, 10, 101}) {
    std::vector<double> v(n);
    for (double& x : v) x = u(rng);
    std::vector<double> sorted = v;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(median(v), sorted[n / 2]) << n;
    EXPECT_EQ(percentile(v, 0.0), sorted.front());
    EXPECT_EQ(percentile(v, 1.0), sorted.back());
    EXPECT_EQ(percentile(v, 0.1), sorted[static_cast<std::size_t>(0.1 * (n - 1))]);
  }
  EXPECT_EQ(median({}), 0.0);
  EXPECT_EQ(percentile({}, 0.5), 0.0);
  EXPECT_EQ(median({4.0, 1.0}), 4.0);  // the upper of two
}

TEST(Statistics, MedianAbsoluteDeviationByHand) {
  // |v - 3| = 2, 1, 0, 4, 7: sorted 0 1 2 4 7, median 2.
  EXPECT_EQ(median_absolute_deviation({1.0, 2.0, 3.0, 7.0, 10.0}, 3.0), 2.0);
  // About another centre: |v - 0| = 1 2 3 7 10, median 3.
  EXPECT_EQ(median_absolute_deviation({1.0, 2.0, 3.0, 7.0, 10.0}, 0.0), 3.0);
  EXPECT_EQ(median_absolute_deviation({}, 5.0), 0.0);
}

TEST(ParallelFor, RunsEveryIndexOnceOnAnyThreadCount) {
  for (int threads : {0, 1, 2, 7}) {
    std::vector<std::atomic<int>> hits(1000);
    parallel_for_each(1000, threads, [&](int i) { ++hits[i]; });
    for (const auto& h : hits) ASSERT_EQ(h.load(), 1) << threads;
  }
  parallel_for_each(0, 4, [](int) { FAIL(); });
}

TEST(ParallelFor, RethrowsTheFirstFailure) {
  EXPECT_THROW(parallel_for_each(100, 3,
                                 [](int i) {
                                   if (i == 17) throw std::runtime_error("seventeen");
                                 }),
               std::runtime_error);
  EXPECT_EQ(resolve_thread_count(5), 5);
  EXPECT_GE(resolve_thread_count(0), 1);
}

TEST(GreyImage, LumaOfBgrAndPassThroughOfGrey) {
  cv::Mat bgr(2, 4, CV_8UC3, cv::Scalar(255, 0, 0));  // pure blue
  const cv::Mat g = grey_image(bgr, "test");
  ASSERT_EQ(g.type(), CV_8UC1);
  EXPECT_NEAR(g.at<unsigned char>(0, 0), 0.114 * 255, 1.0);  // ITU-R BT.601 weight of blue
  cv::Mat grey(2, 4, CV_8UC1, cv::Scalar(9));
  EXPECT_EQ(grey_image(grey, "test").data, grey.data);  // not copied
  cv::Mat bgra(2, 4, CV_8UC4, cv::Scalar(0, 255, 0, 255));
  EXPECT_NEAR(grey_image(bgra, "test").at<unsigned char>(1, 1), 0.587 * 255, 1.0);
  cv::Mat grey16(2, 4, CV_16UC1, cv::Scalar(300));
  EXPECT_EQ(grey_image_8u(grey16, "test").at<unsigned char>(0, 0), 255);  // saturated as convertTo does
  try {
    grey_image(cv::Mat(2, 4, CV_8UC2), "ring image");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ring image: expected a 1-, 3- or 4-channel"), std::string::npos);
  }
  EXPECT_THROW(grey_image(cv::Mat(), "x"), Error);
}

TEST(GreyImage, EquirectAtWidthHalvesByAreaAveraging) {
  cv::Mat g(4, 8, CV_8UC1);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 8; ++c) g.at<unsigned char>(r, c) = static_cast<unsigned char>(10 * (c % 2));
  const cv::Mat small = equirect_at_width(g, 4);
  ASSERT_EQ(small.cols, 4);
  ASSERT_EQ(small.rows, 2);
  EXPECT_EQ(small.at<unsigned char>(0, 0), 5);  // mean of 0 and 10
  EXPECT_EQ(equirect_at_width(g, 0).cols, 8);
  EXPECT_EQ(equirect_at_width(g, 16).cols, 8);
}

}  // namespace
}  // namespace plenopath
