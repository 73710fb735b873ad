#pragma once
// An input file (scene, experiment, motor plan, schedule, run file) that cannot be used, named
// down to the key: what() reads "<file>: <key path>: <reason>", with " (line <n>)" appended when
// the position in the file is known, e.g.
//   "scenes/x.yaml: material.parameters.c99: unknown parameter ... (line 7)".
// The key path is empty for an error of the whole file ("<file>: <reason>").
#include <stdexcept>
#include <string>

namespace tongue::common {

class KeyPathError : public std::runtime_error {
 public:
  KeyPathError(const std::string& file, const std::string& key_path, const std::string& reason,
               int line = 0);

  const std::string& file() const { return file_; }
  const std::string& key_path() const { return key_path_; }  // e.g. "constraints[1].set"
  const std::string& reason() const { return reason_; }
  int line() const { return line_; }  // 1-based; 0 when unknown

 private:
  std::string file_, key_path_, reason_;
  int line_;
};

}  // namespace tongue::common
