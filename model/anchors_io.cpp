#include "model/anchors_io.h"

#include <set>

#include "model/atomic_file.h"
#include "model/camera_path.h"

namespace plenopath {

nlohmann::json anchors_to_json(const Anchors& anchors) {
  nlohmann::json out = nlohmann::json::array();
  for (const Anchor& a : anchors) {
    nlohmann::json j = {{"index", a.frame}, {"x", a.position.x()}, {"y", a.position.y()}};
    if (a.heading) j["heading_deg"] = degrees(*a.heading);
    out.push_back(std::move(j));
  }
  return out;
}

Anchors anchors_from_json(const JsonReader& r) {
  Anchors anchors;
  std::set<int> seen;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const JsonReader a = r.at(i);
    Anchor anchor;
    anchor.frame = a.integer("index");
    if (!seen.insert(anchor.frame).second)
      a.at("index").fail("two anchors on frame " + std::to_string(anchor.frame));
    anchor.position = {a.number("x"), a.number("y")};
    if (auto h = a.find("heading_deg")) anchor.heading = radians_of_written(h->number());
    anchors.push_back(anchor);
  }
  return anchors;
}

Anchors read_anchors_file(const std::string& file) {
  const nlohmann::json json = read_json_file(file);
  return anchors_from_json(JsonReader(json, file));
}

void write_anchors_file(const Anchors& anchors, const std::string& file) {
  write_file_atomically(
      file, anchors_to_json(anchors).dump(1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n",
      false);
}

}  // namespace plenopath
