#pragma once
// Reads a scene from YAML (schema: scene.hpp and scenes/README.md) and checks everything that
// can be checked without building the mesh: unknown or duplicate keys, types, list lengths,
// required keys, ranges, material parameters, mesh file existence and set names.
#include <stdexcept>
#include <string>

#include "scene/scene.hpp"

namespace tongue::scene {

// A scene that cannot be run. what() reads "<file>: <key path>: <reason>", with " (line <n>)"
// appended when the position in the file is known, e.g.
//   "scenes/x.yaml: material.parameters.c99: unknown parameter ... (line 7)".
class SceneError : public std::runtime_error {
 public:
  SceneError(const std::string& file, const std::string& key_path, const std::string& reason,
             int line = 0);

  const std::string& file() const { return file_; }
  const std::string& key_path() const { return key_path_; }  // e.g. "constraints[1].set"
  const std::string& reason() const { return reason_; }
  int line() const { return line_; }  // 1-based; 0 when unknown

 private:
  std::string file_, key_path_, reason_;
  int line_;
};

// Reads and parses the file; relative mesh paths are taken relative to its directory.
Scene read_scene(const std::string& path);

// Parses YAML text; relative mesh paths are taken relative to base_dir. source_name stands for
// the file in error messages.
Scene parse_scene(const std::string& yaml_text, const std::string& base_dir,
                  const std::string& source_name = "<scene>");

}  // namespace tongue::scene
