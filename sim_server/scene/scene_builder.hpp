#pragma once
// Turns a Scene into a model ready to run: the mesh with every named node set resolved, the
// solid with its constraints, the loads, and the solver settings of the chosen analysis.
#include <map>
#include <memory>
#include <vector>

#include "fem/assembly/solid_model.hpp"
#include "fem/contact/rigid_contact.hpp"
#include "fem/integrator/mechanical_system.hpp"
#include "fem/integrator/newmark_integrator.hpp"
#include "fem/integrator/static_solver.hpp"
#include "fem/mesh/mesh_numbering.hpp"
#include "model/muscle_forces.hpp"
#include "scene/activation_schedule.hpp"
#include "scene/scene.hpp"

namespace tongue::scene {

struct BuiltScene {
  // The solid's mesh holds every node set by name: the mesh's own (box faces, "all", the
  // tongue's boundary and landmark sets), one per element set ("mat_<n>" of an imported mesh,
  // "all", each muscle's: the nodes of its elements), and the scene's. Its element sets are the
  // mesh's and one per muscle.
  std::shared_ptr<const fem::SolidModel> solid;
  // Loads: "gravity" when the scene has gravity, then one per entry of `loads`, then "muscles"
  // when the scene has muscles, then "active muscle stiffening" unless muscle_stiffening is 1,
  // then "contact" when the scene has obstacles, in that order.
  std::unique_ptr<fem::MechanicalSystem> system;
  // The muscles' forces, also among the system's loads; null without muscles. All activations
  // start at 0: the caller sets them from `activations`.
  std::shared_ptr<model::MuscleForces> muscles;
  // The contact with the scene's obstacles, also among the system's loads; null without.
  std::shared_ptr<fem::RigidContact> contact;
  ActivationSchedule activations;              // resolved against `muscles` (empty without muscles)
  fem::StaticSettings static_settings;         // for a static analysis and for settling
  fem::DynamicSettings dynamic_settings;       // for a dynamic analysis
  std::vector<fem::PrescribedDof> prescribed;  // as given to the solid
  std::map<long, int> node_index_of_id;        // imported meshes: file node id -> index
  std::map<long, int> element_index_of_id;     // imported meshes: file element id -> index
  // Imported meshes: the file ids by index, for messages and the run file; empty otherwise.
  fem::MeshNumbering numbering;
};

// The material as text: its type, the parameters the scene gives and the density (a reduced
// basis records the material it was made for).
std::string material_text(const MaterialSpec& material);

// Throws SceneError (scene_reader.hpp) naming the scene file and key path for what only the
// built mesh reveals: a set that selects no nodes, a node or element id not in the mesh, a
// "mat_<n>" set the file lacks, a node given two different prescribed displacements in one
// component, a load set with no boundary face, a mesh that cannot be read or has an inverted
// element, an obstacle file that cannot be read or is not a surface, an obstacle that a node of
// the solid starts behind, a muscle that tongue::model::validate rejects or whose fibre has a
// zero-length segment, and activations naming unknown muscles or groups or asking more than
// max_force.
BuiltScene build_scene(const Scene& scene);

// The Newton settings of the scene's dynamic steps: its solver block, with these defaults for
// the keys it does not give (the static settling keeps fem::NewtonSettings' defaults):
//  - residual_rtol = 1e-4 (the residual against the forces acting) for accepting a predictor
//    already in equilibrium, and increment_rtol = 1e-4 (error left in x against the step's
//    motion) when displacement_tolerance is set to 0;
//  - max_tangent_reuse = 100, reform_ratio = 0.8, quasi_newton_updates = 8: a factorization
//    reused across iterations and steps, re-formed when the residual falls by less than a
//    factor 0.8 in an iteration, its direction improved by BFGS updates. The effective tangent
//    K_T + c0 M + c1 beta_R K0 is dominated by its constant part, so a reused factor keeps
//    converging (a static solve has no such part: there it is full Newton by default).
//  - single_precision_solve = true: the reused factor solves in single precision, about 1.5
//    times faster on the tongue at the same iteration count; the tests and error estimate stay
//    in double precision.
//  - displacement_tolerance = beta dt^2 kDynamicAccelerationTolerance (10 um at dt 4 ms): a step
//    is accepted when Newton's estimate of the error left in it would put the step's
//    acceleration, a = (x - u_n - dt v_n) / (beta dt^2) - ..., off by at most 2.5 m/s^2. With
//    the integrator's predictor, 1.4 iterations per step at dt 4 ms instead of 3.6 and 1.5 at
//    8 ms instead of 5.5, with no larger nodal error against the reference (0.042 mm RMS at
//    4 ms, 0.087 mm at 8 ms, 0.021 mm at 2 ms). A tolerance growing only with dt (2.5 mm/s x dt)
//    took 1.6 iterations at 8 ms and raised the error at 2 ms to 0.025 mm: the errors the many
//    small steps admitted added up.
constexpr double kDynamicAccelerationTolerance = 2.5;  // [m/s^2]
fem::NewtonSettings dynamic_newton_settings(const Scene& scene);

// Time steps of a dynamic analysis: ceil(duration / dt), the last one shortened to end exactly
// at the duration (a remainder below 1e-9 dt is dropped as round-off).
int time_step_count(const AnalysisSpec& analysis);
double time_step_length(const AnalysisSpec& analysis, int step);  // step in [0, count)

}  // namespace tongue::scene
