#pragma once
// The run file of a scene's run, shared by sim_batch and sim_server: the log opened with the
// scene's mesh, text, muscles and obstacles, and the per-muscle and contact values of a frame.
#include <memory>
#include <string>

#include "fem/mesh/mesh.hpp"
#include "run_file/run_file_writer.hpp"
#include "scene/scene.hpp"
#include "scene/scene_builder.hpp"

namespace tongue::scene_run {

// The mesh as the run file takes it (run_file knows no FEM types): nodes, hexahedra, named sets.
run_file::MeshDescription mesh_description(const fem::Mesh& mesh);

// Creates the run file at path for a run of scene (built from it): a static run's time axis is
// the load factor ("1"); root attributes analysis, initial_state and status = "running".
std::unique_ptr<run_file::RunFileWriter> open_scene_run_file(const std::string& path,
                                                             const scene::Scene& scene,
                                                             const scene::BuiltScene& built);

// The muscles' activations, lengths [m] and velocities [m/s] at displacement u and nodal
// velocity v (null: at rest, zero velocities); empty vectors without muscles.
run_file::MuscleFrame scene_muscle_frame(const scene::BuiltScene& built, const fem::Vector& u,
                                         const fem::Vector* v);

// The contact at displacement u (the forces of the obstacles on the nodes, of the solid on each
// obstacle, the deepest penetration); empty vectors without obstacles.
run_file::ContactFrame scene_contact_frame(const scene::BuiltScene& built, const fem::Vector& u);
// The same from a report of the scene's contact already made.
run_file::ContactFrame scene_contact_frame(const scene::BuiltScene& built,
                                           const fem::ContactReport& report);

}  // namespace tongue::scene_run
