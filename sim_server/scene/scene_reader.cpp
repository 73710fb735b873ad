#include "scene/scene_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <set>

#include "common/number_text.hpp"
#include "common/yaml_reader.hpp"
#include "fem/material/material_factory.hpp"
#include "model/ansys_muscle_macros.hpp"
#include "model/default_tongue.hpp"
#include "model/tongue_muscles.hpp"
#include "scene/external_points_file.hpp"
#include "scene/node_list_file.hpp"

namespace tongue::scene {

namespace {

namespace fs = std::filesystem;

using common::child_path;
using common::describe;
using common::index_path;
using common::join;
using common::number_text;
using common::present;

const char* const kComponentNames[3] = {"x", "y", "z"};

// The node sets every box mesh has (fem/mesh/box_generator.hpp, plus "all" from its element set).
const std::vector<std::string>& box_set_names() {
  static const std::vector<std::string> names = {"x_min", "x_max", "y_min", "y_max",
                                                 "z_min", "z_max", "all"};
  return names;
}

// The built-in muscles' names, by the convention of model/tongue_muscles.hpp: "<group>_left"
// and "<group>_right" for a paired group, the group's name otherwise.
std::vector<std::string> builtin_muscle_names() {
  std::vector<std::string> names;
  for (const auto& g : model::muscle_groups()) {
    if (g.paired) {
      names.push_back(g.name + "_left");
      names.push_back(g.name + "_right");
    } else {
      names.push_back(g.name);
    }
  }
  return names;
}

// The node sets of the built-in tongue (model/default_tongue.hpp): its boundary and landmark
// sets, "all", and one per muscle (from its element sets).
const std::vector<std::string>& tongue_set_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n = {"mandible", "root_bottom", "hyoid", "midsagittal"};
    for (const auto& l : model::landmark_names()) n.push_back(l);
    n.push_back("all");
    for (const auto& m : builtin_muscle_names()) n.push_back(m);
    return n;
  }();
  return names;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// Whether the mesh can provide a node set of this name. For an imported mesh "mat_<n>" exists
// only when the file uses material n; the builder checks that against the mesh it reads.
bool mesh_may_provide(const MeshSpec& mesh, const std::string& name) {
  if (std::holds_alternative<BoxMeshSpec>(mesh)) return contains(box_set_names(), name);
  if (std::holds_alternative<TongueMeshSpec>(mesh)) return contains(tongue_set_names(), name);
  if (name == "all") return true;
  if (name.size() <= 4 || name.compare(0, 4, "mat_") != 0) return false;
  return std::all_of(name.begin() + 4, name.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// The mesh's sets and the element sets of the scene's own muscles, which are node sets too.
bool provided(const Scene& scene, const std::string& name) {
  if (mesh_may_provide(scene.mesh, name)) return true;
  return std::any_of(scene.muscles.begin(), scene.muscles.end(),
                     [&](const MuscleSpec& m) { return m.name == name; });
}

// One pass over the YAML tree; the generic accessors (numbers, names, key checks, each naming
// the key path in its error) are the shared reader's.
class Parser : private common::YamlReader {
 public:
  Parser(common::YamlReader yaml, std::string base_dir)
      : YamlReader(std::move(yaml)), base_dir_(std::move(base_dir)) {}

  Scene parse() const {
    const YAML::Node& root = this->root();  // const access never inserts keys
    expect_map(root, "(top level)");
    check_keys(root, "",
               {"mesh", "material", "node_sets", "constraints", "gravity", "loads", "damping",
                "muscles", "muscle_stiffening", "muscle_force_length", "activations", "obstacles",
                "contact", "analysis", "model", "solver", "output"});
    Scene scene;
    scene.source = source();
    scene.text = file_text();
    scene.base_dir = base_dir_;
    read_mesh(required(root, "", "mesh"), "mesh", scene);
    read_material(required(root, "", "material"), "material", scene.material);
    // Muscles before node sets: their element sets are node sets, whose names must not clash.
    if (const auto n = root["muscles"]; present(n)) read_muscles(n, "muscles", scene);
    if (const auto n = root["node_sets"]; present(n)) read_node_sets(n, "node_sets", scene);
    if (const auto n = root["constraints"]; present(n)) read_constraints(n, "constraints", scene);
    if (const auto n = root["gravity"]; present(n)) scene.gravity = vec3(n, "gravity");
    if (const auto n = root["loads"]; present(n)) read_loads(n, "loads", scene);
    if (const auto n = root["damping"]; present(n)) read_damping(n, "damping", scene.damping);
    if (const auto n = root["activations"]; present(n)) read_activations(n, "activations", scene);
    if (const auto n = root["muscle_stiffening"]; present(n)) {
      if (scene.muscle_source == MuscleSource::none) {
        fail("muscle_stiffening", "needs muscles", n);
      }
      scene.muscle_stiffening = positive(n, "muscle_stiffening", "");
      if (scene.muscle_stiffening < 1.0) {
        fail("muscle_stiffening",
             "must be >= 1 (1: no stiffening), got " + number_text(scene.muscle_stiffening), n);
      }
    }
    if (const auto n = root["muscle_force_length"]; present(n)) {
      if (scene.muscle_source == MuscleSource::none) {
        fail("muscle_force_length", "needs muscles", n);
      }
      scene.muscle_force_length = force_length(n, "muscle_force_length");
    }
    if (const auto n = root["obstacles"]; present(n)) read_obstacles(n, "obstacles", scene);
    if (const auto n = root["contact"]; present(n)) {
      if (scene.obstacles.empty()) fail("contact", "needs obstacles", n);
      read_contact(n, "contact", scene.obstacles.contact);
    }
    read_analysis(required(root, "", "analysis"), "analysis", scene.analysis);
    if (const auto n = root["model"]; present(n)) {
      if (scene.analysis.type != AnalysisType::dynamic)
        fail("model", "a reduced model needs a dynamic analysis", n);
      read_model(n, "model", scene.model);
    }
    if (const auto n = root["solver"]; present(n))
      read_solver(n, "solver", scene.solver, scene.solver_keys, scene.threads);
    if (const auto n = root["output"]; present(n)) read_output(n, "output", scene.output);
    check_set_references(root, scene);
    return scene;
  }

 private:
  // ---- scene-specific accessors ----

  // A set or muscle name: it names a dataset in the run file, where '/' would make a group.
  std::string name(const YAML::Node& n, const std::string& path) const {
    const std::string s = text(n, path);
    if (s.empty() || s == "." || s.find('/') != std::string::npos)
      fail(path, "'" + s + "' is not a valid name (non-empty, no '/', not '.')", n);
    return s;
  }

  fem::Vec3 vec3(const YAML::Node& n, const std::string& path) const {
    if (!n.IsSequence() || n.size() != 3) fail(path, "expected a list of 3 numbers", n);
    fem::Vec3 v;
    for (int i = 0; i < 3; ++i) v[i] = number(n[i], index_path(path, i));
    return v;
  }

  // The zero-force length of the force-length relation, in [0, 1), or "constant".
  model::ActiveForceLength force_length(const YAML::Node& n, const std::string& path) const {
    if (n.IsScalar() && n.Scalar() == "constant")
      return model::ActiveForceLength::constant_tension();
    double v = 0.0;
    if (!n.IsScalar() || !YAML::convert<double>::decode(n, v) || !(v >= 0.0 && v < 1.0)) {
      fail(path,
           "expected a zero-force length in [0, 1) (relative to rest) or 'constant', got " +
               describe(n),
           n);
    }
    return model::ActiveForceLength(v);
  }

  // ---- sections ----

  void read_mesh(const YAML::Node& n, const std::string& path, Scene& scene) const {
    expect_map(n, path);
    check_keys(n, path, {"box", "ansys", "tongue"});
    const YAML::Node box = n["box"], ansys = n["ansys"], tongue = n["tongue"];
    const int given = int(present(box)) + int(present(ansys)) + int(present(tongue));
    if (given != 1) fail(path, "give exactly one of 'box', 'ansys' or 'tongue'", n);
    if (present(box)) {
      scene.mesh = read_box(box, child_path(path, "box"));
    } else if (present(ansys)) {
      scene.mesh = read_ansys(ansys, child_path(path, "ansys"));
    } else {
      scene.mesh = read_tongue(tongue, child_path(path, "tongue"));
    }
  }

  TongueMeshSpec read_tongue(const YAML::Node& n, const std::string& path) const {
    expect_map(n, path);
    check_keys(n, path, {"refinement"});
    TongueMeshSpec tongue;
    if (const auto r = n["refinement"]; present(r)) {
      const std::string r_path = child_path(path, "refinement");
      tongue.refinement = at_least(r, r_path, 1);
      // 740 r^3 hexahedra: beyond 8 the mesh no longer fits a workstation's memory.
      if (tongue.refinement > 8) fail(r_path, "must be at most 8", r);
    }
    return tongue;
  }

  BoxMeshSpec read_box(const YAML::Node& n, const std::string& path) const {
    expect_map(n, path);
    check_keys(n, path, {"origin", "size", "divisions"});
    BoxMeshSpec box;
    if (const auto o = n["origin"]; present(o)) box.origin = vec3(o, child_path(path, "origin"));
    const std::string size_path = child_path(path, "size");
    const YAML::Node size = required(n, path, "size");
    box.size = vec3(size, size_path);
    for (int i = 0; i < 3; ++i)
      if (!(box.size[i] > 0.0))
        fail(index_path(size_path, i), "must be positive, got " + number_text(box.size[i]) + " m",
             size);
    const std::string div_path = child_path(path, "divisions");
    const YAML::Node div = required(n, path, "divisions");
    if (!div.IsSequence() || div.size() != 3) fail(div_path, "expected a list of 3 integers", div);
    for (int i = 0; i < 3; ++i) box.divisions[i] = at_least(div[i], index_path(div_path, i), 1);
    return box;
  }

  AnsysMeshSpec read_ansys(const YAML::Node& n, const std::string& path) const {
    expect_map(n, path);
    check_keys(n, path, {"nodes", "elements", "length_scale"});
    AnsysMeshSpec ansys;
    ansys.nodes_path = existing_file(required(n, path, "nodes"), child_path(path, "nodes"), "mesh");
    ansys.elements_path =
        existing_file(required(n, path, "elements"), child_path(path, "elements"), "mesh");
    if (const auto s = n["length_scale"]; present(s))
      ansys.length_scale = positive(s, child_path(path, "length_scale"), "");
    return ansys;
  }

  // The path resolved against the scene's directory; it must name an existing file (`what`:
  // "mesh", "obstacle").
  std::string existing_file(const YAML::Node& n, const std::string& path,
                            const std::string& what) const {
    fs::path p = text(n, path);
    if (p.is_relative() && !base_dir_.empty()) p = fs::path(base_dir_) / p;
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) fail(path, what + " file not found: " + p.string(), n);
    return p.string();
  }

  void read_material(const YAML::Node& n, const std::string& path, MaterialSpec& m) const {
    expect_map(n, path);
    check_keys(n, path, {"type", "parameters", "density", "formulation"});
    const std::string type_path = child_path(path, "type");
    const YAML::Node type = required(n, path, "type");
    m.type = text(type, type_path);
    const auto types = fem::material_types();
    if (std::find(types.begin(), types.end(), m.type) == types.end())
      fail(type_path, "unknown material type '" + m.type + "' (known: " + join(types) + ")", type);
    const std::vector<fem::ParameterSpec>& specs = fem::material_parameters(m.type);

    const std::string params_path = child_path(path, "parameters");
    const YAML::Node params = n["parameters"];
    if (present(params)) {
      expect_map(params, params_path);
      std::vector<std::string> known;
      for (const auto& s : specs) known.push_back(s.name);
      check_keys(params, params_path, known, "parameter of material '" + m.type + "'");
      for (auto it = params.begin(); it != params.end(); ++it) {
        const std::string key = it->first.Scalar();
        const std::string key_path = child_path(params_path, key);
        const double v = number(it->second, key_path);
        const auto spec = std::find_if(specs.begin(), specs.end(),
                                       [&](const fem::ParameterSpec& s) { return s.name == key; });
        if (!spec->in_range(v))
          fail(key_path,
               number_text(v) + (spec->unit == "1" ? "" : " " + spec->unit) + " is out of range (" +
                   number_text(spec->min) + ", " + number_text(spec->max) + "): " + spec->help,
               it->second);
        m.parameters[key] = v;
      }
    }
    if (const auto d = n["density"]; present(d))
      m.density = positive(d, child_path(path, "density"), "kg/m^3");

    // The factory's remaining checks (conflicting pairs, mu0 > 0, required parameters).
    bool split = false;
    try {
      split = fem::make_material(m.type, m.parameters)->as_uncoupled() != nullptr;
    } catch (const std::invalid_argument& e) {
      fail(params_path, e.what(), present(params) ? params : n);
    }
    // Mean dilatation needs the isochoric/volumetric split; without it only standard works.
    m.formulation = split ? fem::Formulation::mean_dilatation : fem::Formulation::standard;
    const std::string form_path = child_path(path, "formulation");
    if (const auto f = n["formulation"]; present(f)) {
      const std::string name = text(f, form_path);
      if (name == "standard") {
        m.formulation = fem::Formulation::standard;
      } else if (name == "mean_dilatation") {
        if (!split)
          fail(form_path,
               "material '" + m.type +
                   "' has no isochoric/volumetric split; use formulation 'standard'",
               f);
        m.formulation = fem::Formulation::mean_dilatation;
      } else {
        fail(form_path, "unknown formulation '" + name + "' (known: mean_dilatation, standard)", f);
      }
    }
  }

  void read_node_sets(const YAML::Node& n, const std::string& path, Scene& scene) const {
    expect_map(n, path);
    std::set<std::string> seen;
    for (auto it = n.begin(); it != n.end(); ++it) {
      const std::string name = this->name(it->first, path);
      const std::string set_path = child_path(path, name);
      if (!seen.insert(name).second) fail(set_path, "set defined twice", it->first);
      if (provided(scene, name))
        fail(set_path, "name is already taken by a node set of the mesh or a muscle", it->first);
      const YAML::Node def = it->second;
      if (!present(def)) fail(set_path, "expected one of 'box', 'ids', 'union'", it->first);
      expect_map(def, set_path);
      check_keys(def, set_path, {"box", "ids", "union", "file", "numbering"});
      NodeSetSpec spec;
      spec.name = name;
      if (present(def["file"])) {
        read_node_list_set(def, set_path, scene, spec);
        scene.node_sets.push_back(std::move(spec));
        continue;
      }
      if (present(def["numbering"]))
        fail(child_path(set_path, "numbering"), "belongs to a node list 'file'", def["numbering"]);
      if (def.size() != 1) fail(set_path, "give exactly one of 'box', 'ids', 'union', 'file'", def);
      if (const auto box = def["box"]; present(box)) {
        const std::string box_path = child_path(set_path, "box");
        expect_map(box, box_path);
        check_keys(box, box_path, {"min", "max"});
        spec.kind = NodeSetSpec::Kind::box;
        spec.box_min = vec3(required(box, box_path, "min"), child_path(box_path, "min"));
        spec.box_max = vec3(required(box, box_path, "max"), child_path(box_path, "max"));
        if ((spec.box_min.array() > spec.box_max.array()).any())
          fail(box_path, "'min' must not exceed 'max' in any component", box);
      } else if (const auto ids = def["ids"]; present(ids)) {
        const std::string ids_path = child_path(set_path, "ids");
        expect_sequence(ids, ids_path);
        if (ids.size() == 0) fail(ids_path, "the set is empty", ids);
        spec.kind = NodeSetSpec::Kind::ids;
        for (std::size_t i = 0; i < ids.size(); ++i)
          spec.ids.push_back(at_least(ids[i], index_path(ids_path, i), 0));
      } else if (const auto members = def["union"]; present(members)) {
        const std::string union_path = child_path(set_path, "union");
        expect_sequence(members, union_path);
        if (members.size() == 0) fail(union_path, "the set is empty", members);
        spec.kind = NodeSetSpec::Kind::set_union;
        for (std::size_t i = 0; i < members.size(); ++i)
          spec.members.push_back(text(members[i], index_path(union_path, i)));
      } else {
        fail(set_path, "give exactly one of 'box', 'ids', 'union'", def);
      }
      scene.node_sets.push_back(std::move(spec));
    }
  }

  // {file: jaw.txt, numbering: one_based}: a node list file (scene/node_list_file.hpp).
  void read_node_list_set(const YAML::Node& def, const std::string& set_path, const Scene& scene,
                          NodeSetSpec& spec) const {
    if (def.size() != 2 || !present(def["numbering"]))
      fail(set_path,
           "a node list file needs 'numbering' (ids, zero_based or one_based) and nothing else",
           def);
    const std::string num_path = child_path(set_path, "numbering");
    const std::string numbering = text(def["numbering"], num_path);
    if (numbering == "ids") {
      spec.numbering = NodeSetSpec::Numbering::ids;
    } else if (numbering == "zero_based") {
      spec.numbering = NodeSetSpec::Numbering::zero_based;
    } else if (numbering == "one_based") {
      spec.numbering = NodeSetSpec::Numbering::one_based;
    } else {
      fail(num_path,
           "unknown numbering '" + numbering +
               "' (known: ids, the mesh's node ids; zero_based and one_based, the position in "
               "the node file counted from 0 or 1)",
           def["numbering"]);
    }
    if (spec.numbering != NodeSetSpec::Numbering::ids &&
        !std::holds_alternative<AnsysMeshSpec>(scene.mesh))
      fail(num_path, "zero_based and one_based count the nodes of an imported mesh (mesh: ansys)",
           def["numbering"]);
    const std::string file_path = child_path(set_path, "file");
    spec.kind = NodeSetSpec::Kind::ids;
    spec.file = existing_file(def["file"], file_path, "node list");
    std::vector<NodeListEntry> entries;
    try {
      entries = read_node_list(spec.file);
    } catch (const std::runtime_error& e) {
      fail(file_path, e.what(), def["file"]);
    }
    for (const auto& entry : entries) {
      if (spec.numbering == NodeSetSpec::Numbering::one_based && entry.number == 0)
        fail(file_path,
             spec.file + ", line " + std::to_string(entry.line) +
                 ": node 0 in a one_based list (is it zero_based?)",
             def["file"]);
      spec.ids.push_back(entry.number);
      spec.lines.push_back(entry.line);
    }
  }

  void read_constraints(const YAML::Node& n, const std::string& path, Scene& scene) const {
    expect_sequence(n, path);
    for (std::size_t i = 0; i < n.size(); ++i) {
      const YAML::Node c = n[i];
      const std::string c_path = index_path(path, i);
      expect_map(c, c_path);
      check_keys(c, c_path, {"set", "components", "displacement"});
      ConstraintSpec spec;
      spec.set = text(required(c, c_path, "set"), child_path(c_path, "set"));
      const std::string comp_path = child_path(c_path, "components");
      const YAML::Node comps = required(c, c_path, "components");
      expect_sequence(comps, comp_path);
      if (comps.size() == 0) fail(comp_path, "list at least one of x, y, z", comps);
      for (std::size_t k = 0; k < comps.size(); ++k) {
        const std::string k_path = index_path(comp_path, k);
        const std::string letter = text(comps[k], k_path);
        const auto* end = std::end(kComponentNames);
        const auto* found = std::find(std::begin(kComponentNames), end, letter);
        if (found == end)
          fail(k_path, "unknown component '" + letter + "' (known: x, y, z)", comps[k]);
        const int component = static_cast<int>(found - std::begin(kComponentNames));
        if (std::find(spec.components.begin(), spec.components.end(), component) !=
            spec.components.end())
          fail(k_path, "component '" + letter + "' listed twice", comps[k]);
        spec.components.push_back(component);
      }
      spec.displacements.assign(spec.components.size(), 0.0);
      const std::string disp_path = child_path(c_path, "displacement");
      if (const auto d = c["displacement"]; present(d)) {
        if (d.IsSequence()) {
          if (d.size() != spec.components.size())
            fail(disp_path,
                 "expected one number or one per component (" +
                     std::to_string(spec.components.size()) + ")",
                 d);
          for (std::size_t k = 0; k < d.size(); ++k)
            spec.displacements[k] = number(d[k], index_path(disp_path, k));
        } else {
          spec.displacements.assign(spec.components.size(), number(d, disp_path));
        }
      }
      scene.constraints.push_back(std::move(spec));
    }
  }

  void read_loads(const YAML::Node& n, const std::string& path, Scene& scene) const {
    expect_sequence(n, path);
    for (std::size_t i = 0; i < n.size(); ++i) {
      const YAML::Node l = n[i];
      const std::string l_path = index_path(path, i);
      expect_map(l, l_path);
      check_keys(l, l_path, {"set", "total_force", "force_per_node"});
      LoadSpec spec;
      spec.set = text(required(l, l_path, "set"), child_path(l_path, "set"));
      const bool total = present(l["total_force"]), per_node = present(l["force_per_node"]);
      if (total == per_node) {
        fail(l_path,
             "give exactly one of total_force (N, spread over the set's boundary faces) "
             "and force_per_node (N on each node)",
             l);
      }
      spec.kind = total ? LoadSpec::Kind::total_force : LoadSpec::Kind::force_per_node;
      const char* key = total ? "total_force" : "force_per_node";
      spec.force = vec3(l[key], child_path(l_path, key));
      scene.loads.push_back(std::move(spec));
    }
  }

  void read_damping(const YAML::Node& n, const std::string& path, fem::RayleighDamping& d) const {
    expect_map(n, path);
    check_keys(n, path, {"alpha", "beta"});
    if (const auto a = n["alpha"]; present(a))
      d.mass_coefficient = non_negative(a, child_path(path, "alpha"), "1/s");
    if (const auto b = n["beta"]; present(b))
      d.stiffness_coefficient = non_negative(b, child_path(path, "beta"), "s");
  }

  void read_muscles(const YAML::Node& n, const std::string& path, Scene& scene) const {
    if (n.IsScalar()) {
      if (n.Scalar() != "builtin")
        fail(path, "expected 'builtin' or a list of muscles, got '" + n.Scalar() + "'", n);
      if (!std::holds_alternative<TongueMeshSpec>(scene.mesh))
        fail(path,
             "'builtin' muscles belong to the built-in tongue (mesh: {tongue: {}}); give a list "
             "of muscles for other meshes",
             n);
      scene.muscle_source = MuscleSource::builtin;
      return;
    }
    if (n.IsMap() && n.size() == 1 && present(n["ansys_macros"]))
      return read_ansys_macros(n, path, scene);
    if (!n.IsSequence())
      fail(path, "expected 'builtin' or a list of muscles, or {ansys_macros: {...}}", n);
    if (n.size() == 0) fail(path, "the list is empty (omit the key for no muscles)", n);
    scene.muscle_source = MuscleSource::list;
    for (std::size_t i = 0; i < n.size(); ++i) {
      const YAML::Node m = n[i];
      const std::string m_path = index_path(path, i);
      expect_map(m, m_path);
      check_keys(m, m_path, {"name", "max_force", "elements", "fibres"});
      MuscleSpec spec;
      const std::string name_path = child_path(m_path, "name");
      const YAML::Node name_node = required(m, m_path, "name");
      spec.name = name(name_node, name_path);
      for (const auto& other : scene.muscles)
        if (other.name == spec.name)
          fail(name_path, "muscle '" + spec.name + "' is defined twice", name_node);
      // Its elements become an element set and a node set of this name.
      if (mesh_may_provide(scene.mesh, spec.name))
        fail(name_path, "name is already taken by a set of the mesh", name_node);
      spec.max_force =
          positive(required(m, m_path, "max_force"), child_path(m_path, "max_force"), "N");
      spec.elements = ids(required(m, m_path, "elements"), child_path(m_path, "elements"));
      const std::string fibres_path = child_path(m_path, "fibres");
      const YAML::Node fibres = required(m, m_path, "fibres");
      expect_sequence(fibres, fibres_path);
      if (fibres.size() == 0) fail(fibres_path, "a muscle needs at least one fibre", fibres);
      for (std::size_t f = 0; f < fibres.size(); ++f) {
        const YAML::Node fibre = fibres[f];
        const std::string f_path = index_path(fibres_path, f);
        expect_map(fibre, f_path);
        check_keys(fibre, f_path, {"nodes", "origin", "weight"});
        FibreSpec fs;
        fs.nodes = ids(required(fibre, f_path, "nodes"), child_path(f_path, "nodes"));
        if (const auto o = fibre["origin"]; present(o))
          fs.origin = vec3(o, child_path(f_path, "origin"));
        if (fs.nodes.size() + (fs.origin ? 1 : 0) < 2)
          fail(f_path, "a fibre needs at least 2 points counting its origin", fibre);
        if (const auto w = fibre["weight"]; present(w))
          fs.weight = positive(w, child_path(f_path, "weight"), "");
        spec.fibres.push_back(std::move(fs));
      }
      scene.muscles.push_back(std::move(spec));
    }
  }

  // muscles: {ansys_macros: {elements, fibres, max_force, external_points, groups}}: the muscles
  // imported from ANSYS macros (model/ansys_muscle_macros.hpp), ids as in the mesh files.
  void read_ansys_macros(const YAML::Node& n, const std::string& path, Scene& scene) const {
    const std::string m_path = child_path(path, "ansys_macros");
    const YAML::Node m = required(n, path, "ansys_macros");
    expect_map(m, m_path);
    check_keys(m, m_path, {"elements", "fibres", "max_force", "external_points", "groups"});
    if (!std::holds_alternative<AnsysMeshSpec>(scene.mesh))
      fail(m_path,
           "ANSYS muscle macros number elements and nodes as the ANSYS mesh files do: they need "
           "mesh: ansys",
           m);
    AnsysMacrosSpec spec;
    spec.elements =
        existing_file(required(m, m_path, "elements"), child_path(m_path, "elements"), "elements");
    spec.fibres =
        existing_file(required(m, m_path, "fibres"), child_path(m_path, "fibres"), "fibres");
    spec.max_force = existing_file(required(m, m_path, "max_force"),
                                   child_path(m_path, "max_force"), "max-force");
    if (const auto e = m["external_points"]; present(e) && e.IsScalar()) {
      // A file of "id x y z" lines (m), e.g. next to the macros.
      const std::string e_path = child_path(m_path, "external_points");
      const std::string file = existing_file(e, e_path, "external points");
      try {
        spec.external_points = read_external_points(file);
      } catch (const std::runtime_error& error) {
        fail(e_path, error.what(), e);
      }
    } else if (present(e)) {
      const std::string e_path = child_path(m_path, "external_points");
      expect_map(e, e_path);
      for (auto it = e.begin(); it != e.end(); ++it) {
        const std::string key = it->first.Scalar();
        const std::string p_path = child_path(e_path, key);
        const long id = at_least(it->first, p_path, 1);
        if (spec.external_points.count(id)) fail(p_path, "point given twice", it->first);
        spec.external_points[id] = vec3(it->second, p_path);
      }
    }
    model::AnsysMuscleFiles files{spec.elements, spec.fibres, spec.max_force, spec.external_points};
    model::ImportedMuscles imported;
    try {
      imported = model::import_ansys_muscles(files);
    } catch (const model::MacroReadError& e) {
      const std::string key = e.path() == spec.elements ? "elements"
                              : e.path() == spec.fibres ? "fibres"
                                                        : "max_force";
      fail(child_path(m_path, key), e.what(), m[key]);
    }
    scene.muscle_source = MuscleSource::list;
    for (auto& muscle : imported.muscles) {
      if (mesh_may_provide(scene.mesh, muscle.name) || muscle.name == "names")
        fail(child_path(m_path, "elements"),
             muscle.source + ": muscle name '" + muscle.name + "' is taken by a set of the mesh",
             m["elements"]);
      MuscleSpec ms;
      ms.name = muscle.name;
      ms.max_force = muscle.max_force;
      ms.elements = std::move(muscle.element_ids);
      ms.source = muscle.source;
      for (auto& fibre : muscle.fibres) {
        FibreSpec fs;
        fs.nodes = std::move(fibre.node_ids);
        fs.origin = fibre.origin;
        fs.source = fibre.source;
        ms.fibres.push_back(std::move(fs));
      }
      scene.muscles.push_back(std::move(ms));
    }
    scene.ansys_macros = std::move(spec);
    if (const auto g = m["groups"]; present(g)) {
      const std::string g_path = child_path(m_path, "groups");
      expect_map(g, g_path);
      for (auto it = g.begin(); it != g.end(); ++it) {
        const std::string group = name(it->first, g_path);
        const std::string group_path = child_path(g_path, group);
        if (scene.muscle_groups.count(group)) fail(group_path, "group defined twice", it->first);
        expect_sequence(it->second, group_path);
        if (it->second.size() == 0) fail(group_path, "the group is empty", it->second);
        std::vector<std::string> members;
        for (std::size_t k = 0; k < it->second.size(); ++k) {
          const std::string k_path = index_path(group_path, k);
          const std::string member = text(it->second[k], k_path);
          if (std::none_of(scene.muscles.begin(), scene.muscles.end(),
                           [&](const MuscleSpec& x) { return x.name == member; })) {
            std::vector<std::string> known;
            for (const auto& x : scene.muscles) known.push_back(x.name);
            fail(k_path, "no imported muscle '" + member + "' (known: " + join(known) + ")",
                 it->second[k]);
          }
          if (contains(members, member))
            fail(k_path, "muscle '" + member + "' listed twice", it->second[k]);
          members.push_back(member);
        }
        scene.muscle_groups[group] = std::move(members);
      }
    }
  }

  // A non-empty list of node or element ids (>= 0; the builder checks them against the mesh).
  std::vector<long> ids(const YAML::Node& n, const std::string& path) const {
    expect_sequence(n, path);
    if (n.size() == 0) fail(path, "the list is empty", n);
    std::vector<long> out;
    for (std::size_t i = 0; i < n.size(); ++i)
      out.push_back(at_least(n[i], index_path(path, i), 0));
    return out;
  }

  void read_activations(const YAML::Node& n, const std::string& path, Scene& scene) const {
    if (scene.muscle_source == MuscleSource::none)
      fail(path, "the scene has no muscles (add 'muscles')", n);
    expect_sequence(n, path);
    for (std::size_t i = 0; i < n.size(); ++i) {
      const YAML::Node a = n[i];
      const std::string a_path = index_path(path, i);
      expect_map(a, a_path);
      check_keys(a, a_path, {"muscles", "group", "level", "force", "start", "end"});
      ActivationSpec spec;
      spec.line = a.Mark().line + 1;
      const YAML::Node muscles = a["muscles"], group = a["group"];
      if (present(muscles) == present(group))
        fail(a_path,
             "give exactly one of 'muscles' (a list of muscle names) and 'group' (every muscle "
             "named G or G_...)",
             a);
      if (present(muscles)) {
        const std::string list_path = child_path(a_path, "muscles");
        expect_sequence(muscles, list_path);
        if (muscles.size() == 0) fail(list_path, "the list is empty", muscles);
        for (std::size_t k = 0; k < muscles.size(); ++k) {
          const std::string k_path = index_path(list_path, k);
          const std::string m = text(muscles[k], k_path);
          if (contains(spec.muscles, m))
            fail(k_path, "muscle '" + m + "' listed twice", muscles[k]);
          spec.muscles.push_back(m);
        }
      } else {
        spec.group = text(group, child_path(a_path, "group"));
        if (spec.group.empty()) fail(child_path(a_path, "group"), "the group name is empty", group);
      }
      const YAML::Node level = a["level"], force = a["force"];
      if (present(level) == present(force))
        fail(a_path,
             "give exactly one of 'level' (in [0, 1] of each muscle's max_force) and 'force' "
             "(N, the total over the muscles)",
             a);
      if (present(level)) {
        const std::string l_path = child_path(a_path, "level");
        const double v = number(level, l_path);
        if (v < 0.0 || v > 1.0)
          fail(l_path, "must lie in [0, 1] (a fraction of max_force), got " + number_text(v),
               level);
        spec.level = v;
      } else {
        spec.force = non_negative(force, child_path(a_path, "force"), "N");
      }
      if (const auto s = a["start"]; present(s))
        spec.start = non_negative(s, child_path(a_path, "start"), "s");
      if (const auto e = a["end"]; present(e)) {
        const std::string e_path = child_path(a_path, "end");
        const double end = number(e, e_path);
        if (!(end > spec.start))
          fail(e_path,
               "must be later than start (" + number_text(spec.start) + " s), got " +
                   number_text(end) + " s",
               e);
        spec.end = end;
      }
      scene.activations.push_back(std::move(spec));
    }
  }

  void read_analysis(const YAML::Node& n, const std::string& path, AnalysisSpec& a) const {
    expect_map(n, path);
    check_keys(
        n, path,
        {"type", "settle", "duration", "dt", "load_steps", "newmark", "lumped_mass", "max_cuts"});
    const std::string type_path = child_path(path, "type");
    const YAML::Node type = required(n, path, "type");
    const std::string name = text(type, type_path);
    if (name == "static") {
      a.type = AnalysisType::static_equilibrium;
    } else if (name == "dynamic") {
      a.type = AnalysisType::dynamic;
    } else {
      fail(type_path, "unknown analysis type '" + name + "' (known: static, dynamic)", type);
    }
    const bool dynamic = a.type == AnalysisType::dynamic;
    if (const auto s = n["settle"]; present(s)) a.settle = boolean(s, child_path(path, "settle"));
    const YAML::Node duration = dynamic ? required(n, path, "duration") : n["duration"];
    if (present(duration)) a.duration = positive(duration, child_path(path, "duration"), "s");
    const YAML::Node dt = dynamic ? required(n, path, "dt") : n["dt"];
    if (present(dt)) {
      a.dt = positive(dt, child_path(path, "dt"), "s");
      // A step longer than the run is almost surely a unit slip (ms for s).
      if (present(duration) && a.dt > a.duration * (1.0 + 1e-12))
        fail(child_path(path, "dt"),
             number_text(a.dt) + " s is longer than the duration " + number_text(a.duration) + " s",
             dt);
    }
    if (const auto s = n["load_steps"]; present(s))
      a.load_steps = at_least(s, child_path(path, "load_steps"), 1);
    if (const auto nm = n["newmark"]; present(nm)) {
      const std::string nm_path = child_path(path, "newmark");
      expect_map(nm, nm_path);
      check_keys(nm, nm_path, {"beta", "gamma", "spectral_radius"});
      if (const auto r = nm["spectral_radius"]; present(r)) {
        const std::string r_path = child_path(nm_path, "spectral_radius");
        if (present(nm["beta"]) || present(nm["gamma"]))
          fail(r_path, "sets beta and gamma itself: give it or them, not both", r);
        const double rho = number(r, r_path);
        try {
          a.newmark = fem::NewmarkParameters::bossak(rho);
        } catch (const std::invalid_argument& e) {
          fail(r_path, std::string(e.what()) + ", got " + number_text(rho), r);
        }
      }
      if (const auto b = nm["beta"]; present(b))
        a.newmark.beta = positive(b, child_path(nm_path, "beta"), "");
      if (const auto g = nm["gamma"]; present(g)) {
        a.newmark.gamma = number(g, child_path(nm_path, "gamma"));
        // gamma < 1/2 adds negative numerical damping: the scheme grows without bound.
        if (a.newmark.gamma < 0.5)
          fail(child_path(nm_path, "gamma"),
               "must be at least 0.5, got " + number_text(a.newmark.gamma), g);
      }
    }
    if (const auto l = n["lumped_mass"]; present(l))
      a.lumped_mass = boolean(l, child_path(path, "lumped_mass"));
    if (const auto c = n["max_cuts"]; present(c)) {
      a.max_cuts = at_least(c, child_path(path, "max_cuts"), 0);
      // 2^30 substeps would take forever; more cuts than this only hide a broken scene.
      if (a.max_cuts > 30) fail(child_path(path, "max_cuts"), "must be at most 30", c);
    }
  }

  void read_solver(const YAML::Node& n, const std::string& path, fem::NewtonSettings& s,
                   std::set<std::string>& keys, int& threads) const {
    expect_map(n, path);
    check_keys(
        n, path,
        {"residual_rtol", "residual_atol", "increment_rtol", "increment_atol", "max_iterations",
         "line_search", "max_tangent_reuse", "reform_ratio", "quasi_newton_updates",
         "displacement_tolerance", "single_precision_solve", "threads"});
    const auto get = [&](const char* key, auto&& read) {
      if (const auto v = n[key]; present(v)) {
        read(v, child_path(path, key));
        keys.insert(key);
      }
    };
    get("residual_rtol", [&](auto v, auto p) { s.residual_rtol = non_negative(v, p, ""); });
    get("residual_atol", [&](auto v, auto p) { s.residual_atol = non_negative(v, p, "N"); });
    get("increment_rtol", [&](auto v, auto p) { s.increment_rtol = non_negative(v, p, ""); });
    get("increment_atol", [&](auto v, auto p) { s.increment_atol = non_negative(v, p, "m"); });
    get("displacement_tolerance",
        [&](auto v, auto p) { s.displacement_tolerance = non_negative(v, p, "m"); });
    get("max_iterations", [&](auto v, auto p) { s.max_iterations = at_least(v, p, 1); });
    get("line_search", [&](auto v, auto p) { s.line_search = boolean(v, p); });
    get("single_precision_solve",
        [&](auto v, auto p) { s.single_precision_solve = boolean(v, p); });
    get("max_tangent_reuse", [&](auto v, auto p) { s.max_tangent_reuse = at_least(v, p, 0); });
    get("quasi_newton_updates",
        [&](auto v, auto p) { s.quasi_newton_updates = at_least(v, p, 0); });
    get("threads", [&](auto v, auto p) {
      threads = at_least(v, p, 1);
      if (threads > 2) fail(p, "must be 1 or 2, got " + std::to_string(threads), v);
    });
    get("reform_ratio", [&](auto v, auto p) {
      s.reform_ratio = positive(v, p, "");
      if (s.reform_ratio > 1.0) fail(p, "must not exceed 1, got " + number_text(s.reform_ratio), v);
    });
  }

  void read_obstacles(const YAML::Node& n, const std::string& path, Scene& scene) const {
    const auto vocal_tract = [&](const YAML::Node& v, const std::string& v_path) {
      if (v.Scalar() != "vocal_tract")
        fail(v_path, "expected 'vocal_tract' or an obstacle file, got '" + v.Scalar() + "'", v);
      if (!std::holds_alternative<TongueMeshSpec>(scene.mesh))
        fail(v_path, "the built-in vocal tract fits the built-in tongue (mesh: {tongue: {}})", v);
      if (scene.obstacles.vocal_tract) fail(v_path, "the vocal tract is given twice", v);
      scene.obstacles.vocal_tract = true;
    };
    if (n.IsScalar()) return vocal_tract(n, path);
    if (!n.IsSequence() || n.size() == 0)
      fail(path, "expected 'vocal_tract' or a list of 'vocal_tract' and obstacle files", n);
    for (std::size_t i = 0; i < n.size(); ++i) {
      const YAML::Node o = n[i];
      const std::string o_path = index_path(path, i);
      if (o.IsScalar()) {
        vocal_tract(o, o_path);
        continue;
      }
      expect_map(o, o_path);
      check_keys(o, o_path, {"name", "file", "length_scale", "rotate", "translate", "normals"});
      ObstacleFileSpec spec;
      const YAML::Node name_node = required(o, o_path, "name");
      spec.name = name(name_node, child_path(o_path, "name"));
      if (spec.name == "names")  // the run file's list of obstacles sits beside them
        fail(child_path(o_path, "name"), "'names' is reserved; choose another name", name_node);
      for (const auto& other : scene.obstacles.files)
        if (other.name == spec.name)
          fail(child_path(o_path, "name"), "obstacle '" + spec.name + "' is defined twice",
               name_node);
      spec.path =
          existing_file(required(o, o_path, "file"), child_path(o_path, "file"), "obstacle");
      if (const auto v = o["length_scale"]; present(v))
        spec.length_scale = positive(v, child_path(o_path, "length_scale"), "");
      if (const auto v = o["rotate"]; present(v))
        spec.rotate_deg = vec3(v, child_path(o_path, "rotate"));
      if (const auto v = o["translate"]; present(v))
        spec.translate = vec3(v, child_path(o_path, "translate"));
      if (const auto v = o["normals"]; present(v)) {
        const std::string normals_path = child_path(o_path, "normals");
        const std::string kind = text(v, normals_path);
        if (kind == "smooth")
          spec.normals = fem::Normals::smooth;
        else if (kind != "faceted")
          fail(normals_path, "unknown normals '" + kind + "' (known: faceted, smooth)", v);
      }
      scene.obstacles.files.push_back(std::move(spec));
    }
  }

  void read_contact(const YAML::Node& n, const std::string& path, fem::ContactSettings& c) const {
    expect_map(n, path);
    check_keys(
        n, path,
        {"penalty", "smoothing", "search_depth", "penetration_tolerance", "max_augmentations"});
    if (const auto v = n["penalty"]; present(v))
      c.penalty = positive(v, child_path(path, "penalty"), "Pa/m");
    if (const auto v = n["smoothing"]; present(v))
      c.smoothing = positive(v, child_path(path, "smoothing"), "m");
    if (const auto v = n["search_depth"]; present(v))
      c.search_depth = positive(v, child_path(path, "search_depth"), "m");
    if (const auto v = n["penetration_tolerance"]; present(v))
      c.penetration_tolerance = non_negative(v, child_path(path, "penetration_tolerance"), "m");
    if (const auto v = n["max_augmentations"]; present(v))
      c.max_augmentations = at_least(v, child_path(path, "max_augmentations"), 0);
  }

  void read_model(const YAML::Node& n, const std::string& path, ModelSpec& m) const {
    expect_map(n, path);
    check_keys(n, path, {"reduced", "check_every", "warn_above", "switch_to_full"});
    m.reduced =
        existing_file(required(n, path, "reduced"), child_path(path, "reduced"), "reduced basis");
    if (const auto c = n["check_every"]; present(c))
      m.check_every = at_least(c, child_path(path, "check_every"), 0);
    if (const auto w = n["warn_above"]; present(w))
      m.warn_above = positive(w, child_path(path, "warn_above"), "m");
    if (const auto s = n["switch_to_full"]; present(s))
      m.switch_to_full = boolean(s, child_path(path, "switch_to_full"));
  }

  void read_output(const YAML::Node& n, const std::string& path, OutputSpec& o) const {
    expect_map(n, path);
    check_keys(n, path, {"file", "every", "compression"});
    if (const auto f = n["file"]; present(f)) o.file = text(f, child_path(path, "file"));
    if (const auto e = n["every"]; present(e)) o.every = at_least(e, child_path(path, "every"), 1);
    if (const auto c = n["compression"]; present(c))
      o.compression = between(c, child_path(path, "compression"), 0, 9);
  }

  // Every set named by a union, constraint or load exists, and unions do not refer to
  // themselves. Names the mesh may provide are checked against the real mesh by the builder.
  void check_set_references(const YAML::Node& root, const Scene& scene) const {
    std::map<std::string, const NodeSetSpec*> defined;
    for (const auto& s : scene.node_sets) defined[s.name] = &s;
    const auto known = [&](const std::string& name) {
      return defined.count(name) != 0 || provided(scene, name);
    };
    const auto unknown = [&](const std::string& name) {
      std::vector<std::string> names;
      if (std::holds_alternative<BoxMeshSpec>(scene.mesh))
        names = box_set_names();
      else if (std::holds_alternative<TongueMeshSpec>(scene.mesh))
        names = tongue_set_names();
      else
        names = {"all", "mat_<n>"};
      for (const auto& m : scene.muscles) names.push_back(m.name);
      for (const auto& s : scene.node_sets) names.push_back(s.name);
      return "unknown node set '" + name + "' (known: " + join(names) + ")";
    };

    const YAML::Node sets = root["node_sets"];
    for (const auto& s : scene.node_sets) {
      for (std::size_t i = 0; i < s.members.size(); ++i) {
        if (!known(s.members[i])) {
          const YAML::Node at = sets[s.name]["union"][i];
          fail(index_path("node_sets." + s.name + ".union", i), unknown(s.members[i]), at);
        }
      }
    }
    // Depth-first search for a union that contains itself; the message spells out the cycle.
    std::map<std::string, int> state;  // 1: on the current path, 2: done
    std::vector<std::string> stack;
    std::function<void(const NodeSetSpec&)> visit = [&](const NodeSetSpec& s) {
      state[s.name] = 1;
      stack.push_back(s.name);
      for (const auto& m : s.members) {
        const auto it = defined.find(m);
        if (it == defined.end()) continue;
        if (state[m] == 1) {
          std::string cycle;
          for (auto n = std::find(stack.begin(), stack.end(), m); n != stack.end(); ++n)
            cycle += *n + " -> ";
          fail("node_sets." + m + ".union", "the unions form a cycle: " + cycle + m, sets[m]);
        }
        if (state[m] == 0) visit(*it->second);
      }
      stack.pop_back();
      state[s.name] = 2;
    };
    for (const auto& s : scene.node_sets)
      if (state[s.name] == 0) visit(s);

    for (std::size_t i = 0; i < scene.constraints.size(); ++i)
      if (!known(scene.constraints[i].set))
        fail(index_path("constraints", i) + ".set", unknown(scene.constraints[i].set),
             root["constraints"][i]["set"]);
    for (std::size_t i = 0; i < scene.loads.size(); ++i)
      if (!known(scene.loads[i].set))
        fail(index_path("loads", i) + ".set", unknown(scene.loads[i].set), root["loads"][i]["set"]);
  }

  std::string base_dir_;
};

}  // namespace

Scene read_scene(const std::string& path) {
  return Parser(common::YamlReader::load(path), fs::path(path).parent_path().string()).parse();
}

Scene parse_scene(const std::string& yaml_text, const std::string& base_dir,
                  const std::string& source_name) {
  return Parser(common::YamlReader::parse(yaml_text, source_name), base_dir).parse();
}

}  // namespace tongue::scene
