#pragma once
// Interop files of a tour package: a Pannellum tour configuration and a GeoJSON of the path in WGS84.
#include <nlohmann/json.hpp>
#include <vector>

#include "model/project.h"
#include "processing/export/cube_tiles.h"
#include "processing/export/tour_json.h"

namespace plenopath {

// One Pannellum scene per keyframe (processing/export/interop_scenes.h): linked to its neighbours along the
// path by "scene" hotspots with targetYaw "sameAzimuth", northOffset in every scene (north from the
// geo-anchor, else the plan's +Y) so that the view keeps its world direction across a change; the
// author's hotspots as "info" hotspots (title, text, URL) or, for jumps, "scene" hotspots. "multires" on
// the cube tiles when `tiles` is given and the keyframes have them, "equirectangular" otherwise.
nlohmann::json pannellum_config(const Project& project, const std::vector<KeyframeImageFiles>& images,
                                const CubeTileLayout* tiles = nullptr);

// FeatureCollection: the path as a LineString and each keyframe as a Point, in WGS84 (lon, lat order),
// placed through the geo-anchor with GeographicLib's LocalCartesian. Throws Error without a valid anchor.
nlohmann::json path_geojson(const Project& project);

// WGS84 (latitude, longitude, altitude) of a plan point through the anchor.
Eigen::Vector3d wgs84_from_plan(const GeoAnchor& anchor, const Eigen::Vector2d& plan);

}  // namespace plenopath
