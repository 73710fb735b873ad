#pragma once
// An HDF5 run file that grows by one frame per logged step, readable while the run goes on and
// complete up to the last flush if the run dies. Layout (format_version 1):
//
//   /time               [T]          double  s (or "1" for the load factor of a static run)
//   /positions          [T x N x 3]  double  m, current node positions
//   /rest_positions     [N x 3]      double  m
//   /elements           [E x 8]      int32   0-based node indices, ANSYS SOLID185 node order
//   /solver/iterations  [T]          int32   Newton iterations since the previous frame
//   /solver/residual    [T]          double  N, final residual norm of the frame's step
//   /solver/wall_time   [T]          double  s, wall-clock time since the previous frame
//   /solver/cuts        [T]          int32   step halvings since the previous frame
// (When every step is logged, "since the previous frame" is simply "of the step".)
//   /mesh/node_sets/<name>     [n]   int32   0-based node indices, one dataset per node set
//   /mesh/element_sets/<name>  [e]   int32   0-based element indices, one per element set
// With M > 0 muscles (omitted without muscles):
//   /muscles/names      [M]          string  UTF-8, the muscles' order in the datasets below
//   /muscles/max_force  [M]          double  N, tension at full activation
//   /activations        [T x M]      double  1, activation level of each muscle
//   /muscles/length     [T x M]      double  m, weighted mean fibre length
//   /muscles/velocity   [T x M]      double  m/s, its rate of change (> 0: lengthening)
//   /muscles/fibres/muscle        [F]      int32   index of the fibre's muscle
//   /muscles/fibres/weight        [F]      double  1, share of the muscle's tension
//   /muscles/fibres/origin        [F x 3]  double  m, fixed bony attachment, NaN when none
//   /muscles/fibres/node_offsets  [F + 1]  int32   fibre f is nodes[node_offsets[f] ..
//   /muscles/fibres/nodes         [sum]    int32   node_offsets[f + 1]), 0-based, in order
//   root attributes: format_version (int), length_unit = "m", time_unit, scene_text (the YAML),
//                    plus any set with set_attribute (e.g. "status").
// Every dataset has a "units" and a "description" attribute. The time-indexed datasets are
// chunked along time and deflate-compressed, extended on each append.
#include <array>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "fem/mesh/mesh.hpp"
#include "fem/types.hpp"

namespace tongue::run_file {

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
  fem::Vector activations;  // [1]
  fem::Vector lengths;      // m
  fem::Vector velocities;   // m/s
};

// Solver figures of one frame: totals over the steps since the previous frame.
struct SolverFigures {
  int iterations = 0;
  double residual = 0.0;   // N
  double wall_time = 0.0;  // s
  int cuts = 0;
};

struct RunFileOptions {
  std::string time_unit = "s";  // "1" when the time axis is a static load factor
  int deflate_level = 4;        // 0: no compression
  double flush_interval = 1.0;  // s of wall time between flushes; 0: after every append
};

// An HDF5 call failed; what() names the file and the operation.
class RunFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class RunFileWriter {
 public:
  // Creates (or truncates) the file, creating missing parent directories, and writes the
  // mesh with its named sets, the muscles' descriptions and the root attributes.
  RunFileWriter(const std::string& path, const fem::Mesh& mesh, const std::string& scene_text,
                const RunFileOptions& options = RunFileOptions{},
                const std::vector<MuscleDescription>& muscles = {});
  ~RunFileWriter();  // flushes and closes; never throws
  RunFileWriter(const RunFileWriter&) = delete;
  RunFileWriter& operator=(const RunFileWriter&) = delete;

  // positions: current node positions flattened as 3 n + c [m], 3 N entries. muscles: required
  // (each vector of size M) when the log has muscles, ignored otherwise. Throws
  // std::invalid_argument for wrong sizes, RunFileError when HDF5 fails.
  void append(double time, const fem::Vector& positions, const SolverFigures& figures,
              const MuscleFrame& muscles = {});
  // A string attribute on the root group, replaced if it exists.
  void set_attribute(const std::string& name, const std::string& value);
  void flush();

  int frames() const { return frames_; }
  int num_nodes() const { return num_nodes_; }
  int num_muscles() const { return num_muscles_; }
  const std::string& path() const { return path_; }

 private:
  struct Handles;
  std::string path_;
  int num_nodes_ = 0;
  int num_muscles_ = 0;
  int frames_ = 0;
  double flush_interval_ = 1.0;
  double last_flush_ = 0.0;  // steady-clock seconds
  std::unique_ptr<Handles> h_;
};

}  // namespace tongue::run_file
