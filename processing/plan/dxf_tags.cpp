#include "processing/plan/dxf_tags.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "model/error.h"

namespace plenopath {

DxfValueType dxf_value_type(int code) {
  auto in = [code](int lo, int hi) { return code >= lo && code <= hi; };
  if (in(310, 319) || code == 1004) return DxfValueType::binary_chunk;
  if (in(290, 299)) return DxfValueType::boolean;
  if (in(10, 59) || in(110, 149) || in(210, 239) || in(460, 469) || in(1010, 1059)) return DxfValueType::real;
  if (in(60, 79) || in(170, 179) || in(270, 289) || in(370, 389) || in(400, 409) || in(1060, 1070))
    return DxfValueType::int16;
  if (in(90, 99) || in(420, 429) || in(440, 459) || code == 1071) return DxfValueType::int32;
  if (in(160, 169)) return DxfValueType::int64;
  return DxfValueType::string;
}

bool dxf_number(const DxfTag& tag, double* value) {
  const char* s = tag.value.c_str();
  while (*s == ' ' || *s == '\t') ++s;
  if (*s == '\0') return false;
  char* end = nullptr;
  const double v = std::strtod(s, &end);
  if (end == s) return false;
  while (*end == ' ' || *end == '\t' || *end == '\r') ++end;
  if (*end != '\0' || !std::isfinite(v)) return false;
  *value = v;
  return true;
}

bool dxf_integer(const DxfTag& tag, int* value) {
  double v = 0.0;
  // Out of range, the conversion to int would be undefined (found by the DXF fuzzer: 4.6e11 as flags).
  if (!dxf_number(tag, &v) || v < static_cast<double>(std::numeric_limits<int>::min()) ||
      v > static_cast<double>(std::numeric_limits<int>::max()))
    return false;
  *value = static_cast<int>(v);
  return true;
}

namespace {

constexpr char kBinarySentinel[] = "AutoCAD Binary DXF\r\n\x1a";  // followed by a NUL: 22 bytes in all
constexpr std::size_t kBinarySentinelSize = 22;

std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

bool parse_group_code(const std::string& line, int* code) {
  const std::string t = trim(line);
  if (t.empty() || t.size() > 6) return false;
  std::size_t i = t[0] == '-' ? 1 : 0;
  if (i == t.size()) return false;
  for (; i < t.size(); ++i)
    if (!std::isdigit(static_cast<unsigned char>(t[i]))) return false;
  *code = std::atoi(t.c_str());
  return true;
}

DxfTags read_ascii(const std::string& bytes, const std::string& name) {
  DxfTags out;
  std::size_t pos = 0, line_no = 1;
  auto next_line = [&](std::string* line) {
    if (pos >= bytes.size()) return false;
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    *line = bytes.substr(pos, end - pos);
    if (!line->empty() && line->back() == '\r') line->pop_back();
    pos = end + 1;
    return true;
  };
  std::string code_line, value;
  while (true) {
    const std::size_t at = line_no;
    if (!next_line(&code_line)) break;
    ++line_no;
    int code = 0;
    if (!parse_group_code(code_line, &code)) {
      if (trim(code_line).empty() && pos >= bytes.size()) break;  // a trailing blank line
      if (out.tags.empty())
        throw file_error(name, "line " + std::to_string(at) + ": expected a DXF group code, found '" +
                                   trim(code_line).substr(0, 40) + "': not a DXF file");
      // Resynchronise on the next entity or section: a "0" line followed by a name in capitals.
      std::size_t resume_pos = std::string::npos, resume_line = 0;
      for (std::size_t p = pos, l = line_no; p < bytes.size();) {
        std::size_t e = bytes.find('\n', p);
        if (e == std::string::npos) e = bytes.size();
        if (trim(bytes.substr(p, e - p)) == "0" && e + 1 < bytes.size()) {
          std::size_t e2 = bytes.find('\n', e + 1);
          if (e2 == std::string::npos) e2 = bytes.size();
          const std::string next = trim(bytes.substr(e + 1, e2 - e - 1));
          const bool name_like =
              std::any_of(next.begin(), next.end(),
                          [](char c) { return std::isupper(static_cast<unsigned char>(c)); }) &&
              std::all_of(next.begin(), next.end(), [](char c) {
                return std::isupper(static_cast<unsigned char>(c)) ||
                       std::isdigit(static_cast<unsigned char>(c)) || c == '_';
              });
          if (name_like) {
            resume_pos = p;
            resume_line = l;
            break;
          }
        }
        p = e + 1;
        ++l;
      }
      if (resume_pos == std::string::npos) {
        out.warnings.push_back("line " + std::to_string(at) + ": expected a group code, found '" +
                               trim(code_line).substr(0, 40) + "'; the rest of the file is ignored");
        break;
      }
      out.warnings.push_back("line " + std::to_string(at) + ": expected a group code, found '" +
                             trim(code_line).substr(0, 40) + "'; skipped to line " +
                             std::to_string(resume_line));
      pos = resume_pos;
      line_no = resume_line;
      continue;
    }
    if (!next_line(&value)) {
      out.warnings.push_back("line " + std::to_string(at) + ": the file ends after group code " +
                             std::to_string(code) + " without its value");
      break;
    }
    ++line_no;
    if (code == 999) continue;  // comment
    if (code == 0) value = trim(value);
    out.tags.push_back({code, value, at});
    if (code == 0 && value == "EOF") {
      out.reached_eof = true;
      break;
    }
  }
  if (out.tags.empty()) throw file_error(name, "no DXF group codes in the file: not a DXF file");
  return out;
}

// Little-endian reads with bounds checks; a value that would run past the end stops the reader.
struct ByteReader {
  const std::string& bytes;
  std::size_t pos;
  bool have(std::size_t n) const { return pos + n <= bytes.size(); }
  std::uint64_t little_endian(std::size_t n) {
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < n; ++i)
      v |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[pos + i])) << (8 * i);
    pos += n;
    return v;
  }
};

