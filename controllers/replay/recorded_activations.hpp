#pragma once
// The parts of an HDF5 run file (names: run_file/run_file_layout.hpp) that a replay needs: the
// time of each frame, the muscles' names and F_max, and the activation levels of each frame.
#include <cstddef>
#include <string>
#include <vector>

namespace tongue::replay {

struct RecordedActivations {
  std::string path;
  std::vector<double> time_s;             // [T]
  std::vector<std::string> muscle_names;  // [M]
  std::vector<double> max_forces_n;       // [M]; empty when the file has none
  std::vector<double> activations;        // [T x M], row-major: frame t, muscle m at t * M + m
  int resets = 0;                         // the "resets" attribute (server runs), 0 when absent

  std::size_t frames() const { return time_s.size(); }
  std::size_t muscles() const { return muscle_names.size(); }
  double level(std::size_t frame, std::size_t muscle) const {
    return activations[frame * muscle_names.size() + muscle];
  }
};

// Reads the run file. Throws InputError naming the file and the dataset when it cannot be opened,
// a dataset is missing or has the wrong shape (/activations must be [T x M] with T the length of
// /time and M that of /muscles/names), or a level is not a finite number in [0, 1].
RecordedActivations read_recorded_activations(const std::string& path);

}  // namespace tongue::replay
