#include "common/untrusted_text.hpp"

namespace tongue::common {

std::string untrusted_text(std::string_view text, std::size_t max_shown) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  const std::size_t shown = text.size() < max_shown ? text.size() : max_shown;
  out.reserve(shown + 16);
  for (std::size_t i = 0; i < shown; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    switch (c) {
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (c >= 0x20 && c < 0x7f) {
          out += static_cast<char>(c);
        } else {
          out += "\\x";
          out += kHex[c >> 4];
          out += kHex[c & 0xf];
        }
    }
  }
  if (shown < text.size()) out += "...(" + std::to_string(text.size()) + " bytes)";
  return out;
}

std::string quoted_untrusted(std::string_view text, std::size_t max_shown) {
  std::string out(1, '"');
  out += untrusted_text(text, max_shown);
  out += '"';
  return out;
}

}  // namespace tongue::common
