// What a real capture adds to the scene, each a deterministic function of the frame index (so any frame can
// be rendered alone, in any order): pitch and roll from an uneven floor, a camera height that rides up and
// down, the exposure's drift and steps, sensor noise.
#include <cmath>

#include "rig/render_internal.h"
#include "rig/scene_textures.h"

namespace plenopath {
namespace {

constexpr double kPi = M_PI;

std::uint64_t key(std::uint32_t seed, std::uint64_t what, long long index) {
  return mix_hash(mix_hash(seed * 0x9e3779b97f4a7c15ull + what) + static_cast<std::uint64_t>(index));
}

// A standard normal value from a key (Box-Muller on two hashed uniforms).
double hash_normal(std::uint64_t k) {
  const double u1 = std::max(hash_unit(k), 1e-300), u2 = hash_unit(k ^ 0x5555555555555555ull);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

// Smooth random walk: normal values at knots every `period` frames, Catmull-Rom in between.
double smooth_walk(std::uint32_t seed, std::uint64_t axis, double frame, double period) {
  const double x = frame / period;
  const long long k = static_cast<long long>(std::floor(x));
  const double t = x - static_cast<double>(k);
  const double p0 = hash_normal(key(seed, axis, k - 1)), p1 = hash_normal(key(seed, axis, k));
  const double p2 = hash_normal(key(seed, axis, k + 1)), p3 = hash_normal(key(seed, axis, k + 2));
  return 0.5 * ((2 * p1) + (-p0 + p2) * t + (2 * p0 - 5 * p1 + 4 * p2 - p3) * t * t +
                (-p0 + 3 * p1 - 3 * p2 + p3) * t * t * t);
}

}  // namespace

CameraTilt camera_tilt_at_frame(const RenderOptions& o, int frame_index) {
  CameraTilt tilt;
  const double deg = kPi / 180.0;
  tilt.pitch = o.pitch_deg * deg;
  tilt.roll = o.roll_deg * deg;
  if (o.tilt_wobble_deg > 0) {
    tilt.pitch += o.tilt_wobble_deg * deg * smooth_walk(o.tilt_seed, 1, frame_index, o.tilt_wobble_frames);
    tilt.roll += o.tilt_wobble_deg * deg * smooth_walk(o.tilt_seed, 2, frame_index, o.tilt_wobble_frames);
  }
  if (o.bump_deg > 0 && o.bumps_per_100_frames > 0) {
    // A wheel dropping over a floor joint: a jolt, then a ringing that dies out over about ten frames.
    constexpr int kRing = 16;
    for (int age = 0; age <= kRing; ++age) {
      const long long start = static_cast<long long>(frame_index) - age;
      if (hash_unit(key(o.tilt_seed, 3, start)) >= o.bumps_per_100_frames / 100.0) continue;
      const double envelope = std::exp(-age / 3.0) * std::cos(2.0 * kPi * age / 7.0);
      tilt.pitch += o.bump_deg * deg * (2.0 * hash_unit(key(o.tilt_seed, 4, start)) - 1.0) * envelope;
      tilt.roll += o.bump_deg * deg * (2.0 * hash_unit(key(o.tilt_seed, 5, start)) - 1.0) * envelope;
    }
  }
  return tilt;
}

double camera_height_offset_at_frame(const RenderOptions& o, int frame_index) {
  if (o.height_wobble_m <= 0) return 0.0;
  return o.height_wobble_m * smooth_walk(o.tilt_seed, 8, frame_index, o.height_wobble_frames);
}

Eigen::Matrix3d world_from_tilted_camera(double heading, const CameraTilt& tilt) {
  const double ch = std::cos(heading), sh = std::sin(heading);
  const double cp = std::cos(tilt.pitch), sp = std::sin(tilt.pitch);
  const double cr = std::cos(tilt.roll), sr = std::sin(tilt.roll);
  Eigen::Matrix3d rz, ry, rx;
  rz << ch, -sh, 0, sh, ch, 0, 0, 0, 1;
  ry << cp, 0, -sp, 0, 1, 0, sp, 0, cp;  // Ry(-pitch): +x towards +z
  rx << 1, 0, 0, 0, cr, -sr, 0, sr, cr;  // Rx(roll): +y towards +z
  return rz * ry * rx;
}

double exposure_gain_at_frame(const RenderOptions& o, int frame_index) {
  double gain = 1.0 + o.exposure_drift * std::sin(2 * kPi * frame_index / o.exposure_period_frames + 0.7);
  if (o.exposure_jump > 0) {
    // Steps at jittered frames: the k-th period [k E, (k + 1) E) has its step somewhere in its first 80 %.
    const double period = o.exposure_jump_frames;
    const long long k = static_cast<long long>(std::floor(frame_index / period));
    const double step_at = (static_cast<double>(k) + 0.8 * hash_unit(key(o.exposure_seed, 6, k))) * period;
    const long long level = frame_index >= step_at ? k : k - 1;
    gain *= std::exp(o.exposure_jump * (2.0 * hash_unit(key(o.exposure_seed, 7, level)) - 1.0));
  }
  return gain;
}

namespace render_detail {

void add_noise(cv::Mat& rgb, const RenderOptions& o, int frame_index) {
  if (o.noise_sigma <= 0) return;
  cv::RNG rng(mix_hash(0x4015eull + o.noise_seed * 1000003ull + static_cast<std::uint64_t>(frame_index)));
  cv::Mat noise(rgb.size(), CV_16SC3);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, o.noise_sigma);
  cv::Mat sum;
  cv::add(rgb, noise, sum, cv::noArray(), CV_16SC3);
  sum.convertTo(rgb, CV_8UC3);
}

}  // namespace render_detail
}  // namespace plenopath
