#include "scene/external_points_file.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <vector>

#include "scene/field_lines.hpp"

namespace tongue::scene {

std::map<long, fem::Vec3> read_external_points(const std::string& path) {
  std::map<long, fem::Vec3> points;
  // A tongue has some tens of bony attachments; 16 MiB is a wrong file.
  for_each_field_line(
      path, "external points", std::uintmax_t{16} << 20,
      [&](int line, const std::vector<std::string_view>& fields) {
        if (fields.size() != 4)
          fail_in_file(path, line,
                       "expected 'id x y z' (4 fields, position in m), got " +
                           std::to_string(fields.size()) + " fields");
        long id = 0;
        const auto [id_end, id_ec] =
            std::from_chars(fields[0].data(), fields[0].data() + fields[0].size(), id);
        if (id_ec != std::errc() || id_end != fields[0].data() + fields[0].size() || id <= 0)
          fail_in_file(path, line, "id '" + std::string(fields[0]) + "' is not a positive integer");
        fem::Vec3 p;
        for (int c = 0; c < 3; ++c) {
          const std::string_view t = fields[c + 1];
          double v = 0.0;
          const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
          if (ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v))
            fail_in_file(path, line,
                         "coordinate '" + std::string(t) + "' is not a finite number (m)");
          p[c] = v;
        }
        if (!points.emplace(id, p).second)
          fail_in_file(path, line, "point " + std::to_string(id) + " is given twice");
      });
  return points;
}

}  // namespace tongue::scene
