#include "scene/node_list_file.hpp"

#include <charconv>
#include <cstdint>
#include <string_view>
#include <system_error>

#include "scene/field_lines.hpp"

namespace tongue::scene {

std::vector<NodeListEntry> read_node_list(const std::string& path) {
  std::vector<NodeListEntry> out;
  // An attachment list of a tongue has some hundred nodes; 64 MiB is a wrong file.
  for_each_field_line(
      path, "node list", std::uintmax_t{64} << 20,
      [&](int line, const std::vector<std::string_view>& fields) {
        for (const std::string_view token : fields) {
          long value = -1;
          const auto [end, err] = std::from_chars(token.data(), token.data() + token.size(), value);
          if (err != std::errc() || end != token.data() + token.size() || value < 0) {
            // Appended, not "'" + text: GCC 12 warns falsely (-Wrestrict)
            // about the latter.
            std::string reason(1, '\'');
            reason.append(token.substr(0, 32)).append("' is not a non-negative integer");
            fail_in_file(path, line, reason);
          }
          out.push_back({value, line});
        }
      });
  if (out.empty()) fail_in_file(path, 0, "the node list file holds no node");
  return out;
}

}  // namespace tongue::scene
