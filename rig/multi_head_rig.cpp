#include "rig/multi_head_rig.h"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <set>

#include "model/atomic_file.h"
#include "model/error.h"
#include "model/option_check.h"
#include "rig/spherical.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace {

Eigen::Matrix3d rotation_z(double a) {
  Eigen::Matrix3d r;
  r << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return r;
}
Eigen::Matrix3d rotation_y(double a) {
  Eigen::Matrix3d r;
  r << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return r;
}
Eigen::Matrix3d rotation_x(double a) {
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return r;
}

}  // namespace

Eigen::Matrix3d PinholeHead::rig_from_head() const {
  Eigen::Matrix3d base;  // columns: right, down, forward of a head looking along +x
  base << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return rotation_z(-radians(yaw_deg)) * rotation_y(-radians(pitch_deg)) * rotation_x(radians(roll_deg)) *
         base;
}

Eigen::Vector3d PinholeHead::bearing(const Eigen::Vector2d& pixel) const {
  return (rig_from_head() * Eigen::Vector3d((pixel.x() - cx) / fx, (pixel.y() - cy) / fy, 1.0)).normalized();
}

bool PinholeHead::project(const Eigen::Vector3d& rig_direction, Eigen::Vector2d* pixel) const {
  const Eigen::Vector3d h = rig_from_head().transpose() * rig_direction;
  if (h.z() <= 1e-9 * rig_direction.norm()) return false;
  *pixel = Eigen::Vector2d(fx * h.x() / h.z() + cx, fy * h.y() / h.z() + cy);
  return true;
}

void MultiHeadRig::check() const {
  if (heads.empty()) throw Error("the rig has no heads");
  std::set<std::string> names;
  for (std::size_t i = 0; i < heads.size(); ++i) {
    const PinholeHead& h = heads[i];
    const std::string who = "head " + std::to_string(i) + " ('" + h.name + "')";
    if (h.name.empty()) throw Error("head " + std::to_string(i) + " has no name");
    if (!names.insert(h.name).second) throw Error("two heads are named '" + h.name + "'");
    if (h.width < 2 || h.height < 2 || h.width > 20000 || h.height > 20000)
      throw Error(who + ": size must be 2..20000 pixels");
    if (!(h.fx > 0) || !(h.fy > 0)) throw Error(who + ": fx and fy must be > 0");
    if (!std::isfinite(h.cx) || !std::isfinite(h.cy)) throw Error(who + ": cx and cy must be finite");
    if (!h.offset.allFinite() || h.offset.norm() > 1.0) throw Error(who + ": offset must be under 1 m");
  }
}

MultiHeadRig make_default_rig(const DefaultRigOptions& o) {
  MultiHeadRig rig;
  auto add = [&](const std::string& name, int w, int h, double hfov, double vfov, double yaw, double pitch) {
    PinholeHead head;
    head.name = name;
    head.width = w;
    head.height = h;
    head.fx = 0.5 * w / std::tan(radians(hfov) / 2);
    head.fy = 0.5 * h / std::tan(radians(vfov) / 2);
    head.cx = 0.5 * (w - 1);
    head.cy = 0.5 * (h - 1);
    head.yaw_deg = yaw;
    head.pitch_deg = pitch;
    head.offset = o.offset_radius * head.rig_from_head().col(2);
    rig.heads.push_back(head);
  };
  for (int i = 0; i < o.ring_heads; ++i)
    add("ring" + std::to_string(i), o.ring_width, o.ring_height, o.ring_horizontal_fov_deg,
        o.ring_vertical_fov_deg, 360.0 * i / o.ring_heads, 0.0);
  if (o.up) add("up", o.cap_size, o.cap_size, o.cap_fov_deg, o.cap_fov_deg, 0.0, 90.0);
  if (o.down) add("down", o.cap_size, o.cap_size, o.cap_fov_deg, o.cap_fov_deg, 0.0, -90.0);
  return rig;
}

nlohmann::json rig_to_json(const MultiHeadRig& rig) {
  nlohmann::json heads = nlohmann::json::array();
  for (const auto& h : rig.heads)
    heads.push_back({{"name", h.name},
                     {"width", h.width},
                     {"height", h.height},
                     {"fx", h.fx},
                     {"fy", h.fy},
                     {"cx", h.cx},
                     {"cy", h.cy},
                     {"yaw_deg", h.yaw_deg},
                     {"pitch_deg", h.pitch_deg},
                     {"roll_deg", h.roll_deg},
                     {"offset_m", {h.offset.x(), h.offset.y(), h.offset.z()}}});
  return {{"format", "plenopath-rig"}, {"version", 1}, {"heads", heads}};
}

