#pragma once
// One 64-bit hash key for a 2-D grid cell (cx, cy): cx in the high 32 bits, cy in the low ones. Shifted as
// unsigned, since a left shift of a negative signed value is undefined (found by the fuzzer's UBSan).
#include <cstdint>

namespace plenopath {

inline std::int64_t grid_cell_key(std::int64_t cx, std::int64_t cy) {
  return static_cast<std::int64_t>((static_cast<std::uint64_t>(cx) << 32) ^
                                   (static_cast<std::uint64_t>(cy) & 0xffffffffULL));
}

}  // namespace plenopath
