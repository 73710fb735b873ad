#include "scene/scene_builder.hpp"

#include "model/active_stiffening.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <set>
#include <stdexcept>

#include "common/number_text.hpp"
#include "fem/assembly/loads.hpp"
#include "fem/assembly/surface_load.hpp"
#include "fem/contact/obstacle_file.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/ansys_reader.hpp"
#include "fem/mesh/box_generator.hpp"
#include "fem/mesh/mesh_quality.hpp"
#include "model/default_tongue.hpp"
#include "model/vocal_tract.hpp"
#include "scene/scene_reader.hpp"

namespace tongue::scene {

namespace {

const char* const kComponentNames[3] = {"x", "y", "z"};

class Builder {
 public:
  explicit Builder(const Scene& scene) : scene_(scene) {}

  BuiltScene build() {
    BuiltScene built;
    std::vector<model::Muscle> muscles;  // the tongue's own; replaced by a scene's list
    fem::Mesh mesh = make_mesh(built.node_index_of_id, built.element_index_of_id, muscles);
    if (std::holds_alternative<AnsysMeshSpec>(scene_.mesh))
      built.numbering =
          fem::MeshNumbering::from_index_maps(built.node_index_of_id, built.element_index_of_id);
    numbering_ = &built.numbering;
    if (scene_.muscle_source == MuscleSource::list) {
      muscles = listed_muscles(mesh, built.node_index_of_id, built.element_index_of_id);
    } else if (scene_.muscle_source == MuscleSource::none) {
      muscles.clear();
    }
    add_element_set_nodes(mesh);
    resolve_scene_sets(mesh, built.node_index_of_id);
    built.prescribed = prescribed_dofs(mesh);

    std::shared_ptr<const fem::Material> material;
    try {
      material = fem::make_material(scene_.material.type, scene_.material.parameters);
    } catch (const std::invalid_argument& e) {
      fail("material.parameters",
           e.what());  // the reader checks this too; kept for hand-made scenes
    }
    try {
      // The fibre stiffness couples consecutive fibre nodes, which may share no element.
      auto solid = std::make_shared<fem::SolidModel>(
          std::move(mesh), material, scene_.material.formulation, scene_.material.density,
          built.prescribed, model::fibre_node_pairs(muscles));
      solid->set_threads(scene_.threads);
      built.solid = std::move(solid);
    } catch (const std::invalid_argument& e) {
      fail("mesh", with_element_id(e.what()));
    }

    built.system = std::make_unique<fem::MechanicalSystem>(built.solid);
    if (scene_.gravity) {
      built.system->add_load(std::make_shared<fem::ConstantForce>(
          "gravity", built.solid->body_force(*scene_.gravity)));
    }
    for (std::size_t i = 0; i < scene_.loads.size(); ++i) {
      const LoadSpec& load = scene_.loads[i];
      const std::string path = "loads[" + std::to_string(i) + "].set";
      const fem::Mesh& mesh = built.solid->mesh();
      const std::vector<int>& nodes = mesh.node_set(load.set);
      fem::Vector force = fem::Vector::Zero(3 * mesh.num_nodes());
      if (load.kind == LoadSpec::Kind::force_per_node) {
        for (int n : nodes) force.segment<3>(3 * n) = load.force;
      } else {
        try {
          force = fem::uniform_surface_force(mesh, nodes, load.force);
        } catch (const std::invalid_argument& e) {
          fail(path, "node set '" + load.set + "': " + e.what());
        }
      }
      built.system->add_load(
          std::make_shared<fem::ConstantForce>("load on " + load.set, std::move(force)));
    }
    if (!muscles.empty()) {
      try {
        built.muscles =
            std::make_shared<model::MuscleForces>(built.solid, muscles, scene_.muscle_force_length);
      } catch (const std::invalid_argument& e) {
        fail(muscle_path(muscles, e.what()), e.what());
      }
      built.system->add_load(built.muscles);
      if (scene_.muscle_stiffening > 1.0) {
        built.system->add_load(std::make_shared<model::ActiveStiffening>(built.solid, built.muscles,
                                                                         scene_.muscle_stiffening));
      }
      built.activations = ActivationSchedule(scene_, built.muscles->muscles());
    }
    if (!scene_.obstacles.empty()) {
      built.contact = make_contact(*built.solid);
      built.system->add_load(built.contact);
    }

    const AnalysisSpec& a = scene_.analysis;
    built.static_settings.load_steps = a.load_steps;
    built.static_settings.max_cuts = a.max_cuts;
    built.static_settings.require_held = scene_.obstacles.empty();  // contact may hold it
    built.static_settings.newton = scene_.solver;
    built.dynamic_settings.newmark = a.newmark;
    built.dynamic_settings.damping = scene_.damping;
    built.dynamic_settings.lumped_mass = a.lumped_mass;
    built.dynamic_settings.max_cuts = a.max_cuts;
    built.dynamic_settings.newton = dynamic_newton_settings(scene_);
    return built;
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& reason) const {
    throw SceneError(scene_.source, path, reason);
  }

