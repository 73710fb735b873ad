#pragma once
// A scene is the data describing one run: mesh, material, node sets, constraints, loads, damping,
// muscles and their activations, analysis, solver settings and output. It is plain data:
// scene_reader.hpp fills it from YAML, scene_builder.hpp turns it into a model. The member
// initializers below are the defaults, and the only place they are written (the material
// parameters' defaults live in the material factory's parameter table; the solver's and Newmark's
// in the fem settings structs used here).
//
// YAML schema (all quantities SI; paths of mesh files relative to the scene file):
//
//   mesh:                          # required; exactly one of box / ansys / tongue
//     box: {origin: [0, 0, 0], size: [0.04, 0.01, 0.01], divisions: [8, 2, 2]}   # m
//         # origin optional (default 0); size > 0 and divisions >= 1 required.
//         # The mesh's node sets: x_min, x_max, y_min, y_max, z_min, z_max (faces), all.
//     ansys: {nodes: file.node, elements: file.elem, length_scale: 0.001}
//         # NWRITE/EWRITE text files; length_scale (default 1) turns file units into metres.
//         # The mesh's node sets: all and mat_<n> (the nodes of the elements of material n).
//     tongue: {refinement: 1}      # the built-in tongue (model/default_tongue.hpp); refinement
//         # 1..8 (default 1) multiplies the elements along each grid direction. Its node sets:
//         # mandible, root_bottom, hyoid, midsagittal, the landmarks tip, blade, palatal_dorsum,
//         # velar_dorsum, root, gg_insertion (one node each); its element sets: all and one per
//         # built-in muscle (each also a node set of the same name, as for every element set).
//   material:                      # required
//     type: mooney_rivlin5         # required: mooney_rivlin5 | exponential | neo_hookean | linear
//     parameters: {poisson_ratio: 0.49}   # optional; names, units and defaults from the material
//                                         # factory's table (fem/material/material_factory.hpp)
//     density: 1000                # kg/m^3, default 1000
//     formulation: mean_dilatation # mean_dilatation | standard; default mean_dilatation for
//                                  # materials with an isochoric/volumetric split, else standard
//   node_sets:                     # optional; named sets in addition to the mesh's own
//     clamped: {box: {min: [-1e-9, -1, -1], max: [1e-9, 1, 1]}}   # rest positions, closed box, m
//     tip: {ids: [5, 7]}           # ANSYS node ids for an imported mesh, 0-based indices otherwise
//     both: {union: [clamped, tip]}
//     jaw: {file: jaw.txt, numbering: one_based}   # a node list file (scene/node_list_file.hpp):
//         # numbering ids (as for `ids`), or zero_based / one_based (mesh: ansys): positions in
//         # the node file's order counted from 0 or 1
//   constraints:                   # optional; per-component Dirichlet conditions
//     - {set: clamped, components: [x, y, z]}            # displacement default 0 (fixed)
//     - {set: tip, components: [z], displacement: 0.0}   # m; a number, or one per component
//   gravity: [0, -9.81, 0]         # m/s^2; optional (none when omitted)
//   loads:                         # optional; one of total_force / force_per_node each
//     - {set: x_max, total_force: [0, -0.01, 0]}   # N in total, a uniform traction on the
//                                                  # boundary faces whose nodes are all in the set
//     - {set: tip, force_per_node: [0, 0, 0.001]}  # N on every node of the set
//   damping: {alpha: 0.0, beta: 0.028}   # Rayleigh C = alpha M + beta K0, 1/s and s; optional.
//                                        # K0: tangent at the initial (settled or rest) state
//   muscles: builtin               # optional; only with mesh: tongue: its 19 muscles,
//                                  # <group>_left / <group>_right for GGp GGm GGa HG SG IL T V MH,
//                                  # and SL; or a list, for any mesh:
//     - {name: GGp_left, max_force: 18.5,          # N at full activation, > 0
//        elements: [1, 2],                         # ids as for node_sets; an element set
//        fibres: [{nodes: [4, 9, 14], origin: [0, 0, 0], weight: 1.0}]}
//         # fibre nodes as for node_sets, in order; origin (m, optional): a fixed attachment before
//         # the first node; weight (default 1) > 0, scaled so that a muscle's weights sum to 1.
//   muscles: {ansys_macros: {elements: CreateMuscles.mac, fibres: Fibers.mac,
//                            max_force: MuscleMaxForce.txt, external_points: {4037: [x, y, z]},
//                            groups: {SG: [STY_L, STY_R]}}}
//         # mesh: ansys only; the list read from ANSYS muscle macros
//         # (model/ansys_muscle_macros.hpp), paths relative to the scene file; external points
//         # in m; groups: the muscles a `group:` activation names
//   muscle_stiffening: 7.333       # optional; needs muscles. Stiffness of fully active muscle
//                                  # tissue over resting tissue, >= 1 (1: off); default 110/15
//                                  # (Gerard et al. 2003 sec. III.2: 15 kPa at rest, 110 kPa
//                                  # fully contracted), linear in the activation in between.
//   muscle_force_length: 0.5       # optional; needs muscles. Length of a fibre segment, relative
//                                  # to its rest length, at which its active tension has fallen
//                                  # to 0 (Hill's ascending limb, model/force_length.hpp), in
//                                  # [0, 1); default 0.5 (Zajac 1989). "constant": the plain
//                                  # fibre model, tension independent of length.
//   activations:                   # optional; needs muscles. Steps of activation, each naming
//                                  # exactly one of muscles / group and one of level / force:
//     - {muscles: [SG_left, SG_right], level: 0.125, start: 0.0, end: 0.12}
//     - {group: SG, force: 3.0, start: 0, end: 0.12}
//         # level in [0, 1] of each muscle's max_force; force [N] >= 0: the total over the named
//         # muscles, split by max_force (level = force / their summed max_force, at most 1).
//         # group G: the declared group G, else every muscle named G or starting with G_.
//         # start (s, default 0) >= 0, end (s, optional: until the end of the run) > start. An
//         entry is active while # start <= t <= end; where active entries overlap on a muscle, the
//         later one in the # list sets its level. Muscles without an active entry are at 0. A
//         dynamic step to # t_{n+1} uses the levels at t_{n+1}, the initial state (settled or not)
//         has every # muscle off; a static analysis uses the levels at t = 0.
//   obstacles: vocal_tract         # optional; rigid surfaces the solid's boundary nodes may not
//                                  # pass (frictionless penalty contact, fem/contact/). The
//                                  # built-in vocal tract (hard_palate, upper_teeth, velum,
//                                  # pharyngeal_wall; model/vocal_tract.hpp), only with mesh:
//                                  # tongue; or a list of vocal_tract and files:
//     - vocal_tract
//     - {name: plate, file: plate.stl, length_scale: 0.001, rotate: [0, 0, 90],
//        translate: [0, 0.06, 0], normals: faceted}
//         # OBJ or STL triangles, path relative to the scene file, normals (right-hand rule)
//         # toward the solid; length_scale (default 1) turns file units into metres, then
//         # rotate (degrees about x, then y, then z; default none) and translate (m). No node of
//         # the solid may start behind an obstacle. normals: faceted (default) or smooth (the
//         # vertex normals interpolated, for a mesh that samples a smooth surface; fem::Normals).
//         # The built-in vocal tract's are smooth.
//   contact: {penalty: 3.0e8, smoothing: 2.0e-5, search_depth: 0.005,
//             penetration_tolerance: 1.0e-4, max_augmentations: 4}   # optional; needs
//         # obstacles; the defaults shown (fem::ContactSettings). penalty [Pa/m]: contact
//         # pressure per metre of penetration; smoothing [m]: the penetration over which the
//         # penalty's stiffness grows from 0; search_depth [m]: points deeper behind a surface
//         # are not in contact with it; penetration_tolerance [m]: a dynamic step that leaves a
//         # node deeper is solved again with augmented-Lagrangian multipliers, at most
//         # max_augmentations times (0: the plain penalty)
//   analysis:                      # required
//     type: dynamic                # required: static | dynamic
//     settle: false                # dynamic: start from static equilibrium under the loads
//     duration: 0.1                # s; required for dynamic
//     dt: 0.001                    # s; required for dynamic, <= duration
//     load_steps: 1                # static (and settle): equal load increments
//     newmark: {beta: 0.25, gamma: 0.5}
//     lumped_mass: false
//     max_cuts: 4                  # a failing step or increment is halved at most this often
//   model:                         # dynamic only; default: the full finite-element model
//     reduced: basis.h5            # required: a reduced basis made by build_reduced_model for
//                                  # this mesh and material, relative to the scene file
//     check_every: 10              # steps between checks of the full model's residual (0: none)
//     warn_above: 0.001            # m: warn once when the full model would correct the reduced
//                                  # state by more than this
//     switch_to_full: false        # then go on with the full model from the reduced state
//   solver: {residual_rtol: 1e-6, residual_atol: 1e-9, increment_rtol: 1e-6,
//            increment_atol: 1e-12, max_iterations: 25, line_search: true,
//            max_tangent_reuse: 0, reform_ratio: 0.5, quasi_newton_updates: 0,
//            displacement_tolerance: 0, single_precision_solve: false, threads: 1}
//                          # all optional; defaults of fem::NewtonSettings for statics and the
//                          # settling; a dynamic analysis defaults residual_rtol and
//                          # increment_rtol to 1e-4, max_tangent_reuse to 100, reform_ratio to
//                          # 0.8, quasi_newton_updates to 8, single_precision_solve to true
//                          # and displacement_tolerance [m] to beta dt^2 x 2.5 m/s^2
//                          # (dynamic_newton_settings);
//                          # threads: element loops on 1 or 2 threads
//   output:
//     file: logs/run.h5            # relative to the working directory; default: no file
//     every: 1                     # write every k-th step (the first and last are always written)
//     compression: 4               # deflate level 0-9 of the series (0: none); default 4 for
//                                  # the full model, 0 for a reduced model (OutputSpec)
//
// A key whose value is empty (`gravity:` with nothing after it) counts as omitted.
#include <array>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "fem/contact/rigid_contact.hpp"
#include "fem/element/hex8_element.hpp"
#include "fem/integrator/newmark_integrator.hpp"
#include "fem/solver/newton_solver.hpp"
#include "fem/types.hpp"
#include "model/active_stiffening.hpp"
#include "model/force_length.hpp"

