#include "processing/plan/dxf_text.h"

#include <iconv.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <map>
#include <vector>

namespace plenopath {
namespace {

void append_utf8(std::uint32_t cp, std::string* out) {
  if (cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) cp = 0xFFFD;
  if (cp < 0x80) {
    out->push_back(static_cast<char>(cp));
  } else if (cp < 0x800) {
    out->push_back(static_cast<char>(0xC0 | (cp >> 6)));
    out->push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else if (cp < 0x10000) {
    out->push_back(static_cast<char>(0xE0 | (cp >> 12)));
    out->push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    out->push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  } else {
    out->push_back(static_cast<char>(0xF0 | (cp >> 18)));
    out->push_back(static_cast<char>(0x80 | ((cp >> 12) & 0x3F)));
    out->push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
    out->push_back(static_cast<char>(0x80 | (cp & 0x3F)));
  }
}

// Length of the valid UTF-8 sequence starting at s[i], 0 if invalid.
std::size_t utf8_sequence(const std::string& s, std::size_t i) {
  const unsigned char c = static_cast<unsigned char>(s[i]);
  std::size_t n = 0;
  std::uint32_t cp = 0;
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF)
    n = 2, cp = c & 0x1F;
  else if (c >= 0xE0 && c <= 0xEF)
    n = 3, cp = c & 0x0F;
  else if (c >= 0xF0 && c <= 0xF4)
    n = 4, cp = c & 0x07;
  else
    return 0;
  if (i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    const unsigned char d = static_cast<unsigned char>(s[i + k]);
    if ((d & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (d & 0x3F);
  }
  if ((n == 3 && cp < 0x800) || (n == 4 && (cp < 0x10000 || cp > 0x10FFFF)) || (cp >= 0xD800 && cp <= 0xDFFF))
    return 0;
  return n;
}

bool is_valid_utf8(const std::string& s) {
  for (std::size_t i = 0; i < s.size();) {
    const std::size_t n = utf8_sequence(s, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

bool is_ascii(const std::string& s) {
  return std::all_of(s.begin(), s.end(), [](char c) { return static_cast<unsigned char>(c) < 0x80; });
}

std::string iconv_to_utf8(const std::string& raw, const std::string& encoding) {
  iconv_t cd = iconv_open("UTF-8", encoding.c_str());
  if (cd == reinterpret_cast<iconv_t>(-1)) cd = iconv_open("UTF-8", "CP1252");
  if (cd == reinterpret_cast<iconv_t>(-1)) return valid_utf8(raw);
  std::string out;
  std::vector<char> buffer(raw.size() * 4 + 16);
  char* in = const_cast<char*>(raw.data());
  std::size_t in_left = raw.size();
  while (in_left > 0) {
    char* o = buffer.data();
    std::size_t o_left = buffer.size();
    const std::size_t r = iconv(cd, &in, &in_left, &o, &o_left);
    out.append(buffer.data(), o - buffer.data());
    if (r == static_cast<std::size_t>(-1)) {
      if (errno == E2BIG) continue;
      // An undecodable byte (EILSEQ) or a cut-off sequence (EINVAL): U+FFFD, then go on after it.
      append_utf8(0xFFFD, &out);
      ++in;
      --in_left;
      iconv(cd, nullptr, nullptr, nullptr, nullptr);
    }
  }
  iconv_close(cd);
  return out;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Code page indices of \M+N escapes (AutoCAD's multi-byte fonts).
const char* mbcs_encoding(char n) {
  switch (n) {
    case '1':
      return "CP932";  // Japanese
    case '2':
      return "BIG5";  // Traditional Chinese
    case '3':
      return "CP949";  // Korean Wansung
    case '4':
      return "JOHAB";  // Korean Johab
    case '5':
      return "GBK";  // Simplified Chinese
    default:
      return nullptr;
  }
}

}  // namespace

std::string dxf_string_encoding(const std::string& acadver, const std::string& dwgcodepage) {
  if (acadver.size() == 6 && acadver.compare(0, 2, "AC") == 0 && acadver >= "AC1021") return "UTF-8";
  std::string cp = dwgcodepage;
  std::transform(cp.begin(), cp.end(), cp.begin(), [](unsigned char c) { return std::tolower(c); });
  static const std::map<std::string, std::string> table = {
      {"ansi_874", "CP874"},       {"ansi_932", "CP932"},       {"ansi_936", "GBK"},
      {"ansi_949", "CP949"},       {"ansi_950", "BIG5"},        {"ansi_1250", "CP1250"},
      {"ansi_1251", "CP1251"},     {"ansi_1252", "CP1252"},     {"ansi_1253", "CP1253"},
      {"ansi_1254", "CP1254"},     {"ansi_1255", "CP1255"},     {"ansi_1256", "CP1256"},
      {"ansi_1257", "CP1257"},     {"ansi_1258", "CP1258"},     {"ansi_1361", "JOHAB"},
      {"dos437", "CP437"},         {"dos850", "CP850"},         {"dos852", "CP852"},
      {"dos855", "CP855"},         {"dos857", "CP857"},         {"dos860", "CP860"},
      {"dos861", "CP861"},         {"dos863", "CP863"},         {"dos864", "CP864"},
      {"dos865", "CP865"},         {"dos866", "CP866"},         {"dos869", "CP869"},
      {"dos932", "CP932"},         {"mac-roman", "MACINTOSH"},  {"big5", "BIG5"},
      {"ksc5601", "CP949"},        {"johab", "JOHAB"},          {"gb2312", "GB2312"},
      {"iso8859-1", "ISO-8859-1"}, {"iso8859-2", "ISO-8859-2"}, {"iso8859-5", "ISO-8859-5"},
      {"iso8859-7", "ISO-8859-7"}, {"iso8859-9", "ISO-8859-9"}, {"ascii", "CP1252"},
      {"utf8", "UTF-8"},           {"utf-8", "UTF-8"}};
  auto it = table.find(cp);
  return it == table.end() ? "CP1252" : it->second;
}

std::string dxf_to_utf8(const std::string& raw, const std::string& encoding) {
  if (is_ascii(raw)) return raw;
  if (encoding == "UTF-8") return is_valid_utf8(raw) ? raw : iconv_to_utf8(raw, "CP1252");
  return iconv_to_utf8(raw, encoding);
}

std::string valid_utf8(const std::string& text) {
  if (is_valid_utf8(text)) return text;
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_sequence(text, i);
    if (n == 0) {
      append_utf8(0xFFFD, &out);
      ++i;
    } else {
      out.append(text, i, n);
      i += n;
    }
  }
  return out;
}

std::string dxf_decode_unicode_escapes(const std::string& text) {
  if (text.find('\\') == std::string::npos) return text;
  std::string out;
  out.reserve(text.size());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    if (text[i] == '\\' && i + 7 <= n && (text[i + 1] == 'U' || text[i + 1] == 'u') && text[i + 2] == '+') {
      std::uint32_t cp = 0;
      bool ok = true;
      for (std::size_t k = i + 3; ok && k < i + 7; ++k) {
        const int d = hex_digit(text[k]);
        ok = d >= 0;
        cp = cp * 16 + static_cast<std::uint32_t>(std::max(d, 0));
      }
      if (ok) {
        append_utf8(cp, &out);
        i += 7;
        continue;
      }
    }
    if (text[i] == '\\' && i + 8 <= n && (text[i + 1] == 'M' || text[i + 1] == 'm') && text[i + 2] == '+') {
      const char* enc = mbcs_encoding(text[i + 3]);
      int h[4];
      bool ok = enc != nullptr;
      for (int k = 0; ok && k < 4; ++k) ok = (h[k] = hex_digit(text[i + 4 + k])) >= 0;
      if (ok) {
        const std::string bytes = {static_cast<char>(h[0] * 16 + h[1]), static_cast<char>(h[2] * 16 + h[3])};
        out += iconv_to_utf8(bytes, enc);
        i += 8;
        continue;
      }
    }
    out += text[i++];
  }
  return valid_utf8(out);
}

std::string dxf_decode_escapes(const std::string& raw) {
  const std::string text = dxf_decode_unicode_escapes(raw);
  std::string out;
  out.reserve(text.size());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    const char c = text[i];
    if (c == '%' && i + 2 < n && text[i + 1] == '%') {
      const char k = static_cast<char>(std::tolower(static_cast<unsigned char>(text[i + 2])));
      if (k == 'd') {
        out += "\xC2\xB0";
        i += 3;
        continue;
      }  // degree
      if (k == 'c') {
        out += "\xE2\x8C\x80";
        i += 3;
        continue;
      }  // diameter sign U+2300
      if (k == 'p') {
        out += "\xC2\xB1";
        i += 3;
        continue;
      }  // plus-minus
      if (k == '%') {
        out += '%';
        i += 3;
        continue;
      }
      if (k == 'o' || k == 'u' || k == 'k') {
        i += 3;
        continue;
      }  // over/underline, strike toggles
      if (std::isdigit(static_cast<unsigned char>(k)) && i + 4 < n &&
          std::isdigit(static_cast<unsigned char>(text[i + 3])) &&
          std::isdigit(static_cast<unsigned char>(text[i + 4]))) {
        const int code = (text[i + 2] - '0') * 100 + (text[i + 3] - '0') * 10 + (text[i + 4] - '0');
        append_utf8(static_cast<std::uint32_t>(code), &out);
        i += 5;
        continue;
      }
    }
    // Caret encoding of control characters: "^J" is a line feed, "^ " a caret.
    if (c == '^' && i + 1 < n) {
      const char k = text[i + 1];
      if (k == ' ') {
        out += '^';
        i += 2;
        continue;
      }
      if (k >= '@' && k <= '_') {
        out += ' ';
        i += 2;
        continue;
      }
    }
    if (static_cast<unsigned char>(c) < 0x20 && c != '\n') {
      out += ' ';
      ++i;
      continue;
    }
    out += c;
    ++i;
  }
  return valid_utf8(out);
}

std::string dxf_plain_mtext(const std::string& text) {
  std::string out;
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    const char c = text[i];
    if (c == '{' || c == '}') {
      ++i;
      continue;
    }
    if (c != '\\' || i + 1 >= n) {
      out += c;
      ++i;
      continue;
    }
    const char k = text[i + 1];
    switch (k) {
      case 'P':
      case 'X':
        out += '\n';
        i += 2;
        break;
      case '~':
        out += ' ';
        i += 2;
        break;
      case '\\':
      case '{':
      case '}':
        out += k;
        i += 2;
        break;
      case 'L':
      case 'l':
      case 'O':
      case 'o':
      case 'K':
      case 'k':
      case 'N':
        i += 2;  // underline, overline, strike-through toggles; column break
        break;
      case 'S': {  // stacked fraction up to ';': "1^2" or "1/2" or "1#2" -> "1/2"
        std::size_t end = text.find(';', i + 2);
        if (end == std::string::npos) end = n;
        std::string stack = text.substr(i + 2, end - i - 2);
        for (char& s : stack)
          if (s == '^' || s == '#') s = '/';
        out += stack;
        i = end + 1;
        break;
      }
      case 'U':
      case 'u':
      case 'M':
      case 'm':
        out += c;  // left for dxf_decode_escapes
        ++i;
        break;
      case 'f':
      case 'F':
      case 'H':
      case 'h':
      case 'C':
      case 'c':
      case 'T':
      case 't':
      case 'Q':
      case 'q':
      case 'W':
      case 'w':
      case 'A':
      case 'a':
      case 'p': {  // a code with an argument up to ';'
        const std::size_t end = text.find(';', i + 2);
        i = end == std::string::npos ? n : end + 1;
        break;
      }
      default:
        out += k;
        i += 2;
        break;
    }
  }
  return out;
}

}  // namespace plenopath