  // The obstacles (the vocal tract's, then the files' in order) and the contact with them.
  std::shared_ptr<fem::RigidContact> make_contact(const fem::SolidModel& solid) const {
    std::vector<std::shared_ptr<const fem::Obstacle>> obstacles;
    if (scene_.obstacles.vocal_tract) obstacles = model::make_vocal_tract();
    for (const ObstacleFileSpec& f : scene_.obstacles.files) {
      const std::string path = "obstacles (" + f.name + ")";
      for (const auto& o : obstacles)
        if (o->name() == f.name) fail(path, "obstacle '" + f.name + "' is defined twice");
      fem::TriangleSurface surface;
      try {
        surface = fem::read_triangle_surface(f.path);
      } catch (const std::runtime_error& e) {
        fail(path, e.what());
      }
      const double deg = std::acos(-1.0) / 180.0;
      const fem::Mat3 rotation = (Eigen::AngleAxisd(f.rotate_deg.z() * deg, fem::Vec3::UnitZ()) *
                                  Eigen::AngleAxisd(f.rotate_deg.y() * deg, fem::Vec3::UnitY()) *
                                  Eigen::AngleAxisd(f.rotate_deg.x() * deg, fem::Vec3::UnitX()))
                                     .toRotationMatrix();
      for (fem::Vec3& v : surface.vertices) v = rotation * (f.length_scale * v) + f.translate;
      try {
        obstacles.push_back(
            std::make_shared<const fem::Obstacle>(f.name, std::move(surface), f.normals));
      } catch (const std::invalid_argument& e) {
        fail(path, "obstacle file " + f.path + ": " + e.what());
      }
    }
    auto contact = std::make_shared<fem::RigidContact>(obstacles, solid.mesh(), solid.dofs(),
                                                       scene_.obstacles.contact);
    // A node that starts behind a surface would be thrown out of it (or, deeper than the
    // search depth, ignored): most often an obstacle misplaced or with its normals reversed.
    for (const auto& o : obstacles) {
      int behind = 0, deepest = -1;
      double depth = 0.0;
      for (int n : contact->nodes()) {
        const fem::SurfacePoint p = o->closest(solid.mesh().nodes[n]);
        if (!p.valid || !(p.distance < 0.0)) continue;
        ++behind;
        if (-p.distance > depth) depth = -p.distance, deepest = n;
      }
      if (behind > 0) {
        fail("obstacles (" + o->name() + ")",
             std::to_string(behind) + " nodes of the mesh start behind obstacle '" + o->name() +
                 "' (deepest: " + numbering().node(deepest) + ", " +
                 common::number_text(depth * 1e3) +
                 " mm): move it, or reverse its triangles if its normals face away from the solid");
      }
    }
    return contact;
  }

  fem::Mesh make_mesh(std::map<long, int>& id_map, std::map<long, int>& element_id_map,
                      std::vector<model::Muscle>& muscles) const {
    if (const auto* tongue = std::get_if<TongueMeshSpec>(&scene_.mesh)) {
      model::TongueModel model = model::make_default_tongue(tongue->refinement);
      muscles = std::move(model.muscles);
      return std::move(model.mesh);
    }
    if (const auto* box = std::get_if<BoxMeshSpec>(&scene_.mesh)) {
      try {
        return fem::make_box(box->origin, box->size, box->divisions[0], box->divisions[1],
                             box->divisions[2]);
      } catch (const std::invalid_argument& e) {
        fail("mesh.box", e.what());
      }
    }
    const auto& ansys = std::get<AnsysMeshSpec>(scene_.mesh);
    try {
      fem::ImportedMesh imported =
          fem::read_ansys_mesh(ansys.nodes_path, ansys.elements_path, ansys.length_scale);
      double volume = 0.0;
      for (int e = 0; e < imported.mesh.num_elements(); ++e)
        volume += fem::element_volume(imported.mesh, e);
      if (const std::string why = fem::implausible_size(imported.mesh, volume); !why.empty())
        fail("mesh.ansys.length_scale",
             why + " (length_scale " + common::number_text(ansys.length_scale) + ")");
      id_map = std::move(imported.node_index_of_id);
      element_id_map = std::move(imported.element_index_of_id);
      return std::move(imported.mesh);
    } catch (const fem::MeshReadError& e) {
      fail("mesh.ansys", e.what());
    } catch (const std::invalid_argument& e) {
      fail("mesh.ansys", e.what());
    }
  }

