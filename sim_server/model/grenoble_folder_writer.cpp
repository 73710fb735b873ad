#include "model/grenoble_folder_writer.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <system_error>

#include "fem/mesh/ansys_writer.hpp"
#include "model/ansys_muscle_macro_writer.hpp"
#include "model/default_tongue.hpp"

namespace tongue::model {

namespace {

namespace fs = std::filesystem;

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

// Writes text produced by write_lines(file) to path; throws naming the file on failure.
template <class F>
void write_text(const fs::path& path, F write_lines) {
  std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "wb"));
  if (!f) throw std::runtime_error(path.string() + ": cannot be written");
  write_lines(f.get());
  const bool failed = std::ferror(f.get()) != 0;
  if (std::fclose(f.release()) != 0 || failed)
    throw std::runtime_error(path.string() + ": write error");
}

// A node set as one node number per line: index + 1 (one-based, and the node's id).
void write_node_list(const fs::path& path, const std::vector<int>& nodes) {
  write_text(path, [&](std::FILE* f) {
    for (int n : nodes) std::fprintf(f, "%d\n", n + 1);
  });
}

}  // namespace

std::string grenoble_bundle_name(const std::string& builtin_name) {
  static const std::map<std::string, std::string> groups = {
      {"GGp", "GGP"}, {"GGm", "GGM"}, {"GGa", "GGA"}, {"HG", "HG"},  {"SG", "STY"},
      {"SL", "SL"},   {"IL", "IL"},   {"T", "TRANS"}, {"V", "VERT"}, {"MH", "MH"}};
  std::string group = builtin_name, side;
  for (const auto& [suffix, short_side] : {std::pair{"_left", "_L"}, std::pair{"_right", "_R"}}) {
    const std::string s = suffix;
    if (builtin_name.size() > s.size() &&
        builtin_name.compare(builtin_name.size() - s.size(), s.size(), s) == 0) {
      group = builtin_name.substr(0, builtin_name.size() - s.size());
      side = short_side;
    }
  }
  const auto it = groups.find(group);
  if (it == groups.end())
    throw std::invalid_argument("grenoble_bundle_name: '" + builtin_name +
                                "' is not a built-in muscle");
  return it->second + side;
}

GrenobleFolder write_builtin_tongue_folder(const std::string& dir, int refinement,
                                           double length_scale) {
  if (refinement < 1)
    throw std::invalid_argument("write_builtin_tongue_folder: refinement " +
                                std::to_string(refinement) + " is below 1");
  if (!(length_scale > 0.0) || !std::isfinite(length_scale))
    throw std::invalid_argument(
        "write_builtin_tongue_folder: length_scale must be positive and finite");
  const TongueModel model = make_default_tongue(refinement);
  const fem::Mesh& mesh = model.mesh;
  const fs::path root(dir);
  std::error_code ec;
  fs::create_directories(root / "landmarks", ec);
  if (ec)
    throw std::runtime_error((root / "landmarks").string() + ": cannot be created (" +
                             ec.message() + ")");

  // The mesh alone: ids index + 1, one material.
  fem::ImportedMesh imported;
  imported.mesh.nodes = mesh.nodes;
  imported.mesh.elements = mesh.elements;
  fem::write_ansys_mesh(imported, (root / "tongue.node").string(), (root / "tongue.elem").string(),
                        length_scale);

  // Muscles, with one id after the last node for each distinct origin.
  GrenobleFolder out;
  std::vector<MacroMuscle> macros;
  long next_id = static_cast<long>(mesh.num_nodes()) + 1;
  for (const Muscle& m : model.muscles) {
    MacroMuscle macro;
    macro.name = grenoble_bundle_name(m.name);
    macro.max_force = m.max_force;
    for (int e : m.elements) macro.element_ids.push_back(e + 1);
    for (const Fibre& fibre : m.fibres) {
      std::vector<long> points;
      if (fibre.origin) {
        long id = 0;
        for (const auto& [known, position] : out.external_points)
          if (position == *fibre.origin) id = known;
        if (id == 0) {
          id = next_id++;
          out.external_points[id] = *fibre.origin;
        }
        points.push_back(id);
      }
      for (int n : fibre.nodes) points.push_back(n + 1);
      macro.fibres.push_back(std::move(points));
    }
    out.bundles.push_back(macro.name);
    macros.push_back(std::move(macro));
  }
  write_ansys_muscle_macros(macros, (root / "CreateMuscles.mac").string(),
                            (root / "Fibers.mac").string(), (root / "MuscleMaxForce.txt").string());
  write_text(root / "external_points.txt", [&](std::FILE* f) {
    std::fprintf(f, "# id x y z [m]: the fibres' bony origins (ids of Fibers.mac)\n");
    for (const auto& [id, p] : out.external_points)
      std::fprintf(f, "%ld %.17g %.17g %.17g\n", id, p.x(), p.y(), p.z());
  });

  write_node_list(root / "jaw_nodes.txt", mesh.node_set("mandible"));
  write_node_list(root / "hyoid_nodes.txt", mesh.node_set("hyoid"));
  write_node_list(root / "root_bottom_nodes.txt", mesh.node_set("root_bottom"));
  for (const char* name : {"tip", "blade", "palatal_dorsum", "velar_dorsum", "root"})
    write_node_list(root / "landmarks" / (std::string(name) + ".txt"), mesh.node_set(name));
  return out;
}

}  // namespace tongue::model
