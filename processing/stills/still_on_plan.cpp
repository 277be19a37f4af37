#include "processing/stills/still_on_plan.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "model/error.h"

namespace plenopath {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

struct Walls {
  std::vector<Eigen::Vector2d> start, along;  // segment k: start[k] + s * along[k], s in [0, 1]
};

// The plan's sight-blocking segments; throws Error when it has none.
Walls walls_of(const FloorPlan& plan) {
  Walls walls;
  for (const PlanSegment& s : plan.occluder_segments())
    if ((s.b - s.a).squaredNorm() > 1e-12) walls.start.push_back(s.a), walls.along.push_back(s.b - s.a);
  if (walls.start.empty())
    throw Error("the plan has no sight-blocking segments: mark the walls' layer as blocking sight first");
  return walls;
}

// Distance from p along the unit direction to the first wall (kInf when none), and which wall.
double cast_ray(const Walls& walls, const Eigen::Vector2d& p, const Eigen::Vector2d& dir, int* wall) {
  double best = kInf;
  *wall = -1;
  for (std::size_t k = 0; k < walls.start.size(); ++k) {
    const Eigen::Vector2d& d = walls.along[k];
    const double denom = cross(dir, d);
    if (std::abs(denom) < 1e-12) continue;
    const Eigen::Vector2d ap = walls.start[k] - p;
    const double t = cross(ap, d) / denom;
    if (t <= 1e-6 || t >= best) continue;
    const double s = cross(ap, dir) / denom;
    if (s < -1e-9 || s > 1.0 + 1e-9) continue;
    best = t;
    *wall = static_cast<int>(k);
  }
  return best;
}

double distance_to_walls(const Walls& walls, const Eigen::Vector2d& p) {
  double best = kInf;
  for (std::size_t k = 0; k < walls.start.size(); ++k) {
    const Eigen::Vector2d& d = walls.along[k];
    const double len2 = d.squaredNorm();
    const double s = len2 > 0 ? std::clamp((p - walls.start[k]).dot(d) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (walls.start[k] + s * d - p).norm());
  }
  return best;
}

// The still's edges as truncated distance maps (CV_32F, work_width x work_width / 2): Canny on the grey
// image, thresholds from its own gradients (so exposure does not matter), across the seam. `all`: every
// edge (what the author is shown); with `oriented`, also oriented[k]: the edges whose direction lies within
// 30 deg of k * 45 deg (0: horizontal, 2: vertical), for oriented chamfer matching (see Scorer).
struct EdgeMaps {
  cv::Mat all;
  std::array<cv::Mat, 4> oriented;
};

EdgeMaps edge_maps(const cv::Mat& still, int width, double truncation, bool oriented) {
  cv::Mat grey;
  if (still.channels() == 3)
    cv::cvtColor(still, grey, cv::COLOR_BGR2GRAY);
  else if (still.channels() == 4)
    cv::cvtColor(still, grey, cv::COLOR_BGRA2GRAY);
  else
    grey = still;
  if (grey.depth() != CV_8U) grey.convertTo(grey, CV_8U);
  cv::Mat small;
  cv::resize(grey, small, cv::Size(width, width / 2), 0, 0, cv::INTER_AREA);
  const int pad = 32;
  cv::Mat padded;
  cv::copyMakeBorder(small, padded, 0, 0, pad, pad, cv::BORDER_WRAP);
  cv::GaussianBlur(padded, padded, cv::Size(5, 5), 1.0);
  cv::Mat gx, gy, magnitude;
  cv::Sobel(padded, gx, CV_32F, 1, 0);
  cv::Sobel(padded, gy, CV_32F, 0, 1);
  cv::magnitude(gx, gy, magnitude);
  std::vector<float> values(magnitude.begin<float>(), magnitude.end<float>());
  const std::size_t at = values.size() * 85 / 100;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(at), values.end());
  const double high = std::max(20.0, static_cast<double>(values[at]));
  cv::Mat edges;
  cv::Canny(padded, edges, 0.4 * high, high, 3, true);
  const auto distance_to = [&](const cv::Mat& on) {
    cv::Mat distance;
    cv::distanceTransform(on == 0, distance, cv::DIST_L2, 3);
    cv::Mat out = distance(cv::Rect(pad, 0, width, width / 2)).clone();
    cv::min(out, truncation, out);
    return out;
  };
  EdgeMaps maps;
  maps.all = distance_to(edges);
  if (!oriented) return maps;
  std::array<cv::Mat, 4> on;
  for (cv::Mat& m : on) m = cv::Mat::zeros(edges.size(), CV_8U);
  for (int r = 0; r < edges.rows; ++r)
    for (int c = 0; c < edges.cols; ++c) {
      if (!edges.at<std::uint8_t>(r, c)) continue;
      // The edge runs across its gradient: direction (-gy, gx), image rows down; mod 180 deg.
      double direction = std::atan2(gx.at<float>(r, c), -gy.at<float>(r, c)) * 180.0 / M_PI;
      if (direction < 0) direction += 180.0;
      for (int k = 0; k < 4; ++k) {
        const double off = std::abs(std::remainder(direction - 45.0 * k, 180.0));
        if (off <= 30.0) on[static_cast<std::size_t>(k)].at<std::uint8_t>(r, c) = 255;
      }
    }
  for (std::size_t k = 0; k < 4; ++k) maps.oriented[k] = distance_to(on[k]);
  return maps;
}

