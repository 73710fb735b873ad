#pragma once
// The built-in tongue's muscle names and F_max as the server's model message gives them (from the
// tongue model's own table, so the controller tests follow it if it changes).
#include <string>
#include <vector>

#include "model/tongue_muscles.hpp"

namespace tongue::testing {

struct MuscleList {
  std::vector<std::string> names;
  std::vector<double> max_forces_n;
};

inline MuscleList builtin_tongue_muscles() {
  MuscleList out;
  for (const model::MuscleGroup& g : model::muscle_groups()) {
    if (g.paired) {
      for (const char* side : {"_left", "_right"}) {
        out.names.push_back(g.name + side);
        out.max_forces_n.push_back(0.5 * g.max_force);
      }
    } else {
      out.names.push_back(g.name);
      out.max_forces_n.push_back(g.max_force);
    }
  }
  return out;
}

}  // namespace tongue::testing
