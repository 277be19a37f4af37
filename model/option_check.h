#pragma once
// The one check() convention for options structs (issue 17): check() throws an Error naming the struct, the
// field, the rule and the value it got, e.g. "EgomotionOptions.keyframe_parallax_deg must be > 0, got -1".
//
//   void EgomotionOptions::check() const {
//     require_option(keyframe_parallax_deg > 0, "EgomotionOptions.keyframe_parallax_deg", "must be > 0",
//                    keyframe_parallax_deg);
//     ring.check();  // a nested struct names itself
//   }
#include <sstream>
#include <string>
#include <type_traits>

#include "model/error.h"

namespace plenopath {

// "FIELD RULE, got VALUE" (strings quoted).
template <typename T>
std::string option_message(const std::string& field, const std::string& rule, const T& value) {
  std::ostringstream o;
  o << field << ' ' << rule << ", got ";
  if constexpr (std::is_convertible_v<const T&, std::string>)
    o << '\'' << std::string(value) << '\'';
  else
    o << value;
  return o.str();
}

// Throws Error(option_message(...)) unless `ok`.
template <typename T>
void require_option(bool ok, const std::string& field, const std::string& rule, const T& value) {
  if (!ok) throw Error(option_message(field, rule, value));
}

}  // namespace plenopath
