#pragma once
// A drifting tracker's view of a walk, for the plan refinement's tests and bench: the walk's own steps
// integrated with a heading bias and a scale error (as in the anchor tests), and the points a tracker
// would triangulate, cast by the project's ray caster from the true poses into the scene built from the
// plan, then carried by the drifted poses (each point tied to the frame it was cast from). Truth: the walk.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "model/camera_path.h"
#include "model/path_points.h"
#include "rig/synthetic_camera.h"

namespace plenopath::test {

// `truth`'s steps with `bias_rad_per_frame` of heading bias, scaled by `scale`, from a start moved by
// `start_offset` and turned by `start_turn`.
inline CameraPath drifted(const CameraPath& truth, double bias_rad_per_frame, double scale,
                          const Eigen::Vector2d& start_offset = {0.7, -0.4}, double start_turn = 0.1) {
  CameraPath out = truth;
  Eigen::Vector2d p = truth.frames.front().position() + start_offset;
  double extra = start_turn;
  for (std::size_t i = 0; i < truth.frames.size(); ++i) {
    if (i > 0) {
      const Eigen::Vector2d step = truth.frames[i].position() - truth.frames[i - 1].position();
      extra += bias_rad_per_frame;
      const double c = std::cos(extra), s = std::sin(extra);
      p += scale * Eigen::Vector2d(c * step.x() - s * step.y(), s * step.x() + c * step.y());
    }
    out.frames[i].x = p.x();
    out.frames[i].y = p.y();
    out.frames[i].heading = wrap_angle(truth.frames[i].heading + extra);
  }
  return out;
}

// Points cast from every `every`-th frame of `truth` (azimuths x elevations rays, 1 % depth noise, hits
// within 12 m), expressed where `observed` (the drifted path, frame by frame the same frames) puts them:
// each moves with its frame's drifted pose, its offset scaled by `scale`. Heights from the camera (z = 0).
inline std::vector<PathPoint> cast_points(const SyntheticScene& scene, const CameraPath& truth,
                                          const CameraPath& observed, double scale, std::size_t every,
                                          int azimuths, int elevations, std::uint32_t seed,
                                          double camera_height = 1.6) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  RenderOptions render;
  std::vector<PathPoint> points;
  for (std::size_t i = 0; i < truth.size(); i += every) {
    const PathFrame& t = truth.frames[i];
    const PathFrame& o = observed.frames[i];
    const Eigen::Vector3d origin(t.x, t.y, camera_height);
    const double turn = o.heading - t.heading, c = std::cos(turn), s = std::sin(turn);
    for (int a = 0; a < azimuths; ++a)
      for (int e = 0; e < elevations; ++e) {
        const double az = 2 * M_PI * (a + 0.37 * (i % 7)) / azimuths;
        const double el = (elevations == 1 ? 0.0 : -48.0 + 96.0 * e / (elevations - 1)) * M_PI / 180.0;
        const Eigen::Vector3d dir(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
        const RayHit hit = trace_ray(scene, origin, dir, render, static_cast<int>(i));
        if (hit.distance <= 0 || hit.distance > 12) continue;
        const Eigen::Vector3d d = dir * hit.distance * (1.0 + 0.01 * noise(rng));
        PathPoint q;
        const Eigen::Vector2d xy =
            o.position() + scale * Eigen::Vector2d(c * d.x() - s * d.y(), s * d.x() + c * d.y());
        q.position = {xy.x(), xy.y(), scale * d.z()};
        q.observations = 4;
        q.frame = t.index;
        points.push_back(q);
      }
  }
  return points;
}

// Absolute position RMS (metres) and heading RMS (degrees) on the plan, no alignment: frame i against frame
// i.
inline double absolute_rms(const CameraPath& placed, const CameraPath& truth) {
  double sum = 0;
  for (std::size_t i = 0; i < truth.size(); ++i)
    sum += (placed.frames[i].position() - truth.frames[i].position()).squaredNorm();
  return std::sqrt(sum / truth.size());
}
inline double heading_rms_deg(const CameraPath& placed, const CameraPath& truth) {
  double sum = 0;
  for (std::size_t i = 0; i < truth.size(); ++i)
    sum += std::pow(wrap_angle(placed.frames[i].heading - truth.frames[i].heading), 2);
  return degrees(std::sqrt(sum / truth.size()));
}

}  // namespace plenopath::test
