#include "model/force_length.hpp"

#include <stdexcept>
#include <string>

namespace tongue::model {

ActiveForceLength::ActiveForceLength(double zero_force_length)
    : zero_force_length_(zero_force_length), constant_(false) {
  if (!(zero_force_length >= 0.0 && zero_force_length < 1.0)) {
    throw std::invalid_argument("active force-length: the zero-force length " +
                                std::to_string(zero_force_length) +
                                " (relative to rest) must be in [0, 1)");
  }
}

ActiveForceLength ActiveForceLength::constant_tension() {
  return ActiveForceLength(0.0, true);
}

double ActiveForceLength::value(double lambda) const {
  if (constant_ || lambda >= 1.0) return 1.0;
  if (lambda <= zero_force_length_) return 0.0;
  const double s = (lambda - zero_force_length_) / (1.0 - zero_force_length_);
  return s * s * (6.0 - 8.0 * s + 3.0 * s * s);
}

double ActiveForceLength::slope(double lambda) const {
  if (constant_ || lambda >= 1.0 || lambda <= zero_force_length_) return 0.0;
  const double s = (lambda - zero_force_length_) / (1.0 - zero_force_length_);
  return 12.0 * s * (1.0 - s) * (1.0 - s) / (1.0 - zero_force_length_);
}

}  // namespace tongue::model
