#pragma once
// A Photo Sphere Viewer (5.x) tour of the package, psv.json: the virtual-tour plugin's nodes (id, name,
// caption, panorama, sphereCorrection, links with positions, gps with a geo-anchor, map position, markers for
// the author's hotspots) and the map plugin's settings on plan.svg (imageUrl, size, center, rotation in
// radians as PSV reads plain numbers). A page
// passes "nodes" and "startNodeId" to VirtualTourPlugin (positionMode "manual") and "map" to MapPlugin.
#include <nlohmann/json.hpp>
#include <vector>

#include "model/project.h"
#include "processing/export/tour_json.h"

namespace plenopath {

// Every node is turned by sphereCorrection so that the viewer's yaw is the compass bearing (north from the
// geo-anchor, else the plan's +Y): PSV opens the next node at the yaw of the link followed, which then
// looks the same way in the world. Link and marker positions are in that corrected frame (radians).
nlohmann::json psv_tour(const Project& project, const std::vector<KeyframeImageFiles>& images);

}  // namespace plenopath
