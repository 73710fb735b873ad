#pragma once
// One state of the tongue as the page draws it, live (a server's state message) or replayed (a
// run file's frame), and its JSON (docs/viewer.md).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bus/messages.hpp"

namespace tongue::viewer {

struct Frame {
  int run = 0;                        // replay: which run file
  std::optional<std::int64_t> index;  // replay: the frame's index in it
  std::int64_t step = 0;
  double time = 0.0;                      // s
  std::optional<std::vector<int>> nodes;  // the nodes of positions; none: every node, in order
  std::vector<double> positions;          // x, y, z per node [m]
  std::vector<double> activations;        // per muscle, in [0, 1]
  std::vector<double> muscle_lengths;     // m
  int iterations = 0;
  double residual = 0.0;   // N
  double wall_time = 0.0;  // s
  int cuts = 0;
  bool converged = true;
  std::string status = "ok";
  std::optional<double> real_time_factor;
  std::vector<int> contact_nodes;
  std::vector<int> contact_obstacles;   // -1: not known (a run file does not say)
  std::vector<double> contact_forces;   // x, y, z per contact [N]
  std::vector<double> obstacle_forces;  // x, y, z per obstacle [N]
  double max_penetration = 0.0;         // m
  // A reduced model's error indicator at its last check (0: the full model) [m].
  double reduced_correction = 0.0;
};

// A state message as a frame; the message has been checked against its model.
Frame frame_from_state(const tongue_lcm::lcmt_tongue_state& state);

// The page's JSON; dropped counts the states not sent to this page since its last frame.
// Positions are rounded to 10 nm, far below anything drawn, so that the text stays short.
std::string frame_json(const Frame& frame, std::int64_t dropped = 0);

// The rounding frame_json applies to a position [m].
double rounded_position(double x);

}  // namespace tongue::viewer
