#pragma once
// Names inside a tour package (a folder or a .zip): the one check every file written into it passes.
#include <string>

namespace plenopath {

// True when `name` is a relative path that stays inside the package: no "..", no leading '/', no '\\',
// no drive letter, no empty component.
bool is_safe_package_path(const std::string& name);

}  // namespace plenopath