MultiHeadRig rig_from_json(const JsonReader& r) {
  if (r.string_or("format", "plenopath-rig") != "plenopath-rig")
    r.at("format").fail("not a rig calibration (expected \"plenopath-rig\")");
  if (r.integer_or("version", 1) > 1) r.at("version").fail("made by a newer Plenopath (version > 1)");
  MultiHeadRig rig;
  const JsonReader heads = r.at("heads");
  for (std::size_t i = 0; i < heads.size(); ++i) {
    const JsonReader h = heads.at(i);
    PinholeHead head;
    head.name = h.string("name");
    head.width = h.integer("width");
    head.height = h.integer("height");
    head.fx = h.number("fx");
    head.fy = h.number("fy");
    head.cx = h.number_or("cx", 0.5 * (head.width - 1));
    head.cy = h.number_or("cy", 0.5 * (head.height - 1));
    head.yaw_deg = h.number_or("yaw_deg", 0.0);
    head.pitch_deg = h.number_or("pitch_deg", 0.0);
    head.roll_deg = h.number_or("roll_deg", 0.0);
    if (auto off = h.find("offset_m")) {
      if (off->size() != 3) off->fail("expected [x, y, z] in metres");
      head.offset = Eigen::Vector3d(off->at(0).number(), off->at(1).number(), off->at(2).number());
    }
    rig.heads.push_back(head);
  }
  try {
    rig.check();
  } catch (const Error& e) {
    throw file_error(r.file(), e.what());
  }
  return rig;
}

MultiHeadRig read_rig_file(const std::string& file) {
  const nlohmann::json j = read_json_file(file);
  return rig_from_json(JsonReader(j, file));
}

