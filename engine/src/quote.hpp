#pragma once
// File content quoted in an error message (engine internal). Input files are untrusted: an id, a
// CSV cell or a .npy header may hold terminal escapes, line breaks or a megabyte of text, and the
// message goes to a terminal as one line. Every piece of file content in an InputError or
// CurveError message goes through these.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace bezinv::detail {

// Characters of escaped text kept; the rest is summarized as "...(N bytes)".
inline constexpr std::size_t kExcerptChars = 80;

namespace quote_internal {

// Length of the well-formed UTF-8 sequence at text[i] (2 to 4) and its code point; 0 if there is
// none (a stray continuation byte, an overlong form, a surrogate, a cut-off sequence).
inline std::size_t utf8_sequence(std::string_view text, std::size_t i, std::uint32_t& code_point) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = 0;
  unsigned char low = 0x80, high = 0xBF;  // the range of the second byte
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    if (lead == 0xE0) low = 0xA0;   // overlong
    if (lead == 0xED) high = 0x9F;  // surrogates
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    if (lead == 0xF0) low = 0x90;   // overlong
    if (lead == 0xF4) high = 0x8F;  // beyond U+10FFFF
  } else {
    return 0;
  }
  if (i + length > text.size() || byte(i + 1) < low || byte(i + 1) > high) return 0;
  code_point = lead & (0x7F >> length);
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    code_point = code_point << 6 | (byte(i + k) & 0x3F);
  }
  return length;
}

// Code points a terminal acts on rather than shows: C1 controls (U+009B is an escape
// introducer), zero-width and direction marks, line separators, bidi overrides and isolates.
inline bool is_invisible_control(std::uint32_t c) {
  return (c >= 0x80 && c <= 0x9F) || c == 0x061C || (c >= 0x200B && c <= 0x200F) ||
         (c >= 0x2028 && c <= 0x202E) || (c >= 0x2060 && c <= 0x206F) || c == 0xFEFF;
}

inline void append_hex(std::string& out, const char* prefix, std::uint32_t value, int digits) {
  static constexpr char kHex[] = "0123456789abcdef";
  out += prefix;
  for (int shift = 4 * (digits - 1); shift >= 0; shift -= 4) out += kHex[(value >> shift) & 0xF];
}

// Appends text, escaped, to `out` until kExcerptChars characters were added; returns the bytes
// of text consumed.
inline std::size_t escape_prefix(std::string_view text, std::string& out) {
  const std::size_t stop = out.size() + kExcerptChars;
  std::size_t i = 0;
  while (i < text.size() && out.size() < stop) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      switch (c) {
        case '\n': out += "\\n"; break;
        case '\r': out += "\\r"; break;
        case '\t': out += "\\t"; break;
        case '\\': out += "\\\\"; break;
        case '"': out += "\\\""; break;
        default:
          if (c < 0x20 || c == 0x7F) append_hex(out, "\\x", c, 2);
          else out += static_cast<char>(c);
      }
      ++i;
      continue;
    }
    std::uint32_t code_point = 0;
    const std::size_t length = utf8_sequence(text, i, code_point);
    if (length == 0) {
      append_hex(out, "\\x", c, 2);  // not UTF-8: the byte itself
      ++i;
    } else {
      if (is_invisible_control(code_point)) append_hex(out, "\\u", code_point, 4);
      else out.append(text.substr(i, length));
      i += length;
    }
  }
  return i;
}

inline std::string size_note(std::string_view text, std::size_t consumed) {
  return consumed < text.size() ? "...(" + std::to_string(text.size()) + " bytes)" : std::string();
}

}  // namespace quote_internal

// `text` as one printable line: control characters, invalid UTF-8 and invisible format
// characters as visible escapes (\n, \x1b, \u202e), backslash and double quote escaped, cut
// after kExcerptChars characters with "...(N bytes)" giving the full size. For text that brings
// its own delimiters (a .npy dtype such as '<f4').
inline std::string escaped_excerpt(std::string_view text) {
  std::string out;
  const std::size_t consumed = quote_internal::escape_prefix(text, out);
  return out + quote_internal::size_note(text, consumed);
}

// escaped_excerpt in double quotes: "abc", "\x1b[31m", "aaaa..."...(1048576 bytes).
inline std::string quoted_excerpt(std::string_view text) {
  std::string out = "\"";
  const std::size_t consumed = quote_internal::escape_prefix(text, out);
  out += '"';
  return out + quote_internal::size_note(text, consumed);
}

}  // namespace bezinv::detail