  // The key path of the listed muscle a message from tongue::model names ("muscle '<name>' ..."),
  // or "muscles" for the built-in ones.
  std::string muscle_path(const std::vector<model::Muscle>& muscles,
                          const std::string& what) const {
    if (scene_.muscle_source == MuscleSource::list)
      for (std::size_t i = 0; i < muscles.size(); ++i)
        if (what.find("muscle '" + muscles[i].name + "'") != std::string::npos)
          return "muscles[" + std::to_string(i) + "]";
    return "muscles";
  }

  // A node (or element) id of the scene as an index: ANSYS ids for an imported mesh, 0-based
  // indices otherwise.
  int index_of(long id, const std::map<long, int>& id_map, int count, const char* what,
               const std::string& path, const std::string& hint = "") const {
    if (std::holds_alternative<AnsysMeshSpec>(scene_.mesh)) {
      const auto it = id_map.find(id);
      if (it == id_map.end())
        fail(path, std::string("no ") + what + " with id " + std::to_string(id) +
                       " in the mesh file" + hint);
      return it->second;
    }
    if (id < 0 || id >= count)
      fail(path, std::string(what) + " index " + std::to_string(id) +
                     " out of range: the mesh has " + std::to_string(count) + " " + what +
                     "s (0-based)");
    return static_cast<int>(id);
  }

  // The scene's own muscles on the mesh; each one's elements become an element set.
  std::vector<model::Muscle> listed_muscles(fem::Mesh& mesh, const std::map<long, int>& node_ids,
                                            const std::map<long, int>& element_ids) const {
    std::vector<model::Muscle> out;
    for (std::size_t i = 0; i < scene_.muscles.size(); ++i) {
      const MuscleSpec& spec = scene_.muscles[i];
      // An imported muscle is named by the macro file and line it came from.
      const bool imported = !spec.source.empty();
      const std::string path =
          imported ? "muscles.ansys_macros (" + spec.source + ", muscle " + spec.name + ")"
                   : "muscles[" + std::to_string(i) + "]";
      if (mesh.element_sets.count(spec.name) || mesh.node_sets.count(spec.name))
        fail(imported ? path : path + ".name", "name is already taken by a set of the mesh");
      model::Muscle m;
      m.name = spec.name;
      m.max_force = spec.max_force;
      for (std::size_t k = 0; k < spec.elements.size(); ++k)
        m.elements.push_back(
            index_of(spec.elements[k], element_ids, mesh.num_elements(), "element",
                     imported ? path : path + ".elements[" + std::to_string(k) + "]"));
      std::sort(m.elements.begin(), m.elements.end());
      m.elements.erase(std::unique(m.elements.begin(), m.elements.end()), m.elements.end());
      for (std::size_t f = 0; f < spec.fibres.size(); ++f) {
        const FibreSpec& fs = spec.fibres[f];
        const std::string f_path = imported ? "muscles.ansys_macros (" + fs.source + ", fibre " +
                                                  std::to_string(f + 1) + " of " + spec.name + ")"
                                            : path + ".fibres[" + std::to_string(f) + "]";
        model::Fibre fibre;
        for (std::size_t k = 0; k < fs.nodes.size(); ++k)
          fibre.nodes.push_back(
              index_of(fs.nodes[k], node_ids, mesh.num_nodes(), "node",
                       imported ? f_path : f_path + ".nodes[" + std::to_string(k) + "]",
                       imported ? " (an external point? list it under external_points)" : ""));
        fibre.origin = fs.origin;
        fibre.weight = fs.weight;
        m.fibres.push_back(std::move(fibre));
      }
      try {
        model::normalize_weights(m);
        model::validate(m, mesh.num_nodes(), mesh.num_elements(), numbering());
      } catch (const std::invalid_argument& e) {
        fail(path, e.what());
      }
      mesh.element_sets[m.name] = m.elements;
      out.push_back(std::move(m));
    }
    return out;
  }