std::string number_text(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

DxfTags read_binary(const std::string& bytes) {
  DxfTags out;
  out.binary = true;
  // R12 and earlier write 1-byte group codes: the first tag (0, "SECTION") then starts "\0S".
  ByteReader r{bytes, kBinarySentinelSize};
  const bool one_byte_codes = r.have(2) && bytes[r.pos] == '\0' && bytes[r.pos + 1] != '\0';
  auto stop = [&](std::size_t at, const std::string& what) {
    out.warnings.push_back("byte " + std::to_string(at) + ": " + what + "; the rest of the file is ignored");
  };
  while (r.pos < bytes.size()) {
    const std::size_t at = r.pos;
    int code = 0;
    if (one_byte_codes) {
      const int c = static_cast<unsigned char>(bytes[r.pos++]);
      if (c == 255) {
        if (!r.have(2)) return stop(at, "truncated group code"), out;
        code = static_cast<int>(r.little_endian(2));
      } else {
        code = c;
      }
    } else {
      if (!r.have(2)) return stop(at, "truncated group code"), out;
      code = static_cast<int>(static_cast<std::int16_t>(r.little_endian(2)));
    }
    std::string value;
    switch (dxf_value_type(code)) {
      case DxfValueType::binary_chunk: {
        if (!r.have(1)) return stop(at, "truncated binary chunk"), out;
        const std::size_t n = static_cast<unsigned char>(bytes[r.pos++]);
        if (!r.have(n)) return stop(at, "truncated binary chunk"), out;
        static const char* hex = "0123456789ABCDEF";
        for (std::size_t i = 0; i < n; ++i) {
          const unsigned char b = static_cast<unsigned char>(bytes[r.pos + i]);
          value += hex[b >> 4];
          value += hex[b & 15];
        }
        r.pos += n;
        break;
      }
      case DxfValueType::boolean:
        if (!r.have(1)) return stop(at, "truncated value"), out;
        value = std::to_string(static_cast<unsigned char>(bytes[r.pos++]));
        break;
      case DxfValueType::int16:
        if (!r.have(2)) return stop(at, "truncated value"), out;
        value = std::to_string(static_cast<std::int16_t>(r.little_endian(2)));
        break;
      case DxfValueType::int32:
        if (!r.have(4)) return stop(at, "truncated value"), out;
        value = std::to_string(static_cast<std::int32_t>(r.little_endian(4)));
        break;
      case DxfValueType::int64:
        if (!r.have(8)) return stop(at, "truncated value"), out;
        value = std::to_string(static_cast<std::int64_t>(r.little_endian(8)));
        break;
      case DxfValueType::real: {
        if (!r.have(8)) return stop(at, "truncated value"), out;
        const std::uint64_t raw = r.little_endian(8);
        double v;
        std::memcpy(&v, &raw, sizeof v);
        value = number_text(v);
        break;
      }
      case DxfValueType::string: {
        const std::size_t end = bytes.find('\0', r.pos);
        if (end == std::string::npos) return stop(at, "unterminated string"), out;
        value = bytes.substr(r.pos, end - r.pos);
        r.pos = end + 1;
        break;
      }
    }
    if (code == 999) continue;
    out.tags.push_back({code, value, at});
    if (code == 0 && value == "EOF") {
      out.reached_eof = true;
      break;
    }
  }
  return out;
}

}  // namespace

DxfTags read_dxf_tags(const std::string& bytes, const std::string& name) {
  if (bytes.empty()) throw file_error(name, "the file is empty");
  if (bytes.size() >= kBinarySentinelSize &&
      bytes.compare(0, kBinarySentinelSize - 1, kBinarySentinel) == 0) {
    DxfTags tags = read_binary(bytes);
    if (tags.tags.empty()) throw file_error(name, "binary DXF without a single readable group code");
    return tags;
  }
  // A NUL byte early in the file: some other binary format (DWG, an image) renamed to .dxf.
  const std::size_t probe = std::min<std::size_t>(bytes.size(), 4096);
  if (std::memchr(bytes.data(), '\0', probe) != nullptr) {
    if (bytes.compare(0, 2, "AC") == 0)
      throw file_error(name, "this is a DWG drawing, not DXF: save it as DXF in the CAD program");
    throw file_error(name, "binary data that is not a binary DXF file: not a DXF file");
  }
  return read_ascii(bytes, name);
}

}  // namespace plenopath
