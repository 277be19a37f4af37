#pragma once
// Shared by `plenopath track --plan` and `plenopath register`: registration results as JSON and as lines.
#include <nlohmann/json.hpp>
#include <ostream>

#include "processing/registration/plan_refinement.h"
#include "processing/registration/registration.h"

namespace plenopath::cli {

// {"pieces": [{"piece", "ok", "message", "wall_points", "ambiguity_ratio", "transform": {...}, "score",
//  "wall_share", "free_share", "rms_m", "candidates": [{"transform", "score", ...}, ...]}], "seconds"}
nlohmann::json registration_to_json(const RegistrationResult& result);
// One line per piece (registration.h describe()).
void print_registration(std::ostream& out, const RegistrationResult& result);
// Throws Error listing the pieces that did not fit (their messages), prefixed by `who`.
void require_registered(const RegistrationResult& result, const std::string& who);

// {"pieces": [{"piece", "refined", "kept", "message", "wall_points", "wall_share_before", "wall_share_after",
//  "rms_before_m", "rms_after_m", "drift_scale", "drift_bias_deg_per_100_frames", "max_shift_m"}], "seconds"}
nlohmann::json plan_refinement_to_json(const PlanRefinementReport& report);
// One line per piece (plan_refinement.h describe()).
void print_plan_refinement(std::ostream& out, const PlanRefinementReport& report);

}  // namespace plenopath::cli