namespace tongue::scene {

struct BoxMeshSpec {
  fem::Vec3 origin = fem::Vec3::Zero();  // m
  fem::Vec3 size = fem::Vec3::Zero();    // m, every component > 0
  std::array<int, 3> divisions{1, 1, 1};
};

struct AnsysMeshSpec {
  std::string nodes_path;     // resolved against the scene file's directory
  std::string elements_path;  // idem
  double length_scale = 1.0;  // file length unit in metres
};

// The built-in tongue (tongue::model::make_default_tongue).
struct TongueMeshSpec {
  int refinement = 1;
};

using MeshSpec = std::variant<BoxMeshSpec, AnsysMeshSpec, TongueMeshSpec>;

struct MaterialSpec {
  std::string type;
  std::map<std::string, double> parameters;  // as given; the factory fills in its defaults
  double density = 1000.0;                   // kg/m^3 (Gerard et al. 2003 sec. IV.1: 1 g/cm^3)
  // Resolved by the reader: mean_dilatation for split materials unless the scene says otherwise.
  fem::Formulation formulation = fem::Formulation::mean_dilatation;
};

struct NodeSetSpec {
  enum class Kind { box, ids, set_union };
  // How Kind::ids numbers its nodes: by the mesh's ids (ANSYS ids for an imported mesh, 0-based
  // indices otherwise), or by position in the mesh's node order counted from 0 or from 1.
  enum class Numbering { ids, zero_based, one_based };
  std::string name;
  Kind kind = Kind::ids;
  fem::Vec3 box_min = fem::Vec3::Zero(), box_max = fem::Vec3::Zero();  // m (Kind::box)
  std::vector<long> ids;             // Kind::ids: ANSYS ids, or 0-based indices for a box mesh
  std::vector<std::string> members;  // Kind::set_union: names of other node sets
  Numbering numbering = Numbering::ids;
  std::string file;        // a node list file the ids were read from (resolved), or empty
  std::vector<int> lines;  // with a file: the line of each id
};

struct ConstraintSpec {
  std::string set;
  std::vector<int> components;        // 0 = x, 1 = y, 2 = z; distinct
  std::vector<double> displacements;  // m, one per component
};

// A dead load on a node set: either a total force spread as a uniform traction over the boundary
// faces whose four nodes are all in the set, or the same force on every node of the set.
struct LoadSpec {
  enum class Kind { total_force, force_per_node };
  std::string set;
  Kind kind = Kind::total_force;
  fem::Vec3 force = fem::Vec3::Zero();  // N
};

// A muscle of a scene's own list; ids as for NodeSetSpec::ids.
struct FibreSpec {
  std::vector<long> nodes;
  std::optional<fem::Vec3> origin;  // m
  double weight = 1.0;              // relative; the builder normalizes a muscle's weights
  std::string source;               // imported: "<file>, line <n>" of its definition
};

struct MuscleSpec {
  std::string name;
  double max_force = 0.0;  // N
  std::vector<long> elements;
  std::vector<FibreSpec> fibres;
  std::string source;  // imported: "<file>, line <n>" of its definition; empty: the scene's list
};

// list: the scene's own list, or imported from ANSYS muscle macros (AnsysMacrosSpec).
enum class MuscleSource { none, builtin, list };

// muscles: {ansys_macros: ...}: where the imported muscles came from (files resolved).
struct AnsysMacrosSpec {
  std::string elements, fibres, max_force;
  std::map<long, fem::Vec3> external_points;  // id in the fibres file -> position [m]
};

// One step of the activation schedule. Exactly one of muscles / group is given, and exactly one
// of level / force; the builder resolves the names against the built muscles.
struct ActivationSpec {
  std::vector<std::string> muscles;
  std::string group;
  std::optional<double> level;  // [1] of each muscle's max_force
  std::optional<double> force;  // N, total over the named muscles
  double start = 0.0;           // s
  std::optional<double> end;    // s; none: until the end of the run
  int line = 0;                 // 1-based line of the entry in the file, for errors; 0: unknown
};

// A rigid obstacle read from an OBJ or STL file, placed by scaling, rotating, translating.
struct ObstacleFileSpec {
  std::string name;
  std::string path;                          // resolved against the scene file's directory
  double length_scale = 1.0;                 // file length unit in metres
  fem::Vec3 rotate_deg = fem::Vec3::Zero();  // degrees about x, then y, then z
  fem::Vec3 translate = fem::Vec3::Zero();   // m
  fem::Normals normals = fem::Normals::faceted;
};

struct ObstaclesSpec {
  bool vocal_tract = false;  // the built-in vocal tract, first
  std::vector<ObstacleFileSpec> files;
  fem::ContactSettings contact;
  bool empty() const { return !vocal_tract && files.empty(); }
};

enum class AnalysisType { static_equilibrium, dynamic };

struct AnalysisSpec {
  AnalysisType type = AnalysisType::static_equilibrium;
  bool settle = false;
  double duration = 0.0;  // s
  double dt = 0.0;        // s
  int load_steps = 1;
  fem::NewmarkParameters newmark;
  bool lumped_mass = false;
  int max_cuts = 4;
};

// The model a dynamic run steps: the full finite-element model, or a reduced one made from it
// by build_reduced_model (docs/reduced.md).
struct ModelSpec {
  std::string reduced;  // the reduced basis file, resolved; empty: the full model
  // Steps between evaluations of the full model's residual at the reduced state (0: never),
  // and the largest nodal correction it calls for above which the run warns [m].
  int check_every = 10;
  double warn_above = 1e-3;
  // Above warn_above, go on with the full model from the reduced model's state.
  bool switch_to_full = false;
  bool is_reduced() const { return !reduced.empty(); }
};

struct OutputSpec {
  std::string file;  // empty: no run file unless the command line names one
  int every = 1;
  // The deflate level of the run file's series, 0 (none) to 9. Unset: 4 for the full model and
  // 0 for a reduced one, whose steps (about 0.2 ms on the tongue) are faster than deflate
  // compresses a frame of positions (about 0.4 ms for 1001 nodes, for a quarter less bytes): at
  // level 4 a long reduced run would wait for its run file.
  std::optional<int> compression;
  int deflate_level(bool reduced) const { return compression.value_or(reduced ? 0 : 4); }
};

struct Scene {
  std::string source;    // the scene file's path (or a label), used in error messages
  std::string text;      // the YAML text as read, stored in the run file
  std::string base_dir;  // directory that relative mesh paths were resolved against

