#pragma once
// Activation sequences that drive the full model through the muscles' range, for the snapshots a
// reduced basis is built from. Muscles named NAME_left and NAME_right form one group, driven
// alike (the built-in tongue is symmetric); any other muscle is a group of its own. For each
// group: a step to a level held and released, and a ramp up and down; then pairs of groups
// stepped together, and mixes in which every group is on at a level of its own with probability
// one half. Levels are drawn in [min_level, 1] by a seeded generator whose sequence of numbers is
// the same on every platform (std::mt19937's raw output, not the library's distributions).
#include <cstdint>
#include <string>
#include <vector>

#include "fem/types.hpp"

namespace tongue::reduced {

struct TrainingOptions {
  double duration = 0.3;   // s, each sequence
  double rise = 0.03;      // s, a step's rise and fall (a ramp takes duration / 2 each way)
  double min_level = 0.2;  // [1], the lowest level a group is driven to
  int pairs = 12;          // sequences with two groups stepped together
  // Sequences with every group on at random. Combinations are what a basis trained on single
  // groups and pairs misses most: on reduced_benchmark's held-out runs, 60 mixes instead of 6
  // took the worst run where the material stays elliptic from 0.85 to 0.45 mm RMS.
  int mixes = 60;
  std::uint32_t seed = 1;
};

// One sequence: the levels [1] of every muscle at the given times [s], linear in between and
// held after the last time.
struct TrainingSequence {
  std::string name;  // e.g. "step SG", "ramp GGp", "pair HG+SL", "mix 3"
  std::vector<double> times;
  std::vector<fem::Vector> levels;
  double duration = 0.0;  // s
  fem::Vector at(double t) const;
};

// The muscle groups of the given muscle names, in first-appearance order: each an index list.
struct MuscleGroup {
  std::string name;
  std::vector<int> muscles;
};
std::vector<MuscleGroup> muscle_groups(const std::vector<std::string>& muscles);

// Throws std::invalid_argument for no muscles or options out of range.
std::vector<TrainingSequence> training_sequences(const std::vector<std::string>& muscles,
                                                 const TrainingOptions& options = {});

}  // namespace tongue::reduced
