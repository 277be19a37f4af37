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
  sub->add_option("plan", options->plan, "Floor plan (*.dxf, ASCII or binary, R12 to R2018)")->required();
  sub->add_option("--layers", options->import.layers, "Import only these layers (default: all)");
  sub->add_option("--occluders", options->import.occluder_layers,
                  "Layers that block sight (default: guessed from the names)");
  sub->add_option("--units", options->import.units_override, "Units of the file (mm, cm, m, in, ft, ...)");
  sub->add_flag("--keep-stray", options->import.keep_stray,
                "Keep entities far from the drawing's bulk (default: reported and left out)");
  sub->add_flag("--json", options->json, "Machine-readable output");
  return {
      sub, [options]() {
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
        nlohmann::json skipped = nlohmann::json::array();
        for (const auto& k : report.skipped)
          skipped.push_back({{"line", k.line}, {"kind", k.kind}, {"layer", k.layer}, {"why", k.why}});
        const nlohmann::json out = {
            {"plan", options->plan},
            {"units", plan.units},
            {"units_from_header", report.units_from_header},
            {"units_source", report.units_source},
            {"units_reason", report.units_reason},
            {"version", report.version},
            {"binary", report.binary},
            {"codepage", report.codepage},
            {"metres_per_unit", plan.metres_per_unit},
            {"extents_m",
             e.valid ? nlohmann::json{{"min", {e.min.x(), e.min.y()}}, {"max", {e.max.x(), e.max.y()}}}
                     : nlohmann::json()},
            {"layers", layers},
            {"segments", plan.segments.size()},
            {"occluder_segments", plan.occluder_segments().size()},
            {"outlines", plan.outlines.size()},
            {"labels", plan.labels.size()},
            {"entities_read", report.entities_read},
            {"entities_skipped", report.entities_skipped},
            {"skipped_by_kind", report.skipped_by_kind},
            {"skipped", skipped},
            {"entities_by_layer", report.entities_by_layer},
            {"drawing_extents",
             report.drawing_extents.valid
                 ? nlohmann::json{{"min", {report.drawing_extents.min.x(), report.drawing_extents.min.y()}},
                                  {"max", {report.drawing_extents.max.x(), report.drawing_extents.max.y()}}}
                 : nlohmann::json()},
            {"origin_m", {report.origin_m.x(), report.origin_m.y()}},
            {"stray_entities", report.stray_entities},
            {"hatch_outlines", report.hatch_outlines},
            {"occluder_reasons", report.occluder_reasons},
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
          std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
          return kExitOk;
        }
        std::cout << std::fixed << std::setprecision(3);
        std::cout << "Plan      " << options->plan << " ("
                  << (report.version.empty() ? "DXF" : report.version) << (report.binary ? ", binary" : "")
                  << ")\n";
        std::cout << "Units     " << plan.units << " (" << report.units_source << ": " << report.units_reason
                  << ")\n";
        if (report.origin_m.norm() > 0)
          std::cout << "Origin    re-centred by (" << report.origin_m.x() << ", " << report.origin_m.y()
                    << ") m\n";
        if (e.valid)
          std::cout << "Extents   " << e.size().x() << " x " << e.size().y() << " m from (" << e.min.x()
                    << ", " << e.min.y() << ")\n";
        std::cout << "Segments  " << plan.segments.size() << " (" << plan.occluder_segments().size()
                  << " occluding), " << plan.labels.size() << " labels\n";
        for (const auto& l : plan.layers)
          std::cout << "  layer " << std::left << std::setw(24) << l.name << std::right << std::setw(6)
                    << l.entity_count << " entities" << (l.occluder ? "  occluder" : "")
                    << (l.visible ? "" : "  (off)")
                    << (report.occluder_reasons.count(l.name)
                            ? "  (" + report.occluder_reasons.at(l.name) + ")"
                            : "")
                    << "\n";
        std::cout << "Entities  " << report.entities_read << " read, " << report.entities_skipped
                  << " skipped";
        for (const auto& [kind, n] : report.skipped_by_kind) std::cout << " " << kind << " " << n;
        std::cout << "\n";
        std::cout << "Cleaned   " << report.snapped_endpoints << " snapped, " << report.zero_length_dropped
                  << " zero-length, " << report.duplicates_dropped << " duplicates, "
                  << report.collinear_merged << " merged, " << report.intersections_split << " splits\n";
        for (const auto& w : report.warnings) std::cout << "warning: " << w << "\n";
        return kExitOk;
      }};
}

}  // namespace plenopath::cli
