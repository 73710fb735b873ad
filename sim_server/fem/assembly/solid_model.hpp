#pragma once
// The discretized solid: mesh, material, element formulation, density and Dirichlet
// constraints, with everything that depends only on the reference configuration computed once
// (element geometry, sparsity pattern and scatter map). It evaluates internal forces, tangent
// stiffness, mass and body forces; it knows nothing of time stepping or of where loads come from.
#include <cstdint>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "fem/assembly/dof_map.hpp"
#include "fem/assembly/sparse_matrix.hpp"
#include "fem/assembly/worker_pool.hpp"
#include "fem/element/hex8_batch.hpp"
#include "fem/element/hex8_batch_tangent.hpp"
#include "fem/element/hex8_element.hpp"
#include "fem/material/material.hpp"
#include "fem/mesh/boundary_faces.hpp"
#include "fem/mesh/mesh.hpp"

namespace tongue::fem {

struct AssemblyStatus {
  bool ok = true;
  int inverted_element = -1;  // first element found with det F <= 0, when !ok
  double min_J = 0.0;         // smallest det F over all Gauss points
};

class SolidModel {
 public:
  SolidModel(Mesh mesh, std::shared_ptr<const Material> material, Formulation formulation,
             double density, const std::vector<PrescribedDof>& prescribed,
             const std::vector<std::pair<int, int>>& extra_node_pairs = {});
  ~SolidModel();
  SolidModel(const SolidModel&) = delete;
  SolidModel& operator=(const SolidModel&) = delete;

  // Threads for the element loops (residual and tangent), the calling one included; 1 (the
  // default) runs them on the calling thread alone. The elements' results are summed in element
  // order whatever the count, so every count gives bit-for-bit the same force and tangent.
  // Throws std::invalid_argument for threads < 1.
  void set_threads(int threads);
  int threads() const { return pool_ ? pool_->threads() : 1; }

  const Mesh& mesh() const { return mesh_; }
  const Material& material() const { return *material_; }
  Formulation formulation() const { return formulation_; }
  double density() const { return density_; }
  const DofMap& dofs() const { return dofs_; }
  std::shared_ptr<const SparsityPattern> pattern() const { return pattern_; }
  int num_dofs() const { return dofs_.num_dofs(); }

  // Rest positions flattened as 3 n + c.
  const Vector& rest_positions() const { return rest_positions_; }

  // Internal force f_int(u) [N] over all dofs (reactions appear at prescribed dofs) and, when
  // stiffness is given, the tangent d f_int / du over the free dofs. u is the full displacement.
  AssemblyStatus assemble(const Vector& u, Vector& internal_force, SymmetricMatrix* stiffness,
                          double* strain_energy = nullptr) const;
  // Adds the internal force, tangent and energy of the elements scaled by per-element weights
  // (one per element; empty: all 1; elements of weight 0 are skipped) to what the arguments
  // hold: for energies that are multiples of the material's, such as active muscle stiffening.
  // Safe to call from several threads at once (each call has its own workspace or waits for it).
  AssemblyStatus add_weighted(const Vector& u, const std::vector<double>& weights,
                              Vector& internal_force, SymmetricMatrix* stiffness,
                              double* strain_energy = nullptr) const;

  // The internal force of element e alone at u (full displacement) on its 8 nodes, in the order
  // of mesh().elements[e] (ElementVector: dof 3a + i) [N]: what assemble() adds for it (to
  // round-off: uncoupled materials are assembled by the batched kernels); false at an inverted
  // element. For hyper-reduction, which weighs elements one by one.
  bool element_force(int e, const Vector& u, ElementVector& force) const;

