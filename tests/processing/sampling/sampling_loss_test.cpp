// Loss measures against independent truth: polygon IoU against a grid oracle written here, hand-computed
// overlaps, stand-ins by hand, and PSNR/SSIM on pairs whose answer is known.
#include "processing/sampling/sampling_loss.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

#include "model/error.h"
#include "processing/sampling/envelope_raster.h"
#include "processing/sampling/image_similarity.h"
#include "processing/sampling/polygon_iou.h"
#include "sampling_test_util.h"

namespace plenopath {
namespace {

using Polygon = std::vector<Eigen::Vector2d>;

bool inside(const Polygon& poly, const Eigen::Vector2d& q) {  // even-odd, the oracle's own
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
    if ((poly[i].y() > q.y()) != (poly[j].y() > q.y()) &&
        q.x() <
            poly[i].x() + (q.y() - poly[i].y()) * (poly[j].x() - poly[i].x()) / (poly[j].y() - poly[i].y()))
      in = !in;
  return in;
}

// Grid oracle: intersection and union counted on a 1200 x 1200 grid of cell centres.
double grid_iou(const Polygon& a, const Polygon& b) {
  Eigen::Vector2d lo(1e9, 1e9), hi(-1e9, -1e9);
  for (const auto* p : {&a, &b})
    for (const auto& q : *p) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const int n = 1200;
  long both = 0, any = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d q(lo.x() + (i + 0.5) * (hi.x() - lo.x()) / n,
                              lo.y() + (j + 0.5) * (hi.y() - lo.y()) / n);
      const bool ia = inside(a, q), ib = inside(b, q);
      both += ia && ib;
      any += ia || ib;
    }
  return any ? static_cast<double>(both) / any : 1.0;
}

// A random star-shaped polygon around c (many reflex vertices, like an envelope).
Polygon random_star(std::mt19937* rng, Eigen::Vector2d c, int n) {
  std::uniform_real_distribution<double> radius(0.5, 3.0);
  Polygon p;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    p.push_back(c + radius(*rng) * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return p;
}

TEST(PolygonIou, HandComputedSquares) {
  const Polygon a = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  const Polygon b = {{1, 1}, {3, 1}, {3, 3}, {1, 3}};  // overlap 1, union 7
  EXPECT_NEAR(polygon_intersection_area(a, b), 1.0, 1e-12);
  EXPECT_NEAR(polygon_iou(a, b), 1.0 / 7.0, 1e-12);
  const Polygon a_cw(a.rbegin(), a.rend());
  EXPECT_NEAR(polygon_iou(a_cw, b), 1.0 / 7.0, 1e-12);  // orientation does not matter
  EXPECT_NEAR(polygon_iou(a, a), 1.0, 1e-12);
  const Polygon far = {{5, 5}, {6, 5}, {6, 6}};
  EXPECT_EQ(polygon_iou(a, far), 0.0);
  // Sharing an edge: touching is no overlap.
  const Polygon next = {{2, 0}, {4, 0}, {4, 2}, {2, 2}};
  EXPECT_NEAR(polygon_iou(a, next), 0.0, 1e-12);
  EXPECT_EQ(polygon_iou({}, {}), 1.0);
  EXPECT_EQ(polygon_iou(a, {}), 0.0);
}

TEST(PolygonIou, AgreesWithAGridOracleOnStarPolygons) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> offset(-2.0, 2.0);
  for (int trial = 0; trial < 8; ++trial) {
    const Polygon a = random_star(&rng, {0, 0}, 40);
    const Polygon b = random_star(&rng, {offset(rng), offset(rng)}, 40);
    bool exact = false;
    const double iou = polygon_iou(a, b, &exact);
    EXPECT_TRUE(exact);
    EXPECT_NEAR(iou, grid_iou(a, b), 0.01) << "trial " << trial;
  }
}

TEST(PolygonIou, AgreesWithAGridOracleOnEnvelopes) {
  const FloorPlan plan = sampling_test::three_rooms();
  const VisibilityIndex index(plan);
  const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> pairs = {
      {{3, 2}, {5.5, 2}}, {{5.5, 2}, {6.5, 2}}, {{8, 1}, {10, 2}}, {{2, 3}, {16, 1}}};
  for (const auto& [p, q] : pairs) {
    const Envelope a = index.envelope(p), b = index.envelope(q);
    ASSERT_EQ(a.status, EnvelopeStatus::ok);
    ASSERT_EQ(b.status, EnvelopeStatus::ok);
    EXPECT_NEAR(polygon_iou(a.polygon, b.polygon), grid_iou(a.polygon, b.polygon), 0.01);
  }
}

TEST(SamplingLoss, StandInIsTheNearestKeyframeAlongThePath) {
  // Frames at x = 0, 1, 2, 3, 4, 10: keyframes 0, 3 and 5 (x = 10).
  CameraPath path = sampling_test::straight_path(5, 1.0);
  path.frames.push_back({5, "", 10.0, 0.0, 0.0, 1.0, kFrameOk, ""});
  Keyframes k;
  k.indices = {0, 3, 5};
  const std::vector<int> stand_in = stand_in_positions(path, k);
  EXPECT_EQ(stand_in, (std::vector<int>{0, 0, 3, 3, 3, 5}));  // x = 1 -> 0 (1 m vs 2 m); x = 4 -> 3
}

TEST(SamplingLoss, GeometricLossByHand) {
  // A 10 m x 2 m corridor with a wall stub splitting it at x = 5 except for a 1 m gap: frames either side.
  FloorPlan plan;
  sampling_test::add_wall(&plan, {0, 0}, {10, 0});
  sampling_test::add_wall(&plan, {10, 0}, {10, 2});
  sampling_test::add_wall(&plan, {10, 2}, {0, 2});
  sampling_test::add_wall(&plan, {0, 2}, {0, 0});
  const VisibilityIndex index(plan);
  const CameraPath path = sampling_test::straight_path(9, 1.0, 1.0, 1.0);  // x = 1 .. 9
  const PathEnvelopes env = compute_path_envelopes(index, path, 1);
  Keyframes k;
  k.indices = {0, 8};
  const GeometricLoss loss = geometric_loss(path, k, env);
  // Every envelope is the whole corridor: nothing is lost.
  EXPECT_EQ(loss.dropped, 7);
  EXPECT_EQ(loss.evaluated, 7);
  EXPECT_NEAR(loss.mean, 0.0, 1e-12);
  EXPECT_NEAR(loss.p95, 0.0, 1e-12);

  // Hand-made envelopes: frame i's envelope is the unit square shifted by i * 0.5 along x; keyframe 0 only.
  PathEnvelopes shifted;
  for (int i = 0; i < 9; ++i) {
    Envelope e;
    e.status = EnvelopeStatus::ok;
    const double x = 0.5 * i;
    e.polygon = {{x, 0}, {x + 1, 0}, {x + 1, 1}, {x, 1}};
    e.area = 1.0;
    shifted.frames.push_back(e);
  }
  k.indices = {0, 8};
  // Frames 1..4 stand in by 0 (shift 0.5 i), frames 5..7 by 8 (shift 0.5 (8 - i)).
  // IoU of unit squares shifted by d < 1: (1 - d) / (1 + d); shift >= 1: 0.
  auto iou = [](double d) { return d >= 1.0 ? 0.0 : (1 - d) / (1 + d); };
  std::vector<double> losses = {1 - iou(0.5), 1 - iou(1.0), 1 - iou(1.5), 1 - iou(2.0),
                                1 - iou(1.5), 1 - iou(1.0), 1 - iou(0.5)};
  double mean = 0;
  for (double l : losses) mean += l / 7;
  const GeometricLoss by_hand = geometric_loss(path, k, shifted);
  EXPECT_NEAR(by_hand.mean, mean, 1e-12);
  EXPECT_NEAR(by_hand.max, 1.0, 1e-12);
  EXPECT_NEAR(by_hand.p95, 1.0, 1e-12);  // nearest rank: the 7th of 7
  EXPECT_THROW(geometric_loss(sampling_test::straight_path(3, 1.0), k, shifted), Error);
}

TEST(SamplingLoss, RasterEstimateIsCloseToTheExactLoss) {
  const FloorPlan plan = sampling_test::three_rooms();
  const CameraPath path = sampling_test::three_rooms_path();
  const VisibilityIndex index(plan);
  const PathEnvelopes env = compute_path_envelopes(index, path);
  const EnvelopeRaster raster(env, 0.05);
  double worst = 0.0;
  for (int i = 0; i < 340; i += 17)
    for (int j : {i + 1, i + 10, i + 40}) {
      if (j >= 341) continue;
      const double exact = 1.0 - polygon_iou(env.frames[i].polygon, env.frames[j].polygon);
      worst = std::max(worst, std::abs(raster.loss(i, j) - exact));
    }
  EXPECT_LT(worst, 0.03);
  EXPECT_EQ(raster.loss(5, 5), 0.0);
}

// ---- photometric

cv::Mat random_panorama(int w, int h, unsigned seed) {
  cv::Mat m(h, w, CV_8UC3);
  cv::RNG rng(seed);
  rng.fill(m, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(m, m, cv::Size(5, 5), 1.2);  // some structure for SSIM
  return m;
}

TEST(ImageSimilarity, RotatingByWholeColumnsIsExact) {
  const cv::Mat pano = random_panorama(256, 128, 3);
  // The same place seen with heading +30 deg: 256 * 30 / 360 = 21.33 columns; use 45 deg = 32 columns.
  const double turn = M_PI / 4;
  const cv::Mat turned = rotate_to_heading(pano, 0.0, turn);
  // Column u of the turned image is column u - 32 of the original (centre column = new heading, which is
  // 45 deg counter-clockwise = 45 deg to the left, i.e. 32 columns towards lower azimuth).
  for (int u : {0, 31, 32, 100, 255}) {
    const int from = ((u - 32) % 256 + 256) % 256;
    EXPECT_EQ(cv::norm(turned.col(u), pano.col(from), cv::NORM_INF), 0.0) << u;
  }
  const cv::Mat back = rotate_to_heading(turned, turn, 0.0);
  EXPECT_TRUE(std::isinf(psnr_db(back, pano)));
  EXPECT_NEAR(ssim(back, pano), 1.0, 1e-12);
  EXPECT_LT(psnr_db(turned, pano), 20.0);  // unrotated, the pair differs
}

TEST(ImageSimilarity, PsnrAndSsimKnownValues) {
  const cv::Mat a(64, 128, CV_8UC3, cv::Scalar(100, 100, 100));
  const cv::Mat b(64, 128, CV_8UC3, cv::Scalar(110, 110, 110));
  EXPECT_NEAR(psnr_db(a, b), 10 * std::log10(255.0 * 255.0 / 100.0), 1e-9);  // MSE 100
  // Flat images: SSIM = luminance term (2 mu_a mu_b + C1) / (mu_a^2 + mu_b^2 + C1).
  const double c1 = std::pow(0.01 * 255, 2);
  EXPECT_NEAR(ssim(a, b), (2 * 100.0 * 110.0 + c1) / (100.0 * 100.0 + 110.0 * 110.0 + c1), 1e-9);
  EXPECT_THROW(psnr_db(a, cv::Mat(10, 10, CV_8UC3)), Error);
}

TEST(ImageSimilarity, PhotometricLossOfARotatedCopyIsPerfect) {
  // Every frame is the same place seen with a different heading: a turned copy of one panorama.
  const cv::Mat pano = random_panorama(256, 128, 9);
  CameraPath path;
  for (int i = 0; i < 10; ++i)
    path.frames.push_back({i, "", 0.0, 0.0, i * 2 * M_PI / 256 * 7, 1.0, kFrameOk, ""});
  auto read = [&](int index) { return rotate_to_heading(pano, 0.0, path.frames[index].heading); };
  Keyframes k;
  k.indices = {0, 9};
  const PhotometricLoss loss = photometric_loss(path, k, read);
  EXPECT_EQ(loss.frames, 8);
  EXPECT_EQ(loss.psnr_min_db, 100.0);  // identical after turning (capped)
  EXPECT_NEAR(loss.ssim_min, 1.0, 1e-12);
  // Without turning to the same heading, the pairs would differ: make the reader lie about headings.
  auto wrong = [&](int index) { return rotate_to_heading(pano, 0.0, 0.5 * index); };
  const PhotometricLoss bad = photometric_loss(path, k, wrong);
  EXPECT_LT(bad.ssim_mean, 0.9);
}

}  // namespace
}  // namespace plenopath
