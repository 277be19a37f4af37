// libFuzzer entry point for the tour.json reader (a packaged walkthrough read back into a project).
#include "processing/export/tour_export.h"
#include "tests/fuzz/fuzz_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return plenopath::fuzz::fuzz_json(data, size, [](const nlohmann::json& json) {
    plenopath::project_from_tour_json(json, "fuzz.tour.json");
  });
}
