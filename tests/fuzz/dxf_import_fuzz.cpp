// libFuzzer entry point for the DXF importer: any bytes must give a plan or a plenopath::Error, never a
// crash, a hang or another exception. Also linked into fuzz_dxf_replay for `make test` under gcc.
#include <cstddef>
#include <cstdint>
#include <string>

#include "model/error.h"
#include "processing/plan/dxf_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    plenopath::import_dxf_from_memory(std::string(reinterpret_cast<const char*>(data), size), "fuzz.dxf");
  } catch (const plenopath::Error&) {
    // A clear error is the right answer for bad bytes.
  }
  return 0;
}
