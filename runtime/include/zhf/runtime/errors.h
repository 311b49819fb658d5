// The one error a caller's input can raise anywhere in zhf (the runtime's readers and the tools
// alike): a file, field or argument that is missing, malformed or out of range. The message is
// one line, "<source>: <field>: <problem>", and quotes at most a short, escaped excerpt. The CLI
// exits 3 on it. An invalid argument, so the runtime's entry points throw std::invalid_argument
// (or this) for whatever they refuse.
#pragma once

#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

namespace zhf::runtime {

struct InputError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// At most max_bytes of text for a message: printable ASCII as is, everything else (control
// characters, NUL, bytes >= 0x80, backslash, quote) as \xNN, and "..." where it was cut.
inline std::string excerpt(std::string_view text, std::size_t max_bytes = 24) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (i == max_bytes) {
      out += "...";
      break;
    }
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\' && c != '\'' && c != '"') {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

// A number for a message: digits significant digits, %g style.
// x to `digits` significant digits, exponents unpadded ("1e-6", not printf's "1e-06").
inline std::string format_number(double x, int digits = 3) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, x);
  std::string out = text;
  const std::size_t e = out.find('e');
  if (e != std::string::npos) {
    std::size_t digit = e + 1 + (out[e + 1] == '-' || out[e + 1] == '+');
    const bool negative = out[e + 1] == '-';
    while (digit + 1 < out.size() && out[digit] == '0') out.erase(digit, 1);
    if (!negative && out[e + 1] == '+') out.erase(e + 1, 1);
  }
  return out;
}

// Text that may be placed as it is into a message or an emitted comment: no control characters
// (a newline would start a new line of code) and no backslashes (which splice lines).
inline bool is_printable_text(std::string_view text) {
  for (char c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == '\\') return false;
  return true;
}

}  // namespace zhf::runtime
