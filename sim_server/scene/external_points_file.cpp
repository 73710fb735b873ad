#include "scene/external_points_file.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <vector>

namespace tongue::scene {

namespace {

[[noreturn]] void fail(const std::string& path, int line, const std::string& reason) {
  throw std::runtime_error(path + ", line " + std::to_string(line) + ": " + reason);
}

std::vector<std::string_view> fields(std::string_view line) {
  std::vector<std::string_view> out;
  const auto separator = [](char c) { return c == ' ' || c == '\t' || c == ',' || c == '\r'; };
  std::size_t k = 0;
  while (k < line.size()) {
    while (k < line.size() && separator(line[k])) ++k;
    const std::size_t start = k;
    while (k < line.size() && !separator(line[k])) ++k;
    if (k > start) out.push_back(line.substr(start, k - start));
  }
  return out;
}

}  // namespace

std::map<long, fem::Vec3> read_external_points(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open the external points file");
  std::map<long, fem::Vec3> points;
  std::string raw;
  int number = 0;
  while (std::getline(in, raw)) {
    ++number;
    std::string_view line = raw;
    if (const auto comment = line.find_first_of("#!"); comment != std::string_view::npos)
      line = line.substr(0, comment);
    const std::vector<std::string_view> f = fields(line);
    if (f.empty()) continue;
    if (f.size() != 4)
      fail(path, number,
           "expected 'id x y z' (4 fields, position in m), got " + std::to_string(f.size()) +
               " fields");
    long id = 0;
    const auto [id_end, id_ec] = std::from_chars(f[0].data(), f[0].data() + f[0].size(), id);
    if (id_ec != std::errc() || id_end != f[0].data() + f[0].size() || id <= 0)
      fail(path, number, "id '" + std::string(f[0]) + "' is not a positive integer");
    fem::Vec3 p;
    for (int c = 0; c < 3; ++c) {
      const std::string_view t = f[c + 1];
      double v = 0.0;
      const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
      if (ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v))
        fail(path, number, "coordinate '" + std::string(t) + "' is not a finite number (m)");
      p[c] = v;
    }
    if (!points.emplace(id, p).second)
      fail(path, number, "point " + std::to_string(id) + " is given twice");
  }
  if (in.bad()) throw std::runtime_error(path + ": read error in the external points file");
  return points;
}

}  // namespace tongue::scene
