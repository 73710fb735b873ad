#include "scene/field_lines.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace tongue::scene {

void fail_in_file(const std::string& path, int line, const std::string& reason) {
  throw std::runtime_error(line > 0 ? path + ", line " + std::to_string(line) + ": " + reason
                                    : path + ": " + reason);
}

void for_each_field_line(
    const std::string& path, const std::string& what, std::uintmax_t max_bytes,
    const std::function<void(int, const std::vector<std::string_view>&)>& on_line) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail_in_file(path, 0, what + " file not found");
  if (const auto size = std::filesystem::file_size(path, ec); !ec && size > max_bytes)
    fail_in_file(path, 0,
                 what + " file is larger than " + std::to_string(max_bytes >> 20) + " MiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail_in_file(path, 0, "cannot open the " + what + " file");
  const auto separator = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == ',' || c == ';';
  };
  std::string raw;
  std::vector<std::string_view> fields;
  int number = 0;
  while (std::getline(in, raw)) {
    ++number;
    std::string_view text = raw;
    if (const auto c = text.find_first_of("#!"); c != std::string_view::npos)
      text = text.substr(0, c);
    for (const char ch : text)
      if (static_cast<unsigned char>(ch) >= 0x80) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned char>(ch));
        fail_in_file(path, number,
                     std::string("byte ") + hex +
                         " outside a comment (only comments may hold non-ASCII text)");
      }
    fields.clear();
    std::size_t i = 0;
    while (i < text.size()) {
      while (i < text.size() && separator(text[i])) ++i;
      const std::size_t start = i;
      while (i < text.size() && !separator(text[i])) ++i;
      if (i > start) fields.push_back(text.substr(start, i - start));
    }
    if (!fields.empty()) on_line(number, fields);
  }
  if (in.bad()) fail_in_file(path, 0, "read error in the " + what + " file");
}

}  // namespace tongue::scene
