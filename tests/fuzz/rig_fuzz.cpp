// libFuzzer entry point for the multi-head rig calibration reader.
#include "model/json_reader.h"
#include "rig/multi_head_rig.h"
#include "tests/fuzz/fuzz_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return plenopath::fuzz::fuzz_json(data, size, [](const nlohmann::json& json) {
    plenopath::rig_from_json(plenopath::JsonReader(json, "fuzz.rig.json"));
  });
}
