#pragma once
// The training snapshots of a reduced basis, in one HDF5 file (HDF5's Lite API):
//   /snapshots      [S, 3N]  each a displacement from the origin [m], run after run
//   /run_snapshots  [R]      how many snapshots each run gave, in order
// and root attributes: format ("tongue-snapshots-1"), run_names (the runs' names, one a line).
#include <string>
#include <vector>

#include "fem/types.hpp"

namespace tongue::reduced {

struct SnapshotSet {
  Eigen::MatrixXd snapshots;  // 3N x S
  std::vector<std::string> run_names;
  std::vector<int> run_snapshots;
};

// Throws std::runtime_error naming the file when it cannot be written or read, or is not a
// snapshot file.
void write_snapshots(const std::string& path, const SnapshotSet& set);
SnapshotSet read_snapshots(const std::string& path);

}  // namespace tongue::reduced
