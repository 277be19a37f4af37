#pragma once
// Shared by the interop tests: running a real reader program and a small hand-made georeferenced project
// whose positions on Earth are known without our code.
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "model/project.h"

namespace plenopath::interop_test {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout
};

inline CommandResult run_command(const std::string& command) {
  CommandResult r;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer;
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) r.output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline bool have_program(const std::string& name) {
  return run_command("command -v " + name + " >/dev/null 2>&1").exit_code == 0;
}

// At latitude 48 deg one degree of latitude is 111 190.3 m and one of longitude 74 625.2 m (WGS84 meridian
// and parallel arc lengths, hand-computed from the series 111132.954 - 559.822 cos 2phi + ..., as in
// tour_export_test's GeoJSON test). Frame 1 is one thousandth of a degree north of the anchor, frame 2 one
// thousandth east; the camera 1.6 m above the floor, the anchor at 35 m.
constexpr double kMetresPerMilliDegreeLat = 111.1903, kMetresPerMilliDegreeLon = 74.6252;

inline Project hand_made_project() {
  Project p;
  p.tour.title = "Hand <made> & placed";
  p.geo = {true, 48.0, 2.0, 35.0, 0.0, 1.0, {0.0, 0.0}};
  p.path.frames = {{0, "", 0.0, 0.0, 0.0, 1.0, 0, ""},
                   {1, "", 0.0, kMetresPerMilliDegreeLat, M_PI / 2, 1.0, 0, ""},
                   {2, "", kMetresPerMilliDegreeLon, 0.0, 200.0 * M_PI / 180.0, 1.0, 0, ""}};
  p.keyframes.indices = {0, 2};
  p.keyframes.rank = {0, 1};
  p.capture.kind = CaptureKind::kImageFolder;
  p.capture.frame_count = 3;
  p.capture.frame_rate = 10.0;
  p.capture.camera_height_m = 1.6;
  return p;
}

}  // namespace plenopath::interop_test
