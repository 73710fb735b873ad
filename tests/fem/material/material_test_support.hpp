#pragma once
// Shared fixtures of the material tests: every material at a given Poisson's ratio, and the
// invariant derivatives W1, W2 of each law written out again here, independently of the classes.
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "fem/material/exponential.hpp"
#include "fem/material/linear_elastic.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/material/mooney_rivlin5.hpp"
#include "fem/material/neo_hookean.hpp"

namespace tongue::fem::testing {

// One material law at one Poisson's ratio: the parameter of the parameterised tests.
struct Case {
  std::string type;
  double nu;
};

inline constexpr double kNeoHookeanMu = 3000.0;  // [Pa]
inline constexpr double kLinearE = 15e3;         // [Pa]

inline std::unique_ptr<Material> make(const Case& c) {
  std::map<std::string, double> p{{"poisson_ratio", c.nu}};
  if (c.type == "neo_hookean") p["shear_modulus"] = kNeoHookeanMu;
  if (c.type == "linear") p["youngs_modulus"] = kLinearE;
  return make_material(c.type, p);
}

// Compressible, the paper's value, and nearly incompressible (K / mu ~ 5000).
inline const std::vector<double>& poisson_ratios() {
  static const std::vector<double> v{0.3, 0.49, 0.4999};
  return v;
}

inline std::vector<Case> cases(bool uncoupled_only) {
  std::vector<Case> out;
  for (const auto& type : material_types()) {
    if (uncoupled_only && type == "linear") continue;
    for (double nu : poisson_ratios()) out.push_back({type, nu});
  }
  return out;
}

inline std::string case_name(const Case& c) {
  std::string nu = std::to_string(c.nu);  // "0.499900"
  while (nu.back() == '0') nu.pop_back();
  for (char& ch : nu)
    if (ch == '.') ch = '_';
  return c.type + "_nu" + nu;
}

struct FirstDerivatives {
  double W1, W2;
};

// dW_iso/dI1b, dW_iso/dI2b from the laws as printed in docs/physics.md, not from the classes'
// isochoric_derivatives, so that the closed-form tests compare two independent codes.
inline FirstDerivatives closed_form_derivatives(const Material& m, double I1b, double I2b) {
  if (const auto* mr = dynamic_cast<const MooneyRivlin5*>(&m)) {
    const auto& c = mr->coefficients();
    return {c.c10 + 2.0 * c.c20 * (I1b - 3.0) + c.c11 * (I2b - 3.0),
            c.c01 + c.c11 * (I1b - 3.0) + 2.0 * c.c02 * (I2b - 3.0)};
  }
  if (const auto* e = dynamic_cast<const Exponential*>(&m))
    return {e->a() * std::exp(e->b() * (I1b - 3.0)), 0.0};
  if (const auto* nh = dynamic_cast<const NeoHookean*>(&m))
    return {0.5 * nh->initial_shear_modulus(), 0.0};
  throw std::logic_error("no closed form for " + m.name());
}

inline Mat3 cauchy(const Mat3& P, const Mat3& F) {
  return P * F.transpose() / F.determinant();
}

// A strongly deformed, non-symmetric F: stretches about 1.5 and 0.7, shear 0.4, det = 1.08775.
inline Mat3 general_F() {
  Mat3 F;
  F << 1.5, 0.4, 0.1,  //
      0.05, 0.7, 0.2,  //
      -0.1, 0.15, 1.1;
  return F;
}

// A compressive one, det = 0.803.
inline Mat3 compressive_F() {
  Mat3 F;
  F << 0.7, -0.3, 0.1,  //
      0.2, 1.2, 0.0,    //
      0.1, 0.25, 0.9;
  return F;
}

inline Mat3 rotation() {
  return Eigen::AngleAxisd(0.9, Vec3(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
}

inline double relative(const auto& a, const auto& b) {
  return (a - b).norm() / b.norm();
}

}  // namespace tongue::fem::testing
