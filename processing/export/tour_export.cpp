#include "processing/export/tour_export.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "model/atomic_file.h"
#include "model/error.h"
#include "processing/capture/frame_source.h"
#include "processing/export/asset_script.h"
#include "processing/export/cube_tiles.h"
#include "processing/export/keyframe_images.h"
#include "processing/export/keyframe_metadata.h"
#include "processing/export/marzipano_export.h"
#include "processing/export/nerfstudio_transforms.h"
#include "processing/export/opensfm_reconstruction.h"
#include "processing/export/package_writer.h"
#include "processing/export/plan_svg_frame.h"
#include "processing/export/player_assets.h"
#include "processing/export/psv_export.h"
#include "processing/export/tour_interop.h"
#include "processing/export/tour_json.h"
#include "processing/export/trajectory_formats.h"
#include "processing/export/xml_escape.h"
#include "processing/hotspots/hotspot_validation.h"
#include "rig/synthetic_camera.h"

namespace plenopath {
namespace fs = std::filesystem;
namespace {

std::string read_binary_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw file_error(file, "cannot open for reading");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// A package-safe file name for a hotspot's media: the id (letters, digits, '-', '_') and the extension.
std::string media_name(const std::string& id, const std::string& suffix, const std::string& source) {
  std::string safe;
  for (char c : id) safe += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
  if (safe.empty()) safe = "hotspot";
  std::string ext = fs::path(source).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext.size() > 6 || ext.find_first_not_of(".abcdefghijklmnopqrstuvwxyz0123456789") != std::string::npos)
    ext = ".bin";
  return "media/" + safe + suffix + ext;
}

std::string mime_type(const std::string& name) {
  const std::string ext = fs::path(name).extension().string();
  if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
  if (ext == ".png") return "image/png";
  if (ext == ".gif") return "image/gif";
  if (ext == ".webp") return "image/webp";
  if (ext == ".mp4" || ext == ".m4v") return "video/mp4";
  if (ext == ".webm") return "video/webm";
  if (ext == ".ogv") return "video/ogg";
  if (ext == ".mp3") return "audio/mpeg";
  if (ext == ".ogg") return "audio/ogg";
  if (ext == ".wav") return "audio/wav";
  return "application/octet-stream";
}

}  // namespace

void TourExportOptions::check() const {
  if (output.empty()) throw Error("export: no output given (a folder or a .zip file)");
  if (max_size < 64 || max_size > 16384) throw Error("export: max_size must be within 64..16384 pixels");
  if (preview_size < 64 || preview_size > max_size)
    throw Error("export: preview_size must be within 64..max_size pixels");
  if (jpeg_quality < 1 || jpeg_quality > 100) throw Error("export: jpeg_quality must be within 1..100");
  if (tile_size < 16 || tile_size > 4096) throw Error("export: tile_size must be within 16..4096 pixels");
  if (preview_quality < 1 || preview_quality > 100)
    throw Error("export: preview_quality must be within 1..100");
  cleaning.check();
}

TourExportOptions TourExportOptions::from_project(const Project& project, const std::string& output) {
  TourExportOptions o;
  o.output = output;
  o.max_size = project.tour.max_size;
  o.preview_size = std::min(project.tour.preview_size, project.tour.max_size);
  o.jpeg_quality = project.tour.jpeg_quality;
  o.pannellum = project.tour.export_pannellum;
  o.multires = project.tour.export_multires;
  o.marzipano = project.tour.export_marzipano;
  o.psv = project.tour.export_psv;
  // The project's choices for georeferenced files wait for a geo-anchor; asked for explicitly (the command
  // line's flags), they are an error without one.
  o.geojson = project.tour.export_geojson && project.geo.valid;
  o.kml_gpx = project.tour.export_kml_gpx ? GeoTrackFiles::kAuto : GeoTrackFiles::kOff;
  o.tum = project.tour.export_tum;
  o.opensfm = project.tour.export_opensfm;
  o.nerfstudio = project.tour.export_nerfstudio;
  o.photo_metadata = project.tour.export_photo_metadata;
  o.cleaning = KeyframeCleaning::from_project(project);
  return o;
}

