// People walking through the synthetic scene: each walks back and forth along a free segment of the plan,
// a deterministic function of the people seed and the frame's time.
#include <cmath>

#include "rig/render_internal.h"
#include "rig/scene_textures.h"

namespace plenopath::render_detail {
namespace {

struct PersonTrack {
  Eigen::Vector2d a, b;
  double speed = 1.2;  // m/s
  double phase = 0.0;  // metres along the back-and-forth walk at t = 0
  cv::Vec3f shirt, trousers;
};

bool segment_blocked(const SyntheticScene& scene, const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                     double clearance) {
  for (const auto& f : scene.faces) {
    // Distance between segments pq and ab is small, or they cross.
    const Eigen::Vector2d e = f.b - f.a, d = q - p;
    const double denom = cross(d, e);
    if (std::abs(denom) > 1e-12) {
      const double t = cross(f.a - p, e) / denom, s = cross(f.a - p, d) / denom;
      if (t >= 0 && t <= 1 && s >= 0 && s <= 1) return true;
    }
    auto point_segment = [](const Eigen::Vector2d& x, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
      const Eigen::Vector2d ab = b - a;
      const double l2 = ab.squaredNorm();
      const double t = l2 > 0 ? std::clamp((x - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
      return (x - (a + t * ab)).norm();
    };
    if (point_segment(p, f.a, f.b) < clearance || point_segment(q, f.a, f.b) < clearance ||
        point_segment(f.a, p, q) < clearance || point_segment(f.b, p, q) < clearance)
      return true;
  }
  for (const auto& fp : scene.footprints)
    if (point_in_polygon(fp.points, p) || point_in_polygon(fp.points, q)) return true;
  return false;
}

std::vector<PersonTrack> people_tracks(const SyntheticScene& scene, int count, std::uint32_t seed) {
  std::vector<PersonTrack> tracks;
  for (int i = 0; i < count; ++i) {
    cv::RNG rng(mix_hash(0x5eed00ull + seed * 7919ull + static_cast<std::uint64_t>(i)));
    PersonTrack t;
    bool found = false;
    for (int attempt = 0; attempt < 500 && !found; ++attempt) {
      t.a = {rng.uniform(scene.floor_min.x(), scene.floor_max.x()),
             rng.uniform(scene.floor_min.y(), scene.floor_max.y())};
      const double angle = rng.uniform(0.0, 2 * kPi), length = rng.uniform(2.0, 7.0);
      t.b = t.a + length * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      found = !segment_blocked(scene, t.a, t.b, 0.4);
    }
    if (!found) continue;  // a plan too cramped for walkers
    t.speed = rng.uniform(0.8, 1.5);
    t.phase = rng.uniform(0.0, 20.0);
    t.shirt = cv::Vec3f(rng.uniform(0.3f, 1.3f), rng.uniform(0.3f, 1.3f), rng.uniform(0.3f, 1.3f));
    t.trousers = cv::Vec3f(rng.uniform(0.2f, 0.6f), rng.uniform(0.2f, 0.6f), rng.uniform(0.2f, 0.6f));
    tracks.push_back(t);
  }
  return tracks;
}

}  // namespace

std::vector<PersonNow> people_now(const SyntheticScene& scene, const RenderOptions& o, int frame_index) {
  std::vector<PersonNow> out;
  if (o.people <= 0) return out;
  const double time = frame_index / o.frame_rate;
  const auto tracks = people_tracks(scene, o.people, o.people_seed);
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const auto& t = tracks[i];
    const double len = (t.b - t.a).norm();
    double s = std::fmod(t.phase + t.speed * time, 2 * len);
    if (s > len) s = 2 * len - s;  // back and forth
    PersonNow p;
    p.pose.centre = t.a + (t.b - t.a) * (s / len);
    p.pose.id = static_cast<int>(i);
    p.shirt = t.shirt;
    p.trousers = t.trousers;
    out.push_back(p);
  }
  return out;
}

}  // namespace plenopath::render_detail

namespace plenopath {

std::vector<PersonPose> people_at_frame(const SyntheticScene& scene, const RenderOptions& options,
                                        int frame_index) {
  std::vector<PersonPose> out;
  for (const auto& p : render_detail::people_now(scene, options, frame_index)) out.push_back(p.pose);
  return out;
}

}  // namespace plenopath