// The orientation bin (EdgeMaps::oriented) of a curve direction (dx, dy) in image pixels, rows down.
int orientation_bin(double dx, double dy) {
  double direction = std::atan2(dy, dx) * 180.0 / M_PI;
  if (direction < 0) direction += 180.0;
  return static_cast<int>(std::lround(direction / 45.0)) % 4;
}

// Bilinear sample at continuous pixel coordinates (pixel u covers [u, u + 1)), wrapping across the seam.
double sample(const cv::Mat& map, double x, double y) {
  const int w = map.cols, h = map.rows;
  const double u = x - 0.5, v = std::clamp(y - 0.5, 0.0, h - 1.0);
  const int u0 = static_cast<int>(std::floor(u)), v0 = std::min(static_cast<int>(v), h - 2);
  const double fu = u - u0, fv = v - v0;
  const int a = ((u0 % w) + w) % w, b = (a + 1) % w;
  const float* r0 = map.ptr<float>(v0);
  const float* r1 = map.ptr<float>(v0 + 1);
  return (1 - fv) * ((1 - fu) * r0[a] + fu * r0[b]) + fv * ((1 - fu) * r1[a] + fu * r1[b]);
}

// What the plan looks like from one spot: the distance to the first wall at world angles (m - 0.5) * step
// for m = 0 .. W-1, and the vertical edges between neighbouring rays (corners, jambs).
struct PlanProfile {
  std::vector<double> distance;
  struct Vertical {
    int m;            // the edge lies at world angle m * step, between rays m - 1 and m
    double distance;  // the nearer side's
  };
  std::vector<Vertical> verticals;
  // Filled by Scorer::profile_at: the floor line's row in the still at each angle (NaN: no wall, or below
  // the nadir limit), and the orientation bin of the line there.
  std::vector<double> floor_row;
  std::vector<std::uint8_t> floor_bin;
};

PlanProfile plan_profile(const Walls& walls, const Eigen::Vector2d& p, int width) {
  PlanProfile profile;
  const double step = 2.0 * M_PI / width;
  profile.distance.resize(static_cast<std::size_t>(width));
  std::vector<int> wall(static_cast<std::size_t>(width));
  for (int m = 0; m < width; ++m) {
    const double angle = (m - 0.5) * step;
    profile.distance[m] = cast_ray(walls, p, {std::cos(angle), std::sin(angle)}, &wall[m]);
  }
  for (int m = 0; m < width; ++m) {
    const int prev = (m + width - 1) % width;
    const double d0 = profile.distance[prev], d1 = profile.distance[m];
    if (wall[prev] == wall[m] || !std::isfinite(d0) || !std::isfinite(d1)) continue;
    const double nearer = std::min(d0, d1);
    const bool jump = std::abs(d0 - d1) > 0.1 * nearer;
    const Eigen::Vector2d a = walls.along[wall[prev]].normalized(), b = walls.along[wall[m]].normalized();
    const bool corner = std::abs(cross(a, b)) > std::sin(15.0 * M_PI / 180.0);
    if (jump || corner) profile.verticals.push_back({m, nearer});
  }
  return profile;
}

