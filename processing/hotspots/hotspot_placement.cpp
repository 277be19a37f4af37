#include "processing/hotspots/hotspot_placement.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "model/error.h"

namespace plenopath {
namespace {

Eigen::Vector3d world_ray(const SphericalAngles& a, const PathFrame& pose) {
  return world_from_camera_rotation(pose.heading) * angles_to_bearing(a);
}

// Whether the open 2-D segments p0-p1 and q0-q1 cross (touching at an end does not count as crossing).
bool segments_cross(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& q0,
                    const Eigen::Vector2d& q1) {
  auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
  };
  const Eigen::Vector2d r = p1 - p0, s = q1 - q0;
  const double denom = cross(r, s);
  if (std::abs(denom) < 1e-15) return false;  // parallel: a sight line grazing a wall is not blocked
  const double t = cross(q0 - p0, s) / denom;
  const double u = cross(q0 - p0, r) / denom;
  return t > 0 && t < 1 && u >= 0 && u <= 1;
}

// The corners on a vertical plane facing the camera, `distance` away along their mean horizontal direction.
LiftedQuad lift_onto_facing_plane(const std::vector<SphericalAngles>& corners, const PathFrame& pose,
                                  double camera_height_m, double distance) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& a : corners) mean += world_ray(a, pose);
  Eigen::Vector3d horizontal(mean.x(), mean.y(), 0.0);
  if (horizontal.norm() < 1e-9)
    throw Error("the hotspot's corners surround the zenith or nadir: mark them nearer the horizon");
  horizontal.normalize();
  const Eigen::Vector3d c(pose.x, pose.y, camera_height_m);
  const Eigen::Vector3d on_plane = c + distance * horizontal;
  LiftedQuad quad;
  quad.normal = -horizontal;
  for (const auto& a : corners) {
    const Eigen::Vector3d d = world_ray(a, pose);
    const double denom = quad.normal.dot(d);
    if (denom > -1e-6)
      throw Error("a hotspot corner points away from the hotspot's plane: mark the corners closer together");
    quad.corners.push_back(c + (quad.normal.dot(on_plane - c) / denom) * d);
  }
  return quad;
}

}  // namespace

const char* to_string(HotspotPlacement placement) {
  switch (placement) {
    case HotspotPlacement::kWall:
      return "wall";
    case HotspotPlacement::kDepth:
      return "depth";
    case HotspotPlacement::kFacingCamera:
      return "facing_camera";
  }
  return "wall";
}

void HotspotPlacementOptions::check() const {
  lift.check();
  if (!(fallback_distance_m > 0)) throw Error("hotspot placement: fallback distance must be > 0");
}

void HotspotVisibilityOptions::check() const {
  if (!(camera_height_m > 0)) throw Error("hotspot visibility: camera height must be > 0");
  if (!(max_distance_m > 0)) throw Error("hotspot visibility: max distance must be > 0");
}

double camera_height_or_default(double capture_camera_height_m) {
  return capture_camera_height_m > 0 ? capture_camera_height_m : 1.6;
}

PlacedQuad place_hotspot_quad(const std::vector<SphericalAngles>& corners, const PathFrame& pose,
                              const FloorPlan& plan, const cv::Mat& depth,
                              const HotspotPlacementOptions& options) {
  options.check();
  if (corners.size() < 3) throw Error("a hotspot needs at least three corners");
  for (const auto& c : corners)
    if (!std::isfinite(c.azimuth) || !std::isfinite(c.elevation))
      throw Error("a hotspot corner is not finite");

  PlacedQuad result;
  std::string wall_problem;
  bool have_wall = false;
  try {
    result.quad = lift_quad_to_wall(corners, pose, plan, options.lift);
    result.placement = HotspotPlacement::kWall;
    have_wall = true;
    if (result.quad.warning.empty()) {
      result.message =
          "snapped to the wall it lies on (plan segment " + std::to_string(result.quad.wall_segment) + ")";
      return result;
    }
    wall_problem = result.quad.warning;
  } catch (const Error& e) {
    wall_problem = e.what();
  }
  if (!depth.empty()) {
    try {
      PlacedQuad from_depth;
      from_depth.quad = lift_quad_from_depth(corners, pose, depth, options.lift);
      from_depth.placement = HotspotPlacement::kDepth;
      from_depth.message = "placed from the depth map (" + wall_problem + ")";
      if (!from_depth.quad.warning.empty()) from_depth.message += "; " + from_depth.quad.warning;
      return from_depth;
    } catch (const Error& e) {
      wall_problem += "; depth: " + std::string(e.what());
    }
  }
  if (have_wall) {
    result.message = "snapped to a wall, but " + wall_problem;
    return result;
  }
  result.quad =
      lift_onto_facing_plane(corners, pose, options.lift.camera_height_m, options.fallback_distance_m);
  result.placement = HotspotPlacement::kFacingCamera;
  char distance[32];
  std::snprintf(distance, sizeof distance, "%.1f", options.fallback_distance_m);
  result.message = "no wall and no depth (" + wall_problem + "): placed on a plane facing the camera " +
                   distance + " m away";
  result.quad.warning = "not on a wall: placed facing the camera at a guessed distance";
  return result;
}

