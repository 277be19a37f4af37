// `plenopath export --project P.plenopath --out DIR|FILE.zip [--max-size 4096] [--preview-size 1024]
//  [--quality 85] [--preview-quality 60] [--pannellum] [--geojson] [--multires [--tile-size 512]]
//  [--marzipano]
//  [--psv] [--kml-gpx|--no-kml-gpx] [--tum] [--opensfm] [--nerfstudio] [--no-photo-metadata]
//  [--clean-plates [--nadir blur|none|FILE] [--rig-mask FILE] [--no-rig-fill]]
//  [--blur-faces] [--json]`: the packaged walkthrough (with --clean-plates, each keyframe without the
//  people who walked through and without the rig: processing/cleanplate).
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "app/cli/console_progress.h"
#include "model/error.h"
#include "model/project_io.h"
#include "processing/export/tour_export.h"
#include "processing/pipeline/export_step.h"

namespace plenopath::cli {

Command add_export_command(CLI::App& parent) {
  struct Options {
    std::string project, out;
    int max_size = 0, preview_size = 0, quality = 0, preview_quality = 0;
    bool pannellum = false, geojson = false, json = false, http_only = false, clean_plates = false;
    bool kml_gpx = false, no_kml_gpx = false, tum = false, opensfm = false, nerfstudio = false,
         no_photo_metadata = false;
    bool no_rig_fill = false, blur_faces = false, multires = false, marzipano = false, psv = false;
    int tile_size = 0;
    std::string nadir, rig_mask;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub =
      parent.add_subcommand("export", "Export a packaged walkthrough (web player, tour.json, images)");
  sub->add_option("--project", o->project, "Project file (*.plenopath)")->required();
  sub->add_option("--out", o->out, "Output folder, or a file ending in .zip")->required();
  sub->add_option("--max-size", o->max_size, "Full keyframe width in pixels (default: the project's, 4096)");
  sub->add_option("--preview-size", o->preview_size, "Preview keyframe width in pixels (default 1024)");
  sub->add_option("--quality", o->quality, "JPEG quality 1..100 (default: the project's, 85)");
  sub->add_option("--preview-quality", o->preview_quality, "Preview JPEG quality 1..100 (default 60)");
  sub->add_flag("--pannellum", o->pannellum, "Also write pannellum.json (one scene per keyframe)");
  sub->add_flag("--geojson", o->geojson, "Also write path.geojson in WGS84 (needs a geo-anchor)");
  CLI::Option* kml_gpx = sub->add_flag(
      "--kml-gpx", o->kml_gpx,
      "Write path.kml and path.gpx in WGS84 (an error without a geo-anchor; by default they are "
      "written whenever the project has one)");
  sub->add_flag("--no-kml-gpx", o->no_kml_gpx, "Leave out path.kml and path.gpx")->excludes(kml_gpx);
  sub->add_flag("--tum", o->tum, "Also write trajectory.tum (TUM RGB-D format: the whole path in the plan)");
  sub->add_flag("--opensfm", o->opensfm,
                "Also write reconstruction.json: the keyframes as OpenSfM spherical cameras");
  sub->add_flag("--nerfstudio", o->nerfstudio,
                "Also write transforms.json: the keyframes as nerfstudio EQUIRECTANGULAR cameras");
  sub->add_flag("--no-photo-metadata", o->no_photo_metadata,
                "Leave the GPano XMP and EXIF GPS out of the keyframe JPEGs");
  sub->add_flag("--multires", o->multires,
                "Also write multi-resolution cube tiles of each keyframe (tiles/; pannellum.json uses them)");
  sub->add_option("--tile-size", o->tile_size, "Largest cube tile in pixels (default 512)");
  sub->add_flag("--marzipano", o->marzipano,
                "Also write a Marzipano tour on the cube tiles (marzipano.html, marzipano-data.js)");
  sub->add_flag("--psv", o->psv, "Also write psv.json (Photo Sphere Viewer virtual tour and map)");
  sub->add_flag("--http-only", o->http_only,
                "Leave out the data-URI copies of hotspot media that file:// viewing needs "
                "(keyframe previews are scripts either way)");
  sub->add_flag("--clean-plates", o->clean_plates,
                "Keyframes without the people who walked through (replaced by what neighbouring frames saw) "
                "and without the rig (trolley, operator, tripod: filled from frames further along)");
  sub->add_option("--nadir", o->nadir,
                  "With --clean-plates, what covers the rig where no frame saw behind it: blur (a blurred "
                  "fill, the default), none, or an image file (a logo on a disc at the nadir)");
  sub->add_flag("--no-rig-fill", o->no_rig_fill, "With --clean-plates, leave the rig as captured");
  sub->add_option("--rig-mask", o->rig_mask,
                  "With --clean-plates, an image black where the rig covers every frame (as track --mask; "
                  "the project's own, else the tracker's estimate alone)");
  sub->add_flag("--blur-faces", o->blur_faces, "Blur the faces of people who remain in the keyframes");
  sub->add_flag("--json", o->json, "Machine-readable report");
  return {sub, [o]() {
            Project project = load_project(o->project);
            if (!o->rig_mask.empty()) project.capture.rig_mask = o->rig_mask;
            TourExportOptions options = TourExportOptions::from_project(project, o->out);
            if (o->max_size > 0) options.max_size = o->max_size;
            if (o->preview_size > 0) options.preview_size = o->preview_size;
            options.preview_size = std::min(options.preview_size, options.max_size);
            if (o->quality > 0) options.jpeg_quality = o->quality;
            if (o->preview_quality > 0) options.preview_quality = o->preview_quality;
            options.pannellum = options.pannellum || o->pannellum;
            options.geojson = options.geojson || o->geojson;
            if (o->kml_gpx) options.kml_gpx = GeoTrackFiles::kOn;
            if (o->no_kml_gpx) options.kml_gpx = GeoTrackFiles::kOff;
            options.tum = options.tum || o->tum;
            options.opensfm = options.opensfm || o->opensfm;
            options.nerfstudio = options.nerfstudio || o->nerfstudio;
            if (o->no_photo_metadata) options.photo_metadata = false;
            options.offline_images = !o->http_only;
            options.multires = options.multires || o->multires;
            options.marzipano = options.marzipano || o->marzipano;
            options.psv = options.psv || o->psv;
            if (o->tile_size > 0) options.tile_size = o->tile_size;
            KeyframeCleaning& cleaning = options.cleaning;
            cleaning.clean_plates = cleaning.clean_plates || o->clean_plates;
            cleaning.fill_rig = !o->no_rig_fill;
            cleaning.blur_faces = cleaning.blur_faces || o->blur_faces;
            if (o->nadir == "blur" || o->nadir == "none") {
              cleaning.nadir.kind = enum_from_string<NadirPatch>(o->nadir);
            } else if (!o->nadir.empty()) {
              cleaning.nadir.kind = NadirPatch::kImage;
              cleaning.nadir.image = read_nadir_image(o->nadir);
            }
            ConsoleProgress progress("export");
            pipeline::ExportStepOptions step;
            step.tour = std::move(options);
            const pipeline::ExportStepResult result =
                pipeline::run_export(std::move(project), step, progress);
            progress.finish();
            const TourExportReport& report = result.report;
            for (const std::string& w : report.warnings) std::cerr << "export: warning: " << w << "\n";
            if (o->json) {
              std::cout << nlohmann::json{{"output", report.output},
                                          {"keyframes", report.keyframes},
                                          {"capture_frames", report.capture_frames},
                                          {"package_bytes", report.package_bytes},
                                          {"full_image_bytes", report.full_image_bytes},
                                          {"package_ratio", report.package_ratio},
                                          {"files", report.files.size()},
                                          {"clean_plates", report.clean_plates},
                                          {"replaced_pct", report.replaced_pct},
                                          {"rig_pct", report.rig_pct},
                                          {"rig_filled_pct", report.rig_filled_pct},
                                          {"faces_blurred", report.faces_blurred},
                                          {"warnings", report.warnings}}
                               .dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
                        << "\n";
            } else {
              std::cout << "Exported " << report.keyframes << " keyframes of " << report.capture_frames
                        << " frames to " << report.output << " (" << report.package_bytes / 1024 << " KiB, "
                        << report.files.size() << " files, " << report.package_ratio
                        << " x the full images' bytes)\n";
            }
            return kExitOk;
          }};
}

}  // namespace plenopath::cli
