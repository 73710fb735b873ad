#pragma once
// Reads a scene from YAML (schema: scene.hpp and scenes/README.md) and checks everything that
// can be checked without building the mesh: unknown or duplicate keys, types, list lengths,
// required keys, ranges, material parameters, mesh file existence and set names.
#include <string>

#include "common/key_path_error.hpp"
#include "scene/scene.hpp"

namespace tongue::scene {

// A scene that cannot be run: the key-path error of every input file (common/key_path_error.hpp),
// "<file>: <key path>: <reason> (line <n>)". The name says which input it came from.
using SceneError = common::KeyPathError;

// Reads and parses the file; relative mesh paths are taken relative to its directory.
Scene read_scene(const std::string& path);

// Parses YAML text; relative mesh paths are taken relative to base_dir. source_name stands for
// the file in error messages.
Scene parse_scene(const std::string& yaml_text, const std::string& base_dir,
                  const std::string& source_name = "<scene>");

}  // namespace tongue::scene
