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

void require_registered(const RegistrationResult& result, const std::string& who) {
  std::string failed;
  for (const PieceRegistration& p : result.pieces)
    if (!p.ok) failed += (failed.empty() ? "" : "; ") + describe(p);
  if (!failed.empty()) throw Error(who + ": " + failed);
}

}  // namespace plenopath::cli
