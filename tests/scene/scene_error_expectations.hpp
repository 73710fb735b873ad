#pragma once
// The scene tests' check of a bad scene: a SceneError whose message names the file ("test.yaml")
// and the key path, and optionally says `also`.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"

namespace tongue::scene_test {

using scene::build_scene;
using scene::parse_scene;
using scene::Scene;
using scene::SceneError;

inline void expect_scene_error(const std::function<void()>& action, const std::string& key_path,
                               const std::string& also) {
  try {
    action();
    FAIL() << "no SceneError for " << key_path;
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.key_path(), key_path) << what;
    // A message names the file, then the key path (none for a whole-file error).
    const std::string head = key_path.empty() ? "test.yaml: " : "test.yaml: " + key_path + ":";
    EXPECT_NE(what.find(head), std::string::npos) << what;
    if (!also.empty()) {
      EXPECT_NE(what.find(also), std::string::npos) << what;
    }
  }
}

// Parsing `text` fails at key_path.
inline void expect_parse_error(const std::string& text, const std::string& key_path,
                               const std::string& also = "") {
  expect_scene_error([&] { parse_scene(text, "", "test.yaml"); }, key_path, also);
}

// `text` parses, and building it fails at key_path.
inline void expect_build_error(const std::string& text, const std::string& key_path,
                               const std::string& also = "") {
  const Scene scene = parse_scene(text, "", "test.yaml");
  expect_scene_error([&] { build_scene(scene); }, key_path, also);
}

}  // namespace tongue::scene_test
