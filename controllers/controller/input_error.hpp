#pragma once
// A controller input (plan, schedule, run log) that cannot be used. what() reads
// "<file>: <key path>: <reason>", with " (line <n>)" when the position in the file is known, so
// that the user sees which file and which key to fix; the programs exit 1 on it.
#include <stdexcept>
#include <string>

namespace tongue::controller {

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& key_path, const std::string& reason,
             int line = 0)
      : std::runtime_error(file + ": " + (key_path.empty() ? "" : key_path + ": ") + reason +
                           (line > 0 ? " (line " + std::to_string(line) + ")" : "")),
        file_(file),
        key_path_(key_path) {}

  const std::string& file() const { return file_; }
  const std::string& key_path() const { return key_path_; }

 private:
  std::string file_, key_path_;
};

}  // namespace tongue::controller
