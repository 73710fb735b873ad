#pragma once
// External forces. A load may depend on the configuration (a muscle fibre pulls along its
// current direction); its derivative then enters the tangent.
#include <string>
#include <vector>

#include "fem/assembly/sparse_matrix.hpp"
#include "fem/types.hpp"

namespace tongue::fem {

// A spring k v v^T on the three dofs of one node: stiffness k [N/m] along the unit direction v.
// With gap > 0 it is not engaged yet: it engages once the node has moved `gap` [m] against v
// (a node that far in front of an obstacle).
struct NodeSpring {
  int node = 0;
  Vec3 direction = Vec3::Zero();
  double stiffness = 0.0;
  double gap = 0.0;
};

// What a load's augmented Lagrangian says of a step's converged state (ForceContribution::augment).
enum class Augmentation {
  held,         // its constraint holds within its tolerance (or it has none)
  solve_again,  // its multipliers were updated: the step is to be solved again
  unmet,        // violated beyond its tolerance, and no updates left in this step
};

class ForceContribution {
 public:
  virtual ~ForceContribution() = default;
  virtual std::string name() const = 0;
  // Adds load_factor * f_ext(u) to force (all dofs, [N]). When stiffness is given, adds the
  // tangent of the residual's load part, -load_factor * d f_ext / du, over the free dofs.
  virtual void add(const Vector& u, double load_factor, Vector& force,
                   SymmetricMatrix* stiffness) const = 0;
  // A load that is a multiple of the solid's own energy on some elements (active muscle
  // stiffening) may instead be folded into the solid's assembly as element weights, so that
  // each element is evaluated once: an element whose energy the load makes (1 + s_e) times the
  // material's has its weight multiplied by 1 + s_e (an empty vector, all 1, is filled with 1
  // first, and left empty while the load adds nothing) and it returns true, and the caller does
  // not call add() for the residual. Weights that are a cubature over a sample of the elements
  // so integrate the load over the same sample. The default: false, not such a load.
  virtual bool add_element_weights(double /*load_factor*/, std::vector<double>& /*weights*/) const {
    return false;
  }
  // The node springs among this load's tangent at u that come and go as u changes (contact
  // engaging and releasing), added to `springs`, and those about to engage (gap > 0). A solver
  // that reuses a factorization corrects it for the springs that changed since it was formed
  // instead of forming it again, and engages those a correction would carry past their gap.
  // Default: none.
  virtual void add_springs(const Vector& /*u*/, std::vector<NodeSpring>& /*springs*/) const {}
  // A load that enforces a constraint by an augmented Lagrangian (contact) keeps multipliers, the
  // part of its force that no longer needs the constraint violated. begin_step() sets them to
  // zero: a time step starts from the plain penalty. augment(u), at a step's converged u, says
  // whether the constraint holds there within the load's tolerance; when not, it updates the
  // multipliers there (Uzawa's update) and the step is solved again from u with them, as long
  // as the load allows updates. Default: no multipliers.
  virtual void begin_step() {}
  virtual Augmentation augment(const Vector& /*u*/) { return Augmentation::held; }
};

// A dead load: a fixed vector of nodal forces (gravity, point loads, tractions on the reference
// surface).
class ConstantForce : public ForceContribution {
 public:
  ConstantForce(std::string name, Vector force)
      : name_(std::move(name)), force_(std::move(force)) {}
  std::string name() const override { return name_; }
  void add(const Vector&, double load_factor, Vector& force, SymmetricMatrix*) const override {
    force += load_factor * force_;
  }
  const Vector& force() const { return force_; }

 private:
  std::string name_;
  Vector force_;
};

}  // namespace tongue::fem
