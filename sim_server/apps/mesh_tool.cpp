// mesh_tool check NODES ELEMENTS [--scale S]
// mesh_tool regularize NODES ELEMENTS --out-nodes FILE --out-elements FILE [--scale S]
//                      [--max-displacement-mm D]
//
// Checks a hexahedral mesh in ANSYS NWRITE/EWRITE text for irregular elements (nodal Jacobian
// determinant not positive at some corner, Gerard et al. 2003 sec. II.3), and regularizes it
// after Luboz et al. (2001), writing it back in the same format with the original ids.
// --scale is the length of one file unit in metres (1e-3 for a file in mm; default 1).
//
// Exit status (common/exit_code.hpp): 0 every element regular (after regularization, for
// regularize); 1 bad command line, unreadable or malformed mesh, an output that cannot be
// written, or irregular elements remaining: the mesh is bad input for a scene (regularize still
// writes its best attempt, for inspection; the report on stdout says which elements).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/exit_code.hpp"
#include "common/number_text.hpp"
#include "fem/mesh/ansys_reader.hpp"
#include "fem/mesh/ansys_writer.hpp"
#include "fem/mesh/mesh_quality.hpp"
#include "fem/mesh/regularization.hpp"

namespace tongue::apps {
namespace {

using common::kExitError;
using common::kExitOk;
// Irregular elements make the mesh unusable: an input error, not a silence (3).
constexpr int kExitIrregular = common::kExitError;
constexpr int kMaxIdsListed = 20;

struct Options {
  std::string command;  // "check" or "regularize"
  std::string nodes, elements;
  std::string out_nodes, out_elements;
  double scale = 1.0;                // m per file unit
  double max_displacement_mm = 1.0;  // the paper's bound
};

void print_usage(std::FILE* to) {
  std::fprintf(to,
               "usage: mesh_tool check NODES ELEMENTS [--scale S]\n"
               "       mesh_tool regularize NODES ELEMENTS --out-nodes FILE --out-elements FILE\n"
               "                 [--scale S] [--max-displacement-mm D]\n"
               "  NODES, ELEMENTS          ANSYS NWRITE node and EWRITE element text files\n"
               "  --scale S                metres per file unit (1e-3 for mm; default 1)\n"
               "  --max-displacement-mm D  no node moves farther than D mm (default 1)\n"
               "exit status: 0 all elements regular, 1 irregular elements remain or error\n");
}

// Returns nullopt (after printing why) on a bad command line.
std::optional<Options> parse_arguments(int argc, char** argv) {
  Options o;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      print_usage(stdout);
      std::exit(kExitOk);
    }
    if (arg.rfind("--", 0) != 0) {
      positional.push_back(arg);
      continue;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "mesh_tool: %s needs a value\n", arg.c_str());
      return std::nullopt;
    }
    const std::string value = argv[++i];
    if (arg == "--out-nodes") {
      o.out_nodes = value;
    } else if (arg == "--out-elements") {
      o.out_elements = value;
    } else if (arg == "--scale") {
      const std::optional<double> scale = common::parse_number(value);
      if (!scale || !(*scale > 0)) {
        std::fprintf(stderr, "mesh_tool: --scale needs a positive number, got '%s'\n",
                     value.c_str());
        return std::nullopt;
      }
      o.scale = *scale;
    } else if (arg == "--max-displacement-mm") {
      const std::optional<double> d = common::parse_number(value);
      if (!d || *d < 0) {
        std::fprintf(stderr, "mesh_tool: --max-displacement-mm needs a number >= 0, got '%s'\n",
                     value.c_str());
        return std::nullopt;
      }
      o.max_displacement_mm = *d;
    } else {
      std::fprintf(stderr, "mesh_tool: unknown option '%s'\n", arg.c_str());
      return std::nullopt;
    }
  }
  if (positional.size() != 3 || (positional[0] != "check" && positional[0] != "regularize")) {
    std::fprintf(stderr,
                 "mesh_tool: expected a command (check or regularize), a node file and "
                 "an element file\n");
    return std::nullopt;
  }
  o.command = positional[0];
  o.nodes = positional[1];
  o.elements = positional[2];
  if (o.command == "regularize" && (o.out_nodes.empty() || o.out_elements.empty())) {
    std::fprintf(stderr, "mesh_tool: regularize needs --out-nodes and --out-elements\n");
    return std::nullopt;
  }
  if (o.command == "check" && (!o.out_nodes.empty() || !o.out_elements.empty())) {
    std::fprintf(stderr, "mesh_tool: check writes nothing; --out-* belong to regularize\n");
    return std::nullopt;
  }
  return o;
}

