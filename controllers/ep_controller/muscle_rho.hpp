#pragma once
// rho of the lambda model (lambda_model.hpp) for each muscle: the force scale of its exponential
// law. The published values are per muscle of the 2D model, i.e. per group of this tongue (both
// halves together); a group's rho is split over its muscles in proportion to their F_max, so that
// both halves driven alike give the group's force, and each half gets the same level M / F_max as
// the whole muscle would.
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tongue::ep_controller {

// rho of a group of the built-in tongue [N], nullopt for other names. Payan & Perrier 1997 /
// SPEECHart (fibre cross-section x 0.22 N/mm^2; docs/controllers.md): GG 5.2 (for each of
// GGp, GGm and GGa), HG 21.7, SG 4.4, V 2.4, SL 14.3, IL 19.4. T and MH have no published
// value; ours (T 15.6, MH 12.1) are their F_max times the median rho / F_max of the eight muscles
// that have one (0.311; the ratios range 0.12 (V) to 2.16 (IL)), so neither is an outlier in how
// soon it reaches its cap.
std::optional<double> default_group_rho(const std::string& group);

// rho [N] of each muscle (muscle_names, max_forces_n in the model's order). overrides maps muscle
// or group names (the plan's rho:) to a group rho in N, which wins over the default; each
// override is split over the muscles it names like a default group. Throws std::invalid_argument
// naming the muscle when one has neither a default nor an override.
std::vector<double> muscle_rhos(const std::vector<std::string>& muscle_names,
                                const std::vector<double>& max_forces_n,
                                const std::vector<std::pair<std::string, double>>& overrides);

}  // namespace tongue::ep_controller
