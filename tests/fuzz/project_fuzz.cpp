// libFuzzer entry point for the project file reader: any JSON gives a project or a plenopath::Error; a
// project that reads saves and reads back equal (what the studio relies on for autosave and undo).
#include <cstdlib>

#include "model/project_io.h"
#include "tests/fuzz/fuzz_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return plenopath::fuzz::fuzz_json(data, size, [](const nlohmann::json& json) {
    const plenopath::Project p = plenopath::project_from_json(json, "/fuzz", "fuzz.plenopath");
    const plenopath::Project again =
        plenopath::project_from_json(plenopath::project_to_json(p, "/fuzz"), "/fuzz", "again.plenopath");
    if (!(again == p)) std::abort();
  });
}
