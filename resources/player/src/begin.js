// Plenopath web player: walks a plenoptic path exported by Plenopath Studio.
// Plain WebGL, no build step at the viewer's end; works from file:// (images then come from small data-URI
// scripts) and from any static server. Conventions (tour.json, schema in tour.schema.json): plan frame X right,
// Y up, Z up; heading = direction of a panorama's centre column, counter-clockwise from +X; equirectangular
// column 0 is azimuth -180 deg and azimuth grows to the right, so the ray at world angle phi is at azimuth
// heading - phi. Every text from the tour is inserted with textContent, never as HTML.
//
// Built from resources/player/src/ by cmake/JoinFiles.cmake: begin.js, enums.js (generated from
// resources/schema/enums.json), tour_data.js, renderer.js, textures.js, multires.js, hotspots.js, walk.js,
// frame_probe.js, orientation.js, ui.js, end.js, joined in that order into one function scope (this file opens it, end.js closes it). Edit those files, not this one.
'use strict';
(function () {
