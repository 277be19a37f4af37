#include "app/cli/registration_common.h"

#include <cmath>

#include "model/error.h"

namespace plenopath::cli {
namespace {

nlohmann::json candidate_json(const RegistrationCandidate& c) {
  return {{"transform",
           {{"rotation_deg", degrees(c.transform.rotation)},
            {"translation", {c.transform.translation.x(), c.transform.translation.y()}},
            {"scale", c.transform.scale}}},
          {"score", c.score},
          {"wall_share", c.wall_share},
          {"free_share", c.free_share},
          {"through_share", c.through_share},
          {"rms_m", c.rms_m}};
}

}  // namespace

nlohmann::json registration_to_json(const RegistrationResult& result) {
  nlohmann::json pieces = nlohmann::json::array();
  for (const PieceRegistration& p : result.pieces) {
    nlohmann::json j = {
        {"piece", p.piece}, {"ok", p.ok}, {"wall_points", p.wall_points}, {"ceiling_m", p.ceiling_m}};
    if (!p.message.empty()) j["message"] = p.message;
    const double ratio = p.ambiguity_ratio();
    j["ambiguity_ratio"] = std::isfinite(ratio) ? nlohmann::json(ratio) : nlohmann::json(nullptr);
    nlohmann::json candidates = nlohmann::json::array();
    for (const RegistrationCandidate& c : p.candidates) candidates.push_back(candidate_json(c));
    if (!p.candidates.empty()) j.update(candidate_json(p.candidates.front()));
    j["candidates"] = std::move(candidates);
    pieces.push_back(std::move(j));
  }
  return {{"pieces", std::move(pieces)}, {"seconds", result.seconds}};
}

void print_registration(std::ostream& out, const RegistrationResult& result) {
  for (const PieceRegistration& p : result.pieces) out << "  " << describe(p) << "\n";
}

nlohmann::json plan_refinement_to_json(const PlanRefinementReport& report) {
  nlohmann::json pieces = nlohmann::json::array();
  for (const PieceRefinement& p : report.pieces) {
    nlohmann::json j = {{"piece", p.piece},
                        {"refined", p.refined},
                        {"kept", p.kept},
                        {"wall_points", p.wall_points},
                        {"wall_share_before", p.wall_share_before},
                        {"wall_share_after", p.wall_share_after},
                        {"rms_before_m", p.rms_before_m},
                        {"rms_after_m", p.rms_after_m},
                        {"free_share_before", p.free_share_before},
                        {"free_share_after", p.free_share_after},
                        {"drift_scale", p.drift_scale},
                        {"drift_bias_deg_per_100_frames", p.drift_bias_deg_per_100_frames},
                        {"max_shift_m", p.max_shift_m},
                        {"iterations", p.iterations}};
    if (!p.message.empty()) j["message"] = p.message;
    pieces.push_back(std::move(j));
  }
  return {{"pieces", std::move(pieces)}, {"seconds", report.seconds}};
}

void print_plan_refinement(std::ostream& out, const PlanRefinementReport& report) {
  for (const PieceRefinement& p : report.pieces) out << "  " << describe(p) << "\n";
}

void require_registered(const RegistrationResult& result, const std::string& who) {
  std::string failed;
  for (const PieceRegistration& p : result.pieces)
    if (!p.ok) failed += (failed.empty() ? "" : "; ") + describe(p);
  if (!failed.empty()) throw Error(who + ": " + failed);
}

}  // namespace plenopath::cli
