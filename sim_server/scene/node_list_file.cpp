#include "scene/node_list_file.hpp"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <system_error>

namespace tongue::scene {

namespace {

[[noreturn]] void fail(const std::string& path, int line, const std::string& reason) {
  throw std::runtime_error(line > 0 ? path + ", line " + std::to_string(line) + ": " + reason
                                    : path + ": " + reason);
}

}  // namespace

std::vector<NodeListEntry> read_node_list(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, 0, "node list file not found");
  // An attachment list of a tongue has some hundred nodes; 64 MiB is a wrong file.
  constexpr std::uintmax_t kMaxBytes = std::uintmax_t{64} << 20;
  if (const auto size = std::filesystem::file_size(path, ec); !ec && size > kMaxBytes)
    fail(path, 0, "node list file is larger than 64 MiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, 0, "cannot open the node list file");
  std::vector<NodeListEntry> out;
  std::string raw;
  int line = 0;
  while (std::getline(in, raw)) {
    ++line;
    std::string_view text = raw;
    if (const auto c = text.find_first_of("#!"); c != std::string_view::npos)
      text = text.substr(0, c);
    std::size_t i = 0;
    const auto separator = [](char c) {
      return c == ' ' || c == '\t' || c == '\r' || c == ',' || c == ';';
    };
    while (i < text.size()) {
      while (i < text.size() && separator(text[i])) ++i;
      const std::size_t start = i;
      while (i < text.size() && !separator(text[i])) ++i;
      if (i == start) continue;
      const std::string_view token = text.substr(start, i - start);
      for (const char ch : token) {
        if (static_cast<unsigned char>(ch) >= 0x80) {
          char hex[8];
          std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned char>(ch));
          fail(path, line,
               std::string("byte ") + hex +
                   " outside a comment (only comments may hold non-ASCII "
                   "text)");
        }
      }
      long value = -1;
      const auto [end, err] = std::from_chars(token.data(), token.data() + token.size(), value);
      if (err != std::errc() || end != token.data() + token.size() || value < 0) {
        // Appended, not "'" + text: GCC 12 warns falsely (-Wrestrict) about the latter.
        std::string reason(1, '\'');
        reason.append(token.substr(0, 32)).append("' is not a non-negative integer");
        fail(path, line, reason);
      }
      out.push_back({value, line});
    }
  }
  if (in.bad()) fail(path, 0, "read error in the node list file");
  if (out.empty()) fail(path, 0, "the node list file holds no node");
  return out;
}

}  // namespace tongue::scene
