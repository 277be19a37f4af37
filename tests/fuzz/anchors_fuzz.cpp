// libFuzzer entry point for the anchors file reader.
#include "model/anchors_io.h"
#include "model/json_reader.h"
#include "tests/fuzz/fuzz_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return plenopath::fuzz::fuzz_json(data, size, [](const nlohmann::json& json) {
    plenopath::anchors_from_json(plenopath::JsonReader(json, "fuzz.anchors.json"));
  });
}