  MeshSpec mesh = BoxMeshSpec{};
  MaterialSpec material;
  std::vector<NodeSetSpec> node_sets;  // in file order
  std::vector<ConstraintSpec> constraints;
  std::optional<fem::Vec3> gravity;  // m/s^2
  std::vector<LoadSpec> loads;
  fem::RayleighDamping damping;  // zero coefficients: no damping
  MuscleSource muscle_source = MuscleSource::none;
  std::vector<MuscleSpec> muscles;              // MuscleSource::list, in file order
  std::optional<AnsysMacrosSpec> ansys_macros;  // the list was imported from these files
  // Named groups of muscles for activations' `group:`, declared by the scene; a group not
  // declared here is every muscle named G or G_<anything>.
  std::map<std::string, std::vector<std::string>> muscle_groups;
  std::vector<ActivationSpec> activations;
  // E_contracted / E_rest of active muscle tissue (model/active_stiffening.hpp); 1: none.
  double muscle_stiffening = model::kContractedToRestStiffness;
  // Active force-length relation of every fibre segment (model/force_length.hpp).
  model::ActiveForceLength muscle_force_length;
  ObstaclesSpec obstacles;
  AnalysisSpec analysis;
  ModelSpec model;
  // The solver block over fem::NewtonSettings' defaults, and the keys it gave: a dynamic
  // analysis takes its own defaults for the keys not given (dynamic_newton_settings in
  // scene_builder.hpp).
  fem::NewtonSettings solver;
  std::set<std::string> solver_keys;
  int threads = 1;  // solver.threads: threads of the element loops, 1 or 2
  OutputSpec output;
};

}  // namespace tongue::scene
