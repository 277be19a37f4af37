#pragma once
// Spherical camera geometry, per ARCHITECTURE.md:
// - equirectangular w x h; continuous pixel coordinates (x, y) with pixel (u, v) covering [u, u+1) x [v,
// v+1);
//   azimuth = x / w * 2pi - pi (column 0 starts at -180 deg, the centre column is the camera's forward),
//   elevation = pi/2 - y / h * pi (row 0 is the zenith);
// - azimuth grows to the right (clockwise seen from above), so a bearing at azimuth a from a camera with
//   heading theta points along world angle theta - a;
// - camera frame: +x forward (azimuth 0), +y left, +z up. A unit bearing at (a, e) is
//   (cos e cos a, -cos e sin a, sin e).
#include <Eigen/Core>
#include <array>

namespace plenopath {

struct SphericalAngles {
  double azimuth = 0.0;    // radians, (-pi, pi]
  double elevation = 0.0;  // radians, [-pi/2, pi/2]
};

SphericalAngles equirect_to_angles(const Eigen::Vector2d& pixel, int width, int height);
// Pixel coordinates of the direction; x wrapped into [0, width).
Eigen::Vector2d angles_to_equirect(const SphericalAngles& angles, int width, int height);

Eigen::Vector3d angles_to_bearing(const SphericalAngles& angles);
SphericalAngles bearing_to_angles(const Eigen::Vector3d& bearing);  // bearing need not be unit

inline Eigen::Vector3d equirect_to_bearing(const Eigen::Vector2d& pixel, int width, int height) {
  return angles_to_bearing(equirect_to_angles(pixel, width, height));
}
inline Eigen::Vector2d bearing_to_equirect(const Eigen::Vector3d& bearing, int width, int height) {
  return angles_to_equirect(bearing_to_angles(bearing), width, height);
}

// World angle (CCW from +X) of the ray at azimuth `azimuth` seen by a camera with heading `heading`.
inline double world_angle_of_azimuth(double heading, double azimuth) { return heading - azimuth; }
// Azimuth at which a camera with heading `heading` sees world angle `world_angle`, wrapped to (-pi, pi].
double azimuth_of_world_angle(double heading, double world_angle);

// Rotation taking camera-frame vectors to the plan frame for a camera with heading theta (about +z).
Eigen::Matrix3d world_from_camera_rotation(double heading);

// Exact solid angle of one pixel of row v: (2pi/w)(sin phi_top - sin phi_bottom).
double equirect_pixel_solid_angle(int row, int width, int height);

// ---- cube map: six square faces in the camera frame.
enum class CubeFace { kFront = 0, kBack, kLeft, kRight, kUp, kDown };
constexpr int kCubeFaceCount = 6;
const char* to_string(CubeFace face);

// Continuous face pixel coordinates (x, y) in [0, size)^2, x to the face's right, y down.
Eigen::Vector3d cube_face_to_bearing(CubeFace face, const Eigen::Vector2d& pixel, int size);
struct CubeFacePixel {
  CubeFace face = CubeFace::kFront;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
};
CubeFacePixel bearing_to_cube_face(const Eigen::Vector3d& bearing, int size);

// The face's axes in the camera frame: the direction it looks along, its image right and image down.
struct CubeFaceAxes {
  Eigen::Vector3d forward, right, down;
};
CubeFaceAxes cube_face_axes(CubeFace face);

}  // namespace plenopath
