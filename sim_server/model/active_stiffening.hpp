#pragma once
// Contracting muscle is stiffer than resting tissue: Gerard et al. 2003 (sec. III.2) chose the
// tongue's material for a Young's modulus of about 15 kPa at rest and 110 kPa when the muscles
// are fully contracted. Here the elements of an active muscle carry the passive strain energy
// scaled by 1 + (ratio - 1) a, with a the largest activation among the muscles the element
// belongs to and ratio = E_contracted / E_rest (default 110 / 15): a linear interpolation in the
// activation, our choice. Without it, tension concentrated at the fibre ends of strongly
// activated muscles collapses the soft resting tissue. The extra energy (ratio - 1) a W acts as
// an additional internal force with its exact tangent.
#include <memory>
#include <vector>

#include "model/muscle_forces.hpp"

namespace tongue::model {

inline constexpr double kContractedToRestStiffness = 110.0 / 15.0;

class ActiveStiffening : public fem::ForceContribution {
 public:
  // Throws std::invalid_argument when ratio < 1 or is not finite.
  ActiveStiffening(std::shared_ptr<const fem::SolidModel> solid,
                   std::shared_ptr<const MuscleForces> muscles,
                   double ratio = kContractedToRestStiffness);

  std::string name() const override { return "active muscle stiffening"; }
  // Adds -load_factor * (extra internal force) and its tangent; nothing while no muscle is active.
  void add(const fem::Vector& u, double load_factor, fem::Vector& force,
           fem::SymmetricMatrix* stiffness) const override;

  // Folds the extra energy into the solid's assembly: adds load_factor (ratio - 1) a_e to each
  // element's weight; nothing while no muscle is active.
  bool add_element_weights(double load_factor, std::vector<double>& weights) const override;

  double ratio() const { return ratio_; }
  // The current energy scale of each element, 1 + (ratio - 1) a_e.
  std::vector<double> element_scales() const;

 private:
  std::vector<double> extra_weights(double load_factor) const;  // (ratio - 1) a_e, all 0 if idle

  std::shared_ptr<const fem::SolidModel> solid_;
  std::shared_ptr<const MuscleForces> muscles_;
  double ratio_;
  std::vector<std::vector<int>> muscles_of_element_;
};

}  // namespace tongue::model
