#pragma once
// Text in a DXF file to UTF-8: the code page ($DWGCODEPAGE, through iconv; R2007 and later are UTF-8),
// AutoCAD's escapes (\U+XXXX, \M+NXXXX, %%d %%c %%p %%nnn, ^-caret control characters) and, for labels,
// MTEXT's formatting codes. Whatever the bytes, the result is valid UTF-8.
#include <string>

namespace plenopath {

// The iconv name of the 8-bit encoding a file's strings are in: "UTF-8" for AC1021 (R2007) and later,
// else from $DWGCODEPAGE ("ANSI_1252" -> "CP1252", "ANSI_936" -> "GBK", ...), CP1252 when unknown.
std::string dxf_string_encoding(const std::string& acadver, const std::string& dwgcodepage);

// `raw` in `encoding` to UTF-8. Bytes that do not decode become U+FFFD; with encoding UTF-8, a string
// that is not valid UTF-8 is read as CP1252 instead (writers that ignore their own header).
std::string dxf_to_utf8(const std::string& raw, const std::string& encoding);

// Only \U+XXXX and \M+NXXXX, which pre-R2007 writers put in every string (layer and block names too).
std::string dxf_decode_unicode_escapes(const std::string& text);

// \U+XXXX and \M+NXXXX (N = code page index, XXXX its double-byte code), %%d (degree), %%c (diameter),
// %%p (plus-minus), %%% and %%nnn (a character code); control characters (but new lines) and ^-caret
// encoded ones become spaces. Input and output UTF-8.
std::string dxf_decode_escapes(const std::string& text);

// MTEXT content without its formatting: \P and \X are new lines, \~ a space, \\ \{ \} literal;
// font, height, colour, width, tracking, oblique, alignment and stacking codes are dropped (a stack
// "\S1^2;" keeps "1/2"), braces removed. Input and output UTF-8.
std::string dxf_plain_mtext(const std::string& text);

// Replaces invalid UTF-8 sequences by U+FFFD (the last line of defence before JSON).
std::string valid_utf8(const std::string& text);

}  // namespace plenopath
