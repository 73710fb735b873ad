#pragma once
// A run file that cannot be written or read. what() reads "<file>: <dataset>: <reason>" (no
// dataset for an error of the whole file), e.g. "run.h5: /muscles/names: missing".
#include <stdexcept>
#include <string>

namespace tongue::run_file {

class RunFileError : public std::runtime_error {
 public:
  RunFileError(const std::string& file, const std::string& dataset, const std::string& reason)
      : std::runtime_error(file + ": " + (dataset.empty() ? "" : dataset + ": ") + reason),
        file_(file),
        dataset_(dataset),
        reason_(reason) {}

  const std::string& file() const { return file_; }
  const std::string& dataset() const { return dataset_; }  // or attribute; empty: the file
  const std::string& reason() const { return reason_; }

 private:
  std::string file_, dataset_, reason_;
};

}  // namespace tongue::run_file
