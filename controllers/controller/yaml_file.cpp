#include "controller/yaml_file.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "controller/input_error.hpp"
#include "controller/number_text.hpp"

namespace tongue::controller {
namespace {

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

}  // namespace

YamlFile YamlFile::load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse(text.str(), path);
}

YamlFile YamlFile::parse(const std::string& text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(source, "", "YAML syntax error: " + e.msg, e.mark.line + 1);
  }
  if (!present(root)) throw InputError(source, "", "the file is empty");
  return YamlFile(root, source);
}

void YamlFile::fail(const std::string& path, const std::string& reason,
                    const YAML::Node& at) const {
  const int line = at.IsDefined() ? at.Mark().line + 1 : 0;
  throw InputError(source_, path, reason, line);
}

void YamlFile::expect_map(const YAML::Node& n, const std::string& path) const {
  if (!n.IsMap()) fail(path, "expected a mapping of keys to values, got " + describe(n), n);
}

void YamlFile::expect_sequence(const YAML::Node& n, const std::string& path) const {
  if (!n.IsSequence()) fail(path, "expected a list, got " + describe(n), n);
}

void YamlFile::check_keys(const YAML::Node& n, const std::string& path,
                          const std::vector<std::string>& allowed) const {
  std::set<std::string> seen;
  for (auto it = n.begin(); it != n.end(); ++it) {
    if (!it->first.IsScalar()) fail(path, "keys must be plain names", it->first);
    const std::string key = it->first.Scalar();
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      fail(child_path(path, key), "unknown key (known: " + join(allowed) + ")", it->first);
    if (!seen.insert(key).second) fail(child_path(path, key), "key given twice", it->first);
  }
}

void YamlFile::check_unique_keys(const YAML::Node& n, const std::string& path) const {
  std::set<std::string> seen;
  for (auto it = n.begin(); it != n.end(); ++it) {
    if (!it->first.IsScalar() || it->first.Scalar().empty())
      fail(path, "keys must be plain names", it->first);
    if (!seen.insert(it->first.Scalar()).second)
      fail(child_path(path, it->first.Scalar()), "key given twice", it->first);
  }
}

YAML::Node YamlFile::required(const YAML::Node& parent, const std::string& path,
                              const std::string& key) const {
  const YAML::Node n = parent[key];
  if (!present(n)) fail(child_path(path, key), "missing required key", parent);
  return n;
}

double YamlFile::number(const YAML::Node& n, const std::string& path) const {
  double v = 0.0;
  if (!n.IsScalar() || !YAML::convert<double>::decode(n, v))
    fail(path, "expected a number, got " + describe(n), n);
  if (!std::isfinite(v)) fail(path, "expected a finite number, got " + number_text(v), n);
  return v;
}

double YamlFile::non_negative(const YAML::Node& n, const std::string& path,
                              const std::string& unit) const {
  const double v = number(n, path);
  if (v < 0.0) fail(path, "must not be negative, got " + number_text(v) + " " + unit, n);
  return v;
}

std::string YamlFile::text(const YAML::Node& n, const std::string& path) const {
  if (!n.IsScalar()) fail(path, "expected a name, got " + describe(n), n);
  return n.Scalar();
}

std::vector<double> YamlFile::numbers(const YAML::Node& n, const std::string& path) const {
  expect_sequence(n, path);
  if (n.size() == 0) fail(path, "expected at least one number", n);
  std::vector<double> out;
  for (std::size_t i = 0; i < n.size(); ++i) out.push_back(number(n[i], index_path(path, i)));
  return out;
}

}  // namespace tongue::controller
