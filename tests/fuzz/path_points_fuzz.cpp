// libFuzzer entry point for the tracker's points sidecar (P.points.json beside a project), which the studio
// reads when it opens someone else's project.
#include "model/json_reader.h"
#include "model/path_points.h"
#include "tests/fuzz/fuzz_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return plenopath::fuzz::fuzz_json(data, size, [](const nlohmann::json& json) {
    plenopath::path_points_from_json(plenopath::JsonReader(json, "fuzz.points.json"));
  });
}
