// `plenopath track --capture DIR|VIDEO | --stills DIR [--first N] [--last M] [--stride K] [--camera-height M]
// [--plan PLAN.dxf [--layers L ...] [--occluders L ...]] [--anchors ANCHORS.json] [--out PATH.json]
// [--json]`: the camera path from the panoramas alone (processing/egomotion/egomotion.h); with --plan, each
// piece then placed on the plan by the tracker's points (processing/registration/registration.h) and refined
// on the walls (plan_refinement.h: drift taken out by the building) unless --no-refine; with
// --anchors, aligned to the anchors and refined with them as priors (processing/anchors/anchor_refinement.h).
// With --out, the tracker's points go beside the path file (PATH.points.json, model/path_points.h), in the
// path's frame, for `plenopath register` later.
// Still panoramas (issue 20, processing/stills/stills.h): `--stills DIR` solves a folder of tripod stills
// metres apart by wide-baseline matching instead of tracking; `--capture DIR` switches to that by itself
// when KLT follows too few corners between neighbouring images (processing/stills/stills_detection.h) and
// says so on stderr; --no-auto-stills keeps the tracker.
// Progress goes to stderr. --first/--last/--stride choose the frames tracked (positions in the natural order
// of the folder's image files, or the video's frame numbers); the frame indices of the path file,
// --known-distance and --anchors are the Capture's (model/capture.h): a video's frame numbers, a folder's
// positions among the frames kept (0, 1, ...), as the studio numbers them.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <numeric>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "app/cli/command.h"
#include "app/cli/console_progress.h"
#include "app/cli/registration_common.h"
#include "model/anchors_io.h"
#include "model/error.h"
#include "model/path_io.h"
#include "model/path_points.h"
#include "model/project_io.h"
#include "processing/anchors/anchor_refinement.h"
#include "processing/capture/frame_source.h"
#include "processing/capture/stills_folder.h"
#include "processing/egomotion/egomotion.h"
#include "processing/egomotion/tracking_health.h"
#include "processing/pipeline/track_step.h"
#include "processing/plan/dxf_import.h"
#include "processing/registration/registration.h"
#include "processing/stills/candidate_fit.h"
#include "processing/stills/stills.h"
#include "processing/stills/stills_along_pairs.h"
#include "processing/stills/stills_detection.h"
#include "processing/stills/stills_tracking.h"

