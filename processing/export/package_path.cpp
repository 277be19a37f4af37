#include "processing/export/package_path.h"

#include <sstream>

namespace plenopath {

bool is_safe_package_path(const std::string& name) {
  if (name.empty() || name.front() == '/' || name.find('\\') != std::string::npos) return false;
  if (name.size() >= 2 && name[1] == ':') return false;
  std::stringstream parts(name);
  std::string part;
  while (std::getline(parts, part, '/'))
    if (part.empty() || part == "." || part == "..") return false;
  return name.back() != '/';
}

}  // namespace plenopath
