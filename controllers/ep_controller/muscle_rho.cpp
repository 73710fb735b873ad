#include "ep_controller/muscle_rho.hpp"

#include <stdexcept>

#include "controller/muscle_selection.hpp"

namespace tongue::ep_controller {

std::optional<double> default_group_rho(const std::string& group) {
  static const std::map<std::string, double> table = {
      {"GGp", 5.2}, {"GGm", 5.2}, {"GGa", 5.2}, {"HG", 21.7}, {"SG", 4.4},
      {"V", 2.4},   {"SL", 14.3}, {"IL", 19.4}, {"T", 15.6},  {"MH", 12.1}};
  const auto it = table.find(group);
  if (it == table.end()) return std::nullopt;
  return it->second;
}

std::vector<double> muscle_rhos(const std::vector<std::string>& muscle_names,
                                const std::vector<double>& max_forces_n,
                                const std::vector<std::pair<std::string, double>>& overrides) {
  const std::size_t n = muscle_names.size();
  std::vector<std::optional<double>> rho(n);
  // A group rho over the muscles it names, in proportion to their F_max.
  const auto share = [&](const std::vector<int>& members, double group_rho) {
    double total = 0.0;
    for (int m : members) total += max_forces_n[m];
    for (int m : members) rho[m] = group_rho * max_forces_n[m] / total;
  };
  for (std::size_t m = 0; m < n; ++m) {
    if (rho[m]) continue;
    const std::string group = controller::muscle_group(muscle_names[m]);
    if (const auto r = default_group_rho(group))
      share(controller::select_muscles(group, muscle_names), *r);
  }
  for (const auto& [name, group_rho] : overrides)
    share(controller::select_muscles(name, muscle_names), group_rho);
  std::vector<double> out(n);
  for (std::size_t m = 0; m < n; ++m) {
    if (!rho[m])
      throw std::invalid_argument("muscle " + muscle_names[m] +
                                  " has no default rho (only the built-in tongue's groups have "
                                  "one): give it in the plan's rho:");
    out[m] = *rho[m];
  }
  return out;
}

}  // namespace tongue::ep_controller
