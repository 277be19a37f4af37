// `plenopath eval-path --estimate PATH.json --truth GT.json [--match index|file] [--json]`: frames matched by
// index (or by image file name: a path tracked with --stride or --first numbers the frames it kept 0, 1, ...,
// as the studio does), a 2-D similarity alignment without reflection (Umeyama), then heading RMS and
// absolute trajectory error. An estimate in pieces (CameraPath::pieces) is also scored piece by piece, each
// aligned on its own.
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "model/error.h"
#include "model/path_io.h"
#include "processing/egomotion/path_evaluation.h"

namespace plenopath::cli {
namespace {

// `estimate` with each frame numbered as the truth's frame of the same image file name (folders left out);
// frames whose file the truth does not have are left out, as unmatched indices are.
CameraPath numbered_by_file(const CameraPath& estimate, const CameraPath& truth,
                            const std::string& estimate_file, const std::string& truth_file) {
  const auto name = [](const std::string& file) { return std::filesystem::path(file).filename().string(); };
  std::map<std::string, int> truth_index;
  for (const PathFrame& f : truth.frames) {
    if (f.file.empty())
      throw file_error(truth_file, "frame " + std::to_string(f.index) + " has no file name");
    if (!truth_index.emplace(name(f.file), f.index).second)
      throw file_error(truth_file, "two frames have the file name " + name(f.file));
  }
  CameraPath out = estimate;
  out.frames.clear();
  for (PathFrame f : estimate.frames) {
    if (f.file.empty())
      throw file_error(estimate_file, "frame " + std::to_string(f.index) + " has no file name to match by");
    const auto at = truth_index.find(name(f.file));
    if (at == truth_index.end()) continue;
    f.index = at->second;
    out.frames.push_back(std::move(f));
  }
  return out;
}

}  // namespace

Command add_eval_path_command(CLI::App& parent) {
  struct Options {
    std::string estimate, truth, match = "index";
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub = parent.add_subcommand("eval-path", "Score an estimated camera path against ground truth");
  sub->add_option("--estimate", options->estimate, "Estimated path file (JSON)")->required();
  sub->add_option("--truth", options->truth, "Ground-truth path file (JSON)")->required();
  sub->add_option("--match", options->match,
                  "Match frames by index, or by image file name (a path tracked with --stride or --first)")
      ->check(CLI::IsMember({"index", "file"}))
      ->capture_default_str();
  sub->add_flag("--json", options->json, "Machine-readable output");
  return {sub, [options]() {
            const CameraPath truth = read_path_file(options->truth);
            const CameraPath estimate = options->match == "file"
                                            ? numbered_by_file(read_path_file(options->estimate), truth,
                                                               options->estimate, options->truth)
                                            : read_path_file(options->estimate);
            const PathErrors e = evaluate_path(estimate, truth);
            const nlohmann::json j = {
                {"frames_matched", e.frames_matched}, {"rot_rms_deg", e.rot_rms_deg},
                {"rot_max_deg", e.rot_max_deg},       {"ate_rms_m", e.ate_rms_m},
                {"ate_max_m", e.ate_max_m},           {"ate_pct", e.ate_pct},
                {"truth_length_m", e.truth_length_m}, {"scale_error_pct", e.scale_error_pct}};
            auto scores = [](const PathErrors& p) {
              return nlohmann::json{{"frames_matched", p.frames_matched},
                                    {"rot_rms_deg", p.rot_rms_deg},
                                    {"rot_max_deg", p.rot_max_deg},
                                    {"ate_rms_m", p.ate_rms_m},
                                    {"ate_pct", p.ate_pct},
                                    {"truth_length_m", p.truth_length_m},
                                    {"scale_error_pct", p.scale_error_pct}};
            };
            nlohmann::json pieces = nlohmann::json::array();
            std::vector<PathErrors> piece_errors;
            if (estimate.piece_count() > 1) {
              for (int k = 0; k < estimate.piece_count(); ++k) {
                const CameraPath piece = estimate.piece_path(k);
                if (piece.size() < 2) continue;
                piece_errors.push_back(evaluate_path(piece, truth));
                nlohmann::json q = scores(piece_errors.back());
                q["piece"] = k;
                q["first_index"] = piece.frames.front().index;
                q["last_index"] = piece.frames.back().index;
                pieces.push_back(std::move(q));
              }
            }
            if (options->json) {
              nlohmann::json out = j;
              out["pieces"] = pieces;
              std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
            } else {
              std::cout << std::fixed << std::setprecision(4) << e.frames_matched
                        << " frames matched; heading RMS " << e.rot_rms_deg << " deg; ATE " << e.ate_rms_m
                        << " m RMS (" << e.ate_pct << " % of " << e.truth_length_m << " m); scale error "
                        << e.scale_error_pct << " %\n";
              for (std::size_t k = 0; k < piece_errors.size(); ++k) {
                const PathErrors& p = piece_errors[k];
                std::cout << "  piece " << pieces[k]["piece"].get<int>() << ": " << p.frames_matched
                          << " frames; heading RMS " << p.rot_rms_deg << " deg; ATE " << p.ate_pct
                          << " %; scale error " << p.scale_error_pct << " %\n";
              }
            }
            return kExitOk;
          }};
}

}  // namespace plenopath::cli