std::string plan_svg(const FloorPlan& plan) {
  const PlanSvgFrame frame = plan_svg_frame(plan);
  const Eigen::Vector2d lo = frame.lo, hi = frame.hi;
  std::ostringstream svg;
  svg.precision(6);
  svg << std::fixed;
  // viewBox in metres with y flipped: plan (x, y) is drawn at (x, -y).
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"" << lo.x() << " " << -hi.y() << " "
      << hi.x() - lo.x() << " " << hi.y() - lo.y() << "\" width=\"" << frame.width_px() << "\" height=\""
      << frame.height_px() << "\">\n";
  std::map<std::string, std::vector<const PlanSegment*>> by_layer;
  for (const auto& s : plan.segments) by_layer[s.layer].push_back(&s);
  for (const auto& [layer, segments] : by_layer) {
    const bool occluder = !segments.empty() && segments.front()->occluder;
    svg << "<g class=\"layer" << (occluder ? " occluder" : "") << "\" data-layer=\"" << xml_escape(layer)
        << "\" stroke=\"" << (occluder ? "#222" : "#888") << "\" stroke-width=\"" << (occluder ? 0.08 : 0.03)
        << "\" stroke-linecap=\"round\" fill=\"none\">\n";
    for (const PlanSegment* s : segments)
      svg << "<line x1=\"" << s->a.x() << "\" y1=\"" << -s->a.y() << "\" x2=\"" << s->b.x() << "\" y2=\""
          << -s->b.y() << "\"/>\n";
    svg << "</g>\n";
  }
  svg << "<g class=\"labels\" font-family=\"sans-serif\" fill=\"#555\" text-anchor=\"middle\">\n";
  for (const auto& l : plan.labels)
    svg << "<text x=\"" << l.position.x() << "\" y=\"" << -l.position.y() << "\" font-size=\""
        << (l.height > 0 ? l.height : 0.3) << "\">" << xml_escape(l.text) << "</text>\n";
  svg << "</g>\n</svg>\n";
  return svg.str();
}