// Chamfer matching of the plan's curves with the still's edges. With `oriented`, each curve pixel is
// compared with the edges that run its way only (a wall's vertical edge with vertical edges, the floor
// line with edges along it): a tiled floor's edges run every way and otherwise fit a wall anywhere over
// it (the POV-Ray gallery: one click placed 6 of 17 stills a metre off, at a spot where columns drawn
// over the chequered floor fitted better than at the truth).
struct Scorer {
  const EdgeMaps& maps;
  int width, height;
  double camera_height, top_above, nadir_limit;
  bool oriented = true;

  double row_of(double elevation) const { return (M_PI / 2 - elevation) / M_PI * height; }
  const cv::Mat& map(int bin) const {
    return oriented ? maps.oriented[static_cast<std::size_t>(bin)] : maps.all;
  }

  // The plan's profile from p, with the floor line's rows and orientations.
  PlanProfile profile_at(const Walls& walls, const Eigen::Vector2d& p) const {
    PlanProfile profile = plan_profile(walls, p, width);
    profile.floor_row.resize(static_cast<std::size_t>(width));
    profile.floor_bin.assign(static_cast<std::size_t>(width), 0);
    for (int m = 0; m < width; ++m) {
      const double d = profile.distance[static_cast<std::size_t>(m)];
      const double e = std::isfinite(d) ? -std::atan(camera_height / d) : -M_PI;
      profile.floor_row[static_cast<std::size_t>(m)] =
          e < nadir_limit ? std::numeric_limits<double>::quiet_NaN() : row_of(e);
    }
    // Column u sees index m = j - u + W/2: the next column, m - 1.
    for (int m = 0; m < width; ++m) {
      const double row = profile.floor_row[static_cast<std::size_t>(m)];
      const double before = profile.floor_row[static_cast<std::size_t>((m + 1) % width)];
      const double after = profile.floor_row[static_cast<std::size_t>((m + width - 1) % width)];
      const double dy = !std::isnan(before) && !std::isnan(after) ? (after - before) / 2.0
                        : !std::isnan(after)                      ? after - row
                        : !std::isnan(before)                     ? row - before
                                                                  : 0.0;
      profile.floor_bin[static_cast<std::size_t>(m)] = static_cast<std::uint8_t>(orientation_bin(1.0, dy));
    }
    return profile;
  }

  // Mean chamfer distance of the plan's curves (profile_at) with the still's centre at world angle
  // j * step; `stride` > 1 samples every stride-th column and row (the coarse pass).
  double score(const PlanProfile& profile, int j, int stride, int* samples = nullptr) const {
    double sum = 0.0;
    int count = 0;
    const int half = width / 2;
    for (int u = 0; u < width; u += stride) {
      const std::size_t m = static_cast<std::size_t>(((j - u + half) % width + width) % width);
      const double row = profile.floor_row[m];
      if (std::isnan(row)) continue;
      sum += sample(map(profile.floor_bin[m]), u + 0.5, row);
      ++count;
    }
    const cv::Mat& vertical = map(2);
    for (const PlanProfile::Vertical& v : profile.verticals) {
      const double x = j - v.m + half;
      const double y_top = row_of(std::atan(top_above / v.distance));
      const double y_floor = row_of(std::max(nadir_limit, -std::atan(camera_height / v.distance)));
      for (double y = y_top; y <= y_floor; y += stride) {
        sum += sample(vertical, x, y);
        ++count;
      }
    }
    if (samples) *samples = count;
    return count > 0 ? sum / count : kInf;
  }
};

