#pragma once
// Text and attribute values for the XML the export writes (plan.svg, path.kml, path.gpx).
#include <string>

namespace plenopath {

// & < > " as entities; everything else as it is (UTF-8 passes through).
std::string xml_escape(const std::string& text);

}  // namespace plenopath