void write_rig_file(const MultiHeadRig& rig, const std::string& file) {
  try {
    rig.check();
  } catch (const Error& e) {
    throw file_error(file, e.what());
  }
  write_file_atomically(
      file, rig_to_json(rig).dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n", false);
}

std::vector<cv::Mat> render_heads(const SyntheticScene& scene, const MultiHeadRig& rig, const PathFrame& pose,
                                  const RenderOptions& options, std::vector<cv::Mat>* depths) {
  rig.check();
  const Eigen::Matrix3d world_from_rig = world_from_camera_rotation(pose.heading);
  const Eigen::Vector3d nodal(
      pose.x, pose.y, scene.options.camera_height + camera_height_offset_at_frame(options, pose.index));
  std::vector<cv::Mat> images;
  if (depths) depths->clear();
  for (const auto& head : rig.heads) {
    cv::Mat directions(head.height, head.width, CV_64FC3);
    const Eigen::Matrix3d world_from_head = world_from_rig * head.rig_from_head();
    for (int v = 0; v < head.height; ++v)
      for (int u = 0; u < head.width; ++u) {
        const Eigen::Vector3d d =
            world_from_head * Eigen::Vector3d((u - head.cx) / head.fx, (v - head.cy) / head.fy, 1.0);
        directions.at<cv::Vec3d>(v, u) = cv::Vec3d(d.x(), d.y(), d.z());
      }
    RenderedPanorama r = render_directions(scene, nodal + world_from_rig * head.offset, directions,
                                           1.0 / std::max(head.fx, head.fy), options, pose.index);
    images.push_back(r.rgb);
    if (depths) depths->push_back(r.depth);
  }
  return images;
}

void StitchOptions::check() const {
  require_option(width >= 8, "StitchOptions.width", "must be >= 8", width);
  require_option(height >= 4, "StitchOptions.height", "must be >= 4", height);
  require_option(feather > 0.0 && feather <= 1.0, "StitchOptions.feather", "must be in (0, 1]", feather);
  require_option(stitch_distance >= 0.0, "StitchOptions.stitch_distance", "must be >= 0", stitch_distance);
}

namespace {

// Where head `head` samples the panorama's bearing b, given the stitch distance.
bool head_pixel(const PinholeHead& head, const Eigen::Vector3d& b, double stitch_distance,
                Eigen::Vector2d* p) {
  const Eigen::Vector3d dir = stitch_distance > 0 ? Eigen::Vector3d(stitch_distance * b - head.offset) : b;
  return head.project(dir, p) && head.inside(*p);
}

double feather_weight(const PinholeHead& head, const Eigen::Vector2d& p, double feather) {
  const double dx = std::min(p.x() + 0.5, head.width - 0.5 - p.x()) / (feather * 0.5 * head.width);
  const double dy = std::min(p.y() + 0.5, head.height - 0.5 - p.y()) / (feather * 0.5 * head.height);
  const double t = std::clamp(std::min(dx, dy), 0.0, 1.0);
  return t * t * (3 - 2 * t) + 1e-6;  // smoothstep; never exactly 0 inside the image
}

}  // namespace

StitchMaps make_stitch_maps(const MultiHeadRig& rig, const StitchOptions& options) {
  rig.check();
  options.check();
  StitchMaps m;
  m.width = options.width;
  m.height = options.height;
  const std::size_t n = rig.heads.size();
  for (std::size_t i = 0; i < n; ++i) {
    m.map_x.emplace_back(options.height, options.width, CV_32F, cv::Scalar(-10));
    m.map_y.emplace_back(options.height, options.width, CV_32F, cv::Scalar(-10));
    m.weight.emplace_back(options.height, options.width, CV_32F, cv::Scalar(0));
  }
  m.coverage = cv::Mat::zeros(options.height, options.width, CV_8U);
  cv::parallel_for_(cv::Range(0, options.height), [&](const cv::Range& r) {
    for (int v = r.start; v < r.end; ++v)
      for (int u = 0; u < options.width; ++u) {
        const Eigen::Vector3d b = equirect_to_bearing({u + 0.5, v + 0.5}, options.width, options.height);
        double total = 0;
        int covered = 0;
        for (std::size_t i = 0; i < n; ++i) {
          Eigen::Vector2d p;
          if (!head_pixel(rig.heads[i], b, options.stitch_distance, &p)) continue;
          const double w = feather_weight(rig.heads[i], p, options.feather);
          m.map_x[i].at<float>(v, u) = static_cast<float>(p.x());
          m.map_y[i].at<float>(v, u) = static_cast<float>(p.y());
          m.weight[i].at<float>(v, u) = static_cast<float>(w);
          total += w;
          ++covered;
        }
        m.coverage.at<uchar>(v, u) = static_cast<uchar>(std::min(covered, 255));
        if (total > 0)
          for (std::size_t i = 0; i < n; ++i) m.weight[i].at<float>(v, u) /= static_cast<float>(total);
      }
  });
  return m;
}

cv::Mat stitch_heads(const StitchMaps& maps, const std::vector<cv::Mat>& head_images) {
  if (head_images.size() != maps.map_x.size())
    throw Error("stitch: " + std::to_string(head_images.size()) + " head images for a rig of " +
                std::to_string(maps.map_x.size()) + " heads");
  cv::Mat acc = cv::Mat::zeros(maps.height, maps.width, CV_32FC3);
  for (std::size_t i = 0; i < head_images.size(); ++i) {
    if (head_images[i].type() != CV_8UC3)
      throw Error("stitch: head image " + std::to_string(i) + " is not 8-bit BGR");
    cv::Mat warped, warped_f, w3;
    cv::remap(head_images[i], warped, maps.map_x[i], maps.map_y[i], cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    warped.convertTo(warped_f, CV_32FC3);
    cv::Mat channels[3] = {maps.weight[i], maps.weight[i], maps.weight[i]};
    cv::merge(channels, 3, w3);
    acc += warped_f.mul(w3);
  }
  cv::Mat out;
  acc.convertTo(out, CV_8UC3);
  return out;
}

SeamParallax seam_parallax(const MultiHeadRig& rig, const cv::Mat& depth, const StitchOptions& options) {
  if (depth.type() != CV_32F) throw Error("seam_parallax: depth must be CV_32F metres");
  SeamParallax result;
  double sum = 0;
  long count = 0, overlap = 0;
  const double px_per_radian = depth.cols / (2 * M_PI);
  for (int v = 0; v < depth.rows; ++v)
    for (int u = 0; u < depth.cols; ++u) {
      const Eigen::Vector3d b = equirect_to_bearing({u + 0.5, v + 0.5}, depth.cols, depth.rows);
      int covering = 0;
      double worst = 0;
      for (const auto& head : rig.heads) {
        Eigen::Vector2d assumed;
        if (!head_pixel(head, b, options.stitch_distance, &assumed)) continue;
        ++covering;
        const double r = depth.at<float>(v, u);
        Eigen::Vector2d actual;
        if (r <= 0 || !head.project(r * b - head.offset, &actual)) continue;
        worst = std::max(worst, (actual - assumed).norm() / std::max(head.fx, head.fy) * px_per_radian);
      }
      if (covering < 2) continue;
      ++overlap;
      sum += worst;
      ++count;
      result.max_px = std::max(result.max_px, worst);
    }
  result.mean_px = count ? sum / count : 0.0;
  result.overlap_fraction = static_cast<double>(overlap) / (static_cast<double>(depth.rows) * depth.cols);
  return result;
}

std::array<cv::Mat, 6> equirect_to_cube(const cv::Mat& equirect, int face_size) {
  if (equirect.empty() || face_size < 1) throw Error("equirect_to_cube: empty image or bad face size");
  // One extra column on each side (wrapped) and row (replicated), so sampling crosses the seam.
  cv::Mat wrapped, padded;
  cv::copyMakeBorder(equirect, wrapped, 0, 0, 1, 1, cv::BORDER_WRAP);
  cv::copyMakeBorder(wrapped, padded, 1, 1, 0, 0, cv::BORDER_REPLICATE);
  std::array<cv::Mat, 6> faces;
  for (int f = 0; f < kCubeFaceCount; ++f) {
    cv::Mat mx(face_size, face_size, CV_32F), my(face_size, face_size, CV_32F);
    for (int j = 0; j < face_size; ++j)
      for (int i = 0; i < face_size; ++i) {
        const Eigen::Vector3d b =
            cube_face_to_bearing(static_cast<CubeFace>(f), {i + 0.5, j + 0.5}, face_size);
        const Eigen::Vector2d p = bearing_to_equirect(b, equirect.cols, equirect.rows);
        mx.at<float>(j, i) = static_cast<float>(p.x() - 0.5 + 1.0);
        my.at<float>(j, i) = static_cast<float>(p.y() - 0.5 + 1.0);
      }
    cv::remap(padded, faces[f], mx, my, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  }
  return faces;
}

cv::Mat cube_to_equirect(const std::array<cv::Mat, 6>& faces, int width, int height) {
  const int size = faces[0].cols;
  for (const auto& f : faces)
    if (f.empty() || f.cols != size || f.rows != size || f.type() != faces[0].type())
      throw Error("cube_to_equirect: the six faces must be square images of one size and type");
  cv::Mat out(height, width, faces[0].type(), cv::Scalar::all(0));
  std::vector<cv::Mat> mx(6), my(6), mask(6);
  for (int f = 0; f < 6; ++f) {
    mx[f] = cv::Mat(height, width, CV_32F, cv::Scalar(-1));
    my[f] = cv::Mat(height, width, CV_32F, cv::Scalar(-1));
    mask[f] = cv::Mat::zeros(height, width, CV_8U);
  }
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      const CubeFacePixel p =
          bearing_to_cube_face(equirect_to_bearing({u + 0.5, v + 0.5}, width, height), size);
      const int f = static_cast<int>(p.face);
      mx[f].at<float>(v, u) = static_cast<float>(p.pixel.x() - 0.5);
      my[f].at<float>(v, u) = static_cast<float>(p.pixel.y() - 0.5);
      mask[f].at<uchar>(v, u) = 255;
    }
  for (int f = 0; f < 6; ++f) {
    cv::Mat warped;
    cv::remap(faces[f], warped, mx[f], my[f], cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    warped.copyTo(out, mask[f]);
  }
  return out;
}

double psnr(const cv::Mat& a, const cv::Mat& b, const cv::Mat& mask) {
  if (a.size() != b.size() || a.type() != b.type()) throw Error("psnr: images differ in size or type");
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  diff.convertTo(diff, CV_64F);
  diff = diff.mul(diff);
  if (!mask.empty()) diff.setTo(cv::Scalar::all(0), mask == 0);
  const cv::Scalar sum = cv::sum(diff);
  double total = 0;
  for (int k = 0; k < a.channels(); ++k) total += sum[k];
  const double n = (mask.empty() ? static_cast<double>(a.total()) : cv::countNonZero(mask)) * a.channels();
  const double mse = total / std::max(n, 1.0);
  return mse <= 0 ? 99.0 : 10.0 * std::log10(255.0 * 255.0 / mse);
}

}  // namespace plenopath
