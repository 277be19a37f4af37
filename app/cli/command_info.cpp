// `plenopath info PROJECT.plenopath [--json]`: a summary of the document.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "model/project_io.h"
#include "processing/hotspots/hotspot_validation.h"

namespace plenopath::cli {
namespace {

// Problems an author should fix before exporting (missing media, inconsistent quads, markup in text).
nlohmann::json hotspot_warnings(const Project& p) {
  nlohmann::json out = nlohmann::json::array();
  for (const HotspotWarning& w : validate_hotspots(p))
    out.push_back({{"hotspot", w.hotspot_id}, {"field", w.field}, {"message", w.message}});
  return out;
}

nlohmann::json summarize(const Project& p, const std::string& file) {
  const PlanExtents e = p.plan.extents();
  int flagged = 0;
  for (const auto& f : p.path.frames) flagged += f.flags != kFrameOk;
  nlohmann::json plan = {{"source_file", p.plan.source_file},
                         {"units", p.plan.units},
                         {"layers", p.plan.layers.size()},
                         {"segments", p.plan.segments.size()},
                         {"occluder_segments", p.plan.occluder_segments().size()},
                         {"labels", p.plan.labels.size()}};
  if (e.valid) plan["extents_m"] = {{"min", {e.min.x(), e.min.y()}}, {"max", {e.max.x(), e.max.y()}}};
  return {{"project", file},
          {"title", p.tour.title},
          {"plan", plan},
          {"capture",
           {{"kind", to_string(p.capture.kind)},
            {"source", p.capture.source},
            {"frames", p.capture.frame_count},
            {"size", {p.capture.width, p.capture.height}},
            {"depth", !p.capture.depth_folder.empty()},
            {"gps_samples", p.capture.gps_track.size()}}},
          {"path",
           {{"frames", p.path.size()},
            {"length_m", p.path.length()},
            {"flagged_frames", flagged},
            {"scale_source", p.path.scale_source}}},
          {"anchors", p.anchors.size()},
          {"visibility", {{"events", p.visibility.events.size()}, {"cells", p.visibility.cells.size()}}},
          {"keyframes",
           {{"count", p.keyframes.indices.size()}, {"method", to_string(p.keyframes.parameters.method)}}},
          {"hotspots", p.hotspots.size()},
          {"hotspot_warnings", hotspot_warnings(p)},
          {"geo_anchor", p.geo.valid}};
}

void print_text(const nlohmann::json& s) {
  std::cout << std::fixed << std::setprecision(2);
  std::cout << "Project   " << s["project"].get<std::string>() << "  (\"" << s["title"].get<std::string>()
            << "\")\n";
  const auto& plan = s["plan"];
  std::cout << "Plan      " << plan["segments"] << " segments (" << plan["occluder_segments"]
            << " occluding) on " << plan["layers"] << " layers, " << plan["labels"] << " labels";
  if (plan.contains("extents_m")) {
    const auto& e = plan["extents_m"];
    std::cout << ", " << (e["max"][0].get<double>() - e["min"][0].get<double>()) << " x "
              << (e["max"][1].get<double>() - e["min"][1].get<double>()) << " m";
  }
  std::cout << "\n";
  const auto& c = s["capture"];
  std::cout << "Capture   " << c["kind"].get<std::string>() << ", " << c["frames"] << " frames of "
            << c["size"][0] << "x" << c["size"][1] << (c["depth"].get<bool>() ? ", with depth" : "") << "\n";
  const auto& path = s["path"];
  std::cout << "Path      " << path["frames"] << " frames, " << path["length_m"].get<double>() << " m, "
            << path["flagged_frames"] << " flagged\n";
  std::cout << "Anchors   " << s["anchors"] << "\n";
  std::cout << "Cells     " << s["visibility"]["cells"] << " (" << s["visibility"]["events"] << " events)\n";
  std::cout << "Keyframes " << s["keyframes"]["count"] << " (" << s["keyframes"]["method"].get<std::string>()
            << ")\n";
  std::cout << "Hotspots  " << s["hotspots"] << "\n";
  for (const auto& w : s["hotspot_warnings"])
    std::cout << "  warning: " << w["message"].get<std::string>() << "\n";
}

}  // namespace

Command add_info_command(CLI::App& parent) {
  struct Options {
    std::string project;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub = parent.add_subcommand("info", "Summarize a project file");
  sub->add_option("project", options->project, "Project file (*.plenopath)")->required();
  sub->add_flag("--json", options->json, "Machine-readable output");
  return {sub, [options]() {
            const Project project = load_project(options->project);
            const nlohmann::json summary = summarize(project, options->project);
            if (options->json)
              std::cout << summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
            else
              print_text(summary);
            return kExitOk;
          }};
}

}  // namespace plenopath::cli
