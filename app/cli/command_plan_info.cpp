// `plenopath plan-info PLAN.dxf [--layers L ...] [--occluders L ...] [--units U] [--json]`: what the
// importer made of a DXF plan: units, extents in metres, layers with entity counts and occluder flags,
// occluder segment count, what was cleaned.
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "processing/plan/dxf_import.h"

namespace plenopath::cli {

Command add_plan_info_command(CLI::App& parent) {
  struct Options {
    std::string plan;
    DxfImportOptions import;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub = parent.add_subcommand("plan-info", "Summarize what a DXF floor plan imports as");
  sub->add_option("plan", options->plan, "Floor plan (*.dxf, ASCII)")->required();
  sub->add_option("--layers", options->import.layers, "Import only these layers (default: all)");
  sub->add_option("--occluders", options->import.occluder_layers,
                  "Layers that block sight (default: guessed from the names)");
  sub->add_option("--units", options->import.units_override, "Units of the file (mm, cm, m, in, ft, ...)");
  sub->add_flag("--json", options->json, "Machine-readable output");
  return {sub, [options]() {
            DxfImportReport report;
            const FloorPlan plan = import_dxf(options->plan, options->import, &report);
            const PlanExtents e = plan.extents();
            nlohmann::json layers = nlohmann::json::array();
            for (const auto& l : plan.layers)
              layers.push_back({{"name", l.name},
                                {"color", l.color},
                                {"visible", l.visible},
                                {"occluder", l.occluder},
                                {"entities", l.entity_count}});
            const nlohmann::json out = {
                {"plan", options->plan},
                {"units", plan.units},
                {"units_from_header", report.units_from_header},
                {"metres_per_unit", plan.metres_per_unit},
                {"extents_m", e.valid ? nlohmann::json{{"min", {e.min.x(), e.min.y()}}, {"max", {e.max.x(), e.max.y()}}}
                                      : nlohmann::json()},
                {"layers", layers},
                {"segments", plan.segments.size()},
                {"occluder_segments", plan.occluder_segments().size()},
                {"outlines", plan.outlines.size()},
                {"labels", plan.labels.size()},
                {"entities_read", report.entities_read},
                {"entities_skipped", report.entities_skipped},
                {"blocks_expanded", report.blocks_expanded},
                {"arcs_tessellated", report.arcs_tessellated},
                {"cleaned",
                 {{"snapped_endpoints", report.snapped_endpoints},
                  {"zero_length_dropped", report.zero_length_dropped},
                  {"duplicates_dropped", report.duplicates_dropped},
                  {"collinear_merged", report.collinear_merged},
                  {"intersections_split", report.intersections_split}}},
                {"warnings", report.warnings}};
            if (options->json) {
              std::cout << out.dump(2) << "\n";
              return kExitOk;
            }
            std::cout << std::fixed << std::setprecision(3);
            std::cout << "Plan      " << options->plan << " (" << plan.units << ")\n";
            if (e.valid)
              std::cout << "Extents   " << e.size().x() << " x " << e.size().y() << " m from (" << e.min.x() << ", "
                        << e.min.y() << ")\n";
            std::cout << "Segments  " << plan.segments.size() << " (" << plan.occluder_segments().size()
                      << " occluding), " << plan.labels.size() << " labels\n";
            for (const auto& l : plan.layers)
              std::cout << "  layer " << std::left << std::setw(24) << l.name << std::right << std::setw(6)
                        << l.entity_count << " entities" << (l.occluder ? "  occluder" : "")
                        << (l.visible ? "" : "  (off)") << "\n";
            std::cout << "Cleaned   " << report.snapped_endpoints << " snapped, " << report.zero_length_dropped
                      << " zero-length, " << report.duplicates_dropped << " duplicates, " << report.collinear_merged
                      << " merged, " << report.intersections_split << " splits\n";
            for (const auto& w : report.warnings) std::cout << "warning: " << w << "\n";
            return kExitOk;
          }};
}

}  // namespace plenopath::cli
