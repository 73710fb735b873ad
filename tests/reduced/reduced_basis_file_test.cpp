// The reduced basis and snapshot files: written and read back exactly; a file made for another
// mesh or material, a missing file, a file that is not HDF5 and an HDF5 file of another kind
// refused with errors that name the file.
#include "reduced/reduced_basis_file.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <fstream>

#include "fem/mesh/box_generator.hpp"
#include "reduced/snapshot_file.hpp"
#include "support/temp_dir_test.hpp"

namespace tongue::reduced {
namespace {

class ReducedFiles : public testing::TempDirTest {
 protected:
  fem::Mesh mesh = fem::make_box(fem::Vec3::Zero(), {0.01, 0.02, 0.03}, 2, 2, 2);
  ReducedBasis basis() const {
    ReducedBasis b;
    const int n = 3 * mesh.num_nodes();
    std::srand(3);
    b.origin = fem::Vector::Random(n) * 1e-3;
    b.modes = Eigen::MatrixXd::Random(n, 4).householderQr().householderQ() *
              Eigen::MatrixXd::Identity(n, 4);
    b.singular_values = fem::Vector::LinSpaced(6, 6.0, 1.0);
    b.energy_fraction = 0.99;
    b.captured = 0.995;
    b.snapshots = 6;
    b.runs = 2;
    b.mesh_signature = mesh_signature(mesh);
    b.material = "neo_hookean shear_modulus=1000";
    b.scene = "analysis: {type: dynamic}\n";
    b.sample_elements = {1, 4, 6};
    b.sample_weights = fem::Vector::LinSpaced(3, 2.5, 0.75);
    b.sample_tolerance = 0.01;
    b.sample_error = 0.0087;
    return b;
  }
  void expect_error_naming(const std::string& path, const std::string& part) {
    try {
      read_reduced_basis(path);
      ADD_FAILURE() << path << " was read";
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_NE(what.find(part), std::string::npos) << what;
    }
  }
};

TEST_F(ReducedFiles, BasisIsReadBackExactly) {
  const std::string path = (dir_ / "basis.h5").string();
  const ReducedBasis b = basis();
  write_reduced_basis(path, b);
  const ReducedBasis r = read_reduced_basis(path);
  EXPECT_EQ(r.origin, b.origin);
  EXPECT_EQ(r.modes, b.modes);
  EXPECT_EQ(r.singular_values, b.singular_values);
  EXPECT_EQ(r.energy_fraction, b.energy_fraction);
  EXPECT_EQ(r.captured, b.captured);
  EXPECT_EQ(r.snapshots, b.snapshots);
  EXPECT_EQ(r.runs, b.runs);
  EXPECT_EQ(r.mesh_signature, b.mesh_signature);
  EXPECT_EQ(r.material, b.material);
  EXPECT_EQ(r.scene, b.scene);
  EXPECT_EQ(r.sample_elements, b.sample_elements);
  EXPECT_EQ(r.sample_weights, b.sample_weights);
  EXPECT_EQ(r.sample_tolerance, b.sample_tolerance);
  EXPECT_EQ(r.sample_error, b.sample_error);
  EXPECT_NO_THROW(check_fits(r, path, mesh, b.material));
}

TEST_F(ReducedFiles, ABasisForAnotherMeshOrMaterialIsRefused) {
  const ReducedBasis b = basis();
  fem::Mesh other = mesh;
  other.nodes[3].x() += 1e-9;  // the same counts, one node moved by a nanometre
  EXPECT_NE(mesh_signature(other), b.mesh_signature);
  try {
    check_fits(b, "basis.h5", other, b.material);
    ADD_FAILURE() << "another mesh was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("basis.h5: made for another mesh"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(check_fits(b, "basis.h5", mesh, "mooney_rivlin5"), std::invalid_argument);
  ReducedBasis beyond = b;
  beyond.sample_elements.back() = mesh.num_elements();  // one past the last
  EXPECT_THROW(check_fits(beyond, "basis.h5", mesh, b.material), std::invalid_argument);
}

TEST_F(ReducedFiles, ABasisWithoutASampleOrWithABadWeightIsRefused) {
  const std::string path = (dir_ / "basis.h5").string();
  ReducedBasis b = basis();
  b.sample_weights[1] = 0.0;  // a sampled element must weigh something
  write_reduced_basis(path, b);
  expect_error_naming(path, "not a finite positive number");
  b.sample_elements.clear();
  b.sample_weights.resize(0);
  write_reduced_basis(path, b);
  expect_error_naming(path, "are empty");
}

TEST_F(ReducedFiles, MissingForeignAndOtherHdf5FilesAreRefused) {
  expect_error_naming((dir_ / "none.h5").string(), "missing or not an HDF5 file");
  const std::string text = write("text.h5", "not a basis\n");
  expect_error_naming(text, "missing or not an HDF5 file");
  SnapshotSet set;
  set.snapshots = Eigen::MatrixXd::Ones(6, 2);
  set.run_names = {"a"};
  set.run_snapshots = {2};
  const std::string snapshots = (dir_ / "snapshots.h5").string();
  write_snapshots(snapshots, set);
  expect_error_naming(snapshots, "not a reduced-basis file");
}

TEST_F(ReducedFiles, SnapshotsAreReadBackExactly) {
  SnapshotSet set;
  std::srand(5);
  set.snapshots = Eigen::MatrixXd::Random(9, 5);
  set.run_names = {"step SG", "ramp GGp"};
  set.run_snapshots = {3, 2};
  const std::string path = (dir_ / "snapshots.h5").string();
  write_snapshots(path, set);
  const SnapshotSet r = read_snapshots(path);
  EXPECT_EQ(r.snapshots, set.snapshots);
  EXPECT_EQ(r.run_names, set.run_names);
  EXPECT_EQ(r.run_snapshots, set.run_snapshots);
  set.run_snapshots = {3, 3};  // more than there are
  EXPECT_THROW(write_snapshots(path, set), std::invalid_argument);
}

}  // namespace
}  // namespace tongue::reduced
