#pragma once
// A GoogleTest fixture giving each test its own fresh directory under the system temp dir, removed
// again after the test. The directory is named after the test suite and the test, plus a random
// number, so parallel test processes never share one.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <system_error>

namespace tongue::testing {

class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    dir_ = std::filesystem::temp_directory_path() /
           (file_name_safe(name) + "_" + std::to_string(std::random_device{}()));
    std::filesystem::create_directories(dir_);
  }

  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }

  // Writes text to the file name in the test's directory and returns the file's path.
  std::string write(const std::string& name, const std::string& text) const {
    const std::filesystem::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }

  std::filesystem::path dir_;

 private:
  // Parameterized suite and test names contain '/', which must not make subdirectories.
  static std::string file_name_safe(std::string s) {
    for (char& c : s) {
      if (c == '/' || c == '\\') c = '_';
    }
    return s;
  }
};

}  // namespace tongue::testing
