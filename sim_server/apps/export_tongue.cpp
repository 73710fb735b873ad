// export_tongue DIR [--refinement R] [--unit mm|m]
//
// Writes the built-in tongue as a user's folder of Grenoble files (docs/your_tongue.md): the
// mesh (tongue.node, tongue.elem), the muscles (CreateMuscles.mac, Fibers.mac,
// MuscleMaxForce.txt) and their bony origins (external_points.txt), the attached nodes
// (jaw_nodes.txt, hyoid_nodes.txt, root_bottom_nodes.txt) and the landmarks (landmarks/*.txt);
// model/grenoble_folder_writer.hpp. --unit is the unit of the mesh files: mm (default), as the
// scene templates scenes/templates/grenoble_*.yaml read them, or m (length_scale: 1), which
// reads back bit for bit.
//
// Exit status (common/exit_code.hpp): 0 written; 1 bad command line or a file that cannot be
// written.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "common/exit_code.hpp"
#include "common/number_text.hpp"
#include "model/grenoble_folder_writer.hpp"

namespace tongue::apps {
namespace {

struct Options {
  std::string dir;
  int refinement = 1;
  double length_scale = 1e-3;  // m per file unit
};

void print_usage(std::FILE* to) {
  std::fprintf(to,
               "usage: export_tongue DIR [--refinement R] [--unit mm|m]\n"
               "  DIR             the folder to write (created if missing)\n"
               "  --refinement R  the built-in tongue's refinement, an integer >= 1 (default 1)\n"
               "  --unit U        unit of tongue.node: mm (default, as the templates read) or m\n"
               "exit status: 0 written, 1 error\n");
}

std::optional<Options> parse_arguments(int argc, char** argv) {
  Options o;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      print_usage(stdout);
      std::exit(common::kExitOk);
    }
    if (arg.rfind("--", 0) != 0) {
      positional.push_back(arg);
      continue;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "export_tongue: %s needs a value\n", arg.c_str());
      return std::nullopt;
    }
    const std::string value = argv[++i];
    if (arg == "--refinement") {
      const std::optional<double> r = common::parse_number(value);
      if (!r || *r < 1 || *r > 8 || *r != static_cast<int>(*r)) {
        std::fprintf(stderr, "export_tongue: --refinement needs an integer 1..8, got '%s'\n",
                     value.c_str());
        return std::nullopt;
      }
      o.refinement = static_cast<int>(*r);
    } else if (arg == "--unit") {
      if (value != "mm" && value != "m") {
        std::fprintf(stderr, "export_tongue: --unit is mm or m, got '%s'\n", value.c_str());
        return std::nullopt;
      }
      o.length_scale = value == "mm" ? 1e-3 : 1.0;
    } else {
      std::fprintf(stderr, "export_tongue: unknown option '%s'\n", arg.c_str());
      return std::nullopt;
    }
  }
  if (positional.size() != 1) {
    std::fprintf(stderr, "export_tongue: expected one folder, got %zu arguments\n",
                 positional.size());
    return std::nullopt;
  }
  o.dir = positional[0];
  return o;
}

int run(const Options& o) {
  const model::GrenobleFolder folder =
      model::write_builtin_tongue_folder(o.dir, o.refinement, o.length_scale);
  std::printf("wrote the built-in tongue (refinement %d, mesh in %s) to %s\n", o.refinement,
              o.length_scale == 1.0 ? "m" : "mm", o.dir.c_str());
  std::printf("%zu bundles:", folder.bundles.size());
  for (const std::string& name : folder.bundles) std::printf(" %s", name.c_str());
  std::printf("\n%zu external points (external_points.txt): ids %ld..%ld\n",
              folder.external_points.size(), folder.external_points.begin()->first,
              folder.external_points.rbegin()->first);
  return common::kExitOk;
}

}  // namespace
}  // namespace tongue::apps

int main(int argc, char** argv) {
  const auto options = tongue::apps::parse_arguments(argc, argv);
  if (!options) {
    tongue::apps::print_usage(stderr);
    return tongue::common::kExitError;
  }
  try {
    return tongue::apps::run(*options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "export_tongue: %s\n", e.what());
    return tongue::common::kExitError;
  }
}
