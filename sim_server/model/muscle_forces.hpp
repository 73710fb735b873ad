#pragma once
// Muscle fibre forces (Payan & Perrier 1997; Gerard et al. 2003 sec. III.3.2; docs/physics.md),
// with an active force-length relation f per fibre segment (force_length.hpp). A fibre of
// tension T = activation * F_max * weight is a chain of segments; the segment of length l (rest
// length l_r, unit vector e from its first point to its second) carries the tension
// t = T f(l / l_r) and pulls its two ends toward each other with it. The nodal force is
//   F = -sum over segments t dl/dx  (dl/dx_second = e, dl/dx_first = -e).
// With f = 1 (constant tension) this is -T dL/dx, L the fibre's length (including |x_0 - P| for
// an origin P): the end nodes are pulled along the fibre and an inner node feels
// T (e_prev + e_next), the curvature force that straightens a curved muscle. Either way F is
// minus the gradient of the potential sum T l_r Phi(l / l_r), Phi' = f, so its tangent -dF/dx is
// symmetric: per segment the 6 x 6 block [[B, -B], [-B, B]] (only B on the node of a segment
// from a fixed origin) with
//   B = t (I - e e^T) / l + T f'(l / l_r) / l_r e e^T,
// positive semidefinite since f, f' >= 0.
#include <memory>
#include <string>
#include <vector>

#include "fem/assembly/loads.hpp"
#include "fem/assembly/solid_model.hpp"
#include "model/force_length.hpp"
#include "model/muscle.hpp"

namespace tongue::model {

// Length of a fibre at current positions x (3 n, [m]) [m].
double fibre_length(const Fibre& fibre, const fem::Vector& x);
// The length (the same sum in the same order as fibre_length) and its rate of change
// dL/dt = grad L . v at positions x and nodal velocities v (3 n), in one pass over the segments.
struct FibreKinematics {
  double length = 0.0;  // m
  double rate = 0.0;    // m/s, positive when the fibre lengthens
};
FibreKinematics fibre_kinematics(const Fibre& fibre, const fem::Vector& x, const fem::Vector& v);

class MuscleForces : public fem::ForceContribution {
 public:
  // Throws std::invalid_argument when a muscle fails validate() against the solid's mesh, two
  // muscles share a name, a fibre segment has zero length at rest, or two consecutive fibre
  // nodes are not coupled in the solid's sparsity pattern (build the SolidModel with
  // fibre_node_pairs(muscles) as extra_node_pairs). All activations start at 0. Segment rest
  // lengths are taken from the solid's rest positions.
  MuscleForces(std::shared_ptr<const fem::SolidModel> solid, std::vector<Muscle> muscles,
               ActiveForceLength force_length = ActiveForceLength());

  std::string name() const override { return "muscles"; }
  // Adds load_factor * f_muscles(u) to force and, when stiffness is given, the tangent
  // load_factor * (the block sum above) over the free dofs. Muscles at zero activation cost
  // nothing. A segment at zero tension adds nothing; so does one whose two points coincide (its
  // direction is undefined; with the force-length relation its tension is 0 there anyway).
  void add(const fem::Vector& u, double load_factor, fem::Vector& force,
           fem::SymmetricMatrix* stiffness) const override;

  int num_muscles() const { return static_cast<int>(muscles_.size()); }
  const std::vector<Muscle>& muscles() const { return muscles_; }
  const ActiveForceLength& force_length() const { return force_length_; }
  // Index of the muscle with this name, or -1.
  int index_of(const std::string& name) const;

  // Activation levels in [0, 1]. Throw std::invalid_argument for a NaN, infinite or out-of-range
  // level, an index out of range, or a vector whose size is not num_muscles(); callers are
  // expected to have validated earlier with their own messages.
  void set_activation(int index, double level);
  void set_activations(const fem::Vector& levels);
  const fem::Vector& activations() const { return activations_; }

  // Total tension per muscle at the plateau of the force-length relation, activation * F_max [N].
  fem::Vector muscle_forces() const;
  // Per muscle, the weighted mean of its fibre lengths [m] at displacement u (3 n).
  fem::Vector muscle_lengths(const fem::Vector& u) const;
  // Per muscle, the weighted means of its fibres' lengths (as muscle_lengths) and of their dL/dt
  // [m/s], at displacement u and velocity v.
  void muscle_kinematics(const fem::Vector& u, const fem::Vector& v, fem::Vector& lengths,
                         fem::Vector& velocities) const;

 private:
  fem::Vector positions(const fem::Vector& u) const;

  std::shared_ptr<const fem::SolidModel> solid_;
  std::vector<Muscle> muscles_;
  fem::Vector activations_;
  ActiveForceLength force_length_;
  // Rest length of every segment [m]: fibre f of muscle m has its segments at
  // rest_lengths_[first_segment_[m][f] + i], in fibre order.
  std::vector<double> rest_lengths_;
  std::vector<std::vector<int>> first_segment_;
};

}  // namespace tongue::model
