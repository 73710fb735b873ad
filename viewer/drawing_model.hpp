#pragma once
// What the page needs to draw a tongue: the mesh at rest and its boundary, the muscles and their
// fibres, the landmarks and the obstacles; from a server's model message (live) or a run file
// (replay), checked before it is used, and written as the page's JSON (docs/viewer.md).
#include <array>
#include <string>
#include <vector>

#include "bus/messages.hpp"
#include "run_file/run_file_reader.hpp"

namespace tongue::viewer {

struct DrawingModel {
  struct Muscle {
    std::string name;
    double max_force = 0.0;  // N
  };
  struct Landmark {
    std::string name;
    int node = 0;
  };
  struct Obstacle {
    std::string name;
    std::vector<double> vertices;  // x, y, z per vertex [m]
    std::vector<int> triangles;    // 3 vertex indices per triangle
  };

  std::vector<double> rest_positions;  // x, y, z per node [m]
  std::vector<int> elements;           // 8 node indices per hex8
  std::vector<int> surface;            // 4 node indices per boundary quad, in cyclic order
  std::vector<Muscle> muscles;
  std::vector<int> fibre_muscles;  // the muscle of each fibre
  std::vector<int> fibre_offsets;  // fibre f: fibre_nodes[offsets[f] .. offsets[f + 1])
  std::vector<int> fibre_nodes;
  std::vector<bool> fibre_has_origin;
  std::vector<double> fibre_origins;  // x, y, z per fibre [m]
  std::vector<Landmark> landmarks;
  std::vector<Obstacle> obstacles;
  double dt = 0.0;    // s
  std::string scene;  // the scene file's text

  int num_nodes() const { return static_cast<int>(rest_positions.size() / 3); }
};

// From a model message, which may come from any process on the bus: throws
// std::invalid_argument naming the field when an index is out of range or the counts disagree.
DrawingModel drawing_model(const tongue_lcm::lcmt_tongue_model& message);

// From a run file (docs/run_file.md); throws run_file::RunFileError or std::invalid_argument
// naming the file and dataset when something is missing or inconsistent.
DrawingModel drawing_model(const run_file::RunFileReader& file);

// The page's JSON of the model; version tells the page when a live model changed.
std::string model_json(const DrawingModel& model, int version);

}  // namespace tongue::viewer