TourExportReport export_tour(const Project& project, const TourExportOptions& options, Progress& progress) {
  options.check();
  if (project.path.empty()) throw Error("export: the project has no camera path (track or import one first)");
  if (project.keyframes.empty()) throw Error("export: the project has no keyframes (run sampling first)");
  require_placed(project.path, "export");
  const bool geo_tracks = wants_geo_tracks(options.kml_gpx, project);  // before any work: may throw
  auto report_progress = [&](double fraction, const std::string& stage) {
    progress.checkpoint(fraction, stage);
  };

  TourExportReport report;
  report.output = options.output;
  report.capture_frames =
      project.capture.frame_count > 0 ? project.capture.frame_count : static_cast<int>(project.path.size());
  PackageWriter package(options.output);  // streamed: each file written as it is made
  std::uintmax_t full_image_bytes = 0;

  // Keyframe images, in progressive order so that a streaming reader gets the coarse tour first.
  report_progress(0.0, "opening capture");
  SubProgress opening(progress, 0.0, 0.05, "opening capture");
  KeyframeCleaner cleaner(project, options.cleaning, opening);
  FrameSource* frames = &cleaner.frames();
  const std::vector<int> order = project.keyframes.progressive_order();
  report.rig_pct = cleaner.rig_pct();
  double replaced = 0, rig_filled = 0;
  std::vector<KeyframeImageFiles> images;
  int full_width = 0, preview_width = 0;
  std::optional<CubeTileLayout> tiles;
  for (std::size_t i = 0; i < order.size(); ++i) {
    report_progress(0.05 + 0.8 * i / order.size(), "encoding keyframes");
    const int frame = order[i];
    if (!project.path.find_frame(frame))
      throw Error("export: keyframe " + std::to_string(frame) + " has no pose in the path");
    if (frame < 0 || frame >= frames->frame_count())
      throw Error("export: keyframe " + std::to_string(frame) + " is outside the capture (" +
                  std::to_string(frames->frame_count()) + " frames)");
    SubProgress keyframe_progress(progress, 0.05 + 0.8 * i / order.size(),
                                  0.05 + 0.8 * (i + 0.9) / order.size(), "keyframe " + std::to_string(frame));
    const CleanedKeyframe cleaned = cleaner.clean(frame, keyframe_progress);
    const cv::Mat& image = cleaned.image;
    if (cleaned.cleaned) {
      ++report.clean_plates;
      replaced += cleaned.plate.moving_share;
      rig_filled += 1.0 - cleaned.plate.rig_unfilled_share;
    }
    report.faces_blurred += cleaned.faces;
    report.warnings.insert(report.warnings.end(), cleaned.warnings.begin(), cleaned.warnings.end());
    full_width = std::min(options.max_size, image.cols) / 2 * 2;
    preview_width = std::min(options.preview_size, full_width) / 2 * 2;
    const KeyframeImageEncoding encoding{full_width, preview_width, options.jpeg_quality,
                                         options.preview_quality};
    KeyframeImageBytes bytes;
    auto tag = [&](std::vector<unsigned char> jpeg, const std::string& name) {
      return with_photo_tags(jpeg, keyframe_photo_tags(project, frame), name);
    };
    KeyframeImageFiles files = write_keyframe_images(package, frame, image, encoding, &bytes,
                                                     options.photo_metadata ? JpegEdit(tag) : JpegEdit());
    full_image_bytes += bytes.full;
    if (options.writes_cube_tiles()) {
      if (!tiles) tiles = cube_tile_layout(full_width, options.tile_size);  // one layout for the tour
      files.tiles = "tiles/" + keyframe_stem(frame);
      write_cube_tiles(image, *tiles, options.jpeg_quality, [&](const std::string& path, std::string jpeg) {
        package.add(files.tiles + "/" + path, std::move(jpeg));
      });
    }
    images.push_back(files);
  }

  if (report.clean_plates > 0) {
    report.replaced_pct = 100 * replaced / report.clean_plates;
    if (!cleaner.rig_mask().empty()) report.rig_filled_pct = 100 * rig_filled / report.clean_plates;
  }

  // Hotspot media: copied under media/ with safe names. Problems (missing or undecodable media, inconsistent
  // quads, markup in text, unusable targets) are warnings, not failures: the author hears of each once.
  report_progress(0.86, "hotspot media");
  for (const HotspotWarning& w : validate_hotspots(project)) report.warnings.push_back(w.message);
  std::vector<HotspotMediaFile> media;
  for (const Hotspot& h : project.hotspots) {
    HotspotMediaFile m;
    m.id = h.id;
    auto copy_media = [&](const std::string& source, const std::string& suffix) -> std::string {
      if (source.empty()) return "";
      std::error_code ec;
      if (!fs::is_regular_file(source, ec)) return "";  // validate_hotspots has warned about it
      const std::string name = media_name(h.id, suffix, source);
      if (options.offline_images) {
        const std::string data = read_binary_file(source);
        package.add(name.substr(0, name.rfind('.')) + ".js",
                    asset_script(name, mime_type(name), reinterpret_cast<const unsigned char*>(data.data()),
                                 data.size()));
      }
      package.add_file(name, source);
      return name;
    };
    m.media = copy_media(h.media, "");
    if (hotspot_action_uses_media(h.action)) m.action_media = copy_media(h.action_target, "_action");
    media.push_back(m);
  }

  report_progress(0.9, "tour description");
  nlohmann::json tour = make_tour_json(project, images, media, full_width, preview_width);
  if (tiles) tour["tiles"] = cube_tiles_json(*tiles);
  package.add("tour.json", tour.dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  // The same data as a script: browsers refuse fetch() of file:// URLs, but load scripts.
  package.add("tour.js", "window.PLENOPATH_TOUR = " +
                             tour.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + ";\n");
  package.add("plan.svg", plan_svg(project.plan));
  for (const EmbeddedFile& f : player_assets())
    package.add(f.name, std::string(reinterpret_cast<const char*>(f.data), f.size));
  if (options.pannellum)
    package.add("pannellum.json", pannellum_config(project, images, tiles ? &*tiles : nullptr)
                                          .dump(1, ' ', false, nlohmann::json::error_handler_t::replace) +
                                      "\n");
  if (options.marzipano) {
    package.add("marzipano-data.js", marzipano_data_js(project, images, *tiles));
    for (const MarzipanoPageFile& f : marzipano_page_files()) package.add(f.name, f.text);
  }
  if (options.psv)
    package.add(
        "psv.json",
        psv_tour(project, images).dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  if (options.geojson)
    package.add("path.geojson",
                path_geojson(project).dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");

  if (geo_tracks) {
    package.add("path.kml", path_kml(project));
    package.add("path.gpx", path_gpx(project));
  }
  if (options.tum) package.add("trajectory.tum", tum_trajectory(project));
  if (options.opensfm)
    for (auto& [name, data] : opensfm_files(project, images, full_width, full_width / 2))
      package.add(name, data);
  if (options.nerfstudio)
    package.add("transforms.json",
                nerfstudio_transforms(project, images, full_width, full_width / 2).dump(1) + "\n");

  report_progress(0.95, "writing package");
  report.files = package.files();
  report.package_bytes = package.commit();
  report.full_image_bytes = full_image_bytes;
  report.package_ratio =
      full_image_bytes > 0 ? static_cast<double>(report.package_bytes) / full_image_bytes : 0;
  report.keyframes = static_cast<int>(images.size());
  progress.report(1.0, "done");  // written: too late to cancel
  return report;
}

}  // namespace plenopath
