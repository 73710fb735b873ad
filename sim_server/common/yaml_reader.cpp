#include "common/yaml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "common/bounded_file.hpp"
#include "common/number_text.hpp"

namespace tongue::common {
namespace {

std::string with_unit(double v, const std::string& unit) {
  return number_text(v) + (unit.empty() ? "" : " " + unit);
}

}  // namespace

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

std::string describe(const YAML::Node& n) {
  if (n.IsScalar()) return "'" + n.Scalar() + "'";
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a mapping";
  return "nothing";
}

YamlReader YamlReader::load(const std::string& path) {
  return parse(read_bounded_file(path), path);
}

YamlReader YamlReader::parse(const std::string& text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw KeyPathError(source, "", "YAML syntax error: " + e.msg, e.mark.line + 1);
  }
  if (!present(root)) throw KeyPathError(source, "", "the file is empty");
  return YamlReader(root, source, text);
}

void YamlReader::fail(const std::string& path, const std::string& reason,
                      const YAML::Node& at) const {
  const int line = at.IsDefined() ? at.Mark().line + 1 : 0;
  throw KeyPathError(source_, path, reason, line);
}

void YamlReader::expect_map(const YAML::Node& n, const std::string& path) const {
  if (!n.IsMap()) fail(path, "expected a mapping of keys to values, got " + describe(n), n);
}

void YamlReader::expect_sequence(const YAML::Node& n, const std::string& path) const {
  if (!n.IsSequence()) fail(path, "expected a list, got " + describe(n), n);
}

void YamlReader::check_keys(const YAML::Node& n, const std::string& path,
                            const std::vector<std::string>& allowed,
                            const std::string& noun) const {
  std::set<std::string> seen;
  for (auto it = n.begin(); it != n.end(); ++it) {
    if (!it->first.IsScalar()) fail(path, "keys must be plain names", it->first);
    const std::string key = it->first.Scalar();
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      fail(child_path(path, key), "unknown " + noun + " (known: " + join(allowed) + ")", it->first);
    if (!seen.insert(key).second) fail(child_path(path, key), noun + " given twice", it->first);
  }
}

void YamlReader::check_unique_keys(const YAML::Node& n, const std::string& path) const {
  std::set<std::string> seen;
  for (auto it = n.begin(); it != n.end(); ++it) {
    if (!it->first.IsScalar() || it->first.Scalar().empty())
      fail(path, "keys must be plain names", it->first);
    if (!seen.insert(it->first.Scalar()).second)
      fail(child_path(path, it->first.Scalar()), "key given twice", it->first);
  }
}

YAML::Node YamlReader::required(const YAML::Node& parent, const std::string& path,
                                const std::string& key) const {
  const YAML::Node n = parent[key];
  if (!present(n)) fail(child_path(path, key), "missing required key", parent);
  return n;
}

double YamlReader::number(const YAML::Node& n, const std::string& path) const {
  double v = 0.0;
  if (!n.IsScalar() || !YAML::convert<double>::decode(n, v))
    fail(path, "expected a number, got " + describe(n), n);
  if (!std::isfinite(v)) fail(path, "expected a finite number, got " + describe(n), n);
  return v;
}

double YamlReader::positive(const YAML::Node& n, const std::string& path,
                            const std::string& unit) const {
  const double v = number(n, path);
  if (!(v > 0.0)) fail(path, "must be positive, got " + with_unit(v, unit), n);
  return v;
}

double YamlReader::non_negative(const YAML::Node& n, const std::string& path,
                                const std::string& unit) const {
  const double v = number(n, path);
  if (v < 0.0) fail(path, "must not be negative, got " + with_unit(v, unit), n);
  return v;
}

int YamlReader::integer(const YAML::Node& n, const std::string& path) const {
  int v = 0;
  if (!n.IsScalar() || !YAML::convert<int>::decode(n, v))
    fail(path, "expected an integer, got " + describe(n), n);
  return v;
}

int YamlReader::at_least(const YAML::Node& n, const std::string& path, int lo) const {
  const int v = integer(n, path);
  if (v < lo)
    fail(path, "must be at least " + std::to_string(lo) + ", got " + std::to_string(v), n);
  return v;
}

int YamlReader::between(const YAML::Node& n, const std::string& path, int lo, int hi) const {
  const int v = integer(n, path);
  if (v < lo || v > hi)
    fail(path,
         "must be from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " +
             std::to_string(v),
         n);
  return v;
}

bool YamlReader::boolean(const YAML::Node& n, const std::string& path) const {
  bool v = false;
  if (!n.IsScalar() || !YAML::convert<bool>::decode(n, v))
    fail(path, "expected true or false, got " + describe(n), n);
  return v;
}

std::string YamlReader::text(const YAML::Node& n, const std::string& path) const {
  if (!n.IsScalar()) fail(path, "expected a name, got " + describe(n), n);
  return n.Scalar();
}

std::vector<double> YamlReader::numbers(const YAML::Node& n, const std::string& path,
                                        std::size_t min_count) const {
  expect_sequence(n, path);
  if (n.size() < min_count)
    fail(path,
         min_count == 1 ? std::string("expected at least one number")
                        : "expected at least " + std::to_string(min_count) + " numbers",
         n);
  std::vector<double> out;
  for (std::size_t i = 0; i < n.size(); ++i) out.push_back(number(n[i], index_path(path, i)));
  return out;
}

std::vector<std::string> YamlReader::texts(const YAML::Node& n, const std::string& path) const {
  expect_sequence(n, path);
  std::vector<std::string> out;
  for (std::size_t i = 0; i < n.size(); ++i) out.push_back(text(n[i], index_path(path, i)));
  return out;
}

}  // namespace tongue::common
