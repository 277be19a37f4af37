#include "processing/export/trajectory_formats.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

namespace plenopath {

Eigen::Matrix3d world_from_pano_camera(double heading) {
  const double c = std::cos(heading), s = std::sin(heading);
  Eigen::Matrix3d r;
  // columns: right (plan angle heading - 90 deg), down, forward (plan angle heading)
  r << s, 0, c,  //
      -c, 0, s,  //
      0, -1, 0;
  return r;
}

WorldCamera world_camera(const Project& project, const PathFrame& frame) {
  const GeoAnchor& geo = project.geo;
  // The anchor's rotation turns plan angles into east/north ones; its scale applies to the ground only.
  const Eigen::Vector2d ground = geo.valid ? geo.enu_from_plan(frame.position()) : frame.position();
  WorldCamera c;
  c.centre = {ground.x(), ground.y(), std::max(0.0, project.capture.camera_height_m)};
  c.heading = frame.heading + (geo.valid ? geo.plan_rotation : 0.0);
  return c;
}

std::string tum_trajectory(const Project& project) {
  const double z = std::max(0.0, project.capture.camera_height_m);
  std::string out =
      "# Plenopath Studio camera path: world = plan (metres, X right, Y up, Z up), z = camera height\n"
      "# camera axes: x right of the panorama centre, y down, z forward (the centre column)\n"
      "# timestamp tx ty tz qx qy qz qw\n";
  char line[256];
  for (const PathFrame& f : project.path.frames) {
    Eigen::Quaterniond q(world_from_pano_camera(f.heading));
    q.normalize();
    if (q.w() < 0) q.coeffs() = -q.coeffs();  // one of the two signs, so that files compare line by line
    std::snprintf(line, sizeof line, "%.6f %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n",
                  project.capture.time_at_index_s(f.index), f.x, f.y, z, q.x(), q.y(), q.z(), q.w());
    out += line;
  }
  return out;
}

}  // namespace plenopath
