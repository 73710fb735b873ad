#pragma once
// The run file of a scene's run, shared by sim_batch and sim_server: the log opened with the
// scene's mesh, text and muscles, and the per-muscle values of one frame.
#include <memory>
#include <string>

#include "run_file/run_file_writer.hpp"
#include "scene/scene.hpp"
#include "scene/scene_builder.hpp"

namespace tongue::scene_run {

// Creates the run file at path for a run of scene (built from it): a static run's time axis is
// the load factor ("1"); root attributes analysis, initial_state and status = "running".
std::unique_ptr<run_file::RunFileWriter> open_scene_run_file(const std::string& path,
                                                             const scene::Scene& scene,
                                                             const scene::BuiltScene& built);

// The muscles' activations, lengths [m] and velocities [m/s] at displacement u and nodal
// velocity v (null: at rest, zero velocities); empty vectors without muscles.
run_file::MuscleFrame scene_muscle_frame(const scene::BuiltScene& built, const fem::Vector& u,
                                         const fem::Vector* v);

}  // namespace tongue::scene_run
