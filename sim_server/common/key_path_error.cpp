#include "common/key_path_error.hpp"

namespace tongue::common {
namespace {

std::string message(const std::string& file, const std::string& key_path, const std::string& reason,
                    int line) {
  std::string s = file + ": " + (key_path.empty() ? "" : key_path + ": ") + reason;
  if (line > 0) s += " (line " + std::to_string(line) + ")";
  return s;
}

}  // namespace

KeyPathError::KeyPathError(const std::string& file, const std::string& key_path,
                           const std::string& reason, int line)
    : std::runtime_error(message(file, key_path, reason, line)),
      file_(file),
      key_path_(key_path),
      reason_(reason),
      line_(line) {}

}  // namespace tongue::common
