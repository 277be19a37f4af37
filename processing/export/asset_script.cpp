#include "processing/export/asset_script.h"

namespace plenopath {

std::string base64(const unsigned char* bytes, std::size_t size) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < size; i += 3) {
    const unsigned v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    out += {table[v >> 18], table[(v >> 12) & 63], table[(v >> 6) & 63], table[v & 63]};
  }
  if (i + 1 == size) {
    const unsigned v = bytes[i] << 16;
    out += {table[v >> 18], table[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == size) {
    const unsigned v = (bytes[i] << 16) | (bytes[i + 1] << 8);
    out += {table[v >> 18], table[(v >> 12) & 63], table[(v >> 6) & 63], '='};
  }
  return out;
}

std::string asset_script(const std::string& name, const std::string& mime, const unsigned char* bytes,
                         std::size_t size) {
  return "plenopathAsset(\"" + name + "\",\"data:" + mime + ";base64," + base64(bytes, size) + "\");\n";
}

}  // namespace plenopath
