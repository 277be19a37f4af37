#pragma once
// Shared by the JSON readers' fuzz targets: bytes that are not JSON are the parser's business (the readers
// get them through read_json_file, which turns parse errors into an Error naming the file); bytes that are
// JSON must give the reader's result or a plenopath::Error, never another exception or a crash.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "model/error.h"

namespace plenopath::fuzz {

template <class Reader>
int fuzz_json(const std::uint8_t* data, std::size_t size, Reader read) {
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(reinterpret_cast<const char*>(data),
                                 reinterpret_cast<const char*>(data) + size);
  } catch (const nlohmann::json::exception&) {  // read_json_file turns these into an Error naming the file
    return 0;
  }
  try {
    read(json);
  } catch (const Error&) {
    // A clear error is the right answer for bad content.
  }
  return 0;
}

}  // namespace plenopath::fuzz