  // Mass matrix over the free dofs [kg]: consistent, or lumped by row sums.
  SymmetricMatrix mass_matrix(bool lumped) const;
  // Body force of a uniform acceleration field (e.g. gravity) [N]: rho g int N_a dV.
  Vector body_force(const Vec3& acceleration) const;
  double total_mass() const;
  double reference_volume() const { return reference_volume_; }  // m^3, the elements' sum
  // Current volume int J dV over the solid [m^3] at displacement u, by the divergence theorem
  // over the boundary faces: (1/3) sum of int x . n dA, exact for trilinear elements as the
  // elements' 2x2x2 Gauss sum is (the interior faces cancel), at a fraction of its cost.
  double current_volume(const Vector& u) const;

 private:
  struct Workspace;
  hex8::ElementCoords element_coords(int e, const Vector& positions) const;
  // The element's current nodal positions, rest (precomputed) plus displacement.
  hex8::ElementCoords current_coords(int e, const Vector& u) const;
  // Adds w times one element's force and tangent (when K is given) to the global arrays.
  void scatter(int e, double w, const ElementVector& force, const ElementMatrix* stiffness,
               Vector& internal_force, SymmetricMatrix* K) const;
  // The element loop of an uncoupled material: the elements in batches of kBatchLanes
  // (hex8_batch.hpp, hex8_batch_tangent.hpp), batch b holding elements kBatchLanes b onwards.
  AssemblyStatus add_batches(const Vector& u, const std::vector<double>& weights,
                             Vector& internal_force, SymmetricMatrix* K,
                             double* strain_energy) const;
  // Elements packed into batches: batch b holds elements[kBatchLanes b] onwards (count of
  // them, ascending).
  struct BatchLayout {
    std::vector<int> elements;
    std::vector<ElementBatchGeometry> batches;
  };
  BatchLayout make_layout(std::vector<int> elements) const;
  // The layout to evaluate the elements of nonzero weight with: every element's (empty
  // weights), or, when they fill fewer batches packed than they touch of it, a layout of their
  // own, kept while the same elements are weighted (a hyper-reduction sample: a few hundred
  // elements of a mesh spread over nearly every batch of eight).
  std::shared_ptr<const BatchLayout> layout_for(const std::vector<double>& weights) const;
  BatchCoords batch_coords(const BatchLayout& layout, int b, const Vector& u) const;
  // Adds batch b's weighted forces, energies and (with K) stiffnesses in element order; false,
  // with status telling which element, at an inverted element.
  bool add_batch_result(const BatchLayout& layout, int b, const ElementBatchResponse& r,
                        const ElementBatchTangent* tangent, const std::vector<double>& weights,
                        Vector& internal_force, SymmetricMatrix* K, double* strain_energy,
                        AssemblyStatus& status) const;

  Mesh mesh_;
  std::shared_ptr<const Material> material_;
  Formulation formulation_;
  double density_;
  DofMap dofs_;
  Vector rest_positions_;
  std::vector<ElementGeometry> geometry_;
  double reference_volume_ = 0.0;  // m^3
  std::vector<Quad4> boundary_;  // outward-oriented boundary faces, for current_volume
  std::shared_ptr<const BatchLayout> all_batches_;  // null unless the material is uncoupled
  mutable std::mutex packed_mutex_;
  mutable std::shared_ptr<const BatchLayout> packed_;  // the last packed layout, or null
  std::vector<hex8::ElementCoords> rest_coords_;       // per element, gathered once
  std::shared_ptr<const SparsityPattern> pattern_;
  std::vector<std::array<int, 24 * 24>> element_scatter_;
  // The tangent kernel's scatter (uncoupled materials): element e adds stiffness entry
  // tangent_source_[i] (an index into ElementBatchTangent::stiffness) to K.values()
  // [tangent_value_[i]] for i in [tangent_begin_[e], tangent_begin_[e + 1]): element_scatter_
  // resolved once to the upper node blocks the kernel stores.
  std::vector<int> tangent_begin_, tangent_value_;
  std::vector<std::uint16_t> tangent_source_;
  std::unique_ptr<WorkerPool> pool_;  // null: one thread
  std::unique_ptr<Workspace> workspace_;
};

}  // namespace tongue::fem
