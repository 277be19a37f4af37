#pragma once
// The group-code/value pairs ("tags") of a DXF file, ASCII or binary, as one list that the importer walks.
//
// ASCII: a line with an integer group code, then a line with its value. Binary ("AutoCAD Binary DXF"
// sentinel): little-endian values typed by their group code; R12 files have 1-byte codes (255 escapes a
// 2-byte one), later versions 2-byte codes. Both end at "0 EOF"; whatever follows is ignored. A file that
// breaks off or turns to garbage keeps the tags read before the break, with a warning saying where.
// Values stay as the file's bytes (strings are decoded to UTF-8 later, once the code page is known;
// binary numbers are written out in full precision) so that one code path reads both kinds.
#include <cstddef>
#include <string>
#include <vector>

namespace plenopath {

struct DxfTag {
  int code = 0;
  std::string value;
  std::size_t line = 0;  // line of the group code in an ASCII file; byte offset in a binary one
};

struct DxfTags {
  std::vector<DxfTag> tags;
  bool binary = false;
  bool reached_eof = false;           // "0 EOF" was read
  std::vector<std::string> warnings;  // where reading stopped early, and why
};

// Throws plenopath::Error naming `name` only when not even the first tag can be read (empty file, not DXF).
DxfTags read_dxf_tags(const std::string& bytes, const std::string& name);

// What the value of a group code is, by the DXF reference's ranges.
enum class DxfValueType { string, real, int16, int32, int64, boolean, binary_chunk };
DxfValueType dxf_value_type(int code);

// The value as a number; false when it is not one (or not finite).
bool dxf_number(const DxfTag& tag, double* value);
// The value as an integer (flags, colours, counts); false when it is not a number or out of int range
// (fractions are cut toward zero, as a hand-edited "70\n1.0" means 1).
bool dxf_integer(const DxfTag& tag, int* value);

}  // namespace plenopath
