#pragma once
// Muscle fibre forces (Payan & Perrier 1997; Gerard et al. 2003 sec. III.3.2; DESIGN.md sec. 2).
// A fibre of tension T = activation * F_max * weight acts on its nodes with
//   f = -T dL/dx,  L(x) = sum of its segment lengths (including |x_0 - P| for an origin P):
// each segment pulls its two ends toward each other with force T, so the end nodes are pulled
// along the fibre and an inner node feels T (e_prev + e_next), the curvature force that
// straightens a curved muscle. Its tangent -df/dx = T d2L/dx2 is, per segment of length l and
// unit vector e, the 6 x 6 block [[B, -B], [-B, B]] with B = (I - e e^T) / l (only B on the node
// for a segment from a fixed origin): symmetric and positive semidefinite.
#include <memory>
#include <string>
#include <vector>

#include "fem/assembly/loads.hpp"
#include "fem/assembly/solid_model.hpp"
#include "tongue/muscle.hpp"

namespace tongue::model {

// Length of a fibre at current positions x (3 n, [m]) [m].
double fibre_length(const Fibre& fibre, const fem::Vector& x);
// Rate of change of that length dL/dt = grad L . v at positions x and nodal velocities v (3 n)
// [m/s]; positive when the fibre lengthens.
double fibre_lengthening_rate(const Fibre& fibre, const fem::Vector& x, const fem::Vector& v);

class MuscleForces : public fem::ForceContribution {
 public:
  // Throws std::invalid_argument when a muscle fails validate() against the solid's mesh, two
  // muscles share a name, a fibre segment has zero length at rest, or two consecutive fibre
  // nodes are not coupled in the solid's sparsity pattern (build the SolidModel with
  // fibre_node_pairs(muscles) as extra_node_pairs). All activations start at 0.
  MuscleForces(std::shared_ptr<const fem::SolidModel> solid, std::vector<Muscle> muscles);

  std::string name() const override { return "muscles"; }
  // Adds load_factor * f_muscles(u) to force and, when stiffness is given, the tangent
  // load_factor * sum T d2L/dx2 over the free dofs. Muscles at zero activation cost nothing. A
  // segment whose two points coincide adds nothing (its direction is undefined).
  void add(const fem::Vector& u, double load_factor, fem::Vector& force,
           fem::SymmetricMatrix* stiffness) const override;

  int num_muscles() const { return static_cast<int>(muscles_.size()); }
  const std::vector<Muscle>& muscles() const { return muscles_; }
  // Index of the muscle with this name, or -1.
  int index_of(const std::string& name) const;

  // Activation levels in [0, 1]. Throw std::invalid_argument for a NaN, infinite or out-of-range
  // level, an index out of range, or a vector whose size is not num_muscles(); callers are
  // expected to have validated earlier with their own messages.
  void set_activation(int index, double level);
  void set_activations(const fem::Vector& levels);
  const fem::Vector& activations() const { return activations_; }

  // Total tension per muscle, activation * F_max [N].
  fem::Vector muscle_forces() const;
  // Per muscle, the weighted mean of its fibre lengths [m] at displacement u (3 n).
  fem::Vector muscle_lengths(const fem::Vector& u) const;
  // Per muscle, the weighted mean of its fibres' dL/dt [m/s] at displacement u and velocity v.
  fem::Vector muscle_velocities(const fem::Vector& u, const fem::Vector& v) const;

 private:
  fem::Vector positions(const fem::Vector& u) const;

  std::shared_ptr<const fem::SolidModel> solid_;
  std::vector<Muscle> muscles_;
  fem::Vector activations_;
};

}  // namespace tongue::model