  // An element set names a region (a material of an imported mesh); its nodes are the node set
  // of the same name, so constraints and loads can refer to it.
  static void add_element_set_nodes(fem::Mesh& mesh) {
    for (const auto& [name, elements] : mesh.element_sets) {
      if (mesh.node_sets.count(name)) continue;
      std::set<int> nodes;
      for (int e : elements) nodes.insert(mesh.elements[e].begin(), mesh.elements[e].end());
      mesh.node_sets.emplace(name, std::vector<int>(nodes.begin(), nodes.end()));
    }
  }

  void resolve_scene_sets(fem::Mesh& mesh, const std::map<long, int>& id_map) const {
    std::map<std::string, const NodeSetSpec*> specs;
    for (const auto& s : scene_.node_sets) {
      if (mesh.node_sets.count(s.name))
        fail("node_sets." + s.name, "name is already taken by a node set of the mesh");
      specs[s.name] = &s;
    }
    // Unions may name sets defined later in the file: resolve on demand. The reader has
    // rejected cycles; `depth` guards hand-made scenes.
    std::function<const std::vector<int>&(const std::string&, const std::string&, int)> resolve =
        [&](const std::string& name, const std::string& used_at,
            int depth) -> const std::vector<int>& {
      if (const auto it = mesh.node_sets.find(name); it != mesh.node_sets.end()) return it->second;
      const auto spec_it = specs.find(name);
      if (spec_it == specs.end()) fail(used_at, "unknown node set '" + name + "'");
      if (depth > static_cast<int>(specs.size()))
        fail(used_at, "node set '" + name + "' refers back to itself");
      const NodeSetSpec& s = *spec_it->second;
      const std::string path = "node_sets." + s.name;
      std::vector<int> nodes;
      switch (s.kind) {
        case NodeSetSpec::Kind::box:
          // Tolerance: the box is closed and meant to catch nodes on its faces; scale-relative
          // round-off of coordinates like 0.1 * 0.4 would otherwise drop them.
          nodes = fem::nodes_in_box(mesh, s.box_min, s.box_max, box_tolerance(mesh));
          if (nodes.empty())
            fail(path + ".box", "selects no nodes (rest positions in m: check units and bounds)");
          break;
        case NodeSetSpec::Kind::ids:
          for (std::size_t i = 0; i < s.ids.size(); ++i) {
            const std::string at = s.file.empty() ? path + ".ids[" + std::to_string(i) + "]"
                                                  : path + ".file (" + s.file + ", line " +
                                                        std::to_string(s.lines[i]) + ")";
            if (s.numbering == NodeSetSpec::Numbering::ids) {
              nodes.push_back(index_of(s.ids[i], id_map, mesh.num_nodes(), "node", at));
              continue;
            }
            const int base = s.numbering == NodeSetSpec::Numbering::one_based ? 1 : 0;
            const long index = s.ids[i] - base;
            if (index < 0 || index >= mesh.num_nodes())
              fail(at, "node " + std::to_string(s.ids[i]) + " is outside the mesh's " +
                           std::to_string(mesh.num_nodes()) + " nodes (numbered from " +
                           std::to_string(base) + " in node file order)");
            nodes.push_back(static_cast<int>(index));
          }
          break;
        case NodeSetSpec::Kind::set_union:
          for (std::size_t i = 0; i < s.members.size(); ++i) {
            const auto& part =
                resolve(s.members[i], path + ".union[" + std::to_string(i) + "]", depth + 1);
            nodes.insert(nodes.end(), part.begin(), part.end());
          }
          break;
      }
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
      if (nodes.empty()) fail(path, "the set is empty");
      return mesh.node_sets.emplace(s.name, std::move(nodes)).first->second;
    };
    for (const auto& s : scene_.node_sets) resolve(s.name, "node_sets." + s.name, 0);
    // Sets named by constraints and loads must exist now (e.g. "mat_7" of an imported mesh).
    for (std::size_t i = 0; i < scene_.constraints.size(); ++i)
      check_exists(mesh, scene_.constraints[i].set, "constraints[" + std::to_string(i) + "].set");
    for (std::size_t i = 0; i < scene_.loads.size(); ++i)
      check_exists(mesh, scene_.loads[i].set, "loads[" + std::to_string(i) + "].set");
  }

  void check_exists(const fem::Mesh& mesh, const std::string& name, const std::string& path) const {
    try {
      if (mesh.node_set(name).empty()) fail(path, "node set '" + name + "' is empty");
    } catch (const std::invalid_argument& e) {
      fail(path, e.what());
    }
  }

