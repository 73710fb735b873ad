#pragma once
// The simulator in-process, without a bus: a dynamic scene read from its file, settled, and
// stepped by the scene's dt with the activation levels the caller gives, through the same run
// object sim_batch and sim_server step (scene_run::SceneRun). The Python module `tongue`
// (module.cpp) exposes it; this class holds everything but the Python types, so that the
// binding only converts.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fem/types.hpp"
#include "run_file/run_file_queue.hpp"
#include "scene/scene.hpp"
#include "scene_run/scene_run.hpp"

namespace tongue::python {

// What one step did.
struct StepFigures {
  double time = 0.0;  // s, at the end of the step
  int iterations = 0, factorizations = 0, cuts = 0;
  double error_estimate = 0.0;  // m, Newton's estimate of the error left
  double wall_seconds = 0.0;    // s, of the step in C++ (SceneRun::step)
  bool held = false;            // taken as the identity from a state at rest
  // Warnings the step raised, empty when none: the material's first loss of strong ellipticity
  // (found off the step's critical path, so reported with the step after the state it names),
  // a reduced model's error indicator above the scene's threshold.
  std::vector<std::string> warnings;
};

class Simulation {
 public:
  // Reads, builds and settles the scene. Throws common::KeyPathError (a std::runtime_error)
  // naming the file and key for a scene that cannot be read or built, std::invalid_argument for
  // a scene that is not dynamic, std::runtime_error when the settling does not converge.
  explicit Simulation(const std::string& scene_path);
  ~Simulation();
  Simulation(const Simulation&) = delete;  // the run refers to the scene held here
  Simulation& operator=(const Simulation&) = delete;

  // One step of the scene's dt with the levels [1] of every muscle, in muscle_names() order.
  // Throws std::invalid_argument for the wrong count or a level outside [0, 1], and
  // std::runtime_error with the solver's message when the step does not converge (the state
  // stays at the last accepted step).
  StepFigures step(const fem::Vector& levels);
  // The same with some muscles named (muscle or group names: "SG" sets SG_left and SG_right);
  // the others keep the levels of the last step. Throws std::invalid_argument for a name that
  // is neither.
  StepFigures step(const std::map<std::string, double>& levels);
  // The warnings of the checks still under way on the last state: the material's loss of strong
  // ellipticity is found off the step's critical path and comes with the next step otherwise.
  std::vector<std::string> finish_checks();
  // Back to the settled state at time 0, all levels 0; the run that follows repeats the first,
  // its warnings too. Returns the ended run's finish_checks(). A run file being written gets the
  // settled state as its next frame and counts it in "resets".
  // first_levels: the first step's levels when the caller knows them (empty: all 0), under which
  // the first step's factor is formed here, as sim_batch's is (scene_run::SceneRun::restart):
  // a first step with other levels forms it again, a factorization more (about 7 ms on the
  // tongue, a sixth of a 0.2 s run). The states are the same either way. Throws
  // std::invalid_argument for the wrong count or a level outside [0, 1].
  std::vector<std::string> reset(const fem::Vector& first_levels = {});
  // The same with some muscles named (as step()); the others 0.
  std::vector<std::string> reset(const std::map<std::string, double>& first_levels);

  // Writes the run from here on into a run file at path (docs/run_file.md, as sim_batch's): the
  // current state as its first frame, then a frame per step. A file already being written is
  // closed first. Throws run_file::RunFileError naming the file when it cannot be created.
  void open_run_file(const std::string& path);
  // Marks the file being written "completed" (or "failed: <why>" after a step that did not
  // converge) and closes it; nothing when none is open. Also done by the destructor.
  void close_run_file();
  const std::string& run_file_path() const { return log_path_; }

  // The state after the last step.
  double time() const { return run_->time(); }  // s
  std::int64_t step_count() const { return run_->step_count(); }
  double dt() const { return scene_.analysis.dt; }              // s
  Eigen::MatrixX3d positions() const;                           // m, one row per node
  Eigen::MatrixX3d displacements() const;                       // m, from the rest positions
  Eigen::MatrixX3d velocities() const;                          // m/s
  const fem::Vector& levels() const { return run_->levels(); }  // [1], of the last step
  const fem::Vector& muscle_lengths() const;                    // m
  const fem::Vector& muscle_velocities() const;                 // m/s, lengthening

  // The model.
  const std::string& scene_path() const { return scene_.source; }
  const std::vector<std::string>& muscle_names() const { return muscle_names_; }
  fem::Vector max_forces() const;           // F_max [N], in muscle_names() order
  Eigen::MatrixX3d rest_positions() const;  // m
  Eigen::Matrix<int, Eigen::Dynamic, 8, Eigen::RowMajor> elements() const;  // node indices
  const std::map<std::string, std::vector<int>>& node_sets() const;

 private:
  // base with the named muscles' and groups' levels set; std::invalid_argument for a name that
  // is neither.
  fem::Vector with_named(fem::Vector base, const std::map<std::string, double>& levels) const;
  static Eigen::MatrixX3d by_node(const fem::Vector& v);
  void write_frame(const run_file::SolverFigures& figures);
  scene::Scene scene_;
  std::unique_ptr<scene_run::SceneRun> run_;
  std::vector<std::string> muscle_names_;
  std::unique_ptr<run_file::RunFileQueue> log_;  // written on its own thread
  std::string log_path_;
  std::string failure_;  // why the last step failed, for the run file's status
  int resets_ = 0;
};

}  // namespace tongue::python
