#pragma once
// Reading a YAML input file (scene, experiment, motor plan, activation schedule) with errors that
// name the file, the key path and the line: every accessor takes the node and its key path, and
// throws KeyPathError when the node is not what it should be. Messages say what was expected and
// what was found, e.g. "scene.yaml: analysis.dt: expected a number, got 'fast' (line 12)".
#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <string>
#include <vector>

#include "common/key_path_error.hpp"

namespace tongue::common {

// True when the key is there with a value (`key:` with nothing after it counts as omitted).
inline bool present(const YAML::Node& n) {
  return n.IsDefined() && !n.IsNull();
}

// "a.b" from "a" and "b" ("b" at the top level); "a[2]" from "a" and 2.
inline std::string child_path(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}
inline std::string index_path(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

// "a, b, c", for the lists of known names in messages.
std::string join(const std::vector<std::string>& names);
// What a node is, for messages: "'text'", "a list", "a mapping" or "nothing".
std::string describe(const YAML::Node& n);

class YamlReader {
 public:
  // Reads and parses the file. Throws KeyPathError naming the file when it cannot be read, is
  // not valid YAML (with the line) or is empty.
  static YamlReader load(const std::string& path);
  // Parses text; source names it in errors.
  static YamlReader parse(const std::string& text, const std::string& source);

  // Const access: reading a missing key through a const node never inserts it.
  const YAML::Node& root() const { return root_; }
  const std::string& source() const { return source_; }
  const std::string& file_text() const { return text_; }  // as read, e.g. to be logged

  // ---- checks; each throws KeyPathError naming source, path and the node's line ----
  [[noreturn]] void fail(const std::string& path, const std::string& reason,
                         const YAML::Node& at) const;
  void expect_map(const YAML::Node& n, const std::string& path) const;
  void expect_sequence(const YAML::Node& n, const std::string& path) const;
  // Rejects keys not in allowed (listing those) and keys given twice; noun names a key in the
  // messages ("unknown parameter of material 'x' (known: ...)").
  void check_keys(const YAML::Node& n, const std::string& path,
                  const std::vector<std::string>& allowed, const std::string& noun = "key") const;
  // Rejects keys given twice and keys that are not plain names (a map of user-chosen names).
  void check_unique_keys(const YAML::Node& n, const std::string& path) const;
  // parent[key], which must be present.
  YAML::Node required(const YAML::Node& parent, const std::string& path,
                      const std::string& key) const;

  double number(const YAML::Node& n, const std::string& path) const;  // finite
  // unit follows the value in the message ("must be positive, got -1 N"); may be empty.
  double positive(const YAML::Node& n, const std::string& path, const std::string& unit) const;
  double non_negative(const YAML::Node& n, const std::string& path, const std::string& unit) const;
  int integer(const YAML::Node& n, const std::string& path) const;
  int at_least(const YAML::Node& n, const std::string& path, int lo) const;
  int between(const YAML::Node& n, const std::string& path, int lo, int hi) const;  // inclusive
  bool boolean(const YAML::Node& n, const std::string& path) const;
  std::string text(const YAML::Node& n, const std::string& path) const;  // a scalar
  // A list of at least min_count finite numbers, or of scalars.
  std::vector<double> numbers(const YAML::Node& n, const std::string& path,
                              std::size_t min_count = 1) const;
  std::vector<std::string> texts(const YAML::Node& n, const std::string& path) const;

 private:
  YamlReader(YAML::Node root, std::string source, std::string text)
      : root_(std::move(root)), source_(std::move(source)), text_(std::move(text)) {}
  YAML::Node root_;
  std::string source_;
  std::string text_;
};

}  // namespace tongue::common
