#pragma once
// The figures a run summary quotes, read back from what the run left on disk: the HDF5 run file
// (read with run_file/run_file_reader.hpp) and the LCM log of the bus.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tongue::runner {

struct LandmarkMotion {
  std::string name;                  // a landmark node set: tip, velar_dorsum, ...
  std::array<double, 3> final_mm{};  // displacement at the last frame from the first [mm]
  double peak_mm = 0.0;              // largest distance from the first frame [mm]
  double peak_time = 0.0;            // s
};

struct RunFigures {
  int steps = 0;              // frames - 1
  double simulated = 0.0;     // s
  double physics_wall = 0.0;  // s, summed step wall times
  long newton_iterations = 0;
  long step_cuts = 0;
  std::string status;                     // the run file's status attribute
  std::vector<LandmarkMotion> landmarks;  // the landmark sets the mesh has
};

// Throws run_file::RunFileError naming the file and dataset when something is missing.
RunFigures read_run_figures(const std::filesystem::path& run_file);

struct BusFigures {
  int states = 0;                // messages on the state channel
  double state_span = 0.0;       // s between the first and the last of them (logger's clock)
  int activations = 0;           // distinct messages on the activation channel
  int repeated_activations = 0;  // copies of one already counted: a controller's answers to a
                                 // state published again (protocol.md, lost messages)
};

// Counts the messages of the two channels in an LCM log; nullopt when it cannot be read.
std::optional<BusFigures> read_bus_figures(const std::filesystem::path& lcm_log,
                                           const std::string& state_channel,
                                           const std::string& activation_channel);

}  // namespace tongue::runner
