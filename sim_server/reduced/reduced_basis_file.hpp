#pragma once
// The reduced basis of a model and what it was made for, in one HDF5 file (HDF5's Lite API):
//   /origin           [3N]     the displacement the reduced coordinates are measured from [m]
//                               (the gravity-settled state of the training scene)
//   /modes            [k, 3N]  the basis, one mode per row (orthonormal) [1]
//   /singular_values  [S]      every singular value of the snapshots, largest first [m]
//   /sample_elements  [m]      the elements that hyper-reduction integrates over (0-based,
//                               ascending; element_sampling.hpp)
//   /sample_weights   [m]      their weights [1]
// and root attributes: format ("tongue-reduced-basis-1"), mesh_signature and material (the model
// it fits: mesh_signature() of its mesh, the scene's material as text), energy_fraction asked,
// captured, snapshots, runs, scene (the training scene's text), sample_tolerance and
// sample_error (the sampling's tolerance and the misfit it reached).
#include <string>
#include <vector>

#include "fem/mesh/mesh.hpp"
#include "fem/types.hpp"

namespace tongue::reduced {

struct ReducedBasis {
  fem::Vector origin;
  Eigen::MatrixXd modes;  // 3N x k
  fem::Vector singular_values;
  std::vector<int> sample_elements;
  fem::Vector sample_weights;
  double sample_tolerance = 0.0, sample_error = 0.0;
  double energy_fraction = 0.0, captured = 0.0;
  int snapshots = 0, runs = 0;
  std::string mesh_signature, material, scene;
};

// "<N> nodes, <E> hex8, <16 hex digits>": the counts and an FNV-1a hash of the rest positions'
// and the connectivity's bytes, so that another mesh, or the same one numbered otherwise, differs.
std::string mesh_signature(const fem::Mesh& mesh);

// Throws std::runtime_error naming the file when it cannot be written.
void write_reduced_basis(const std::string& path, const ReducedBasis& basis);
// Throws std::runtime_error naming the file when it is missing, not HDF5, not a reduced-basis
// file, or its datasets' shapes or the sample's elements and weights disagree.
ReducedBasis read_reduced_basis(const std::string& path);
// Throws std::invalid_argument naming the file when the basis was made for another mesh or
// another material than the ones given (its sample's elements are then in the mesh).
void check_fits(const ReducedBasis& basis, const std::string& path, const fem::Mesh& mesh,
                const std::string& material);

}  // namespace tongue::reduced
