#include "processing/export/marzipano_export.h"

#include <algorithm>
#include <cmath>

#include "model/error.h"
#include "processing/export/interop_scenes.h"

namespace plenopath {
namespace {

double rad(double deg) { return deg * M_PI / 180.0; }
// Marzipano's pitch grows downwards (a view at pitch +1 rad shows what lies 57 deg below the horizon:
// measured in tests/app/viewer_check.py), the opposite of an elevation.
double pitch_of_elevation(double elevation_deg) { return -rad(elevation_deg); }

const char* kPage = R"(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<link rel="icon" href="data:,">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>Tour</title>
<style>
html, body { margin: 0; height: 100%; overflow: hidden; background: #000; font-family: sans-serif; }
#pano { position: absolute; inset: 0; }
.link, .info { cursor: pointer; transform: translate(-50%, -50%); color: #fff; background: rgba(0, 0, 0, 0.6);
  border: 2px solid #fff; border-radius: 14px; padding: 4px 10px; font-size: 14px; white-space: nowrap; }
.info .text { display: none; margin-top: 4px; max-width: 260px; white-space: normal; }
.info.open .text { display: block; }
</style>
</head>
<body>
<div id="pano"></div>
<script src="marzipano-data.js"></script>
<script>
// Marzipano is not bundled: ./marzipano.js when it is there (npm marzipano, dist/marzipano.js), else unpkg.
(function () {
  function start() {
    var s = document.createElement('script');
    s.src = 'marzipano-app.js';
    document.body.appendChild(s);
  }
  var local = document.createElement('script');
  local.src = 'marzipano.js';
  local.onload = start;
  local.onerror = function () {
    var cdn = document.createElement('script');
    cdn.src = 'https://unpkg.com/marzipano@@VERSION@/dist/marzipano.js';
    cdn.onload = start;
    document.body.appendChild(cdn);
  };
  document.body.appendChild(local);
})();
</script>
</body>
</html>
)";

const char* kApp =
    R"(// One Marzipano scene per keyframe from marzipano-data.js (APP_DATA). A scene change keeps the direction
// of view in the world: the new yaw is the old one plus the difference of the two scenes' northOffset.
(function () {
  'use strict';
  var data = window.APP_DATA;
  var viewer = new Marzipano.Viewer(document.getElementById('pano'), {controls: {mouseViewMode: data.settings.mouseViewMode}});
  var scenes = {};
  var tour = {viewer: viewer, scenes: scenes, current: null, switchScene: switchScene};

  function hotspotElement(className, label) {
    var el = document.createElement('div');
    el.className = className;
    var title = document.createElement('div');
    title.textContent = label;  // titles are plain text, never markup
    el.appendChild(title);
    return el;
  }

  data.scenes.forEach(function (d) {
    var source = Marzipano.ImageUrlSource.fromString(d.tiles + '/{z}/{f}/{y}_{x}.jpg');
    var geometry = new Marzipano.CubeGeometry(d.levels);
    // At most 90 degrees high: wider, Marzipano leaves tiles partly behind the eye undrawn (holes).
    var limiter = Marzipano.RectilinearView.limit.traditional(d.faceSize, 90 * Math.PI / 180);
    var view = new Marzipano.RectilinearView(d.initialViewParameters, limiter);
    var scene = viewer.createScene({source: source, geometry: geometry, view: view, pinFirstLevel: true});
    d.linkHotspots.forEach(function (h) {
      var el = hotspotElement('link', h.label);
      el.addEventListener('click', function () { switchScene(h.target); });
      scene.hotspotContainer().createHotspot(el, {yaw: h.yaw, pitch: h.pitch});
    });
    d.infoHotspots.forEach(function (h) {
      var el = hotspotElement('info', h.title);
      if (h.text) {
        var text = document.createElement('div');
        text.className = 'text';
        text.textContent = h.text;
        el.appendChild(text);
      }
      el.addEventListener('click', function () {
        if (h.url) window.open(h.url, '_blank', 'noopener');
        else el.classList.toggle('open');
      });
      scene.hotspotContainer().createHotspot(el, {yaw: h.yaw, pitch: h.pitch});
    });
    scenes[d.id] = {data: d, scene: scene, view: view};
  });

  function switchScene(id) {
    var next = scenes[id];
    if (!next) return;
    var from = tour.current && scenes[tour.current];
    if (from) {
      var turn = (from.data.northOffset - next.data.northOffset) * Math.PI / 180;
      next.view.setParameters({yaw: from.view.yaw() + turn, pitch: from.view.pitch(), fov: from.view.fov()});
    } else {
      next.view.setParameters(next.data.initialViewParameters);
    }
    next.scene.switchTo({transitionDuration: from ? 600 : 0});
    tour.current = id;
  }

  window.marzipanoTour = tour;
  switchScene(data.startScene || data.scenes[0].id);
})();
)";

}  // namespace

std::string marzipano_data_js(const Project& project, const std::vector<KeyframeImageFiles>& images,
                              const CubeTileLayout& tiles) {
  using nlohmann::json;
  json levels = json::array();
  for (const CubeTileLevel& l : tiles.levels) {
    // Level 0 stays an ordinary level: Marzipano draws a fallbackOnly level only when it comes from a
    // cubeMapPreviewUrl strip, and left the screen black where finer tiles were still loading (seen in
    // tests/app/viewer_check.py). Being selectable it is only chosen for very small views.
    levels.push_back({{"tileSize", l.tile_size}, {"size", l.size}});
  }
  json scenes = json::array();
  for (const InteropScene& s : interop_scenes(project, images)) {
    if (s.images->tiles.empty())
      throw Error("Marzipano export: keyframe " + std::to_string(s.frame) + " has no cube tiles");
    json links = json::array(), infos = json::array();
    for (const InteropLink& l : s.links)
      links.push_back({{"yaw", rad(l.yaw_deg)},
                       {"pitch", pitch_of_elevation(l.pitch_deg)},
                       {"rotation", 0},
                       {"target", l.target_id},
                       {"label", l.label}});
    for (const InteropSpot& h : s.spots) {
      if (h.jump_frame >= 0) {
        links.push_back({{"yaw", rad(h.yaw_deg)},
                         {"pitch", pitch_of_elevation(h.pitch_deg)},
                         {"rotation", 0},
                         {"target", interop_scene_id(h.jump_frame)},
                         {"label", h.title}});
        continue;
      }
      json info = {{"yaw", rad(h.yaw_deg)},
                   {"pitch", pitch_of_elevation(h.pitch_deg)},
                   {"title", h.title},
                   {"text", h.text}};
      if (!h.url.empty()) info["url"] = h.url;
      infos.push_back(info);
    }
    scenes.push_back({{"id", s.id},
                      {"name", s.title},
                      {"tiles", s.images->tiles},
                      {"levels", levels},
                      {"faceSize", tiles.face_size()},
                      {"northOffset", s.north_offset_deg},
                      {"initialViewParameters", {{"yaw", 0.0}, {"pitch", 0.0}, {"fov", M_PI / 2}}},
                      {"linkHotspots", links},
                      {"infoHotspots", infos}});
  }
  int start = images.empty() ? 0 : images.front().frame;  // the coarsest keyframe, as Pannellum's firstScene
  for (const KeyframeImageFiles& img : images)
    if (img.frame == project.tour.start_frame) start = img.frame;
  const json data = {{"scenes", scenes},
                     {"name", project.tour.title},
                     {"startScene", interop_scene_id(start)},
                     {"settings",
                      {{"mouseViewMode", "drag"},
                       {"autorotateEnabled", false},
                       {"fullscreenButton", false},
                       {"viewControlButtons", false}}}};
  return "var APP_DATA = " + data.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + ";\n";
}

const std::vector<MarzipanoPageFile>& marzipano_page_files() {
  static const std::string page = [] {
    std::string p = kPage;
    const std::string key = "@VERSION@";
    p.replace(p.find(key), key.size(), kMarzipanoVersion);
    return p;
  }();
  static const std::vector<MarzipanoPageFile> files = {{"marzipano.html", page.c_str()},
                                                       {"marzipano-app.js", kApp}};
  return files;
}

}  // namespace plenopath