Plane3 fit_plane(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 3) throw Error("a plane needs at least three points");
  Plane3 plane;
  for (const auto& p : points) plane.point += p;
  plane.point /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : points) scatter += (p - plane.point) * (p - plane.point).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  // The two larger spreads span the plane; collinear points leave the normal undetermined.
  if (solver.eigenvalues()(1) < 1e-12 * std::max(1.0, solver.eigenvalues()(2)))
    throw Error("the hotspot's corners are on one line: no plane through them");
  plane.normal = solver.eigenvectors().col(0).normalized();
  double sum = 0;
  for (const auto& p : points) sum += std::pow(plane.normal.dot(p - plane.point), 2);
  plane.rms_m = std::sqrt(sum / static_cast<double>(points.size()));
  return plane;
}

Eigen::Vector3d point_on_quad_plane(const std::vector<Eigen::Vector3d>& quad, const SphericalAngles& angles,
                                    const PathFrame& pose, double camera_height_m) {
  const Plane3 plane = fit_plane(quad);
  const Eigen::Vector3d c(pose.x, pose.y, camera_height_m);
  const Eigen::Vector3d d = world_ray(angles, pose);
  const double denom = plane.normal.dot(d);
  if (std::abs(denom) < 1e-9) throw Error("the corner's ray runs along the hotspot's plane");
  const double t = plane.normal.dot(plane.point - c) / denom;
  if (t <= 0) throw Error("the corner's ray meets the hotspot's plane behind the camera");
  return c + t * d;
}

bool hotspot_visible_from(const std::vector<Eigen::Vector3d>& quad, const PathFrame& pose,
                          const FloorPlan& plan, const HotspotVisibilityOptions& options,
                          const PathFrame* authoring_pose) {
  options.check();
  if (quad.empty()) return false;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& p : quad) centre += p;
  centre /= static_cast<double>(quad.size());
  const Eigen::Vector3d eye(pose.x, pose.y, options.camera_height_m);
  const double distance = (centre - eye).norm();
  if (distance > options.max_distance_m) return false;
  // The end of the sight line: 5 cm off the quad on its front side.
  Eigen::Vector3d front = eye - centre;
  if (authoring_pose && quad.size() >= 3) {
    try {
      Eigen::Vector3d normal = fit_plane(quad).normal;
      const Eigen::Vector3d author(authoring_pose->x, authoring_pose->y, options.camera_height_m);
      if (normal.dot(author - centre) < 0) normal = -normal;
      if (normal.dot(eye - centre) <= 0) return false;  // behind the quad
      front = normal;
    } catch (const Error&) {
      // Collinear corners: no side to speak of; keep the sight line towards the camera.
    }
  }
  Eigen::Vector2d step = front.head<2>();
  const Eigen::Vector2d target = centre.head<2>();
  if (step.norm() < 1e-9) return true;  // a floor or ceiling quad right above or below
  const Eigen::Vector2d stop = target + 0.05 * step.normalized();
  const Eigen::Vector2d from = pose.position();
  for (const PlanSegment& s : plan.segments) {
    if (!s.occluder) continue;
    if (segments_cross(from, stop, s.a, s.b)) return false;
  }
  return true;
}

int position_to_show_hotspot(const Hotspot& hotspot, const CameraPath& path, const FloorPlan& plan,
                             int near_position, const HotspotVisibilityOptions& options) {
  const int n = static_cast<int>(path.frames.size());
  for (int i = 0; i < n; ++i)
    if (path.frames[static_cast<std::size_t>(i)].index == hotspot.frame) return i;
  if (hotspot.world_corners.empty()) return -1;
  // Outwards from near_position, alternating sides: the first visible frame is the nearest.
  near_position = std::clamp(near_position, 0, std::max(0, n - 1));
  for (int step = 0; step < n; ++step)
    for (int candidate : {near_position - step, near_position + step}) {
      if (candidate < 0 || candidate >= n) continue;
      if (hotspot_visible_from(hotspot.world_corners, path.frames[static_cast<std::size_t>(candidate)], plan,
                               options))
        return candidate;
    }
  return -1;
}

}  // namespace plenopath
