#include "fem/assembly/ellipticity_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "fem/element/hex8_shape.hpp"
#include "fem/material/ellipticity.hpp"

namespace tongue::fem {
namespace {

// The 8 x 3 coordinates of element e's nodes taken from positions (3 per node).
hex8::ElementCoords coords(const Mesh& mesh, int e, const Vector& positions) {
  hex8::ElementCoords X;
  for (int a = 0; a < 8; ++a) X.row(a) = positions.segment<3>(3 * mesh.elements[e][a]).transpose();
  return X;
}

}  // namespace

EllipticityMonitor::EllipticityMonitor(const SolidModel& solid, double screen)
    : solid_(solid), screen_(screen) {
  const hex8::ShapeGradients dN_dxi = hex8::reference_gradients(Vec3::Zero());
  const Vector& rest = solid.rest_positions();
  centre_gradients_.reserve(solid.mesh().num_elements());
  for (int e = 0; e < solid.mesh().num_elements(); ++e) {
    const hex8::ElementCoords X = coords(solid.mesh(), e, rest);
    centre_gradients_.push_back(dN_dxi * hex8::jacobian(X, Vec3::Zero()).inverse());
  }
  reset();
}

void EllipticityMonitor::reset() {
  reported_ = false;
  call_ = 0;
  last_strain_.assign(centre_gradients_.size(), std::numeric_limits<double>::infinity());
  searched_at_.assign(centre_gradients_.size(), screen_);
}

// The isochoric strain ||C_bar - I|| at element e's centre and its F; strain < 0 for an
// inverted centre (reported by the solver itself, not here).
std::pair<double, Mat3> EllipticityMonitor::centre_state(int e, const Vector& x) const {
  const Mat3 F = coords(solid_.mesh(), e, x).transpose() * centre_gradients_[e];
  const double J = F.determinant();
  if (!(J > 0.0)) return {-1.0, F};
  const double cube_root = std::cbrt(J);  // J^(-2/3) without pow, which took a third of this
  const Mat3 C_bar = (F.transpose() * F) / (cube_root * cube_root);
  return {(C_bar - Mat3::Identity()).norm(), F};
}

std::optional<EllipticityLoss> EllipticityMonitor::search(int e, const Vector& x) const {
  const auto [strain, F] = centre_state(e, x);
  if (strain <= screen_) return std::nullopt;
  const EllipticityCheck c = check_ellipticity(solid_.material(), F);
  if (c.elliptic()) return std::nullopt;
  return EllipticityLoss{e, c.min_eigenvalue, strain};
}

std::optional<EllipticityLoss> EllipticityMonitor::check(const Vector& u) const {
  const Vector x = solid_.rest_positions() + u;
  std::optional<EllipticityLoss> worst;
  for (int e = 0; e < static_cast<int>(centre_gradients_.size()); ++e) {
    const auto loss = search(e, x);
    if (loss && (!worst || loss->min_eigenvalue < worst->min_eigenvalue)) worst = loss;
  }
  return worst;
}

std::optional<EllipticityLoss> EllipticityMonitor::first_loss(const Vector& u) {
  if (reported_) return std::nullopt;
  const Vector x = solid_.rest_positions() + u;
  const int n = static_cast<int>(centre_gradients_.size());
  // The screen: an element last seen within half the screen is screened again in its share of
  // calls only (its strain would have to double in a few steps to matter), the others (and, at
  // the first call, all) every call.
  const int share = static_cast<int>(call_++ % kCallsPerRound);
  candidates_.clear();
  for (int e = 0; e < n; ++e) {
    if (last_strain_[e] <= 0.5 * screen_ && e % kCallsPerRound != share) continue;
    last_strain_[e] = centre_state(e, x).first;
    if (last_strain_[e] > screen_) candidates_.push_back(e);
  }
  // The searches: of the elements screened in, those whose strain grew most since they were
  // last searched (or since they crossed the screen), the lower element first on a tie.
  const auto growth = [&](int e) { return last_strain_[e] - searched_at_[e]; };
  const auto first = [&](int a, int b) {
    return growth(a) > growth(b) || (growth(a) == growth(b) && a < b);
  };
  const auto end =
      candidates_.begin() + std::min<std::ptrdiff_t>(kSearchesPerCall, std::ssize(candidates_));
  std::partial_sort(candidates_.begin(), end, candidates_.end(), first);
  for (auto it = candidates_.begin(); it != end; ++it) {
    searched_at_[*it] = last_strain_[*it];
    if (auto loss = search(*it, x)) {
      reported_ = true;
      return loss;
    }
  }
  return std::nullopt;
}

std::string describe(const EllipticityLoss& loss, const Material& material,
                     const MeshNumbering& numbering) {
  char text[512];
  std::snprintf(text, sizeof text,
                "the material law %s is no longer strongly elliptic in %s (smallest "
                "acoustic-tensor eigenvalue %.3g Pa = %.2f x its initial shear modulus, isochoric "
                "strain |C_bar - I| = %.2f): the law is unstable there, strain can localize at "
                "the scale of the mesh, and results from here on are not to be trusted",
                material.name().c_str(), numbering.element(loss.element).c_str(),
                loss.min_eigenvalue, loss.min_eigenvalue / material.initial_shear_modulus(),
                loss.strain);
  std::string s = text;
  if (material.name() == "mooney_rivlin5") {
    s += " (mooney_rivlin5 with Gerard et al.'s c01, c11 < 0 loses ellipticity beyond a uniaxial "
         "stretch of about 1.54 or a simple shear of about 0.93; exponential does not)";
  }
  return s;
}

}  // namespace tongue::fem