double wrap_degrees(double deg) {
  deg = std::fmod(deg, 360.0);
  if (deg <= -180.0) deg += 360.0;
  if (deg > 180.0) deg -= 360.0;
  return deg;
}

}  // namespace

void StillOnPlanOptions::check() const {
  if (!(camera_height_m > 0)) throw Error("camera_height_m must be > 0");
  if (!(search_radius_m >= 0)) throw Error("search_radius_m must be >= 0");
  if (!(coarse_step_m > 0) || !(fine_step_m > 0) || fine_step_m > coarse_step_m)
    throw Error("coarse_step_m and fine_step_m must be > 0, fine no larger than coarse");
  if (candidates < 1) throw Error("candidates must be >= 1");
  if (work_width < 360 || work_width % 4) throw Error("work_width must be >= 360 and a multiple of 4");
  if (!(truncation_px > 0)) throw Error("truncation_px must be > 0");
  if (!(top_above_camera_m >= 0)) throw Error("top_above_camera_m must be >= 0");
  if (!(nadir_limit_deg > -90 && nadir_limit_deg < 0)) throw Error("nadir_limit_deg must be in (-90, 0)");
  if (heading_hint_deg && !std::isfinite(*heading_hint_deg)) throw Error("heading_hint_deg must be finite");
  if (!(heading_hint_spread_deg > 0)) throw Error("heading_hint_spread_deg must be > 0");
  if (!(elsewhere_gap_m >= 0)) throw Error("elsewhere_gap_m must be >= 0");
}

