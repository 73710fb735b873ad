#pragma once
// The active force-length relation of a muscle fibre segment (Hill-type muscle: Gordon, Huxley &
// Julian 1966; Zajac 1989, fig. 3): a sarcomere's active tension falls as it shortens below its
// optimal length, to zero near half of it, where the thick filaments butt against the Z-discs.
// So a muscle cannot pull a piece of itself to zero length. Each fibre segment between two nodes
// (or an origin and a node) stands for such a series of sarcomeres; its length in the mesh at
// rest is taken as its optimal length, and its tension is T f(l / l_rest) with
//   f(lambda) = 0                              for lambda <= lambda_0,
//             = s^2 (6 - 8 s + 3 s^2)          for lambda_0 < lambda < 1,
//                 s = (lambda - lambda_0) / (1 - lambda_0),
//             = 1                              for lambda >= 1.
// lambda_0 = 0.5 by default (Zajac's generic curve). The quartic is 1 - (1 - s)^3 (1 + 3 s):
// continuous with its slope at both ends (C1, so Newton keeps its quadratic rate) and flat to
// second order at the plateau; with lambda_0 = 0.5 it stays within 0.12 of Thelen's (2003)
// Gaussian exp(-(lambda - 1)^2 / 0.45) rescaled to vanish at lambda_0. Our choices: the shape,
// and no descending limb: a stretched segment keeps its full tension, as in the plain fibre
// model, and its stiffness stays positive semidefinite (a descending limb's negative stiffness
// along the fibre would compete with the soft tissue's, about 15 kPa).

namespace tongue::model {

class ActiveForceLength {
 public:
  static constexpr double kDefaultZeroForceLength = 0.5;  // lambda_0 (Zajac 1989)

  // The relation above. Throws std::invalid_argument unless 0 <= zero_force_length < 1.
  explicit ActiveForceLength(double zero_force_length = kDefaultZeroForceLength);
  // f = 1 at every length: the plain fibre model of Payan & Perrier 1997.
  static ActiveForceLength constant_tension();

  bool is_constant() const { return constant_; }
  double zero_force_length() const { return zero_force_length_; }  // lambda_0 [1]

  double value(double lambda) const;  // f(lambda) in [0, 1]
  double slope(double lambda) const;  // df / dlambda >= 0

 private:
  ActiveForceLength(double zero_force_length, bool constant)
      : zero_force_length_(zero_force_length), constant_(constant) {}
  double zero_force_length_;
  bool constant_;
};

}  // namespace tongue::model
