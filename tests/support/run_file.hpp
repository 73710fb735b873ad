#pragma once
// Read-only access to an HDF5 run file for end-to-end tests: run_file::RunFileReader, forgiving
// so that a test asserts on what it finds (ok() false when the file does not open, empty results
// and "<missing>" for what is not there) instead of failing on an exception.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "run_file/run_file_reader.hpp"

namespace tongue::testing {

namespace fs = std::filesystem;

class RunFile {
 public:
  explicit RunFile(const fs::path& p) {
    try {
      reader_.emplace(p.string());
    } catch (const run_file::RunFileError&) {
    }
  }
  bool ok() const { return reader_.has_value(); }

  std::vector<std::size_t> shape(const std::string& name) const {
    return get([&] { return reader_->shape(name); });
  }
  std::vector<double> doubles(const std::string& name) const {
    return get([&] { return reader_->doubles(name); });
  }
  std::vector<int> ints(const std::string& name) const {
    return get([&] { return reader_->ints(name); });
  }
  std::vector<std::string> strings(const std::string& name) const {
    return get([&] { return reader_->strings(name); });
  }
  bool exists(const std::string& name) const { return reader_ && reader_->exists(name); }

  // A string attribute of the root group (loc "/") or of a dataset.
  std::string string_attribute(const std::string& loc, const std::string& name) const {
    const auto v = get([&] { return std::optional(reader_->string_attribute(loc, name)); });
    return v.value_or("<missing>");
  }
  int int_attribute(const std::string& name) const {
    return get([&] { return std::optional(reader_->int_attribute("/", name)); }).value_or(-1);
  }

 private:
  // read(), or an empty result when the file or the item is missing.
  template <typename Read>
  auto get(Read read) const -> decltype(read()) {
    if (!reader_) return {};
    try {
      return read();
    } catch (const run_file::RunFileError&) {
      return {};
    }
  }

  std::optional<run_file::RunFileReader> reader_;
};

}  // namespace tongue::testing