  // 1e-9 of the mesh's extent [m]: far below any element size, far above coordinate round-off.
  static double box_tolerance(const fem::Mesh& mesh) {
    if (mesh.nodes.empty()) return 0.0;
    fem::Vec3 lo = mesh.nodes.front(), hi = lo;
    for (const auto& x : mesh.nodes) {
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
    return 1e-9 * (hi - lo).maxCoeff();
  }

  std::vector<fem::PrescribedDof> prescribed_dofs(const fem::Mesh& mesh) const {
    // dof -> (value, index of the constraint that set it): a later constraint may repeat a value
    // (overlapping sets), but two different values for one dof is a contradiction.
    std::map<int, std::pair<double, std::size_t>> value_of;
    std::vector<fem::PrescribedDof> prescribed;
    for (std::size_t i = 0; i < scene_.constraints.size(); ++i) {
      const ConstraintSpec& c = scene_.constraints[i];
      for (int node : mesh.node_set(c.set)) {
        for (std::size_t k = 0; k < c.components.size(); ++k) {
          const int component = c.components[k];
          const double value = c.displacements[k];
          const auto [it, inserted] = value_of.emplace(3 * node + component, std::pair{value, i});
          if (!inserted) {
            if (it->second.first != value)
              fail("constraints[" + std::to_string(i) + "]",
                   numbering().node(node) + " component " + kComponentNames[component] +
                       " is prescribed " + common::number_text(value) + " m here and " +
                       common::number_text(it->second.first) + " m by constraints[" +
                       std::to_string(it->second.second) + "]");
            continue;
          }
          prescribed.push_back({node, component, value});
        }
      }
    }
    return prescribed;
  }

  // A message of the solid starting "element <index>: ..." with the element as the user's
  // files number it.
  std::string with_element_id(const std::string& what) const {
    const std::string head = "element ";
    if (what.compare(0, head.size(), head) != 0) return what;
    std::size_t end = head.size();
    while (end < what.size() && std::isdigit(static_cast<unsigned char>(what[end]))) ++end;
    if (end == head.size() || end >= what.size() || what[end] != ':') return what;
    return numbering().element(std::stoi(what.substr(head.size(), end - head.size()))) +
           what.substr(end);
  }

  // The file ids of an imported mesh, for messages (empty numbering otherwise).
  const fem::MeshNumbering& numbering() const {
    static const fem::MeshNumbering none;
    return numbering_ ? *numbering_ : none;
  }

  const Scene& scene_;
  const fem::MeshNumbering* numbering_ = nullptr;  // the BuiltScene's, while building
};

}  // namespace

BuiltScene build_scene(const Scene& scene) {
  return Builder(scene).build();
}

fem::NewtonSettings dynamic_newton_settings(const Scene& scene) {
  fem::NewtonSettings s = scene.solver;
  const auto given = [&](const char* key) { return scene.solver_keys.count(key) > 0; };
  if (!given("residual_rtol")) s.residual_rtol = 1e-4;
  if (!given("increment_rtol")) s.increment_rtol = 1e-4;
  if (!given("max_tangent_reuse")) s.max_tangent_reuse = 100;
  if (!given("reform_ratio")) s.reform_ratio = 0.8;
  if (!given("quasi_newton_updates")) s.quasi_newton_updates = 8;
  if (!given("single_precision_solve")) s.single_precision_solve = true;
  if (!given("displacement_tolerance"))
    s.displacement_tolerance = kDynamicAccelerationTolerance * scene.analysis.newmark.beta *
                               scene.analysis.dt * scene.analysis.dt;
  return s;
}

int time_step_count(const AnalysisSpec& analysis) {
  if (!(analysis.dt > 0.0) || !(analysis.duration > 0.0)) return 0;
  const double ratio = analysis.duration / analysis.dt;
  return std::max(1, static_cast<int>(std::ceil(ratio - 1e-9)));
}

double time_step_length(const AnalysisSpec& analysis, int step) {
  const int count = time_step_count(analysis);
  if (step < count - 1) return analysis.dt;
  // Keep dt itself when the remainder differs only by round-off: a new step length costs a
  // fresh factorization.
  const double rest = analysis.duration - (count - 1) * analysis.dt;
  return std::abs(rest - analysis.dt) <= 1e-9 * analysis.dt ? analysis.dt : rest;
}

std::string material_text(const MaterialSpec& material) {
  std::string text = material.type;
  char value[64];
  for (const auto& [name, v] : material.parameters) {
    std::snprintf(value, sizeof value, "%.17g", v);
    text += " " + name + "=" + value;
  }
  std::snprintf(value, sizeof value, " density=%.17g", material.density);
  return text + value;
}

}  // namespace tongue::scene
