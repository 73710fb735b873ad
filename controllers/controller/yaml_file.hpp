#pragma once
// Reading the controllers' YAML inputs (motor plans, activation schedules) with errors that name
// the file, the key path and the line: every accessor takes the node and its key path.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace tongue::controller {

class YamlFile {
 public:
  // Reads and parses the file. Throws InputError naming the file when it cannot be read, is not
  // valid YAML, or is empty.
  static YamlFile load(const std::string& path);
  // Parses text; source names it in errors.
  static YamlFile parse(const std::string& text, const std::string& source);

  const YAML::Node& root() const { return root_; }
  const std::string& source() const { return source_; }

  // ---- checks; each throws InputError naming source, path and the node's line ----
  [[noreturn]] void fail(const std::string& path, const std::string& reason,
                         const YAML::Node& at) const;
  void expect_map(const YAML::Node& n, const std::string& path) const;
  void expect_sequence(const YAML::Node& n, const std::string& path) const;
  // Rejects keys not in allowed (listing those) and keys given twice.
  void check_keys(const YAML::Node& n, const std::string& path,
                  const std::vector<std::string>& allowed) const;
  // Rejects keys given twice and keys that are not plain names (a map of user-chosen names).
  void check_unique_keys(const YAML::Node& n, const std::string& path) const;
  YAML::Node required(const YAML::Node& parent, const std::string& path,
                      const std::string& key) const;
  double number(const YAML::Node& n, const std::string& path) const;  // finite
  double non_negative(const YAML::Node& n, const std::string& path, const std::string& unit) const;
  std::string text(const YAML::Node& n, const std::string& path) const;
  // A list of finite numbers (at least one).
  std::vector<double> numbers(const YAML::Node& n, const std::string& path) const;

 private:
  YamlFile(YAML::Node root, std::string source)
      : root_(std::move(root)), source_(std::move(source)) {}
  YAML::Node root_;
  std::string source_;
};

// True when the key is there with a value (`key:` with nothing after it counts as omitted).
inline bool present(const YAML::Node& n) {
  return n.IsDefined() && !n.IsNull();
}

inline std::string child_path(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

inline std::string index_path(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

}  // namespace tongue::controller
