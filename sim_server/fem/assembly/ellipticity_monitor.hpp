#pragma once
// Watches whether a solid's material stays strongly elliptic (fem/material/ellipticity.hpp) as
// it deforms, so that a run entering a region where its law is unstable says so instead of
// producing mesh-dependent bands or failing later without a reason. Checked at each element's
// centre; only elements strained beyond a screen get the full direction search, which keeps
// the cost per step to a few tens of microseconds on the tongue.
#include <optional>
#include <string>
#include <vector>

#include "fem/assembly/solid_model.hpp"

namespace tongue::fem {

struct EllipticityLoss {
  int element = -1;
  double min_eigenvalue = 0.0;  // smallest acoustic-tensor eigenvalue [Pa], <= 0
  double strain = 0.0;          // ||C_bar - I|| at the element's centre
};

class EllipticityMonitor {
 public:
  // Elements whose isochoric strain ||C_bar - I|| (Frobenius) stays within screen are not
  // searched; the tests show every law of this project elliptic there.
  static constexpr double kDefaultScreen = 0.5;

  explicit EllipticityMonitor(const SolidModel& solid, double screen = kDefaultScreen);

  // The element with the most negative eigenvalue among those that lost ellipticity at
  // displacement u (full vector), or nullopt when every element is elliptic.
  std::optional<EllipticityLoss> check(const Vector& u) const;
  // As check, but reports a loss only the first time one is found (a run warns once); after
  // that it costs nothing.
  std::optional<EllipticityLoss> first_loss(const Vector& u);

 private:
  const SolidModel& solid_;
  double screen_;
  bool reported_ = false;
  std::vector<Eigen::Matrix<double, 8, 3>> centre_gradients_;  // dN_a/dX at each centre
};

// One line for a user: where ellipticity was lost, by how much, and what it means for the run.
std::string describe(const EllipticityLoss& loss, const Material& material);

}  // namespace tongue::fem
