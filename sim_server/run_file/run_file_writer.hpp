#pragma once
// An HDF5 run file that grows by one frame per logged step, readable while the run goes on and
// complete up to the last flush if the run dies. Layout and names: run_file_layout.hpp.
#include <Eigen/Core>

#include <array>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "run_file/run_file_error.hpp"

namespace tongue::run_file {

// The mesh as the run file describes it (a plain copy, so that this library needs no FEM).
struct MeshDescription {
  std::vector<std::array<double, 3>> nodes;  // rest positions [m]
  std::vector<std::array<int, 8>> elements;  // 0-based node indices, ANSYS SOLID185 node order
  std::map<std::string, std::vector<int>> node_sets;     // 0-based node indices
  std::map<std::string, std::vector<int>> element_sets;  // 0-based element indices
  // An imported mesh's file ids by index (node_ids[i]: the id of node i); empty: none.
  std::vector<long> node_ids;
  std::vector<long> element_ids;
};

// A muscle as the run file describes it.
struct FibreDescription {
  std::vector<int> nodes;  // 0-based node indices, in order along the fibre
  std::array<double, 3> origin{std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::quiet_NaN()};  // m; NaN: none
  double weight = 1.0;  // share of the muscle's tension
};

struct MuscleDescription {
  std::string name;
  double max_force = 0.0;  // N
  std::vector<FibreDescription> fibres;
};

// Per-muscle values of one frame, each of size M (in the order of the descriptions).
struct MuscleFrame {
  Eigen::VectorXd activations;  // [1]
  Eigen::VectorXd lengths;      // m
  Eigen::VectorXd velocities;   // m/s
};

// A rigid obstacle as the run file describes it.
struct ObstacleDescription {
  std::string name;
  std::vector<std::array<double, 3>> vertices;  // m
  std::vector<std::array<int, 3>> triangles;    // 0-based vertex indices, normals toward the solid
};

// The contact of one frame with O obstacles: the force the obstacles exert on each node
// (3 N entries, n-major; zero off contact) and the force the solid exerts on each obstacle
// (3 O entries) [N], and the deepest penetration [m].
struct ContactFrame {
  Eigen::VectorXd node_forces;
  Eigen::VectorXd obstacle_forces;
  double max_penetration = 0.0;
};

// Solver figures of one frame: totals over the steps since the previous frame.
struct SolverFigures {
  int iterations = 0;
  double residual = 0.0;   // N
  double wall_time = 0.0;  // s
  int cuts = 0;
  // A reduced model's error indicator at its last check [m]; 0 for the full model.
  double reduced_correction = 0.0;
};

struct RunFileOptions {
  std::string time_unit = "s";  // "1" when the time axis is a static load factor
  int deflate_level = 4;        // 0: no compression
  double flush_interval = 1.0;  // s of wall time between flushes; 0: after every append
};

class RunFileWriter {
 public:
  // Creates (or truncates) the file, creating missing parent directories, and writes the
  // mesh with its named sets, the muscles' descriptions and the root attributes.
  // Throws RunFileError (naming the file and the operation) when HDF5 fails.
  RunFileWriter(const std::string& path, const MeshDescription& mesh, const std::string& scene_text,
                const RunFileOptions& options = RunFileOptions{},
                const std::vector<MuscleDescription>& muscles = {},
                const std::vector<ObstacleDescription>& obstacles = {});
  ~RunFileWriter();  // flushes and closes; never throws
  RunFileWriter(const RunFileWriter&) = delete;
  RunFileWriter& operator=(const RunFileWriter&) = delete;

  // positions: current node positions flattened as 3 n + c [m], 3 N entries. muscles: required
  // (each vector of size M) when the log has muscles, ignored otherwise; contact likewise with
  // obstacles (3 N and 3 O entries). Throws std::invalid_argument for wrong sizes, RunFileError
  // when HDF5 fails.
  void append(double time, const Eigen::VectorXd& positions, const SolverFigures& figures,
              const MuscleFrame& muscles = {}, const ContactFrame& contact = {});
  // A string attribute on the root group, replaced if it exists.
  void set_attribute(const std::string& name, const std::string& value);
  void flush();

  // The check append makes before writing anything, for a caller that holds the sizes itself
  // (RunFileQueue checks a frame on its caller's thread, without the writer).
  static void check_frame(const std::string& path, int num_nodes, int num_muscles,
                          int num_obstacles, const Eigen::VectorXd& positions,
                          const MuscleFrame& muscles, const ContactFrame& contact);

  int frames() const { return frames_; }
  int num_nodes() const { return num_nodes_; }
  int num_muscles() const { return num_muscles_; }
  int num_obstacles() const { return num_obstacles_; }
  const std::string& path() const { return path_; }

 private:
  struct Handles;
  std::string path_;
  int num_nodes_ = 0;
  int num_muscles_ = 0;
  int num_obstacles_ = 0;
  int frames_ = 0;
  double flush_interval_ = 1.0;
  double last_flush_ = 0.0;  // steady-clock seconds
  std::unique_ptr<Handles> h_;
};

}  // namespace tongue::run_file
