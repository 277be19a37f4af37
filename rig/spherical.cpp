#include "rig/spherical.h"

#include <cmath>

namespace plenopath {
namespace {
constexpr double kPi = M_PI;

double wrap_pi(double a) {
  double r = std::remainder(a, 2.0 * kPi);
  return r <= -kPi ? r + 2.0 * kPi : r;
}
}  // namespace

SphericalAngles equirect_to_angles(const Eigen::Vector2d& pixel, int width, int height) {
  return {wrap_pi(pixel.x() / width * 2.0 * kPi - kPi), kPi / 2.0 - pixel.y() / height * kPi};
}

Eigen::Vector2d angles_to_equirect(const SphericalAngles& angles, int width, int height) {
  double x = (angles.azimuth + kPi) / (2.0 * kPi) * width;
  x = std::fmod(x, static_cast<double>(width));
  if (x < 0) x += width;
  if (x >= width) x -= width;  // fmod of a value a hair below 0 can land exactly on width
  const double y = (kPi / 2.0 - angles.elevation) / kPi * height;
  return {x, y};
}

Eigen::Vector3d angles_to_bearing(const SphericalAngles& a) {
  const double ce = std::cos(a.elevation);
  return {ce * std::cos(a.azimuth), -ce * std::sin(a.azimuth), std::sin(a.elevation)};
}

SphericalAngles bearing_to_angles(const Eigen::Vector3d& b) {
  return {std::atan2(-b.y(), b.x()), std::atan2(b.z(), std::hypot(b.x(), b.y()))};
}

double azimuth_of_world_angle(double heading, double world_angle) { return wrap_pi(heading - world_angle); }

Eigen::Matrix3d world_from_camera_rotation(double heading) {
  const double c = std::cos(heading), s = std::sin(heading);
  Eigen::Matrix3d r;
  r << c, -s, 0, s, c, 0, 0, 0, 1;
  return r;
}

double equirect_pixel_solid_angle(int row, int width, int height) {
  const double top = kPi / 2.0 - static_cast<double>(row) / height * kPi;
  const double bottom = kPi / 2.0 - static_cast<double>(row + 1) / height * kPi;
  return (2.0 * kPi / width) * (std::sin(top) - std::sin(bottom));
}

const char* to_string(CubeFace face) {
  static const char* names[] = {"front", "back", "left", "right", "up", "down"};
  return names[static_cast<int>(face)];
}

CubeFaceAxes cube_face_axes(CubeFace face) {
  using V = Eigen::Vector3d;
  // Camera frame: +x forward, +y left, +z up. Side faces keep "down" = -z; up/down faces keep "right" = -y
  // (the camera's right) so that their tops touch the front face's top and bottom.
  switch (face) {
    case CubeFace::kFront:
      return {V(1, 0, 0), V(0, -1, 0), V(0, 0, -1)};
    case CubeFace::kBack:
      return {V(-1, 0, 0), V(0, 1, 0), V(0, 0, -1)};
    case CubeFace::kLeft:
      return {V(0, 1, 0), V(1, 0, 0), V(0, 0, -1)};
    case CubeFace::kRight:
      return {V(0, -1, 0), V(-1, 0, 0), V(0, 0, -1)};
    case CubeFace::kUp:
      return {V(0, 0, 1), V(0, -1, 0), V(1, 0, 0)};
    case CubeFace::kDown:
      return {V(0, 0, -1), V(0, -1, 0), V(-1, 0, 0)};
  }
  return {V(1, 0, 0), V(0, -1, 0), V(0, 0, -1)};
}

Eigen::Vector3d cube_face_to_bearing(CubeFace face, const Eigen::Vector2d& pixel, int size) {
  const CubeFaceAxes ax = cube_face_axes(face);
  const double u = 2.0 * pixel.x() / size - 1.0;
  const double v = 2.0 * pixel.y() / size - 1.0;
  return (ax.forward + u * ax.right + v * ax.down).normalized();
}

CubeFacePixel bearing_to_cube_face(const Eigen::Vector3d& bearing, int size) {
  // The face is the one whose forward axis has the largest dot product with the bearing.
  int best = 0;
  double best_dot = -1e300;
  for (int f = 0; f < kCubeFaceCount; ++f) {
    const double d = cube_face_axes(static_cast<CubeFace>(f)).forward.dot(bearing);
    if (d > best_dot) {
      best_dot = d;
      best = f;
    }
  }
  const CubeFace face = static_cast<CubeFace>(best);
  const CubeFaceAxes ax = cube_face_axes(face);
  const double u = ax.right.dot(bearing) / best_dot;
  const double v = ax.down.dot(bearing) / best_dot;
  return {face, Eigen::Vector2d((u + 1.0) * 0.5 * size, (v + 1.0) * 0.5 * size)};
}

}  // namespace plenopath
