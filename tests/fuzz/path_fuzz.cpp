// libFuzzer entry point for the camera path file reader (path.json, the ground-truth and track format).
#include "model/json_reader.h"
#include "model/path_io.h"
#include "tests/fuzz/fuzz_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return plenopath::fuzz::fuzz_json(data, size, [](const nlohmann::json& json) {
    plenopath::path_from_json(plenopath::JsonReader(json, "fuzz.path.json"));
  });
}
