// The render loops of the synthetic camera: the equirectangular panorama (level or tilted, with the trolley
// and its operator), single rays, and images along arbitrary directions (pinhole heads, cube faces).
#include <algorithm>
#include <cmath>
#include <functional>
#include <opencv2/core/utility.hpp>

#include "model/error.h"
#include "model/option_check.h"
#include "rig/render_internal.h"
#include "rig/scene_textures.h"

namespace plenopath {

using namespace render_detail;

namespace render_detail {

FrameContext make_context(const SyntheticScene& scene, const RenderOptions& o, const Eigen::Vector3d& origin,
                          int frame_index) {
  FrameContext c;
  c.scene = &scene;
  c.origin = origin.head<2>();
  c.cam_z = origin.z();
  for (const auto& p : people_now(scene, o, frame_index))  // nobody stands inside the camera
    if ((p.pose.centre - c.origin).norm() > p.pose.radius + 0.05) c.people.push_back(p);
  for (const auto& fp : scene.footprints) c.footprint_tops.push_back(static_cast<float>(fp.top));
  for (const auto& p : c.people) c.footprint_tops.push_back(static_cast<float>(p.pose.height));
  for (std::size_t i = 0; i < scene.footprints.size(); ++i)
    if (point_in_polygon(scene.footprints[i].points, c.origin)) c.start_footprint = static_cast<int>(i);
  c.gain = static_cast<float>(exposure_gain_at_frame(o, frame_index));
  return c;
}

}  // namespace render_detail

void RenderOptions::check() const {
  const std::string s = "RenderOptions.";
  require_option(width >= 8 && width <= 32768, s + "width", "must be in [8, 32768]", width);
  require_option(height >= 4 && height <= 16384, s + "height", "must be in [4, 16384]", height);
  require_option(threads >= 0, s + "threads", "must be >= 0", threads);
  require_option(noise_sigma >= 0.0 && noise_sigma <= 100.0, s + "noise_sigma", "must be in [0, 100]",
                 noise_sigma);
  require_option(exposure_drift >= 0.0 && exposure_drift < 1.0, s + "exposure_drift", "must be in [0, 1)",
                 exposure_drift);
  require_option(exposure_period_frames > 0.0, s + "exposure_period_frames", "must be > 0",
                 exposure_period_frames);
  require_option(people >= 0 && people <= 1000, s + "people", "must be in [0, 1000]", people);
  require_option(frame_rate > 0.0, s + "frame_rate", "must be > 0", frame_rate);
  require_option(jpeg_quality >= 1 && jpeg_quality <= 100, s + "jpeg_quality", "must be in [1, 100]",
                 jpeg_quality);
  require_option(exposure_jump >= 0.0 && exposure_jump <= 2.0, s + "exposure_jump", "must be in [0, 2]",
                 exposure_jump);
  require_option(exposure_jump_frames >= 1.0, s + "exposure_jump_frames", "must be >= 1",
                 exposure_jump_frames);
  require_option(tilt_wobble_deg >= 0.0 && tilt_wobble_deg <= 20.0, s + "tilt_wobble_deg",
                 "must be in [0, 20]", tilt_wobble_deg);
  require_option(tilt_wobble_frames >= 1.0, s + "tilt_wobble_frames", "must be >= 1", tilt_wobble_frames);
  require_option(bump_deg >= 0.0 && bump_deg <= 20.0, s + "bump_deg", "must be in [0, 20]", bump_deg);
  require_option(bumps_per_100_frames >= 0.0 && bumps_per_100_frames <= 100.0, s + "bumps_per_100_frames",
                 "must be in [0, 100]", bumps_per_100_frames);
  require_option(std::abs(pitch_deg) <= 45.0, s + "pitch_deg", "must be in [-45, 45]", pitch_deg);
  require_option(std::abs(roll_deg) <= 45.0, s + "roll_deg", "must be in [-45, 45]", roll_deg);
  require_option(height_wobble_m >= 0.0 && height_wobble_m <= 0.3, s + "height_wobble_m",
                 "must be in [0, 0.3] m", height_wobble_m);
  require_option(height_wobble_frames > 0.0, s + "height_wobble_frames", "must be > 0", height_wobble_frames);
  require_option(operator_distance_m >= 0.4 && operator_distance_m <= 3.0, s + "operator_distance_m",
                 "must be in [0.4, 3] m", operator_distance_m);
}

// ---- rendering
RenderedPanorama render_panorama(const SyntheticScene& scene, const PathFrame& pose,
                                 const RenderOptions& options) {
  RenderedPanorama out;
  render_panorama(scene, pose, options, out);
  return out;
}

void render_panorama(const SyntheticScene& scene, const PathFrame& pose, const RenderOptions& options,
                     RenderedPanorama& out) {
  options.check();
  if (!scene.textures) throw Error("render_panorama: the scene was not built with build_synthetic_scene");
  const int w = options.width, h = options.height;
  const double cam_h = scene.options.camera_height + camera_height_offset_at_frame(options, pose.index);
  const FrameContext ctx = make_context(scene, options, {pose.x, pose.y, cam_h}, pose.index);
  const CameraTilt tilt = camera_tilt_at_frame(options, pose.index);
  const std::vector<RigSolid> solids = rig_solids(options, cam_h);

  std::vector<ColumnRay> columns(w);
  // threads == 1 keeps everything on the calling thread; otherwise OpenCV's pool does the work.
  const int stripes = std::max(1, cv::getNumThreads());
  auto run = [&options](const cv::Range& range, int nstripes,
                        const std::function<void(const cv::Range&)>& body) {
    if (options.threads == 1)
      body(range);
    else
      cv::parallel_for_(range, body, nstripes);
  };
  run(cv::Range(0, w), stripes * 4, [&](const cv::Range& r) {
    FaceStamps stamps;
    for (int u = r.start; u < r.end; ++u) {
      const double azimuth = (u + 0.5) / w * 2.0 * kPi - kPi;
      const double angle = pose.heading - azimuth;  // world angle of the column
      cast_column(ctx, Eigen::Vector2d(std::cos(angle), std::sin(angle)), columns[u], stamps);
    }
  });

  out.rgb.create(h, w, CV_8UC3);
  if (options.depth)
    out.depth.create(h, w, CV_32F);
  else
    out.depth.release();
  const double pixel_angle = 2.0 * kPi / w;
  // Per-row and per-column constants, then the pixels in tiles: neighbouring pixels of a tile sample
  // neighbouring texels, which keeps the textures' working set in cache.
  std::vector<RayRow> rows;
  rows.reserve(h);
  for (int v = 0; v < h; ++v) {
    const double elevation = kPi / 2.0 - (v + 0.5) / h * kPi;
    rows.emplace_back(std::tan(elevation), std::cos(elevation), std::sin(elevation));
  }
  std::vector<double> cos_a(w), sin_a(w);
  for (int u = 0; u < w; ++u) {
    const double azimuth = (u + 0.5) / w * 2.0 * kPi - kPi;
    cos_a[u] = std::cos(azimuth);
    sin_a[u] = std::sin(azimuth);
  }
  const bool tilted = tilt.any();
  const Eigen::Matrix3d world_from_camera = world_from_tilted_camera(pose.heading, tilt);
  const Eigen::Matrix3d level_from_camera = world_from_tilted_camera(0.0, tilt);
  const SceneTextures& textures = *scene.textures;
  // The solids a row can meet: those whose bounding sphere's elevation range (widened by the tilt for the
  // level ones) covers the row's.
  std::vector<std::vector<RigSolid>> row_solids(solids.empty() ? 0 : h);
  if (!solids.empty()) {
    const double slack = std::abs(tilt.pitch) + std::abs(tilt.roll) + 2.0 * kPi / h;
    for (const RigSolid& solid : solids) {
      const double distance = solid.centre.norm();
      const double centre_elevation = std::asin(std::clamp(solid.centre.z() / distance, -1.0, 1.0));
      const double spread = distance > solid.bound ? std::asin(solid.bound / distance) : kPi;
      const double lo = centre_elevation - spread - (solid.level ? slack : 2.0 * kPi / h);
      const double hi = centre_elevation + spread + (solid.level ? slack : 2.0 * kPi / h);
      for (int v = 0; v < h; ++v) {
        const double elevation = kPi / 2.0 - (v + 0.5) / h * kPi;
        if (elevation >= lo && elevation <= hi) row_solids[v].push_back(solid);
      }
    }
  }
  constexpr int kTileW = 64, kTileH = 32;
  const int tiles_x = (w + kTileW - 1) / kTileW, tiles_y = (h + kTileH - 1) / kTileH;
  run(cv::Range(0, tiles_x * tiles_y), stripes * 8, [&](const cv::Range& r) {
    ColumnRay own;  // a tilted pixel's own ray
    std::vector<int> candidates;
    Log2Memo memo;
    for (int t = r.start; t < r.end; ++t) {
      const int u0 = (t % tiles_x) * kTileW, v0 = (t / tiles_x) * kTileH;
      const int u1 = std::min(w, u0 + kTileW), v1 = std::min(h, v0 + kTileH);
      for (int v = v0; v < v1; ++v) {
        const RayRow& row = rows[v];
        cv::Vec3b* rgb = out.rgb.ptr<cv::Vec3b>(v);
        float* depth = options.depth ? out.depth.ptr<float>(v) : nullptr;
        for (int u = u0; u < u1; ++u) {
          auto b_camera = [&] {
            return Eigen::Vector3d(row.cos_e * cos_a[u], -row.cos_e * sin_a[u], row.sin_e);
          };
          cv::Vec3b colour;
          double distance = 0.0;
          if (!tilted) {
            const Hit hit = first_hit(ctx, columns[u], row);
            distance = hit.kind == SurfaceKind::kNone ? 0.0 : hit.d * row.sec_e;
            colour = shade(ctx, columns[u], hit, row, distance, pixel_angle, &memo);
          } else {
            const Eigen::Vector3d d = world_from_camera * b_camera();
            const double horizontal = std::hypot(d.x(), d.y());
            Hit hit;
            if (horizontal < 1e-12) {
              hit = vertical_hit(ctx, d.z() < 0, own, &distance);
              colour = shade(ctx, own, hit, RayRow(0.0, 0.0, d.z()), distance, pixel_angle);
            } else {
              // The columns cast at the camera's level azimuths bracket this ray's horizontal direction:
              // the faces they met are the ones it can meet (but for one narrower than a column's spacing).
              double azimuth = pose.heading - std::atan2(d.y(), d.x());
              azimuth -= 2.0 * kPi * std::floor((azimuth + kPi) / (2.0 * kPi));
              const double x = (azimuth + kPi) / (2.0 * kPi) * w - 0.5;
              int k0 = static_cast<int>(std::floor(x)) % w;
              if (k0 < 0) k0 += w;
              const int k1 = (k0 + 1) % w;
              candidates.clear();
              for (int k : {k0, k1})
                for (const Crossing& c : columns[k].crossings)
                  if (c.face >= 0) candidates.push_back(c.face);
              cast_from_candidates(ctx, Eigen::Vector2d(d.x(), d.y()) / horizontal, candidates, own);
              const RayRow tilted_row(d.z() / horizontal, horizontal, d.z());
              hit = first_hit(ctx, own, tilted_row);
              distance = hit.kind == SurfaceKind::kNone ? 0.0 : hit.d / horizontal;
              colour = shade(ctx, own, hit, tilted_row, distance, pixel_angle, &memo);
            }
          }
          if (!solids.empty() && !row_solids[v].empty()) {
            const Eigen::Vector3d b = b_camera();
            const Eigen::Vector3d b_level = tilted ? Eigen::Vector3d(level_from_camera * b) : b;
            const RigHit near = hit_rig(row_solids[v], textures, b, b_level, pixel_angle);
            if (near.kind != SurfaceKind::kNone && (distance == 0.0 || near.distance < distance)) {
              distance = near.distance;
              colour = to_bgr(near.colour * ctx.gain);
            }
          }
          rgb[u] = colour;
          if (depth) depth[u] = static_cast<float>(distance);
        }
      }
    }
  });
  add_noise(out.rgb, options, pose.index);
}

RayHit trace_ray(const SyntheticScene& scene, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                 const RenderOptions& options, int frame_index) {
  if (!scene.textures) throw Error("trace_ray: the scene was not built with build_synthetic_scene");
  const FrameContext ctx = make_context(scene, options, origin, frame_index);
  const Eigen::Vector3d d = direction.normalized();
  const double horizontal = std::hypot(d.x(), d.y());
  ColumnRay ray;
  const double pixel_angle = 2.0 * kPi / options.width;
  RayHit result;
  const double cos_e = horizontal, sin_e = d.z();
  if (horizontal < 1e-12) {  // straight up or down: no face can be met
    double dist = 0;
    const Hit hit = vertical_hit(ctx, d.z() < 0, ray, &dist);
    result.distance = dist;
    result.kind = hit.kind;
    result.bgr = shade(ctx, ray, hit, RayRow(0.0, 0.0, sin_e), dist, pixel_angle);
    return result;
  }
  FaceStamps stamps;
  cast_column(ctx, Eigen::Vector2d(d.x(), d.y()) / horizontal, ray, stamps);
  const double s = d.z() / horizontal;
  const RayRow row(s, cos_e, sin_e);
  const Hit hit = first_hit(ctx, ray, row);
  result.kind = hit.kind;
  result.distance = hit.kind == SurfaceKind::kNone ? 0.0 : hit.d / horizontal;
  result.bgr = shade(ctx, ray, hit, row, result.distance, pixel_angle);
  return result;
}

RenderedPanorama render_directions(const SyntheticScene& scene, const Eigen::Vector3d& origin,
                                   const cv::Mat& directions, double pixel_angle,
                                   const RenderOptions& options, int frame_index) {
  if (!scene.textures) throw Error("render_directions: the scene was not built with build_synthetic_scene");
  if (directions.type() != CV_64FC3) throw Error("render_directions: directions must be CV_64FC3");
  options.check();
  const FrameContext ctx = make_context(scene, options, origin, frame_index);
  RenderedPanorama out;
  out.rgb.create(directions.size(), CV_8UC3);
  out.depth.create(directions.size(), CV_32F);
  auto body = [&](const cv::Range& r) {
    ColumnRay ray;
    FaceStamps stamps;
    for (int v = r.start; v < r.end; ++v)
      for (int u = 0; u < directions.cols; ++u) {
        const cv::Vec3d& dv = directions.at<cv::Vec3d>(v, u);
        const Eigen::Vector3d d = Eigen::Vector3d(dv[0], dv[1], dv[2]).normalized();
        const double horizontal = std::hypot(d.x(), d.y());
        if (horizontal < 1e-12) {  // straight up or down: rare, use the general path
          const RayHit hit = trace_ray(scene, origin, d, options, frame_index);
          out.rgb.at<cv::Vec3b>(v, u) = hit.bgr;
          out.depth.at<float>(v, u) = static_cast<float>(hit.distance);
          continue;
        }
        cast_column(ctx, Eigen::Vector2d(d.x(), d.y()) / horizontal, ray, stamps);
        const RayRow row(d.z() / horizontal, horizontal, d.z());
        const Hit hit = first_hit(ctx, ray, row);
        const double distance = hit.kind == SurfaceKind::kNone ? 0.0 : hit.d / horizontal;
        out.rgb.at<cv::Vec3b>(v, u) = shade(ctx, ray, hit, row, distance, pixel_angle);
        out.depth.at<float>(v, u) = static_cast<float>(distance);
      }
  };
  if (options.threads == 1)
    body(cv::Range(0, directions.rows));
  else
    cv::parallel_for_(cv::Range(0, directions.rows), body, std::max(1, cv::getNumThreads()) * 4);
  add_noise(out.rgb, options, frame_index);
  return out;
}

}  // namespace plenopath
