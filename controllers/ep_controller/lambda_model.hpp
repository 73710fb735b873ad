#pragma once
// Feldman's lambda model of muscle force (the equilibrium-point hypothesis), as Payan & Perrier
// (1997) used it for the tongue, with the constants of the SPEECHart code (docs/controllers.md).
// For one muscle of length l and lengthening velocity l' seen through the reflex delay d:
//
//   A = [l(t - d) - lambda(t) + mu l'(t - d)]^+          lengths in mm, mu = 0.01 s
//   M = rho (exp(c A) - 1)                               c = 0.112 / mm, rho in N
//   M' = M (f1 + f2 atan(f3 + f4 l'/l0) + f5 l'/l0)      optional velocity factor, l0 the
//                                                        muscle's rest length
//   level = min(M' / F_max, 1)                           the activation sent, in [0, 1]
//
// A is the stretch of the muscle beyond its threshold length lambda (Feldman's "activation");
// a muscle shorter than its threshold (plus the velocity term) exerts no force. The velocity
// factor (Laboissiere et al. 1996, after Hill) is about 1 at rest (f1 + f2 atan f3 = 1.003),
// lower while the muscle shortens and higher while it lengthens; it is clamped at 0, because a
// muscle shortening faster than the factor's zero cannot push.
namespace tongue::ep_controller {

struct LambdaConstants {
  double c_per_mm = 0.112;  // 1/mm, steepness of the exponential force law
  double mu_s = 0.01;       // s, weight of the velocity in the threshold comparison
  // Velocity factor constants (docs/controllers.md); l'/l0 in 1/s.
  double f1 = 0.80;
  double f2 = 0.5;
  double f3 = 0.43;
  double f4 = 0.8 / 1.5;    // s
  double f5 = 0.023 / 0.7;  // s
};

// A = [length - lambda + mu velocity]^+ [mm]; length and lambda in mm, velocity in mm/s.
double stretch_beyond_threshold_mm(double length_mm, double lambda_mm, double velocity_mm_s,
                                   const LambdaConstants& k = {});

// M = rho (exp(c A) - 1) [N]; A in mm, rho in N.
double exponential_force(double stretch_mm, double rho_n, const LambdaConstants& k = {});

// f1 + f2 atan(f3 + f4 r) + f5 r, clamped at 0; r = l'/l0 [1/s].
double velocity_factor(double relative_velocity_per_s, const LambdaConstants& k = {});

// The force as a level of max_force, clamped to [0, 1]; max_force > 0 [N].
double force_level(double force_n, double max_force_n);

// One muscle's parameters for the law above.
struct MuscleLaw {
  double rho_n = 0.0;           // N
  double max_force_n = 0.0;     // N, the force at level 1 (the server's F_max)
  double rest_length_mm = 0.0;  // l0, for the velocity factor
};

struct MuscleCommand {
  double stretch_mm = 0.0;  // A
  double force_n = 0.0;     // M, or M' with the velocity factor (before the cap)
  double level = 0.0;       // in [0, 1]
};

// The whole law for one muscle: lambda [mm], length [mm] and velocity [mm/s] as seen through
// the delay.
MuscleCommand muscle_command(const MuscleLaw& law, double lambda_mm, double length_mm,
                             double velocity_mm_s, bool use_velocity_factor,
                             const LambdaConstants& k = {});

}  // namespace tongue::ep_controller
