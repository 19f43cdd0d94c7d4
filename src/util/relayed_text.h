#pragma once
/// Text that a program other than rockbench wrote (an external engine's standard error, a poses
/// file's header or field), as rockbench relays it to the terminal or into a message: escaped,
/// so that no escape sequence or carriage return reaches the terminal (no forged line), and
/// capped, so that a 50 MB line is a few kilobytes of message.
#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

namespace rockbench {

/// Most bytes of foreign text a message carries.
inline constexpr size_t kMaxRelayedBytes = 4096;

/// Appends byte c as the four characters \xHH (upper-case hex): how every text from outside
/// rockbench shows a byte it must not carry as it is.
inline void AppendHexEscape(std::string& out, unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "\\x%02X", c);
  out += buf;
}

namespace relayed_text_detail {

// Appends the bytes of `text` from `i` that make one character: a printable ASCII character as
// it is; \t, \r and \n (unless `keep_newline`) and every other control character, DEL, a byte
// of no valid UTF-8 sequence and the C1 controls (U+0080 to U+009F, which some terminals obey)
// as \xHH; a valid UTF-8 sequence of a printable character as it is. Returns the next index.
inline size_t AppendChar(std::string& out, std::string_view text, size_t i) {
  const auto c = static_cast<unsigned char>(text[i]);
  if (c >= 0x20 && c < 0x7f) {
    out += static_cast<char>(c);
    return i + 1;
  }
  if (c == '\t') {
    out += "\\t";
    return i + 1;
  }
  if (c == '\r') {
    out += "\\r";
    return i + 1;
  }
  if (c == '\n') {
    out += "\\n";
    return i + 1;
  }
  // UTF-8: the sequence's length from its lead byte, its continuation bytes, its code point.
  size_t n = 0;
  unsigned cp = 0;
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
    cp = c & 0x1Fu;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    cp = c & 0x0Fu;
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    cp = c & 0x07u;
  }
  bool valid = n > 0 && i + n <= text.size();
  for (size_t k = 1; valid && k < n; ++k) {
    const auto b = static_cast<unsigned char>(text[i + k]);
    valid = (b & 0xC0u) == 0x80u;
    cp = (cp << 6) | (b & 0x3Fu);
  }
  // Overlong forms, surrogates, beyond U+10FFFF and the C1 controls are shown as bytes.
  const unsigned min_cp = n == 2 ? 0x80u : n == 3 ? 0x800u : 0x10000u;
  valid =
      valid && cp >= min_cp && cp <= 0x10FFFFu && !(cp >= 0xD800u && cp <= 0xDFFFu) && cp >= 0xA0u;
  if (!valid) {
    AppendHexEscape(out, c);
    return i + 1;
  }
  out.append(text.substr(i, n));
  return i + n;
}

}  // namespace relayed_text_detail

/// One line of foreign text for a message: every control character (line breaks included) and
/// every byte that is not printable UTF-8 shown as \xHH (\t, \r, \n as such); at most
/// `max_bytes` of the text, then "... (N bytes more)".
inline std::string EscapedText(std::string_view text, size_t max_bytes = kMaxRelayedBytes) {
  std::string out;
  size_t i = 0;
  while (i < text.size() && i < max_bytes) i = relayed_text_detail::AppendChar(out, text, i);
  if (i < text.size()) out += "... (" + std::to_string(text.size() - i) + " bytes more)";
  return out;
}

/// Lines of foreign text (an engine's last words on standard error) for a message: each line
/// after `indent` (so that none starts a line of rockbench's own: no forged "verdict ..."),
/// escaped as EscapedText; at most `max_bytes` of the text, then "... (N bytes more)".
inline std::string RelayedLines(std::string_view text, const std::string& indent = "  | ",
                                size_t max_bytes = kMaxRelayedBytes) {
  std::string out = indent;
  size_t i = 0;
  while (i < text.size() && i < max_bytes) {
    if (text[i] == '\n') {
      out += "\n" + indent;
      ++i;
    } else {
      i = relayed_text_detail::AppendChar(out, text, i);
    }
  }
  if (i < text.size()) out += "... (" + std::to_string(text.size() - i) + " bytes more)";
  return out;
}

}  // namespace rockbench
