// Equality and small helpers of the document's parts (kept together: each is a few lines).
#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

#include "model/error.h"
#include "model/project.h"

namespace plenopath {

bool operator==(const Anchor& l, const Anchor& r) {
  return std::tie(l.frame, l.position, l.heading) == std::tie(r.frame, r.position, r.heading);
}

bool operator==(const VisibilityEvent& l, const VisibilityEvent& r) {
  return std::tie(l.frame, l.s) == std::tie(r.frame, r.s);
}
bool operator==(const VisibilityCell& l, const VisibilityCell& r) {
  return std::tie(l.first_frame, l.last_frame, l.s_begin, l.s_end, l.length, l.area_mid, l.area_mean) ==
         std::tie(r.first_frame, r.last_frame, r.s_begin, r.s_end, r.length, r.area_mid, r.area_mean);
}
bool operator==(const CriticalLine& l, const CriticalLine& r) { return l.a == r.a && l.b == r.b; }
bool operator==(const VisibilityCells& l, const VisibilityCells& r) {
  return std::tie(l.events, l.cells, l.critical_lines) == std::tie(r.events, r.cells, r.critical_lines);
}

bool operator==(const SamplingParameters& l, const SamplingParameters& r) {
  return std::tie(l.method, l.rule, l.count, l.ratio, l.exponent, l.transition_boost, l.min_spacing_m,
                  l.max_spacing_m) == std::tie(r.method, r.rule, r.count, r.ratio, r.exponent,
                                               r.transition_boost, r.min_spacing_m, r.max_spacing_m);
}
bool operator==(const SamplerSettings& l, const SamplerSettings& r) {
  const auto tie = [](const SamplerSettings& s) {
    return std::tie(s.expected_loss.probe_spacing_m, s.expected_loss.loss_power,
                    s.expected_loss.density_floor, s.refinement.applied, s.refinement.sweeps,
                    s.refinement.raster_cell_m, s.cell_rule.transition_window_m, s.cell_rule.min_size,
                    s.depth_changes.log_ratio_threshold, s.depth_changes.use_mean_range,
                    s.depth_changes.min_coverage, s.depth_changes.max_depth_width);
  };
  return tie(l) == tie(r);
}
bool operator==(const Keyframes& l, const Keyframes& r) {
  return std::tie(l.indices, l.rank, l.pinned, l.parameters, l.sampler) ==
         std::tie(r.indices, r.rank, r.pinned, r.parameters, r.sampler);
}
std::vector<int> Keyframes::progressive_order() const {
  std::vector<std::size_t> order(indices.size());
  std::iota(order.begin(), order.end(), 0);
  const bool ranked = rank.size() == indices.size();
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return ranked && rank[a] < rank[b]; });
  std::vector<int> frames;
  frames.reserve(order.size());
  for (std::size_t i : order) frames.push_back(indices[i]);
  return frames;
}

bool hotspot_action_uses_media(HotspotAction action) {
  switch (action) {
    case HotspotAction::kSwapImage:
    case HotspotAction::kPlayVideo:
    case HotspotAction::kPlaySound:
      return true;
    case HotspotAction::kNone:
    case HotspotAction::kJump:
    case HotspotAction::kOpenUrl:
    case HotspotAction::kShowText:
      return false;
  }
  return false;
}
bool operator==(const Hotspot& l, const Hotspot& r) {
  return std::tie(l.id, l.kind, l.title, l.media, l.frame, l.image_corners, l.world_corners, l.trigger,
                  l.trigger_distance_m, l.action, l.action_target) ==
         std::tie(r.id, r.kind, r.title, r.media, r.frame, r.image_corners, r.world_corners, r.trigger,
                  r.trigger_distance_m, r.action, r.action_target);
}

Eigen::Vector2d GeoAnchor::enu_from_plan(const Eigen::Vector2d& plan) const {
  const Eigen::Vector2d d = (plan - plan_origin) * scale;
  const double c = std::cos(plan_rotation), s = std::sin(plan_rotation);
  return {c * d.x() - s * d.y(), s * d.x() + c * d.y()};
}
Eigen::Vector2d GeoAnchor::plan_from_enu(const Eigen::Vector2d& enu) const {
  const double c = std::cos(plan_rotation), s = std::sin(plan_rotation);
  const Eigen::Vector2d d(c * enu.x() + s * enu.y(), -s * enu.x() + c * enu.y());
  return plan_origin + d / scale;
}
bool operator==(const GeoAnchor& l, const GeoAnchor& r) {
  return std::tie(l.valid, l.latitude_deg, l.longitude_deg, l.altitude_m, l.plan_rotation, l.scale,
                  l.plan_origin) == std::tie(r.valid, r.latitude_deg, r.longitude_deg, r.altitude_m,
                                             r.plan_rotation, r.scale, r.plan_origin);
}

bool operator==(const CleanPlateEdit& l, const CleanPlateEdit& r) {
  return l.frame == r.frame && l.mask == r.mask;
}

const CleanPlateEdit* TourSettings::clean_plate_edit(int frame) const {
  for (const CleanPlateEdit& e : clean_plate_edits)
    if (e.frame == frame) return &e;
  return nullptr;
}

bool operator==(const TourSettings& l, const TourSettings& r) {
  return std::tie(l.title, l.description, l.max_size, l.preview_size, l.jpeg_quality, l.start_frame,
                  l.export_pannellum, l.export_geojson, l.export_multires, l.export_marzipano, l.export_psv,
                  l.export_kml_gpx, l.export_tum, l.export_opensfm, l.export_nerfstudio,
                  l.export_photo_metadata, l.export_clean_plates, l.nadir_patch, l.nadir_image, l.blur_faces,
                  l.clean_plate_edits) ==
         std::tie(r.title, r.description, r.max_size, r.preview_size, r.jpeg_quality, r.start_frame,
                  r.export_pannellum, r.export_geojson, r.export_multires, r.export_marzipano, r.export_psv,
                  r.export_kml_gpx, r.export_tum, r.export_opensfm, r.export_nerfstudio,
                  r.export_photo_metadata, r.export_clean_plates, r.nadir_patch, r.nadir_image, r.blur_faces,
                  r.clean_plate_edits);
}

bool operator==(const Project& l, const Project& r) {
  return std::tie(l.plan, l.capture, l.path, l.path_points, l.anchors, l.visibility, l.keyframes, l.hotspots,
                  l.geo, l.tour) == std::tie(r.plan, r.capture, r.path, r.path_points, r.anchors,
                                             r.visibility, r.keyframes, r.hotspots, r.geo, r.tour);
}

}  // namespace plenopath
