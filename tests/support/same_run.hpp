#pragma once
// Bit-for-bit comparison of two run files' results, for end-to-end tests that reach one run by
// two routes (one controller or several, one server or two at once, C++ or Lua).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "support/run_file.hpp"

namespace tongue::testing {

// Everything a run logs per step that does not depend on the machine (the solver's wall time
// does): times, positions, activations, muscle lengths and velocities, Newton figures.
inline const std::vector<std::string>& run_result_datasets() {
  static const std::vector<std::string> names{"/time",
                                              "/positions",
                                              "/activations",
                                              "/muscles/length",
                                              "/muscles/velocity",
                                              "/solver/iterations",
                                              "/solver/residual",
                                              "/solver/cuts"};
  return names;
}

// The state of the model alone: times, positions, activations, muscle lengths and velocities
// (sim_batch logs its settling's Newton figures in frame 0, sim_server none).
inline const std::vector<std::string>& run_state_datasets() {
  static const std::vector<std::string> names{"/time", "/positions", "/activations",
                                              "/muscles/length", "/muscles/velocity"};
  return names;
}

// Expects the run files at a and b to hold the same datasets, bit for bit, with frames frames.
inline void expect_same_results(const std::filesystem::path& a, const std::filesystem::path& b,
                                std::size_t frames,
                                const std::vector<std::string>& datasets = run_result_datasets()) {
  const RunFile first(a), second(b);
  ASSERT_TRUE(first.ok()) << a;
  ASSERT_TRUE(second.ok()) << b;
  ASSERT_EQ(first.doubles("/time").size(), frames) << a;
  for (const std::string& name : datasets) {
    const std::vector<double> values = first.doubles(name);
    EXPECT_FALSE(values.empty()) << a << " has no " << name;
    EXPECT_EQ(second.doubles(name), values) << name << " differs between " << a << " and " << b;
  }
}

}  // namespace tongue::testing
