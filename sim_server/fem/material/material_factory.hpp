#pragma once
// Materials by name, with their parameters declared once (name, unit, default, range) so that
// scene validation, documentation and error messages all read the same table (in the spirit of
// FEBio's parameter lists).
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fem/material/material.hpp"

namespace tongue::fem {

struct ParameterSpec {
  std::string name, unit;
  double default_value;  // NaN: no numeric default (required, or derived: see help)
  double min, max;       // allowed values lie strictly inside (min, max)
  std::string help;

  bool has_default() const { return !std::isnan(default_value); }
  bool in_range(double v) const { return min < v && v < max; }  // false for NaN
};

// {"mooney_rivlin5", "exponential", "neo_hookean", "linear"}.
std::vector<std::string> material_types();

// The parameter table of one type; throws std::invalid_argument for an unknown type.
const std::vector<ParameterSpec>& material_parameters(const std::string& type);

// Builds a material from named parameters; missing ones take their defaults. Uncoupled materials
// take K either as "bulk_modulus" or from "poisson_ratio" (default 0.49) and the material's mu0,
// never both. Throws std::invalid_argument naming the offending key for an unknown type, an
// unknown parameter, a value out of range, a missing required parameter or a conflicting pair.
std::unique_ptr<Material> make_material(const std::string& type,
                                        const std::map<std::string, double>& params);

}  // namespace tongue::fem
