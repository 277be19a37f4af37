#include "rig/spherical.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace plenopath {
namespace {

constexpr double kPi = M_PI;

TEST(Spherical, PixelCentresFollowTheConvention) {
  const int w = 2048, h = 1024;
  // Pixel centre (u + 1/2, v + 1/2) -> azimuth (u + 1/2)/w * 360 - 180, elevation 90 - (v + 1/2)/h * 180.
  for (int u : {0, 1, 511, 1023, 1024, 2047})
    for (int v : {0, 1, 511, 512, 1023}) {
      const SphericalAngles a = equirect_to_angles({u + 0.5, v + 0.5}, w, h);
      EXPECT_NEAR(a.azimuth * 180 / kPi, (u + 0.5) / w * 360.0 - 180.0, 1e-12);
      EXPECT_NEAR(a.elevation * 180 / kPi, 90.0 - (v + 0.5) / h * 180.0, 1e-12);
    }
  // The centre column looks forward (+x), azimuth +90 deg looks right (-y), elevation +90 deg up.
  EXPECT_LT((equirect_to_bearing({w / 2.0, h / 2.0}, w, h) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((equirect_to_bearing({0.75 * w, h / 2.0}, w, h) - Eigen::Vector3d(0, -1, 0)).norm(), 1e-12);
  EXPECT_LT((equirect_to_bearing({0.25 * w, h / 2.0}, w, h) - Eigen::Vector3d(0, 1, 0)).norm(), 1e-12);
  EXPECT_NEAR(equirect_to_bearing({123.0, 0.0}, w, h).z(), 1.0, 1e-12);
  EXPECT_NEAR(equirect_to_bearing({123.0, h}, w, h).z(), -1.0, 1e-12);
}

TEST(Spherical, WorldAngleOfAzimuth) {
  // A camera heading 90 deg (facing +Y) sees +X at azimuth +90 deg (to its right).
  EXPECT_NEAR(world_angle_of_azimuth(kPi / 2, kPi / 2), 0.0, 1e-15);
  EXPECT_NEAR(azimuth_of_world_angle(kPi / 2, 0.0), kPi / 2, 1e-15);
  // world_from_camera rotates the camera's bearing at azimuth a to world angle theta - a.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-kPi, kPi);
  for (int i = 0; i < 100; ++i) {
    const double theta = U(rng), a = U(rng);
    const Eigen::Vector3d world = world_from_camera_rotation(theta) * angles_to_bearing({a, 0.0});
    EXPECT_NEAR(std::remainder(std::atan2(world.y(), world.x()) - (theta - a), 2 * kPi), 0.0, 1e-12);
  }
}

TEST(Spherical, RandomRoundTrips) {
  std::mt19937 rng(42);
  for (auto [w, h] : {std::pair{2048, 1024}, std::pair{512, 256}, std::pair{7, 3}}) {
    std::uniform_real_distribution<double> X(0.0, w), Y(0.0, h);
    for (int i = 0; i < 10000; ++i) {
      const Eigen::Vector2d p(X(rng), Y(rng));
      const Eigen::Vector3d b = equirect_to_bearing(p, w, h);
      EXPECT_NEAR(b.norm(), 1.0, 1e-12);
      const Eigen::Vector2d q = bearing_to_equirect(b, w, h);
      // Near the poles azimuth is ill-conditioned; compare on the sphere there.
      EXPECT_NEAR(q.y(), p.y(), 1e-9);
      EXPECT_LT((equirect_to_bearing(q, w, h) - b).norm(), 1e-12);
      if (std::abs(p.y() - h / 2.0) < 0.45 * h) {
        EXPECT_NEAR(q.x(), p.x(), 1e-8 * w);
      }
    }
  }
}

TEST(Spherical, SeamWrapsExactly) {
  const int w = 2048, h = 1024;
  // x = 0 and x = w are the same direction (azimuth -180 = +180).
  const Eigen::Vector3d a = equirect_to_bearing({0.0, 300.0}, w, h);
  const Eigen::Vector3d b = equirect_to_bearing({double(w), 300.0}, w, h);
  EXPECT_LT((a - b).norm(), 1e-12);
  // Straight behind maps into [0, w).
  const Eigen::Vector2d q = bearing_to_equirect({-1.0, 0.0, 0.0}, w, h);
  EXPECT_GE(q.x(), 0.0);
  EXPECT_LT(q.x(), double(w));
  EXPECT_NEAR(std::min(q.x(), w - q.x()), 0.0, 1e-9);
  // Just either side of the seam.
  for (double eps : {1e-9, 1e-6, 1e-3}) {
    const Eigen::Vector2d l = bearing_to_equirect(angles_to_bearing({kPi - eps, 0.1}), w, h);
    const Eigen::Vector2d r = bearing_to_equirect(angles_to_bearing({-kPi + eps, 0.1}), w, h);
    EXPECT_NEAR(l.x(), w - eps / (2 * kPi) * w, 1e-6);
    EXPECT_NEAR(r.x(), eps / (2 * kPi) * w, 1e-6);
  }
}

TEST(Spherical, PolesAreHandled) {
  const SphericalAngles up = bearing_to_angles({0.0, 0.0, 1.0});
  EXPECT_NEAR(up.elevation, kPi / 2, 1e-15);
  const SphericalAngles down = bearing_to_angles({0.0, 0.0, -2.0});
  EXPECT_NEAR(down.elevation, -kPi / 2, 1e-15);
  const Eigen::Vector2d p = bearing_to_equirect({1e-17, 0.0, 1.0}, 100, 50);
  EXPECT_NEAR(p.y(), 0.0, 1e-12);
  EXPECT_TRUE(std::isfinite(p.x()));
}

TEST(Spherical, PixelSolidAnglesSumToFourPi) {
  for (auto [w, h] : {std::pair{2048, 1024}, std::pair{4096, 2048}, std::pair{6, 3}, std::pair{1, 1}}) {
    double sum = 0;
    for (int v = 0; v < h; ++v) sum += w * equirect_pixel_solid_angle(v, w, h);
    EXPECT_NEAR(sum / (4 * kPi), 1.0, 1e-9) << w << "x" << h;
  }
  // Symmetric about the equator; largest at the equator.
  EXPECT_NEAR(equirect_pixel_solid_angle(0, 64, 32), equirect_pixel_solid_angle(31, 64, 32), 1e-15);
  EXPECT_GT(equirect_pixel_solid_angle(15, 64, 32), equirect_pixel_solid_angle(0, 64, 32));
}

TEST(CubeMap, FaceCentresLookAlongTheirAxes) {
  EXPECT_LT((cube_face_to_bearing(CubeFace::kFront, {64, 64}, 128) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((cube_face_to_bearing(CubeFace::kLeft, {64, 64}, 128) - Eigen::Vector3d(0, 1, 0)).norm(), 1e-12);
  EXPECT_LT((cube_face_to_bearing(CubeFace::kUp, {64, 64}, 128) - Eigen::Vector3d(0, 0, 1)).norm(), 1e-12);
  // Front face: image right is the camera's right (azimuth grows to the right), image down is down.
  const SphericalAngles r = bearing_to_angles(cube_face_to_bearing(CubeFace::kFront, {100, 64}, 128));
  EXPECT_GT(r.azimuth, 0.0);
  const SphericalAngles d = bearing_to_angles(cube_face_to_bearing(CubeFace::kFront, {64, 100}, 128));
  EXPECT_LT(d.elevation, 0.0);
  // Each face's axes form a right-handed-or-not orthonormal triple.
  for (int f = 0; f < kCubeFaceCount; ++f) {
    const CubeFaceAxes ax = cube_face_axes(static_cast<CubeFace>(f));
    EXPECT_NEAR(ax.forward.dot(ax.right), 0, 1e-15);
    EXPECT_NEAR(ax.forward.dot(ax.down), 0, 1e-15);
    EXPECT_NEAR(ax.right.dot(ax.down), 0, 1e-15);
  }
}

TEST(CubeMap, RandomRoundTrips) {
  std::mt19937 rng(3);
  std::normal_distribution<double> N;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d b = Eigen::Vector3d(N(rng), N(rng), N(rng)).normalized();
    const CubeFacePixel p = bearing_to_cube_face(b, 512);
    EXPECT_GE(p.pixel.x(), -1e-9);
    EXPECT_LE(p.pixel.x(), 512 + 1e-9);
    EXPECT_GE(p.pixel.y(), -1e-9);
    EXPECT_LE(p.pixel.y(), 512 + 1e-9);
    EXPECT_LT((cube_face_to_bearing(p.face, p.pixel, 512) - b).norm(), 1e-12);
  }
  // Face edges and corners (the bearing lies on two or three faces at once).
  const Eigen::Vector3d corner = Eigen::Vector3d(1, 1, 1).normalized();
  const CubeFacePixel c = bearing_to_cube_face(corner, 64);
  EXPECT_LT((cube_face_to_bearing(c.face, c.pixel, 64) - corner).norm(), 1e-12);
}

}  // namespace
}  // namespace plenopath
