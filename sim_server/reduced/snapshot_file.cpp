#include "reduced/snapshot_file.hpp"

#include <numeric>
#include <sstream>

#include "reduced/hdf5_lite.hpp"

namespace tongue::reduced {
namespace {

constexpr char kFormat[] = "tongue-snapshots-1";

}  // namespace

void write_snapshots(const std::string& path, const SnapshotSet& set) {
  if (set.run_names.size() != set.run_snapshots.size() ||
      std::accumulate(set.run_snapshots.begin(), set.run_snapshots.end(), 0L) !=
          static_cast<long>(set.snapshots.cols()))
    throw std::invalid_argument("snapshots: the runs' counts do not add up to the snapshots");
  const detail::Hdf5File f(path, true);
  // A column-major 3N x S matrix is, in memory, the row-major S x 3N one.
  const hsize_t dims[2] = {static_cast<hsize_t>(set.snapshots.cols()),
                           static_cast<hsize_t>(set.snapshots.rows())};
  f.check(H5LTmake_dataset_double(f.id(), "/snapshots", 2, dims, set.snapshots.data()),
          "cannot write /snapshots");
  const hsize_t runs = set.run_snapshots.size();
  f.check(H5LTmake_dataset_int(f.id(), "/run_snapshots", 1, &runs, set.run_snapshots.data()),
          "cannot write /run_snapshots");
  std::string names;
  for (const std::string& n : set.run_names) names += n + "\n";
  detail::write_text(f, "format", kFormat);
  detail::write_text(f, "run_names", names);
}

SnapshotSet read_snapshots(const std::string& path) {
  const detail::Hdf5File f(path, false);
  if (detail::read_text(f, "format") != kFormat)
    f.fail(std::string("not a snapshot file (format is not ") + kFormat + ")");
  SnapshotSet set;
  const std::vector<hsize_t> dims = detail::dataset_shape(f, "/snapshots", 2);
  const hsize_t runs = detail::dataset_shape(f, "/run_snapshots", 1, H5T_INTEGER)[0];
  set.snapshots.resize(static_cast<Eigen::Index>(dims[1]), static_cast<Eigen::Index>(dims[0]));
  set.run_snapshots.resize(runs);
  f.check(H5LTread_dataset_double(f.id(), "/snapshots", set.snapshots.data()),
          "cannot read /snapshots");
  f.check(H5LTread_dataset_int(f.id(), "/run_snapshots", set.run_snapshots.data()),
          "cannot read /run_snapshots");
  std::istringstream names(detail::read_text(f, "run_names"));
  for (std::string line; std::getline(names, line);) set.run_names.push_back(line);
  if (set.run_names.size() != runs ||
      std::accumulate(set.run_snapshots.begin(), set.run_snapshots.end(), 0L) !=
          static_cast<long>(dims[0]))
    f.fail("the runs' names and counts do not match the snapshots");
  return set;
}

}  // namespace tongue::reduced
