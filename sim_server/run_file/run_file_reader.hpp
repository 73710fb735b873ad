#pragma once
// Read-only access to an HDF5 run file (names: run_file_layout.hpp), for every program and test
// that reads one back: datasets by name, whole, with their shapes; root and dataset attributes.
// Every failure is a RunFileError naming the file and the dataset or attribute, e.g.
//   "logs/ai/run.h5: /muscles/names: missing".
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "run_file/run_file_error.hpp"
#include "run_file/run_file_layout.hpp"

namespace tongue::run_file {

class RunFileReader {
 public:
  // Opens the file read-only; RunFileError "<path>: cannot open as an HDF5 run file" otherwise.
  // A file still being written reads up to its last flush.
  explicit RunFileReader(const std::string& path);
  ~RunFileReader();
  RunFileReader(RunFileReader&&) noexcept;
  RunFileReader& operator=(RunFileReader&&) noexcept;

  const std::string& path() const { return path_; }

  // True when a dataset or group of this name (e.g. "/muscles/names") is in the file.
  bool exists(const std::string& name) const;
  // Extent of each dimension, slowest first ({T, N, 3} for /positions).
  std::vector<std::size_t> shape(const std::string& dataset) const;
  // The whole dataset, row-major, converted to the element type asked for.
  std::vector<double> doubles(const std::string& dataset) const;
  std::vector<int> ints(const std::string& dataset) const;
  // A one-dimensional dataset of strings (variable or fixed length).
  std::vector<std::string> strings(const std::string& dataset) const;

  // object is "/" (layout::kRoot) for the root group, or a dataset's name.
  bool has_attribute(const std::string& object, const std::string& name) const;
  std::string string_attribute(const std::string& object, const std::string& name) const;
  int int_attribute(const std::string& object, const std::string& name) const;

 private:
  struct File;
  std::string path_;
  std::unique_ptr<File> file_;
};

}  // namespace tongue::run_file
