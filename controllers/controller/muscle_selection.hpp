#pragma once
// Muscle names in controller inputs: a muscle of the model ("SG_left") or a group ("SG": every
// muscle named SG or starting with "SG_"), the same rule as a scene's activations
// (sim_server/scene/activation_schedule.cpp), so that paired halves and unpaired muscles are
// addressed alike.
#include <string>
#include <vector>

namespace tongue::controller {

// Indices into muscle_names of the muscles name selects, in the model's order; empty when none.
std::vector<int> select_muscles(const std::string& name,
                                const std::vector<std::string>& muscle_names);

// The group a muscle belongs to: its name without a "_left" or "_right" suffix ("GGp_left" ->
// "GGp", "SL" -> "SL").
std::string muscle_group(const std::string& muscle_name);

// "a, b, c", for error messages that list the known muscles.
std::string joined_names(const std::vector<std::string>& names);

}  // namespace tongue::controller
