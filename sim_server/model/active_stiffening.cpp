#include "model/active_stiffening.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tongue::model {

ActiveStiffening::ActiveStiffening(std::shared_ptr<const fem::SolidModel> solid,
                                   std::shared_ptr<const MuscleForces> muscles, double ratio)
    : solid_(std::move(solid)),
      muscles_(std::move(muscles)),
      ratio_(ratio),
      muscles_of_element_(solid_->mesh().num_elements()) {
  if (!(ratio >= 1.0) || !std::isfinite(ratio)) {
    throw std::invalid_argument(
        "active stiffening: the contracted-to-rest stiffness ratio must "
        "be finite and >= 1");
  }
  for (int m = 0; m < muscles_->num_muscles(); ++m)
    for (int e : muscles_->muscles()[m].elements) muscles_of_element_[e].push_back(m);
}

std::vector<double> ActiveStiffening::extra_weights(double load_factor) const {
  const fem::Vector& a = muscles_->activations();
  if (ratio_ == 1.0 || load_factor == 0.0 || a.size() == 0 || a.maxCoeff() == 0.0) return {};
  std::vector<double> w(muscles_of_element_.size(), 0.0);
  for (std::size_t e = 0; e < w.size(); ++e) {
    double level = 0.0;
    for (int m : muscles_of_element_[e]) level = std::max(level, a[m]);
    w[e] = load_factor * (ratio_ - 1.0) * level;
  }
  return w;
}

void ActiveStiffening::add(const fem::Vector& u, double load_factor, fem::Vector& force,
                           fem::SymmetricMatrix* stiffness) const {
  const std::vector<double> w = extra_weights(load_factor);
  if (w.empty()) return;  // no active muscle: no cost
  fem::Vector extra = fem::Vector::Zero(force.size());
  // An inverted element is reported by the solid's own assembly of the same state.
  solid_->add_weighted(u, w, extra, stiffness);
  force -= extra;
}

bool ActiveStiffening::add_element_weights(double load_factor, std::vector<double>& weights) const {
  const std::vector<double> w = extra_weights(load_factor);
  if (w.empty()) return true;
  if (weights.empty()) weights.assign(w.size(), 1.0);
  // Element e's energy is (1 + w_e) times the material's: under a cubature weight (a
  // hyper-reduction sample) its stiffening is integrated by the same rule.
  for (std::size_t e = 0; e < w.size(); ++e) weights[e] *= 1.0 + w[e];
  return true;
}

std::vector<double> ActiveStiffening::element_scales() const {
  std::vector<double> w = extra_weights(1.0);
  if (w.empty()) w.assign(muscles_of_element_.size(), 0.0);
  for (double& s : w) s += 1.0;
  return w;
}

}  // namespace tongue::model
