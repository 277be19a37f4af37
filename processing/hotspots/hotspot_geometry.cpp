#include "processing/hotspots/hotspot_geometry.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "model/error.h"

namespace plenopath {
namespace {

Eigen::Vector3d camera_centre(const PathFrame& pose, double camera_height_m) {
  return {pose.x, pose.y, camera_height_m};
}

Eigen::Vector3d world_ray(const SphericalAngles& a, const PathFrame& pose) {
  return world_from_camera_rotation(pose.heading) * angles_to_bearing(a);
}

// Fits a plane through the points; returns (unit normal, point on it, rms distance).
void fit_plane(const std::vector<Eigen::Vector3d>& points, Eigen::Vector3d* normal, Eigen::Vector3d* centroid,
               double* rms) {
  *centroid = Eigen::Vector3d::Zero();
  for (const auto& p : points) *centroid += p;
  *centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : points) scatter += (p - *centroid) * (p - *centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  *normal = solver.eigenvectors().col(0);
  double sum = 0;
  for (const auto& p : points) sum += std::pow(normal->dot(p - *centroid), 2);
  *rms = std::sqrt(sum / static_cast<double>(points.size()));
}

// Bilinear sample of a flat image at continuous coordinates (pixel centres at +0.5), clamped at the edges.
cv::Vec3b sample_clamped(const cv::Mat& image, double x, double y) {
  const double fx = std::clamp(x - 0.5, 0.0, image.cols - 1.0),
               fy = std::clamp(y - 0.5, 0.0, image.rows - 1.0);
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  const int x1 = std::min(x0 + 1, image.cols - 1), y1 = std::min(y0 + 1, image.rows - 1);
  const double tx = fx - x0, ty = fy - y0;
  cv::Vec3b out;
  for (int k = 0; k < 3; ++k) {
    const double top = (1 - tx) * image.at<cv::Vec3b>(y0, x0)[k] + tx * image.at<cv::Vec3b>(y0, x1)[k];
    const double bottom = (1 - tx) * image.at<cv::Vec3b>(y1, x0)[k] + tx * image.at<cv::Vec3b>(y1, x1)[k];
    out[k] = cv::saturate_cast<uchar>((1 - ty) * top + ty * bottom);
  }
  return out;
}

void check_corners(const std::vector<SphericalAngles>& corners) {
  if (corners.size() < 3) throw Error("a hotspot needs at least three corners");
  for (const auto& c : corners)
    if (!std::isfinite(c.azimuth) || !std::isfinite(c.elevation))
      throw Error("a hotspot corner is not finite");
}

}  // namespace

void HotspotLiftOptions::check() const {
  if (!(camera_height_m > 0)) throw Error("hotspot lift: camera height must be > 0");
  if (!(wall_height_m > 0)) throw Error("hotspot lift: wall height must be > 0");
  if (!(max_corner_spread_m > 0)) throw Error("hotspot lift: max corner spread must be > 0");
}

LiftedQuad lift_quad_to_wall(const std::vector<SphericalAngles>& corners, const PathFrame& pose,
                             const FloorPlan& plan, const HotspotLiftOptions& options) {
  options.check();
  check_corners(corners);
  const Eigen::Vector3d c = camera_centre(pose, options.camera_height_m);
  // The wall: the nearest occluder segment hit by the horizontal ray through the corners' mean direction.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& a : corners) mean += world_ray(a, pose);
  Eigen::Vector2d dir(mean.x(), mean.y());
  if (dir.norm() < 1e-9) throw Error("the hotspot is straight up or down: it cannot lie on a wall");
  dir.normalize();
  const Eigen::Vector2d origin = pose.position();
  const Eigen::Vector2d far_point = origin + 1e4 * dir;
  int best = -1;
  double best_t = 2.0;
  for (std::size_t i = 0; i < plan.segments.size(); ++i) {
    const PlanSegment& s = plan.segments[i];
    if (!s.occluder || s.length() < 1e-9) continue;
    const Eigen::Vector2d d = far_point - origin, e = s.b - s.a;
    const double denom = d.x() * e.y() - d.y() * e.x();
    if (std::abs(denom) < 1e-15) continue;
    const Eigen::Vector2d w = s.a - origin;
    const double t = (w.x() * e.y() - w.y() * e.x()) / denom;
    const double u = (w.x() * d.y() - w.y() * d.x()) / denom;
    if (t > 1e-9 && t < best_t && u >= -1e-9 && u <= 1 + 1e-9) {
      best_t = t;
      best = static_cast<int>(i);
    }
  }
  if (best < 0)
    throw Error("no wall of the plan is hit in the hotspot's direction: place it from depth instead");
  const PlanSegment& wall = plan.segments[static_cast<std::size_t>(best)];
  const Eigen::Vector2d along = (wall.b - wall.a).normalized();
  Eigen::Vector3d n(-along.y(), along.x(), 0.0);
  if (n.head<2>().dot(origin - wall.a) < 0) n = -n;  // face the camera
  const Eigen::Vector3d on_plane(wall.a.x(), wall.a.y(), 0.0);

  LiftedQuad quad;
  quad.normal = n;
  quad.wall_segment = best;
  for (const auto& a : corners) {
    const Eigen::Vector3d d = world_ray(a, pose);
    const double denom = n.dot(d);
    if (denom > -1e-9) throw Error("a hotspot corner's ray does not meet the wall's plane");
    quad.corners.push_back(c + (n.dot(on_plane - c) / denom) * d);
  }
  // Corners beyond the wall's ends or above its top suggest the quad straddles two surfaces.
  const double length = (wall.b - wall.a).norm();
  for (const auto& p : quad.corners) {
    const double u = along.dot(p.head<2>() - wall.a);
    if (u < -0.05 || u > length + 0.05) quad.warning = "the hotspot reaches past the end of its wall";
    if (p.z() < -0.05 || p.z() > options.wall_height_m + 0.05)
      quad.warning = "the hotspot reaches above or below its wall";
  }
  return quad;
}

LiftedQuad lift_quad_from_depth(const std::vector<SphericalAngles>& corners, const PathFrame& pose,
                                const cv::Mat& depth, const HotspotLiftOptions& options) {
  options.check();
  check_corners(corners);
  if (depth.empty() || depth.type() != CV_32FC1)
    throw Error("placing a hotspot from depth needs a depth map");
  const Eigen::Vector3d c = camera_centre(pose, options.camera_height_m);
  std::vector<Eigen::Vector3d> raw;
  for (const auto& a : corners) {
    const Eigen::Vector2d px = angles_to_equirect(a, depth.cols, depth.rows);
    float d = 0;
    // Nearest pixel, not bilinear: a corner on a depth edge must not average two surfaces.
    const int u = std::min(depth.cols - 1, static_cast<int>(px.x()));
    const int v = std::clamp(static_cast<int>(px.y()), 0, depth.rows - 1);
    d = depth.at<float>(v, u);
    if (!(d > 0)) throw Error("a hotspot corner has no depth (the ray hits nothing)");
    raw.push_back(c + d * world_ray(a, pose));
  }
  LiftedQuad quad;
  Eigen::Vector3d centroid;
  fit_plane(raw, &quad.normal, &centroid, &quad.planarity_rms_m);
  if (quad.normal.dot(c - centroid) < 0) quad.normal = -quad.normal;
  // Each corner where its own ray meets the fitted plane (keeps it on its marked direction).
  for (const auto& a : corners) {
    const Eigen::Vector3d d = world_ray(a, pose);
    const double denom = quad.normal.dot(d);
    if (std::abs(denom) < 1e-9) throw Error("a hotspot corner's ray is parallel to the fitted plane");
    quad.corners.push_back(c + (quad.normal.dot(centroid - c) / denom) * d);
  }
  if (quad.planarity_rms_m > options.max_corner_spread_m)
    quad.warning = "the corners are not on one plane in the depth map (rms " +
                   std::to_string(quad.planarity_rms_m) + " m)";
  return quad;
}

SphericalAngles direction_in_frame(const Eigen::Vector3d& world, const PathFrame& pose,
                                   double camera_height_m) {
  const Eigen::Vector3d v = world - camera_centre(pose, camera_height_m);
  return bearing_to_angles(world_from_camera_rotation(pose.heading).transpose() * v);
}

Eigen::Vector2d project_to_equirect(const Eigen::Vector3d& world, const PathFrame& pose,
                                    double camera_height_m, int width, int height) {
  return angles_to_equirect(direction_in_frame(world, pose, camera_height_m), width, height);
}

std::optional<Eigen::Vector2d> project_to_view(const Eigen::Vector3d& world, const PathFrame& pose,
                                               double camera_height_m, const PerspectiveView& view) {
  const Eigen::Vector3d v = world - camera_centre(pose, camera_height_m);
  const double cp = std::cos(view.pitch), sp = std::sin(view.pitch);
  const Eigen::Vector3d f(cp * std::cos(view.yaw), cp * std::sin(view.yaw), sp);
  const Eigen::Vector3d r(std::sin(view.yaw), -std::cos(view.yaw), 0.0);
  const Eigen::Vector3d u = r.cross(f);
  const double z = v.dot(f);
  if (z <= 1e-9) return std::nullopt;
  const double focal = 0.5 * view.height / std::tan(view.fov_y / 2);
  return Eigen::Vector2d(0.5 * view.width + focal * v.dot(r) / z, 0.5 * view.height - focal * v.dot(u) / z);
}

cv::Matx33d media_to_view_homography(const std::vector<Eigen::Vector3d>& quad, const PathFrame& pose,
                                     double camera_height_m, const PerspectiveView& view,
                                     cv::Size media_size) {
  if (quad.size() != 4) throw Error("a homography needs a quad of four corners");
  const double w = media_size.width, h = media_size.height;
  const Eigen::Vector2d from[4] = {{0, 0}, {w, 0}, {w, h}, {0, h}};
  // The 4-point homography in double precision (cv::getPerspectiveTransform works in float).
  Eigen::Matrix<double, 8, 8> a;
  Eigen::Matrix<double, 8, 1> b;
  for (int i = 0; i < 4; ++i) {
    const auto px = project_to_view(quad[static_cast<std::size_t>(i)], pose, camera_height_m, view);
    if (!px) throw Error("a hotspot corner is behind the viewer");
    const double x = from[i].x(), y = from[i].y(), u = px->x(), v = px->y();
    a.row(2 * i) << x, y, 1, 0, 0, 0, -u * x, -u * y;
    a.row(2 * i + 1) << 0, 0, 0, x, y, 1, -v * x, -v * y;
    b(2 * i) = u;
    b(2 * i + 1) = v;
  }
  const Eigen::Matrix<double, 8, 1> hv = a.fullPivLu().solve(b);
  return cv::Matx33d(hv(0), hv(1), hv(2), hv(3), hv(4), hv(5), hv(6), hv(7), 1.0);
}

int warp_media_into_equirect(cv::Mat& equirect, const cv::Mat& media,
                             const std::vector<Eigen::Vector3d>& quad, const PathFrame& pose,
                             double camera_height_m) {
  if (equirect.empty() || equirect.type() != CV_8UC3) throw Error("warp: the panorama must be 8-bit BGR");
  if (media.empty() || media.type() != CV_8UC3) throw Error("warp: the media must be 8-bit BGR");
  if (quad.size() != 4) throw Error("warp: a quad needs four corners");
  const Eigen::Vector3d c = camera_centre(pose, camera_height_m);
  // Plane coordinates: (s, t) with corner0 + s (c1 - c0) + t (c3 - c0); a bilinear patch inverse would be
  // exact for general quads, the parallelogram basis is exact for the rectangles lifted onto walls.
  const Eigen::Vector3d o = quad[0], e1 = quad[1] - quad[0], e2 = quad[3] - quad[0];
  const Eigen::Vector3d n = e1.cross(e2);
  if (n.norm() < 1e-12) throw Error("warp: the quad is degenerate");
  Eigen::Matrix<double, 3, 2> basis;
  basis << e1, e2;
  const Eigen::Matrix<double, 2, 3> solve = (basis.transpose() * basis).inverse() * basis.transpose();
  const Eigen::Matrix3d camera_from_world = world_from_camera_rotation(pose.heading).transpose();
  // Only the pixels inside the quad's angular bounding box are visited.
  double x_min = 1e9, x_max = -1e9, y_min = 1e9, y_max = -1e9;
  const double a0 = bearing_to_angles(camera_from_world * (quad[0] - c)).azimuth;
  for (const auto& p : quad) {
    const SphericalAngles a = bearing_to_angles(camera_from_world * (p - c));
    const double az = a0 + std::remainder(a.azimuth - a0, 2 * M_PI);  // unwrapped around corner 0
    const Eigen::Vector2d px = angles_to_equirect({az, a.elevation}, equirect.cols, equirect.rows);
    const double x = (az + M_PI) / (2 * M_PI) * equirect.cols;
    x_min = std::min(x_min, x);
    x_max = std::max(x_max, x);
    y_min = std::min(y_min, px.y());
    y_max = std::max(y_max, px.y());
  }
  int painted = 0;
  const int v0 = std::max(0, static_cast<int>(std::floor(y_min)) - 1);
  const int v1 = std::min(equirect.rows - 1, static_cast<int>(std::ceil(y_max)) + 1);
  const int u0 = static_cast<int>(std::floor(x_min)) - 1, u1 = static_cast<int>(std::ceil(x_max)) + 1;
  for (int v = v0; v <= v1; ++v)
    for (int uu = u0; uu <= u1; ++uu) {
      const int u = ((uu % equirect.cols) + equirect.cols) % equirect.cols;
      const Eigen::Vector3d d = world_from_camera_rotation(pose.heading) *
                                equirect_to_bearing({u + 0.5, v + 0.5}, equirect.cols, equirect.rows);
      const double denom = n.dot(d);
      if (std::abs(denom) < 1e-12) continue;
      const double t = n.dot(o - c) / denom;
      if (t <= 0) continue;
      const Eigen::Vector2d st = solve * (c + t * d - o);
      if (st.x() < 0 || st.x() > 1 || st.y() < 0 || st.y() > 1) continue;
      equirect.at<cv::Vec3b>(v, u) = sample_clamped(media, st.x() * media.cols, st.y() * media.rows);
      ++painted;
    }
  return painted;
}

double quad_consistency_m(const LiftedQuad& a, const LiftedQuad& b) {
  if (a.corners.size() != b.corners.size()) return INFINITY;
  double worst = 0;
  for (std::size_t i = 0; i < a.corners.size(); ++i)
    worst = std::max(worst, (a.corners[i] - b.corners[i]).norm());
  return worst;
}

}  // namespace plenopath
