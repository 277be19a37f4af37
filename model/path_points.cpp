#include "model/path_points.h"

#include <cmath>
#include <sstream>

#include "model/atomic_file.h"
#include "model/error.h"
#include "model/json_reader.h"

namespace plenopath {

bool operator==(const PathPoint& l, const PathPoint& r) {
  return l.position == r.position && l.piece == r.piece && l.observations == r.observations &&
         l.frame == r.frame;
}

std::vector<PathPoint> read_path_points_file(const std::string& file) {
  const nlohmann::json json = read_json_file(file);
  return path_points_from_json(JsonReader(json, file));
}

std::vector<PathPoint> path_points_from_json(const JsonReader& root) {
  if (root.string_or("format", "") != "plenopath-path-points")
    root.fail("not a points file (\"format\" must be \"plenopath-path-points\")");
  if (root.string_or("units", "m") != "m") root.at("units").fail("units must be \"m\"");
  if (root.value().contains("version") && root.at("version").value().is_number_integer() &&
      root.at("version").value().get<long long>() > 2)
    root.at("version").fail("was written by a newer Plenopath Studio (version " +
                            std::to_string(root.at("version").value().get<long long>()) +
                            "; this one reads 1 and 2)");
  const JsonReader points = root.at("points");
  const std::size_t n = points.size();
  std::vector<PathPoint> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const nlohmann::json& p = points.value()[i];
    if (!p.is_array() || (p.size() != 5 && p.size() != 6) || !p[0].is_number() || !p[1].is_number() ||
        !p[2].is_number() || !p[3].is_number_integer() || !p[4].is_number_integer() ||
        (p.size() == 6 && !p[5].is_number_integer()))
      points.at(i).fail("expected [x, y, z, piece, observations, frame]");
    PathPoint& q = out[i];
    q.position = {p[0].get<double>(), p[1].get<double>(), p[2].get<double>()};
    q.piece = p[3].get<int>();
    q.observations = p[4].get<int>();
    const long long frame = p.size() == 6 ? p[5].get<long long>() : -1;
    if (frame < -1 || frame > 1000000000)
      points.at(i).fail("frame must be a capture index (or -1: not known)");
    q.frame = static_cast<int>(frame);
    if (!q.position.allFinite()) points.at(i).fail("coordinates must be finite");
    if (q.piece < 0) points.at(i).fail("piece must be >= 0");
  }
  return out;
}

void write_path_points_file(const std::vector<PathPoint>& points, const std::string& file) {
  // Written by hand: nlohmann's DOM would cost ~200 bytes per number for 100 000 points.
  std::ostringstream o;
  o.precision(5);
  o << std::fixed;
  o << "{\"format\":\"plenopath-path-points\",\"version\":2,\"units\":\"m\",\"points\":[";
  for (std::size_t i = 0; i < points.size(); ++i) {
    const PathPoint& p = points[i];
    o << (i ? ",\n" : "\n") << '[' << p.position.x() << ',' << p.position.y() << ',' << p.position.z() << ','
      << p.piece << ',' << p.observations << ',' << p.frame << ']';
  }
  o << "]}\n";
  write_file_atomically(file, o.str(), false);
}

std::string points_file_beside(const std::string& file) {
  const std::size_t slash = file.find_last_of("/\\"), dot = file.find_last_of('.');
  const bool has_extension = dot != std::string::npos && (slash == std::string::npos || dot > slash + 1);
  return (has_extension ? file.substr(0, dot) : file) + ".points.json";
}

void renumber_point_frames(std::vector<PathPoint>* points, const std::vector<int>& positions) {
  for (PathPoint& p : *points)
    p.frame = p.frame >= 0 && p.frame < static_cast<int>(positions.size())
                  ? positions[static_cast<std::size_t>(p.frame)]
                  : -1;
}

void transform_piece_points(std::vector<PathPoint>* points, int piece, double rotation, double scale,
                            const Eigen::Vector2d& translation) {
  const double c = std::cos(rotation), s = std::sin(rotation);
  for (PathPoint& p : *points) {
    if (p.piece != piece) continue;
    const double x = p.position.x(), y = p.position.y();
    p.position = {scale * (c * x - s * y) + translation.x(), scale * (s * x + c * y) + translation.y(),
                  scale * p.position.z()};
  }
}

}  // namespace plenopath
