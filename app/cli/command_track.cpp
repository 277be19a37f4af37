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
// Progress goes to stderr. Frame indices (path file, --known-distance, --first/--last) are positions in the
// whole capture: the natural order of the folder's image files, or the video's frame numbers.
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
#include "processing/anchors/anchor_refinement.h"
#include "processing/capture/frame_source.h"
#include "processing/capture/stills_folder.h"
#include "processing/egomotion/egomotion.h"
#include "processing/plan/dxf_import.h"
#include "processing/registration/registration.h"
#include "processing/stills/candidate_fit.h"
#include "processing/stills/stills.h"
#include "processing/stills/stills_along_pairs.h"
#include "processing/stills/stills_detection.h"
#include "processing/stills/stills_tracking.h"

namespace plenopath::cli {
namespace {

// Position of each kept frame in the whole capture. A folder's frames are counted in the natural order of
// its image files (as FrameSource sorts them), so a corrupt file left out keeps its place in the count.
std::vector<int> capture_positions(const FrameSource& source) {
  const int n = source.frame_count();
  const FrameSourceOptions& o = source.options();
  std::vector<int> positions(n);
  for (int i = 0; i < n; ++i) positions[i] = o.first_frame + i * o.stride;
  if (source.kind() == CaptureKind::kVideo) {
    for (int i = 0; i < n; ++i) positions[i] = std::max(0, source.frame_number(i));
  } else if (source.kind() == CaptureKind::kImageFolder && source.head_count() == 0) {
    namespace fs = std::filesystem;
    std::vector<std::string> names;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(source.source(), ec)) {
      std::error_code e2;
      if (!e.is_regular_file(e2)) continue;
      const std::string name = e.path().filename().string();
      std::string ext = e.path().extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
      if (name.empty() || name[0] == '.') continue;
      if (ext == ".jpg" || ext == ".jpeg" || ext == ".png" || ext == ".tif" || ext == ".tiff" ||
          ext == ".exr")
        names.push_back(name);
    }
    std::sort(names.begin(), names.end(), natural_less);
    std::map<std::string, int> position_of;
    for (size_t p = 0; p < names.size(); ++p) position_of[names[p]] = static_cast<int>(p);
    for (int i = 0; i < n; ++i) {
      const auto it = position_of.find(source.frame_name(i));
      if (it != position_of.end()) positions[i] = it->second;
    }
  }
  return positions;
}

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
    std::string stills;  // folder of still panoramas: solved as stills without asking
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
    bool level = false;                  // per-frame pitch/roll from vertical edges
    double tilt_prior = RefinementOptions{}.tilt_prior_deg;
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
  sub->parse_complete_callback([options]() {
    if (options->capture.empty() && options->stills.empty())
      throw CLI::RequiredError("--capture or --stills");
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
      "Estimate pitch and roll per frame from vertical edges (a camera rocking on an uneven floor)");
  sub->add_option("--tilt-prior", options->tilt_prior,
                  "Pitch and roll per frame are estimated in the refinement, held near level with this "
                  "spread in degrees (0: a perfectly level camera)")
      ->check(CLI::Range(0.0, 20.0))
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
        FrameSourceOptions source_options;
        source_options.first_frame = options->first;
        source_options.last_frame = options->last;
        source_options.stride = options->stride;
        std::unique_ptr<FrameSource> source = FrameSource::open(options->capture, source_options);
        const int n = source->frame_count();
        const bool plain_folder = source->kind() == CaptureKind::kImageFolder && source->head_count() == 0;
        if (forced_stills && !plain_folder)
          throw Error("--stills " + options->stills +
                      ": not a folder of panoramas (a video or a rig capture is "
                      "tracked with --capture)");
        // Stills or video: forced, or decided by how well KLT follows corners between neighbours.
        const StillsChoice choice = choose_stills(
            n, [&](int i) { return source->read(i); }, forced_stills, plain_folder, !options->no_auto_stills);
        const bool as_stills = choice.stills;
        if (choice.detected && as_stills && !options->quiet)
          std::cerr << "track: " << options->capture << " " << choice.reason
                    << ". Solving them as stills (--no-auto-stills tracks them anyway)\n";
        std::vector<int> positions = capture_positions(*source);
        nlohmann::json stills_order;
        if (as_stills) {
          // Stills come in the order they were shot (EXIF time) when every one says when.
          const StillsFolder folder = stills_folder(*source);
          if (!options->quiet) {
            std::cerr << "track: stills ordered " << folder.order;
            if (folder.stills_with_gps > 0)
              std::cerr << "; " << folder.stills_with_gps << " carry a GPS position";
            std::cerr << "\n";
            for (const std::string& note : folder.notes) std::cerr << "track: " << note << "\n";
          }
          stills_order = {
              {"order", folder.order}, {"with_gps", folder.stills_with_gps}, {"notes", folder.notes}};
          source = FrameSource::open_capture(folder.capture);
          std::iota(positions.begin(), positions.end(), 0);
        }
        // Anchors are read and checked before the long tracking run.
        Anchors anchors;
        if (!options->anchors.empty()) {
          anchors = read_anchors_file(options->anchors);
          if (anchors.empty()) throw Error(options->anchors + ": no anchors in the file");
          for (const Anchor& a : anchors)
            if (std::find(positions.begin(), positions.end(), a.frame) == positions.end())
              throw Error(options->anchors + ": anchor on frame " + std::to_string(a.frame) +
                          ", which is not among the tracked frames (see --first, --last, --stride)");
        }
        // The plan is read before the long tracking run too.
        FloorPlan plan;
        if (!options->plan.empty()) {
          if (!(options->camera_height > 0))
            throw Error(
                "--plan needs --camera-height: registration tells wall points from floor points by it");
          plan = import_dxf(options->plan, options->import);
          if (plan.occluder_segments().empty())
            throw Error(options->plan +
                        ": registration needs walls, but the plan has no sight-blocking "
                        "segments (name the walls' layers with --occluders)");
        }
        EgomotionOptions eo;
        eo.camera_height_m = options->camera_height;
        eo.klt.work_width = options->work_width;
        eo.loop.enabled = !options->no_loop_closure;
        eo.klt.level_bearings = options->level;
        eo.refinement.tilt_prior_deg = options->tilt_prior;
        if (options->no_static_mask) eo.static_mask.frames = 0;
        if (!options->mask.empty()) {
          eo.mask = cv::imread(options->mask, cv::IMREAD_GRAYSCALE);
          if (eo.mask.empty()) throw Error(options->mask + ": cannot read the mask image");
          cv::threshold(eo.mask, eo.mask, 127, 255, cv::THRESH_BINARY);
          if (cv::countNonZero(eo.mask) == 0)
            throw Error(options->mask + ": the mask is all black (no pixel left to track)");
        }
        if (options->known_distance.size() == 3) {
          // Capture positions to positions among the tracked frames.
          auto tracked = [&](double frame) {
            const auto it = std::find(positions.begin(), positions.end(), static_cast<int>(frame));
            if (it == positions.end())
              throw Error("--known-distance: frame " + std::to_string(static_cast<int>(frame)) +
                          " is not among the tracked frames (see --first, --last, --stride)");
            return static_cast<int>(it - positions.begin());
          };
          eo.scale_frame_a = tracked(options->known_distance[0]);
          eo.scale_frame_b = tracked(options->known_distance[1]);
          eo.scale_distance_m = options->known_distance[2];
          try {
            eo.check();
          } catch (const Error& e) {
            throw Error(std::string("--known-distance: ") + e.what());
          }
        }
        EgomotionResult r;
        nlohmann::json stills_summary;
        std::vector<StillsPair> stills_pairs;  // every verified pair, for placing stills along them
        if (as_stills) {
          StillsOptions so;
          const bool height_given = options->camera_height > 0;
          if (height_given)
            so.camera_height_m = options->camera_height;
          else if (!options->quiet)
            std::cerr << "track: stills: no --camera-height given, scale from a tripod height of "
                      << so.camera_height_m << " m\n";
          so.features.work_width = sub->count("--work-width") ? options->work_width : 2048;
          if (so.features.work_width % 2) ++so.features.work_width;
          ConsoleProgress progress("track: stills", options->quiet);
          const StillsResult s = solve_stills(
              n, [&](int i) { return source->read(i); }, so, progress);
          progress.finish();
          r = tracker_result_from_stills(s);
          stills_pairs = s.pairs;
          stills_summary = stills_to_json(s, choice.detected ? &choice.detection : nullptr,
                                          so.camera_height_m, height_given);
          stills_summary["capture_order"] = stills_order;
          if (!options->quiet && !s.unconnected.empty()) {
            std::cerr << "track: stills: " << s.unconnected.size() << " of " << n
                      << " stills connect to no other still:";
            for (int i : s.unconnected) std::cerr << " " << source->frame_name(i);
            std::cerr << "\n";
          }
        } else {
          ConsoleProgress progress("track", options->quiet);
          r = EgomotionTracker::run(
              n, [&](int i) { return source->read(i); }, eo, progress);
          progress.finish();
        }
        renumber_frames(&r.path, positions);
        renumber_point_frames(&r.tracked_points, positions);
        if (source->kind() == CaptureKind::kImageFolder)
          for (int i = 0; i < n; ++i) r.path.frames[i].file = source->frame_name(i);
        nlohmann::json registration;
        if (!options->plan.empty()) {
          RegistrationOptions ro;
          ro.camera_height_m = options->camera_height;
          ConsoleProgress register_progress("track: registration", options->quiet);
          RegistrationResult reg = register_on_plan(r.path, r.tracked_points, plan, ro, register_progress);
          register_progress.finish();
          if (as_stills) {  // repeated rooms: what the stills see picks among the placements
            CandidateFitOptions fit_options;
            fit_options.fit.camera_height_m = options->camera_height;
            ConsoleProgress fit_progress("track: stills against the plan", options->quiet);
            const CandidateFitReport fit = rerank_by_still_fit(
                &reg, r.path, [&](int i) { return source->read(i); }, plan, fit_options, fit_progress);
            fit_progress.finish();
            if (!options->quiet && fit.pieces_reordered > 0)
              std::cerr << "track: stills: " << fit.pieces_reordered
                        << " piece(s) placed by what the stills see rather than by their points\n";
            if (!options->quiet && fit.pieces_refused > 0)
              std::cerr
                  << "track: stills: " << fit.pieces_refused
                  << " piece(s) left off the plan: their stills do not fit where their points put them\n";
          }
          registration = registration_to_json(reg);
          if (!options->quiet) print_registration(std::cerr, reg);
          // Stills that registration cannot place (no points of their own, walls too far for their points)
          // are not an error: the path is written with what is placed, and the rest are named below for
          // `place-still` (one click each).
          if (!as_stills) require_registered(reg, options->plan);
          r.path = apply_registration(r.path, reg, {}, &r.tracked_points);
          // A group of stills left where the stills pipeline put it is not on the plan: unplaced.
          if (as_stills)
            for (const PieceRegistration& p : reg.pieces)
              if (!p.ok && p.piece < static_cast<int>(r.path.pieces.size()))
                r.path.pieces[static_cast<std::size_t>(p.piece)].placed = false;
          if (!options->no_refine) {
            PlanRefinementOptions refine_options;
            refine_options.registration = ro;
            ConsoleProgress refine_progress("track: refinement on the walls", options->quiet);
            PlanRefinementReport refinement;
            r.path =
                refine_on_plan(r.path, &r.tracked_points, plan, refine_options, &refinement, refine_progress);
            refine_progress.finish();
            registration["plan_refinement"] = plan_refinement_to_json(refinement);
            if (!options->quiet) print_plan_refinement(std::cerr, refinement);
          }
          if (as_stills) {
            // Stills with a pair to a placed one but no length: along the pair's direction, the plan
            // saying how far.
            PairPlacementOptions pair_options;
            pair_options.fit.camera_height_m = options->camera_height;
            PairPlacementReport pair_report;
            ConsoleProgress pair_progress("track: stills along their pairs", options->quiet);
            r.path = place_stills_along_pairs(
                r.path, stills_pairs, [&](int i) { return source->read(i); }, plan, pair_options,
                &pair_report, pair_progress);
            pair_progress.finish();
            nlohmann::json along = nlohmann::json::array();
            for (const PairPlacement& q : pair_report.placed)
              along.push_back({{"still", q.frame},
                               {"from", q.from_frame},
                               {"fit_px", q.pose.score_px},
                               {"runner_up_fit_px", q.runner_up_fit_px}});
            registration["placed_along_pairs"] = along;
            if (!options->quiet && !pair_report.placed.empty())
              std::cerr << "track: stills: " << pair_report.placed.size()
                        << " still(s) placed along their pairs, the plan fixing the distance\n";
            nlohmann::json unplaced = nlohmann::json::array();
            for (const PathFrame& f : r.path.frames)
              if (!r.path.piece_placed(f.piece))
                unplaced.push_back(f.file.empty() ? std::to_string(f.index) : f.file);
            registration["unplaced_stills"] = unplaced;
            if (!options->quiet && !unplaced.empty()) {
              std::cerr << "track: stills: " << unplaced.size()
                        << " still(s) could not be placed on the plan by themselves:";
              for (const auto& u : unplaced) std::cerr << " " << u.get<std::string>();
              std::cerr << "\ntrack: place each with `plenopath place-still --plan " << options->plan
                        << " --image STILL --at X Y` (roughly where it was shot)\n";
            }
          }
        }
        AnchorRefinementReport anchor_report;
        if (!anchors.empty()) {
          if (!options->quiet) std::cerr << "track: refining with " << anchors.size() << " anchors\n";
          ConsoleProgress anchor_progress("track: anchors", options->quiet);
          r.path = refine_path_with_anchors(r.path, anchors, {}, &anchor_report, anchor_progress);
          anchor_progress.finish();
          // Two anchors or more fix the scale too.
          if (anchors.size() >= 2) r.path.scale_source = r.scale_source = "anchors";
        }
        double worst_residual = 0.0;
        nlohmann::json residuals = nlohmann::json::array();
        for (const AnchorResidual& a : anchor_report.residuals) {
          worst_residual = std::max(worst_residual, a.distance_m);
          residuals.push_back({{"frame", a.frame}, {"distance_m", a.distance_m}});
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
                                  {"loop_closures", r.loop_closures},
                                  {"loop_frames", r.loop_frames},
                                  {"refinement_rms_deg", r.refinement.final_rms * 180.0 / M_PI},
                                  {"seconds", r.seconds_per_frame_stage + r.seconds_geometry},
                                  {"anchors", anchors.size()},
                                  {"anchor_residuals", residuals},
                                  {"out", options->out}};
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
          if (r.path.piece_count() > 1) {
            std::cout << "The images do not connect everywhere: the path is in " << r.path.piece_count()
                      << " pieces, each with its own scale"
                      << (options->plan.empty() ? "; place each on the plan with its own anchors or --plan"
                                                : "")
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
          if (!options->plan.empty())
            std::cout << "Placed on " << options->plan << " by " << r.tracked_points.size() << " points\n";
          if (!options->out.empty()) std::cout << "Wrote " << options->out << "\n";
        }
        return kExitOk;
      }};
}

}  // namespace plenopath::cli
