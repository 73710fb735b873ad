#pragma once
// Watches whether a solid's material stays strongly elliptic (fem/material/ellipticity.hpp) as
// it deforms, so that a run entering a region where its law is unstable says so instead of
// producing mesh-dependent bands or failing later without a reason. Checked at each element's
// centre; only elements strained beyond a screen get the direction search (~10 us each), and
// first_loss spreads those searches over steps (a budget per call, the elements whose strain grew
// most first), so that a run pays a few tenths of a millisecond per step at most and learns of a
// loss within a few steps of it.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fem/assembly/solid_model.hpp"
#include "fem/mesh/mesh_numbering.hpp"

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
  static constexpr double kDefaultScreen = 1.0;
  // Direction searches first_loss may do per call.
  static constexpr int kSearchesPerCall = 4;
  // first_loss screens the elements last seen strained beyond half the screen every call and
  // the others in turn, a share per call, so that a round of them takes this many calls:
  // screening every element every step took a tenth of a full-model step's time on the tongue
  // (720 elements), twice what the searches took.
  static constexpr int kCallsPerRound = 4;

  explicit EllipticityMonitor(const SolidModel& solid, double screen = kDefaultScreen);

  // The element with the most negative eigenvalue among those that lost ellipticity at
  // displacement u (full vector), or nullopt when every element is elliptic.
  std::optional<EllipticityLoss> check(const Vector& u) const;
  // For a run that warns once: screens the strained elements and a share of the others (see
  // kCallsPerRound), searches at most kSearchesPerCall of those screened in, those whose strain
  // grew most since their last search first, and reports a loss only the first time one is
  // found; after that it costs nothing.
  std::optional<EllipticityLoss> first_loss(const Vector& u);
  // Ready to report again, as new: a new run (a restart) finds its loss at the step the first
  // run did.
  void reset();

 private:
  std::pair<double, Mat3> centre_state(int e, const Vector& x) const;
  std::optional<EllipticityLoss> search(int e, const Vector& x) const;

  const SolidModel& solid_;
  double screen_;
  bool reported_ = false;
  long call_ = 0;  // first_loss calls since the last reset: whose share is screened
  std::vector<double> last_strain_;  // each element's strain when last screened (inf: not yet)
  std::vector<double> searched_at_;  // its strain at its last search (the screen: none yet)
  std::vector<int> candidates_;      // first_loss's elements screened in
  std::vector<Eigen::Matrix<double, 8, 3>> centre_gradients_;  // dN_a/dX at each centre
};

// One line for a user: where ellipticity was lost (the element as numbering names it: by its
// file id and index for an imported mesh), by how much, and what it means for the run.
std::string describe(const EllipticityLoss& loss, const Material& material,
                     const MeshNumbering& numbering = {});

}  // namespace tongue::fem