namespace {

// The search itself: every spot (those clear of the walls), every heading allowed, coarse, then the best few
// refined. `click` is only for the summary's "m from the click".
StillPlacement place_still_at_spots(const cv::Mat& still, const FloorPlan& plan,
                                    const std::vector<Eigen::Vector2d>& spots, const Eigen::Vector2d& click,
                                    const StillOnPlanOptions& options, Progress& progress) {
  options.check();
  const auto started = std::chrono::steady_clock::now();
  if (still.empty()) throw Error("the still is empty");
  const Walls walls = walls_of(plan);

  const int width = options.work_width;
  const double step = 2.0 * M_PI / width;
  progress.checkpoint(0.02, "edges of the still");
  const EdgeMaps maps = edge_maps(still, width, options.truncation_px, options.oriented_edges);
  const Scorer scorer{maps,
                      width,
                      width / 2,
                      options.camera_height_m,
                      options.top_above_camera_m,
                      options.nadir_limit_deg * M_PI / 180.0,
                      options.oriented_edges};

  // Headings tried: all, or those near the author's hint.
  const int coarse_heading = width / 360;  // 1 deg
  std::vector<int> headings;
  for (int j = 0; j < width; j += coarse_heading) {
    if (options.heading_hint_deg) {
      const double diff = wrap_degrees(j * step * 180.0 / M_PI - *options.heading_hint_deg);
      if (std::abs(diff) > options.heading_hint_spread_deg) continue;
    }
    headings.push_back(j);
  }

  // Coarse: every spot clear of the walls, every heading.
  std::vector<Eigen::Vector2d> positions;
  for (const Eigen::Vector2d& p : spots)
    if (distance_to_walls(walls, p) >= options.min_wall_distance_m) positions.push_back(p);
  if (positions.empty())
    throw Error("no spot within " + std::to_string(options.search_radius_m) +
                " m of the click is clear of the walls: click inside the room");
  struct Pose {
    double score;
    Eigen::Vector2d p;
    int j;
  };
  // Every position's headings that score better than both their neighbours (the others can be neither a
  // seed nor the runner-up: a neighbour within a degree beats them); a search over a whole room tries
  // thousands of positions.
  std::vector<Pose> coarse;
  const int coarse_stride = 4;
  const bool all_round = !options.heading_hint_deg;
  std::vector<double> scores(headings.size());
  for (std::size_t q = 0; q < positions.size(); ++q) {
    if (q % 16 == 0)
      progress.checkpoint(0.05 + 0.55 * q / positions.size(), "trying the spots around the click");
    const PlanProfile profile = scorer.profile_at(walls, positions[q]);
    for (std::size_t h = 0; h < headings.size(); ++h)
      scores[h] = scorer.score(profile, headings[h], coarse_stride);
    const std::size_t n = headings.size();
    for (std::size_t h = 0; h < n; ++h) {
      const bool has_before = all_round || h > 0, has_after = all_round || h + 1 < n;
      const double before = has_before ? scores[(h + n - 1) % n] : kInf;
      const double after = has_after ? scores[(h + 1) % n] : kInf;
      if (scores[h] <= before && scores[h] <= after) coarse.push_back({scores[h], positions[q], headings[h]});
    }
  }
  std::sort(coarse.begin(), coarse.end(), [](const Pose& a, const Pose& b) { return a.score < b.score; });

  // The best few distinct coarse poses, each refined on the fine grid.
  std::vector<Pose> seeds;
  for (const Pose& c : coarse) {
    bool distinct = true;
    for (const Pose& s : seeds)
      distinct = distinct && ((c.p - s.p).norm() > 2.5 * options.coarse_step_m ||
                              std::abs(wrap_degrees((c.j - s.j) * step * 180 / M_PI)) > 5.0);
    if (distinct) seeds.push_back(c);
    if (static_cast<int>(seeds.size()) >= options.candidates) break;
  }
  // The best few coarse poses away from the best one too, refined alike: the fit elsewhere, to tell a
  // placement from one of several look-alike spots.
  if (options.elsewhere_gap_m > 0) {
    const std::size_t near_seeds = seeds.size();
    for (const Pose& c : coarse) {
      if ((c.p - seeds.front().p).norm() <= options.elsewhere_gap_m) continue;
      bool distinct = true;  // look-alike spots elsewhere, each a gap from the others
      for (std::size_t s = near_seeds; s < seeds.size(); ++s)
        distinct = distinct && (c.p - seeds[s].p).norm() > options.elsewhere_gap_m;
      if (distinct) seeds.push_back(c);
      if (seeds.size() >= near_seeds + 6) break;
    }
  }
  const int fine_reach = static_cast<int>(std::ceil(options.coarse_step_m / options.fine_step_m));
  std::vector<Pose> refined(seeds.size(), Pose{kInf, click, 0});
  std::vector<PlanProfile> refined_profile(seeds.size());
  for (std::size_t s = 0; s < seeds.size(); ++s) {
    progress.checkpoint(0.6 + 0.35 * s / seeds.size(), "refining the best spots");
    for (int i = -fine_reach; i <= fine_reach; ++i)
      for (int k = -fine_reach; k <= fine_reach; ++k) {
        const Eigen::Vector2d p = seeds[s].p + options.fine_step_m * Eigen::Vector2d(i, k);
        if (distance_to_walls(walls, p) < options.min_wall_distance_m) continue;
        const PlanProfile profile = scorer.profile_at(walls, p);
        for (int j = seeds[s].j - 2 * coarse_heading; j <= seeds[s].j + 2 * coarse_heading; ++j) {
          const int jw = ((j % width) + width) % width;
          const double sc = scorer.score(profile, jw, 1);
          if (sc < refined[s].score) refined[s] = {sc, p, jw}, refined_profile[s] = profile;
        }
      }
  }
  std::size_t chosen = 0;
  for (std::size_t s = 1; s < seeds.size(); ++s)
    if (refined[s].score < refined[chosen].score) chosen = s;
  const Pose best = refined[chosen];
  const PlanProfile& best_profile = refined_profile[chosen];
  // Sub-column heading: a parabola through the best heading's neighbours.
  double j_refined = best.j;
  const double s_minus = scorer.score(best_profile, (best.j + width - 1) % width, 1);
  const double s_plus = scorer.score(best_profile, (best.j + 1) % width, 1);
  const double curvature = s_minus - 2 * best.score + s_plus;
  if (curvature > 1e-12) j_refined += std::clamp(0.5 * (s_minus - s_plus) / curvature, -0.5, 0.5);

  StillPlacement out;
  out.x = best.p.x();
  out.y = best.p.y();
  out.heading_deg = wrap_degrees(j_refined * step * 180.0 / M_PI);
  out.score_px = scorer.score(best_profile, best.j, 1, &out.samples);
  // The runner-up: the best coarse pose with another heading, scored at full resolution like the best.
  out.runner_up_score_px = kInf;
  for (const Pose& c : coarse)
    if (std::abs(wrap_degrees(c.j * step * 180.0 / M_PI - out.heading_deg)) > 15.0) {
      out.runner_up_score_px = scorer.score(scorer.profile_at(walls, c.p), c.j, 1);
      out.runner_up_heading_deg = wrap_degrees(c.j * step * 180.0 / M_PI);
      break;
    }
  out.elsewhere_score_px = kInf;
  if (options.elsewhere_gap_m > 0) {
    for (std::size_t s = 0; s < seeds.size(); ++s)
      if ((refined[s].p - best.p).norm() > options.elsewhere_gap_m && std::isfinite(refined[s].score))
        out.elsewhere.push_back({refined[s].p.x(), refined[s].p.y(),
                                 wrap_degrees(refined[s].j * step * 180.0 / M_PI), refined[s].score});
    std::sort(out.elsewhere.begin(), out.elsewhere.end(),
              [](const Eigen::Vector4d& a, const Eigen::Vector4d& b) { return a.w() < b.w(); });
    if (!out.elsewhere.empty()) out.elsewhere_score_px = out.elsewhere.front().w();
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  char text[256];
  std::snprintf(text, sizeof text, "placed %.2f m from the click, heading %.1f deg; fit %.2f px (%s)",
                (best.p - click).norm(), out.heading_deg, out.score_px,
                std::isfinite(out.runner_up_score_px) && out.runner_up_score_px < 1.1 * out.score_px
                    ? "another heading fits almost as well: give the direction with a second click"
                    : "no other heading comes close");
  out.summary = text;
  progress.report(1.0, out.summary);
  return out;
}

}  // namespace

StillPlacement place_still_on_plan(const cv::Mat& still, const FloorPlan& plan, const Eigen::Vector2d& click,
                                   const StillOnPlanOptions& options, Progress& progress) {
  options.check();
  std::vector<Eigen::Vector2d> spots;
  const int reach = static_cast<int>(std::floor(options.search_radius_m / options.coarse_step_m + 1e-9));
  for (int i = -reach; i <= reach; ++i)
    for (int k = -reach; k <= reach; ++k) {
      const Eigen::Vector2d p = click + options.coarse_step_m * Eigen::Vector2d(i, k);
      if ((p - click).norm() <= options.search_radius_m + 1e-9) spots.push_back(p);
    }
  return place_still_at_spots(still, plan, spots, click, options, progress);
}

StillPlacement place_still_among(const cv::Mat& still, const FloorPlan& plan,
                                 const std::vector<Eigen::Vector2d>& spots, const StillOnPlanOptions& options,
                                 Progress& progress) {
  if (spots.empty()) throw Error("no spots to place the still among");
  return place_still_at_spots(still, plan, spots, spots.front(), options, progress);
}

std::vector<double> still_fits_px(const cv::Mat& still, const FloorPlan& plan,
                                  const std::vector<Eigen::Vector3d>& poses,
                                  const StillOnPlanOptions& options) {
  options.check();
  if (still.empty()) throw Error("the still is empty");
  const int width = options.work_width;
  const Walls walls = walls_of(plan);
  const EdgeMaps maps = edge_maps(still, width, options.truncation_px, options.oriented_edges);
  const Scorer scorer{maps,
                      width,
                      width / 2,
                      options.camera_height_m,
                      options.top_above_camera_m,
                      options.nadir_limit_deg * M_PI / 180.0,
                      options.oriented_edges};
  const double step = 2.0 * M_PI / width;
  std::vector<double> fits;
  for (const Eigen::Vector3d& pose : poses) {
    const PlanProfile profile = scorer.profile_at(walls, pose.head<2>());
    const int j = ((static_cast<int>(std::lround(pose.z() * M_PI / 180.0 / step)) % width) + width) % width;
    fits.push_back(scorer.score(profile, j, 1));
  }
  return fits;
}

cv::Mat draw_plan_on_still(const cv::Mat& still, const FloorPlan& plan, double x, double y,
                           double heading_deg, const StillOnPlanOptions& options) {
  options.check();
  const int width = options.work_width, height = width / 2;
  const Walls walls = walls_of(plan);
  cv::Mat out;
  cv::resize(still, out, cv::Size(width, height), 0, 0, cv::INTER_AREA);
  if (out.channels() == 1) cv::cvtColor(out, out, cv::COLOR_GRAY2BGR);
  const EdgeMaps maps = edge_maps(still, width, options.truncation_px, false);
  out.setTo(cv::Scalar(0, 200, 0), maps.all == 0);
  const double step = 2.0 * M_PI / width;
  const PlanProfile profile = plan_profile(walls, {x, y}, width);
  const Scorer scorer{maps,  // for row_of only
                      width,
                      height,
                      options.camera_height_m,
                      options.top_above_camera_m,
                      options.nadir_limit_deg * M_PI / 180.0,
                      false};
  // The pose's heading on the profile's grid (the drawing is to the nearest column).
  const int j = ((static_cast<int>(std::lround(heading_deg * M_PI / 180.0 / step)) % width) + width) % width;
  const auto dot = [&](double px, double py) {
    const int u = ((static_cast<int>(std::floor(px)) % width) + width) % width;
    const int v = std::clamp(static_cast<int>(std::floor(py)), 0, height - 1);
    out.at<cv::Vec3b>(v, u) = cv::Vec3b(0, 0, 255);
  };
  for (int u = 0; u < width; ++u) {
    const double d = profile.distance[((j - u + width / 2) % width + width) % width];
    if (std::isfinite(d)) dot(u + 0.5, scorer.row_of(-std::atan(options.camera_height_m / d)));
  }
  for (const PlanProfile::Vertical& v : profile.verticals)
    for (double py = scorer.row_of(std::atan(options.top_above_camera_m / v.distance));
         py <= scorer.row_of(-std::atan(options.camera_height_m / v.distance)); py += 1.0)
      dot(j - v.m + width / 2, py);
  return out;
}

CameraPath path_with_still_placed(const CameraPath& path, int frame_index, const StillPlacement& placed,
                                  std::vector<PathPoint>* points) {
  const PathFrame* still = path.find_frame(frame_index);
  if (!still) throw Error("the path has no frame " + std::to_string(frame_index));
  const int piece = still->piece;
  const double turn = placed.heading_deg * M_PI / 180.0 - still->heading;
  const Eigen::Rotation2Dd rotation(turn);
  const Eigen::Vector2d shift = Eigen::Vector2d(placed.x, placed.y) - rotation * still->position();
  CameraPath out = path;
  for (PathFrame& f : out.frames) {
    if (f.piece != piece) continue;
    const Eigen::Vector2d p = rotation * f.position() + shift;
    f.x = p.x();
    f.y = p.y();
    f.heading = std::remainder(f.heading + turn, 2.0 * M_PI);
  }
  if (!out.pieces.empty() && piece >= 0 && piece < static_cast<int>(out.pieces.size()))
    out.pieces[static_cast<std::size_t>(piece)].placed = true;
  if (points) transform_piece_points(points, piece, turn, 1.0, shift);
  return out;
}

bool still_can_be_moved(const CameraPath& path, int frame_index) {
  const PathFrame* f = path.find_frame(frame_index);
  if (!f || path.piece_placed(f->piece) || f->piece < 0 || f->piece >= static_cast<int>(path.pieces.size()))
    return false;
  const PathPiece& piece = path.pieces[static_cast<std::size_t>(f->piece)];
  return piece.first_index == piece.last_index || piece.scale_source == "camera_height";
}

}  // namespace plenopath
