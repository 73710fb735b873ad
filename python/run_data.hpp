#pragma once
// A run file read back for Python (the module's RunFile): its datasets as whole arrays with their
// shapes, and each muscle's series by name. The layout is run_file_layout.hpp's.
#include <cstddef>
#include <string>
#include <vector>

#include "run_file/run_file_reader.hpp"

namespace tongue::python {

// A dataset: its values row-major and its shape, slowest dimension first.
struct Dataset {
  std::vector<double> values;
  std::vector<std::size_t> shape;
};

class RunData {
 public:
  // Throws run_file::RunFileError naming the file when it cannot be read as a run file.
  explicit RunData(const std::string& path);

  const std::string& path() const { return reader_.path(); }
  // The whole dataset by name ("/positions", "/muscles/length", ...); RunFileError naming it
  // when it is missing.
  Dataset dataset(const std::string& name) const;
  bool has(const std::string& name) const { return reader_.exists(name); }
  std::vector<std::string> muscle_names() const;  // empty for a run without muscles
  // Column m of a frames x muscles dataset; std::invalid_argument for a name not in the run.
  std::vector<double> muscle_series(const std::string& dataset, const std::string& muscle) const;
  std::string status() const;  // the root's "status" attribute ("completed", ...); "" if none

 private:
  run_file::RunFileReader reader_;
};

}  // namespace tongue::python