// ANSYS id of every element index, to report elements as the meshing tool shows them.
std::vector<long> element_ids(const fem::ImportedMesh& m) {
  std::vector<long> ids(m.mesh.num_elements());
  for (const auto& [id, index] : m.element_index_of_id) ids[index] = id;
  return ids;
}

std::string id_list(const std::vector<int>& elements, const std::vector<long>& ids) {
  std::string s;
  for (std::size_t i = 0; i < elements.size() && i < kMaxIdsListed; ++i) {
    if (!s.empty()) s += ' ';
    s += std::to_string(ids[elements[i]]);
  }
  if (elements.size() > kMaxIdsListed) {
    s += " ... (" + std::to_string(elements.size() - kMaxIdsListed) + " more)";
  }
  return s;
}

void print_quality(const char* label, const fem::Mesh& mesh, const fem::QualityReport& q,
                   const std::vector<long>& ids) {
  const int n = mesh.num_elements();
  std::printf("%sirregular elements: %d of %d (%.1f %%)\n", label, q.num_irregular, n,
              n > 0 ? 100.0 * q.num_irregular / n : 0.0);
  if (q.num_irregular > 0) {
    std::printf("%s  ANSYS ids: %s\n", label, id_list(q.irregular_elements, ids).c_str());
  }
  if (q.worst_element >= 0) {
    std::printf("%sworst element quality (min/max nodal det J): %.4g in element %ld\n", label,
                q.worst_ratio, ids[q.worst_element]);
  }
  std::printf("%svolume: %.6g cm^3\n", label, q.total_volume * 1e6);
}

int check(const fem::ImportedMesh& m) {
  const std::vector<long> ids = element_ids(m);
  std::printf("nodes: %d\nelements: %d\n", m.mesh.num_nodes(), m.mesh.num_elements());
  std::printf("bounding box: %s\n", fem::bounding_box_text(m.mesh).c_str());
  const fem::QualityReport q = fem::check_quality(m.mesh);
  print_quality("", m.mesh, q, ids);
  if (const std::string why = fem::implausible_size(m.mesh, q.total_volume); !why.empty()) {
    std::fflush(stdout);
    std::fprintf(stderr, "mesh_tool: error: %s\n", why.c_str());
    return kExitError;
  }
  return q.num_irregular == 0 ? kExitOk : kExitIrregular;
}

int regularize(const Options& o, fem::ImportedMesh m) {
  const std::vector<long> ids = element_ids(m);
  std::printf("nodes: %d\nelements: %d\n", m.mesh.num_nodes(), m.mesh.num_elements());
  print_quality("before: ", m.mesh, fem::check_quality(m.mesh), ids);

  fem::RegularizationSettings settings;
  settings.max_displacement = o.max_displacement_mm * 1e-3;
  const fem::RegularizationReport r = fem::regularize(m.mesh, settings);
  std::printf("regularization: %s\n", r.message.c_str());
  std::printf("iterations: %d\n", r.iterations);
  std::printf("largest node displacement: %.4f mm (bound %.4g mm)\n", r.max_node_displacement * 1e3,
              o.max_displacement_mm);
  print_quality("after: ", m.mesh, fem::check_quality(m.mesh), ids);

  fem::write_ansys_mesh(m, o.out_nodes, o.out_elements, o.scale);
  std::printf("wrote %s and %s\n", o.out_nodes.c_str(), o.out_elements.c_str());
  if (!r.success) {
    std::fflush(stdout);  // keep the report before the error on a shared terminal
    std::fprintf(stderr,
                 "mesh_tool: %d elements still irregular (ANSYS ids %s); the mesh "
                 "written is not fit for finite-element analysis\n",
                 r.irregular_after, id_list(r.still_irregular, ids).c_str());
    return kExitIrregular;
  }
  return kExitOk;
}

}  // namespace
}  // namespace tongue::apps

int main(int argc, char** argv) {
  using namespace tongue;
  const auto options = apps::parse_arguments(argc, argv);
  if (!options) {
    apps::print_usage(stderr);
    return apps::kExitError;
  }
  try {
    const fem::ImportedMesh mesh =
        fem::read_ansys_mesh(options->nodes, options->elements, options->scale);
    std::printf("mesh: %s, %s (%.6g m per file unit)\n", options->nodes.c_str(),
                options->elements.c_str(), options->scale);
    return options->command == "check" ? apps::check(mesh) : apps::regularize(*options, mesh);
  } catch (const std::exception& e) {
    // MeshReadError names the file and the line; writer errors name the file.
    std::fflush(stdout);
    std::fprintf(stderr, "mesh_tool: error: %s\n", e.what());
    return apps::kExitError;
  }
}