namespace plenopath::cli {
namespace {

nlohmann::json stills_to_json(const StillsResult& s, const StillsDetection* detection, double camera_height,
                              bool height_given) {
  nlohmann::json groups = nlohmann::json::array();
  for (const std::vector<int>& g : s.groups) groups.push_back(g);
  int edges = 0, kept = 0;
  nlohmann::json pairs = nlohmann::json::array();
  for (const StillsPair& p : s.pairs) {
    edges += p.edge;
    kept += p.kept;
    if (p.inliers > 0)
      pairs.push_back({{"a", p.a},
                       {"b", p.b},
                       {"matches", p.matches},
                       {"inliers", p.inliers},
                       {"turn_deg", p.turn_deg},
                       {"direction_deg", p.direction_deg},
                       {"median_parallax_deg", p.median_parallax_deg},
                       {"floor_length_m", p.length_m},
                       {"coverage_deg", p.coverage_deg},
                       {"edge", p.edge},
                       {"kept", p.kept}});
  }
  nlohmann::json j = {{"stills", s.path.size()},
                      {"connected", s.path.size() - s.unconnected.size()},
                      {"unconnected", s.unconnected},
                      {"groups", groups},
                      {"pairs_matched", s.pairs.size()},
                      {"edges", edges},
                      {"edges_kept", kept},
                      {"verified_pairs", pairs},
                      {"features", s.features},
                      {"floor_points", s.floor_points},
                      {"camera_height_m", camera_height},
                      {"camera_height_given", height_given}};
  if (detection)
    j["detection"] = {{"followed_fraction", detection->followed_fraction}, {"reason", detection->reason}};
  return j;
}

}  // namespace

Command add_track_command(CLI::App& parent) {
  struct Options {
    std::string capture;
    std::string stills;   // folder of still panoramas: solved as stills without asking
    std::string project;  // project file: its capture, plan and camera height; the path written into it
    bool no_auto_stills = false;
    bool no_refine = false;
    double camera_height = 0.0;
    std::string out;
    bool json = false;
    bool quiet = false;
    bool no_loop_closure = false;
    int work_width = 1024;
    int first = 0;
    int last = -1;
    int stride = 1;
    std::vector<double> known_distance;  // frame a, frame b, metres
    std::string anchors;                 // anchors file: the path is refined onto them after tracking
    std::string mask;                    // image of the pixels not to use (black), e.g. the trolley
    bool level = false;                  // per-frame pitch/roll from vertical edges, always
    bool no_auto_level = false;          // ... never (default: when the first frames show the camera rocking)
    double tilt_prior = RefinementOptions{}.tilt_prior_deg;
    double step_check = EgomotionOptions{}.step_map_check_factor;
    int floor_steps = EgomotionOptions{}.floor_step_min_points;
    double floor_prior = 100.0 * RefinementOptions{}.floor_sigma;  // percent of the floor's depth
    bool no_static_mask = false;
    std::string mask_out;  // the mask used, written as an image
    std::string plan;      // DXF plan: the path is registered on it after tracking
    DxfImportOptions import;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub =
      parent.add_subcommand("track", "Recover the camera path (x, y, heading per frame) from the panoramas");
  CLI::Option* capture_option = sub->add_option(
      "--capture", options->capture, "Folder of equirectangular frames (natural sort order) or a video");
  sub->add_option("--stills", options->stills,
                  "Folder of still panoramas shot from a tripod metres apart (natural sort order): solved by "
                  "wide-baseline matching, not tracking")
      ->excludes(capture_option);
  // One of the two is needed: a usage error (exit 2) when neither is given.
  sub->add_option("--project", options->project,
                  "Project file: track its capture (its plan and camera height too, as the studio's "
                  "Process > Track does) and write the path and its points into it (keeping .bak)")
      ->excludes(capture_option);
  // One of them is needed: a usage error (exit 2) when none is given.
  sub->parse_complete_callback([options]() {
    if (options->capture.empty() && options->stills.empty() && options->project.empty())
      throw CLI::RequiredError("--capture, --stills or --project");
  });
  sub->add_flag("--no-auto-stills", options->no_auto_stills,
                "Track a folder even when its neighbouring images overlap too little for KLT (by default "
                "such a folder is solved as stills)");
  sub->add_option("--camera-height", options->camera_height,
                  "Camera height above the floor in metres: gives metric scale (else the scale is relative)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--known-distance", options->known_distance,
                  "Metric scale from a distance the author knows: FRAME_A FRAME_B METRES (used without "
                  "--camera-height)")
      ->expected(3);
  sub->add_option("--first", options->first, "First frame tracked (position in the capture, from 0)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--last", options->last, "Last frame tracked, inclusive (default: the capture's last)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--stride", options->stride, "Track every K-th frame from --first on")
      ->check(CLI::PositiveNumber);
  sub->add_option(
      "--anchors", options->anchors,
      "Anchors file [{\"index\", \"x\", \"y\", \"heading_deg\"?}, ...] (plan metres): after tracking, "
      "align the path to them and refine it with them as priors (corrects drift, puts it on the plan)");
  sub->add_option("--plan", options->plan,
                  "Floor plan (DXF): after tracking, place each piece of the path on it by the tracker's "
                  "points on its walls (needs --camera-height)");
  sub->add_flag("--no-refine", options->no_refine,
                "With --plan: place each piece by one similarity only (default: then refine the path on the "
                "walls, which takes out drift)");
  sub->add_option("--layers", options->import.layers, "With --plan: import only these layers (default: all)");
  sub->add_option("--occluders", options->import.occluder_layers,
                  "With --plan: the layers whose lines block sight (default: guessed from the names)");
  sub->add_option("--out", options->out,
                  "Write the path file here (JSON, see ARCHITECTURE.md), and the points beside it");
  sub->add_option("--work-width", options->work_width,
                  "Tracking resolution (frames are resized to this width)")
      ->check(CLI::Range(64, 16384));
  sub->add_option("--mask", options->mask,
                  "Mask image (any size, resized to the frames): black pixels are not used (the trolley, "
                  "the operator); combined with the automatic static-region mask");
  sub->add_option("--mask-out", options->mask_out,
                  "Write the mask the tracker used (the author's and the automatic one; white = used) as an "
                  "image, to check it or to edit it into a --mask");
  sub->add_flag("--no-static-mask", options->no_static_mask,
                "Do not mask image regions that stay put while the camera moves (trolley, operator)");
  sub->add_flag(
      "--level", options->level,
      "Level every frame by its pitch and roll, estimated from vertical edges (by default this is "
      "decided from the first 40 frames: on when the camera rocks, as a trolley on an uneven floor)");
  sub->add_flag("--no-auto-level", options->no_auto_level,
                "Never level the frames unless --level (the first frames' tilt is not judged)");
  sub->add_option("--tilt-prior", options->tilt_prior,
                  "Pitch and roll per frame are estimated in the refinement, held near level with this "
                  "spread in degrees (0: a perfectly level camera)")
      ->check(CLI::Range(0.0, 20.0))
      ->capture_default_str();
  sub->add_option("--floor-prior", options->floor_prior,
                  "Points on the floor are held to one level, with at most this spread in percent of the "
                  "camera height (narrowed to the spread the floor points show): the camera rides at one "
                  "height (trolley, tripod, render), so the scale cannot drift along the walk (0: off, for a "
                  "camera carried at a varying height)")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  sub->add_option("--step-check", options->step_check,
                  "A keyframe step is taken from the points triangulated so far when they place the frame "
                  "with this many times the support of the two-view step (0: never)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  sub->add_option("--floor-steps", options->floor_steps,
                  "With the floor prior, a keyframe step is measured on the floor when this many floor "
                  "tracks agree on it (0: never)")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  sub->add_flag("--no-loop-closure", options->no_loop_closure,
                "Do not tie places the walk comes back to (e.g. rooms that look alike)");
  sub->add_flag("--json", options->json, "Machine-readable summary on stdout");
  sub->add_flag("--quiet", options->quiet, "No progress on stderr");
  return {
      sub, [options, sub]() {
        const bool forced_stills = !options->stills.empty();
        if (forced_stills) options->capture = options->stills;
        if (options->last >= 0 && options->last < options->first)
          throw Error("--last " + std::to_string(options->last) + " is before --first " +
                      std::to_string(options->first));
        // The capture as the studio imports it: its Capture numbers the frames (Capture::frame_index_of_kept:
        // a video's frame numbers, a folder's positions among the frames kept), and the work below is the
        // pipeline's track step (processing/pipeline/track_step.h), as the studio's Process > Track.
        Project project;
        const bool from_project = !options->project.empty();
        if (from_project) {
          if (!options->stills.empty())
            throw Error("--stills with --project: import the stills into the project as stills instead");
          if (options->first != 0 || options->last >= 0 || options->stride != 1)
            throw Error(
                "--first, --last and --stride choose frames of --capture; a project's capture is "
                "tracked as it was imported");
          project = load_project(options->project);
          if (project.capture.empty())
            throw Error(options->project + ": the project has no capture to track");
          options->capture = project.capture.source;
          if (options->camera_height > 0)
            project.capture.camera_height_m = options->camera_height;
          else
            options->camera_height = project.capture.camera_height_m;
        } else {
          FrameSourceOptions source_options;
          source_options.first_frame = options->first;
          source_options.last_frame = options->last;
          source_options.stride = options->stride;
          const std::unique_ptr<FrameSource> source = FrameSource::open(options->capture, source_options);
          if (forced_stills && !(source->kind() == CaptureKind::kImageFolder && source->head_count() == 0))
            throw Error("--stills " + options->stills +
                        ": not a folder of panoramas (a video or a rig capture is "
                        "tracked with --capture)");
          project.capture = capture_from_frame_source(*source);
          project.capture.camera_height_m = options->camera_height;
        }
        const auto tracked = [&](int frame, const std::string& who) {
          const int kept = project.capture.kept_of_frame_index(frame);
          if (kept < 0)
            throw Error(who + "frame " + std::to_string(frame) +
                        ", which is not among the tracked frames (see --first, --last, --stride)");
          return kept;
        };
        // Anchors are read and checked before the long tracking run.
        Anchors anchors;
        if (!options->anchors.empty()) {
          anchors = read_anchors_file(options->anchors);
          if (anchors.empty()) throw Error(options->anchors + ": no anchors in the file");
          for (const Anchor& a : anchors) tracked(a.frame, options->anchors + ": anchor on ");
          project.anchors = anchors;
        }
        // The plan is read before the long tracking run too (a project's own, unless --plan names another).
        if (from_project && options->plan.empty() && !project.plan.empty()) {
          if (!(options->camera_height > 0) && !options->quiet)
            std::cerr
                << "track: the project's camera height is unknown: the path is not placed on its plan\n";
        } else if (!options->plan.empty()) {
          if (!(options->camera_height > 0))
            throw Error(
                "--plan needs --camera-height: registration tells wall points from floor points by it");
          project.plan = import_dxf(options->plan, options->import);
          if (project.plan.occluder_segments().empty())
            throw Error(options->plan +
                        ": registration needs walls, but the plan has no sight-blocking "
                        "segments (name the walls' layers with --occluders)");
        }
        // The plan the path is placed on, by name: --plan's, or the project's own.
        const std::string plan_name = !options->plan.empty()                    ? options->plan
                                      : (from_project && !project.plan.empty()) ? options->project
                                                                                : std::string();
        pipeline::TrackStepOptions to;
        EgomotionOptions& eo = to.egomotion;
        eo.camera_height_m = options->camera_height;
        eo.klt.work_width = options->work_width;
        eo.loop.enabled = !options->no_loop_closure;
        eo.klt.level_bearings = options->level;
        eo.klt.auto_level = !options->no_auto_level;
        eo.refinement.tilt_prior_deg = options->tilt_prior;
        eo.step_map_check_factor = options->step_check;
        eo.floor_step_min_points = options->floor_steps;
        eo.refinement.floor_sigma = options->floor_prior / 100.0;
        if (options->no_static_mask) eo.static_mask.frames = 0;
        if (!options->mask.empty()) {
          eo.mask = cv::imread(options->mask, cv::IMREAD_GRAYSCALE);
          if (eo.mask.empty()) throw Error(options->mask + ": cannot read the mask image");
          cv::threshold(eo.mask, eo.mask, 127, 255, cv::THRESH_BINARY);
          if (cv::countNonZero(eo.mask) == 0)
            throw Error(options->mask + ": the mask is all black (no pixel left to track)");
        }
        if (options->known_distance.size() == 3) {
          // Capture indices to kept frames, the tracker's numbering.
          eo.scale_frame_a = tracked(static_cast<int>(options->known_distance[0]), "--known-distance: ");
          eo.scale_frame_b = tracked(static_cast<int>(options->known_distance[1]), "--known-distance: ");
          eo.scale_distance_m = options->known_distance[2];
          try {
            eo.check();
          } catch (const Error& e) {
            throw Error(std::string("--known-distance: ") + e.what());
          }
        }
        const bool height_given = options->camera_height > 0;
        to.stills.features.work_width = sub->count("--work-width") ? options->work_width : 2048;
        if (to.stills.features.work_width % 2) ++to.stills.features.work_width;
        to.force_stills = forced_stills;
        to.auto_stills = !options->no_auto_stills;
        to.place_on_plan = !plan_name.empty();
        to.place.camera_height_m = options->camera_height;
        to.place.refine_on_walls = !options->no_refine;
        to.place.require = pipeline::PlaceStepOptions::Require::kNone;  // checked below, after the report
        to.refine_with_anchors = !anchors.empty();
        if (!anchors.empty() && !options->quiet)
          std::cerr << "track: refining with " << anchors.size() << " anchors after tracking\n";
        if (forced_stills && !height_given && !options->quiet)
          std::cerr << "track: stills: no --camera-height given, scale from a tripod height of "
                    << to.stills.camera_height_m << " m\n";
        ConsoleProgress progress("track", options->quiet);
        pipeline::TrackStepResult result = pipeline::run_track(std::move(project), to, progress);
        progress.finish();
        const bool as_stills = result.choice.stills;
        if (result.choice.detected && as_stills && !options->quiet) {
          std::cerr << "track: " << options->capture << " " << result.choice.reason
                    << ". Solved them as stills (--no-auto-stills tracks them anyway)\n";
          if (!height_given)
            std::cerr << "track: stills: no --camera-height given, scale from a tripod height of "
                      << to.stills.camera_height_m << " m\n";
        }
        EgomotionResult& r = result.tracking;
        r.path = result.project.path;
        r.tracked_points = result.project.path_points;
        const Capture& capture = result.project.capture;
        const int n = capture.frame_count;
        std::vector<int> positions(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) positions[static_cast<std::size_t>(i)] = capture.frame_index_of_kept(i);
        nlohmann::json stills_summary;
        if (as_stills) {
          const StillsResult& s = *result.stills;
          nlohmann::json stills_order;
          if (result.order) {  // stills come in the order they were shot (EXIF time) when every one says when
            const StillsFolder& folder = *result.order;
            if (!options->quiet) {
              std::cerr << "track: stills ordered " << folder.order;
              if (folder.stills_with_gps > 0)
                std::cerr << "; " << folder.stills_with_gps << " carry a GPS position";
              std::cerr << "\n";
              for (const std::string& note : folder.notes) std::cerr << "track: " << note << "\n";
            }
            stills_order = {
                {"order", folder.order}, {"with_gps", folder.stills_with_gps}, {"notes", folder.notes}};
          }
          const double stills_height = height_given ? options->camera_height : to.stills.camera_height_m;
          StillsResult with_path = s;
          with_path.path = r.path;
          stills_summary =
              stills_to_json(with_path, result.choice.detected ? &result.choice.detection : nullptr,
                             stills_height, height_given);
          stills_summary["capture_order"] = stills_order;
          if (!options->quiet && !s.unconnected.empty()) {
            std::cerr << "track: stills: " << s.unconnected.size() << " of " << n
                      << " stills connect to no other still:";
            for (int i : s.unconnected)
              std::cerr << " "
                        << (i >= 0 && i < static_cast<int>(capture.frame_names.size())
                                ? capture.frame_names[static_cast<std::size_t>(i)]
                                : std::to_string(i));
            std::cerr << "\n";
          }
        }
        nlohmann::json registration;
        if (!plan_name.empty() && !result.placement) {
          // As the studio: a project's path that cannot be placed is still worth having, unplaced.
          if (!from_project) throw Error(plan_name + ": " + result.placement_error);
          if (!options->quiet) std::cerr << "track: " << result.summary << "\n";
          registration = {{"placed", false}, {"reason", result.placement_error}};
        } else if (!plan_name.empty()) {
          const pipeline::PlaceStepResult& placed = *result.placement;
          const RegistrationResult& reg = placed.choices.result;
          if (as_stills &&
              !options->quiet) {  // repeated rooms: what the stills see picks among the placements
            if (placed.still_fit.pieces_reordered > 0)
              std::cerr << "track: stills: " << placed.still_fit.pieces_reordered
                        << " piece(s) placed by what the stills see rather than by their points\n";
            if (placed.still_fit.pieces_refused > 0)
              std::cerr
                  << "track: stills: " << placed.still_fit.pieces_refused
                  << " piece(s) left off the plan: their stills do not fit where their points put them\n";
          }
          registration = registration_to_json(reg);
          if (!options->quiet) print_registration(std::cerr, reg);
          // Stills that registration cannot place (no points of their own, walls too far for their points)
          // are not an error: the path is written with what is placed, and the rest are named below for
          // `place-still` (one click each).
          if (!as_stills && !from_project) require_registered(reg, plan_name);
          if (!options->no_refine) {
            registration["plan_refinement"] = plan_refinement_to_json(placed.choices.refinement);
            if (!options->quiet) print_plan_refinement(std::cerr, placed.choices.refinement);
          }
          if (as_stills) {
            // Stills with a pair to a placed one but no length: along the pair's direction, the plan
            // saying how far.
            const PairPlacementReport& pair_report = result.along_pairs;
            nlohmann::json along = nlohmann::json::array();
            for (const PairPlacement& q : pair_report.placed)
              along.push_back({{"still", q.frame},
                               {"from", q.from_frame},
                               {"fit_px", q.pose.score_px},
                               {"runner_up_fit_px", q.runner_up_fit_px},
                               {"other_pairs", q.other_pairs},
                               {"crossing_pairs", q.crossing_pairs}});
            registration["placed_along_pairs"] = along;
            nlohmann::json by_order = nlohmann::json::array();
            for (const CaptureOrderPlacement& q : result.capture_order.placed)
              by_order.push_back({{"still", q.frame},
                                  {"from", q.from_frames},
                                  {"fit_px", q.pose.score_px},
                                  {"elsewhere_fit_px", q.elsewhere_fit_px},
                                  {"pairs_agreeing", q.pairs_agreeing},
                                  {"pairs_voting", q.pairs_voting}});
            registration["placed_by_capture_order"] = by_order;
            if (!options->quiet && !result.capture_order.placed.empty())
              std::cerr << "track: stills: " << result.capture_order.placed.size()
                        << " still(s) placed next to their neighbours in capture order\n";
            if (!options->quiet && !pair_report.placed.empty())
              std::cerr << "track: stills: " << pair_report.placed.size()
                        << " still(s) placed along their pairs, the plan fixing the distance\n";
            nlohmann::json unplaced = nlohmann::json::array();
            for (const PathFrame& f : r.path.frames)
              if (!r.path.piece_placed(f.piece))
                unplaced.push_back(f.file.empty() ? std::to_string(f.index) : f.file);
            registration["unplaced_stills"] = unplaced;
            // Why each was left, as the last try next to its neighbours said it ("fit 2.9 px", "a spot
            // 3.1 m away fits 1.04x as well").
            std::map<int, std::string> why;
            for (const CaptureOrderRejection& q : result.capture_order.rejected) why[q.frame] = q.reason;
            nlohmann::json unplaced_why = nlohmann::json::array();
            for (const PathFrame& f : r.path.frames)
              if (!r.path.piece_placed(f.piece)) {
                const auto at = why.find(f.index);
                unplaced_why.push_back(
                    {{"still", f.index},
                     {"why", at != why.end()
                                 ? at->second
                                 : std::string("no placed neighbour in capture order to start from")}});
              }
            registration["unplaced_why"] = unplaced_why;
            if (!options->quiet && !unplaced.empty()) {
              std::cerr << "track: stills: " << unplaced.size()
                        << " still(s) could not be placed on the plan by themselves:";
              for (const auto& u : unplaced) std::cerr << " " << u.get<std::string>();
              std::cerr << "\ntrack: place each with `plenopath place-still --plan " << plan_name
                        << " --image STILL --at X Y` (roughly where it was shot)\n";
            }
          }
        }
        const AnchorRefinementReport& anchor_report = result.anchors;
        double worst_residual = 0.0;
        nlohmann::json residuals = nlohmann::json::array();
        for (const AnchorResidual& a : anchor_report.residuals) {
          worst_residual = std::max(worst_residual, a.distance_m);
          residuals.push_back({{"frame", a.frame}, {"distance_m", a.distance_m}});
        }
        if (from_project) {
          save_project(result.project, options->project);
          write_path_points_file(result.project.path_points, points_file_beside(options->project));
        }
        if (!options->out.empty()) {
          write_path_file(r.path, options->out);
          write_path_points_file(r.tracked_points, points_file_beside(options->out));
        }
        if (!options->mask_out.empty()) {
          const cv::Mat used = r.mask.empty() ? cv::Mat(1, 2, CV_8U, cv::Scalar(255)) : r.mask;
          if (!cv::imwrite(options->mask_out, used))
            throw Error(options->mask_out + ": cannot write the mask");
        }
        nlohmann::json pieces = nlohmann::json::array();
        for (int k = 0; k < r.path.piece_count(); ++k) {
          const CameraPath piece = r.path.piece_path(k);
          nlohmann::json j = {{"piece", k},
                              {"frames", piece.size()},
                              {"first_index", piece.empty() ? 0 : piece.frames.front().index},
                              {"last_index", piece.empty() ? 0 : piece.frames.back().index},
                              {"length", piece.length()},
                              {"placed", r.path.piece_placed(k)},
                              {"scale_source", piece.scale_source}};
          if (!r.path.pieces.empty()) {
            j["scale_factor"] = r.path.pieces[k].scale_factor;
            j["break_reason"] = r.path.pieces[k].break_reason;
          }
          pieces.push_back(std::move(j));
        }
        nlohmann::json summary = {{"capture", options->capture},
                                  {"pieces", pieces},
                                  {"joins", r.joins},
                                  {"steps_from_points", r.steps_from_points},
                                  {"steps_on_floor", r.steps_on_floor},
                                  {"frames", r.path.size()},
                                  {"first_index", positions.empty() ? 0 : positions.front()},
                                  {"last_index", positions.empty() ? 0 : positions.back()},
                                  {"stride", options->stride},
                                  {"keyframes", r.keyframes.size()},
                                  {"points", r.points},
                                  {"length", r.path.length()},
                                  {"scale_source", r.scale_source},
                                  {"flagged_frames", r.flagged_frames},
                                  {"masked_pct", 100.0 * r.static_mask_fraction},
                                  {"levelled", r.levelled},
                                  {"tilt_spread_deg", r.tilt_spread_deg},
                                  {"loop_closures", r.loop_closures},
                                  {"loop_frames", r.loop_frames},
                                  {"refinement_rms_deg", r.refinement.final_rms * 180.0 / M_PI},
                                  {"tilt_prior_deg", r.refinement.tilt_prior_used_deg},
                                  {"floor_prior_pct", 100.0 * r.refinement.floor_sigma_used},
                                  {"seconds", r.seconds_per_frame_stage + r.seconds_geometry},
                                  {"anchors", anchors.size()},
                                  {"anchor_residuals", residuals},
                                  {"out", options->out}};
        const TrackingHealth health = as_stills ? TrackingHealth{} : assess_tracking(r.path);
        summary["flag_counts"] = {
            {"bridged", health.bridged},       {"moving_objects", health.moving_objects},
            {"jumps", health.jumps},           {"textureless", health.textureless},
            {"duplicates", health.duplicates}, {"corrupt", health.corrupt}};
        summary["reliable"] = health.reliable;
        if (!health.reliable) summary["warning"] = health.warning;
        if (!registration.is_null()) summary["registration"] = registration;
        summary["mode"] = as_stills ? "stills" : "video";
        if (!stills_summary.is_null()) summary["stills"] = stills_summary;
        if (options->json) {
          std::cout << summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
        } else {
          if (as_stills)
            std::cout << "Solved " << r.path.size()
                      << " stills as stills: " << stills_summary["connected"].get<int>() << " connected, "
                      << stills_summary["unconnected"].size() << " unconnected\n";
          std::cout << "Tracked " << r.path.size() << " frames (" << r.keyframes.size() << " keyframes, "
                    << r.points << " points), path length " << std::fixed << std::setprecision(2)
                    << r.path.length() << (r.scale_source == "relative" ? " (relative units)" : " m")
                    << ", scale from " << r.scale_source << ", " << r.flagged_frames << " frames flagged, "
                    << r.loop_closures << " loop closures\n";
          if (!health.reliable) std::cout << "Warning: " << health.warning << "\n";
          if (r.path.piece_count() > 1) {
            std::cout << "The images do not connect everywhere: the path is in " << r.path.piece_count()
                      << " pieces, each with its own scale"
                      << (plan_name.empty() ? "; place each on the plan with its own anchors or --plan" : "")
                      << "\n";
            for (int k = 0; k < r.path.piece_count(); ++k) {
              const PathPiece& p = r.path.pieces[k];
              std::cout << "  piece " << k << ": frames " << p.first_index << "-" << p.last_index
                        << ", scale from " << p.scale_source << (p.placed ? "" : ", unplaced")
                        << (p.break_reason.empty() ? "" : " (" + p.break_reason + ")") << "\n";
            }
          }
          if (!anchors.empty())
            std::cout << "Aligned and refined with " << anchors.size() << " anchors from " << options->anchors
                      << ": largest anchor residual " << std::setprecision(3) << worst_residual << " m, "
                      << anchor_report.iterations << " iterations\n";
          if (result.placement)
            std::cout << "Placed on " << plan_name << " by " << r.tracked_points.size() << " points\n";
          if (!options->out.empty()) std::cout << "Wrote " << options->out << "\n";
          if (from_project) std::cout << "Wrote the path into " << options->project << "\n";
        }
        return kExitOk;
      }};
}

}  // namespace plenopath::cli
