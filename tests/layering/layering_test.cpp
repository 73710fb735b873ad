// The dependency order of sim_server/CMakeLists.txt, checked on the sources: every #include of a
// file is matched against what its folder may use, and a failure names the file, the line and
// the rule, e.g.
//   sim_server/fem/mesh/mesh.hpp:8: #include "scene/scene.hpp": fem/ uses nothing outside fem/
// Each library's include root (cmake/TongueHeaders.cmake) already stops an include of a target
// it does not link; this states the rule itself, so that a link added across the layers fails
// here too.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#ifndef TONGUE_SOURCE_DIR
#error "TONGUE_SOURCE_DIR must name the source tree"
#endif

namespace tongue::layering {
namespace {

namespace fs = std::filesystem;

// What a folder may include: project folders (the first component of a quoted or angled path,
// e.g. "fem" for "fem/mesh/mesh.hpp") and the third-party headers it must not use. A quoted
// include without a folder ("experiment_file.hpp") is the including folder's own.
struct Rule {
  std::string folder;             // relative to the source root, e.g. "sim_server/fem"
  std::set<std::string> allowed;  // project folders it may include
  std::set<std::string> foreign;  // third-party headers it must not include
  std::string text;               // the rule, as a failure states it
};

const std::set<std::string>& project_folders() {
  static const std::set<std::string> folders = {
      "common", "fem", "model",    "reduced",    "scene",         "scene_run",       "server",
      "apps",   "bus", "run_file", "controller", "ep_controller", "sequence_player", "replay",
      "viewer"};
  return folders;
}

const std::set<std::string> kControllerFolders = {"controller", "ep_controller", "sequence_player",
                                                  "replay"};

std::set<std::string> with(std::set<std::string> a, const std::set<std::string>& b) {
  a.insert(b.begin(), b.end());
  return a;
}

// The first component of an include path; "hdf5.h" and "H5public.h" count as "hdf5".
std::string first_component(const std::string& header) {
  if (header == "hdf5.h" || header.rfind("H5", 0) == 0) return "hdf5";
  return header.substr(0, header.find('/'));
}

const std::vector<Rule>& rules() {
  static const std::vector<Rule> r = {
      {"sim_server/common",
       {"common"},
       {"Eigen", "hdf5", "lcm", "tongue_lcm"},
       "common/ uses nothing of the project outside common/ (yaml-cpp and std only)"},
      {"sim_server/fem",
       {"fem"},
       {"yaml-cpp", "hdf5", "lcm", "tongue_lcm"},
       "fem/ uses nothing outside fem/ (std, Eigen, CGAL, Assimp and system headers only)"},
      {"sim_server/model",
       {"common", "fem", "model"},
       {"yaml-cpp", "hdf5", "lcm", "tongue_lcm"},
       "model/ sits on fem/ and common/: no scene/, server/, bus/ or run_file/"},
      {"sim_server/reduced",
       {"fem", "reduced"},
       {"yaml-cpp", "lcm", "tongue_lcm"},
       "reduced/ sits on the FEM core only: the scene and the apps give it the runs"},
      {"sim_server/run_file",
       {"run_file"},
       {"yaml-cpp", "lcm", "tongue_lcm"},
       "run_file/ is HDF5 and Eigen only: no fem/ or any other layer"},
      {"sim_server/bus",
       {"bus", "common"},
       {"hdf5", "yaml-cpp"},
       "bus/ is the message types and LCM: no fem/, model/, scene/, scene_run/ or server/"},
      {"sim_server/scene",
       {"common", "fem", "model", "scene"},
       {"hdf5", "lcm", "tongue_lcm"},
       "scene/ sits on model/: no scene_run/, server/, bus/ or run_file/"},
      {"sim_server/scene_run",
       {"common", "fem", "model", "reduced", "scene", "scene_run", "run_file"},
       {"lcm", "tongue_lcm"},
       "scene_run/ sits on scene/, reduced/ and run_file/: no server/ or bus/"},
      {"sim_server/server",
       {"common", "fem", "model", "reduced", "scene", "scene_run", "run_file", "bus", "server"},
       {},
       "server/ uses the layers below it, never apps/"},
      {"controllers",
       with({"common", "bus", "run_file"}, kControllerFolders),
       {},
       "controllers/ use common/, bus/ and run_file/, never fem/, model/, scene/, scene_run/ or "
       "server/"},
      {"viewer",
       {"common", "bus", "run_file", "controller", "fem", "model", "viewer"},
       {"yaml-cpp"},
       "viewer/ watches the bus as a controller does and reads run files; of the model it uses "
       "the mesh's boundary and the landmarks' names, never scene/, scene_run/ or server/"},
  };
  return r;
}

struct Violation {
  std::string where;  // "<file>:<line>"
  std::string text;
};

bool is_source(const fs::path& p) {
  const std::string ext = p.extension().string();
  return ext == ".hpp" || ext == ".cpp" || ext == ".h" || ext == ".cc";
}

// Every include of every source under root/rule.folder that the rule forbids.
std::vector<Violation> check(const fs::path& root, const Rule& rule) {
  static const std::regex include(R"(^\s*#\s*include\s*([<"])([^>"]+)[>"])");
  std::vector<Violation> out;
  const fs::path dir = root / rule.folder;
  if (!fs::is_directory(dir)) return out;
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && is_source(entry.path())) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    std::ifstream in(file);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      std::smatch m;
      if (!std::regex_search(line, m, include)) continue;
      const std::string header = m[2];
      const bool quoted = m[1] == "\"";
      const std::string head = first_component(header);
      const bool local = quoted && header.find('/') == std::string::npos;
      const bool bad = (!local && project_folders().count(head) && !rule.allowed.count(head)) ||
                       rule.foreign.count(head);
      if (bad) {
        out.push_back({fs::relative(file, root).string() + ":" + std::to_string(n),
                       "#include " + std::string(quoted ? "\"" : "<") + header +
                           (quoted ? "\"" : ">") + ": " + rule.text});
      }
    }
  }
  return out;
}

std::string listing(const std::vector<Violation>& v) {
  std::string s;
  for (const Violation& x : v) s += "  " + x.where + ": " + x.text + "\n";
  return s;
}

const Rule& rule_for(const std::string& folder) {
  for (const Rule& r : rules())
    if (r.folder == folder) return r;
  throw std::invalid_argument("no rule for " + folder);
}

void expect_clean(const std::string& folder) {
  const fs::path root = TONGUE_SOURCE_DIR;
  ASSERT_TRUE(fs::is_directory(root / folder)) << (root / folder);
  const std::vector<Violation> v = check(root, rule_for(folder));
  EXPECT_TRUE(v.empty()) << v.size() << " include(s) against the layering:\n" << listing(v);
}

TEST(Layering, CommonIncludesNothingOfTheProject) {
  expect_clean("sim_server/common");
}
TEST(Layering, FemIncludesOnlyFem) {
  expect_clean("sim_server/fem");
}
TEST(Layering, ModelIncludesNoSceneServerOrBus) {
  expect_clean("sim_server/model");
}
TEST(Layering, ReducedIncludesOnlyTheFemCore) {
  expect_clean("sim_server/reduced");
}
TEST(Layering, RunFileIncludesNoFem) {
  expect_clean("sim_server/run_file");
}
TEST(Layering, BusIncludesNoModel) {
  expect_clean("sim_server/bus");
}
TEST(Layering, ControllersIncludeNoModel) {
  expect_clean("controllers");
}
TEST(Layering, ViewerIncludesNoSceneOrServer) {
  expect_clean("viewer");
}
TEST(Layering, SceneSceneRunAndServerPointDown) {
  for (const char* folder : {"sim_server/scene", "sim_server/scene_run", "sim_server/server"})
    expect_clean(folder);
}

// The check itself: includes planted in a small tree are found, named by file and line.
TEST(Layering, FindsPlantedViolations) {
  const fs::path root =
      fs::temp_directory_path() /
      ("layering_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::remove_all(root);
  fs::create_directories(root / "sim_server/fem/mesh");
  fs::create_directories(root / "controllers/replay");
  fs::create_directories(root / "sim_server/common");
  std::ofstream(root / "sim_server/fem/mesh/bad.hpp")
      << "#pragma once\n#include <vector>\n#include \"fem/types.hpp\"\n#include "
         "\"scene/scene.hpp\"\n";
  std::ofstream(root / "controllers/replay/bad.cpp")
      << "#include \"replay/recorded_activations.hpp\"\n#include \"run_file/run_file_reader.hpp\"\n"
         "  #  include \"model/muscle.hpp\"\n";
  std::ofstream(root / "sim_server/common/bad.cpp")
      << "#include \"common/exit_code.hpp\"\n#include <lcm/lcm-cpp.hpp>\n#include "
         "\"bus/channels.hpp\"\n";

  const std::vector<Violation> fem = check(root, rule_for("sim_server/fem"));
  ASSERT_EQ(fem.size(), 1u) << listing(fem);
  EXPECT_EQ(fem[0].where, "sim_server/fem/mesh/bad.hpp:4");
  EXPECT_NE(fem[0].text.find("\"scene/scene.hpp\""), std::string::npos) << fem[0].text;

  const std::vector<Violation> controllers = check(root, rule_for("controllers"));
  ASSERT_EQ(controllers.size(), 1u) << listing(controllers);
  EXPECT_EQ(controllers[0].where, "controllers/replay/bad.cpp:3");

  const std::vector<Violation> common = check(root, rule_for("sim_server/common"));
  ASSERT_EQ(common.size(), 2u) << listing(common);
  EXPECT_EQ(common[0].where, "sim_server/common/bad.cpp:2");
  EXPECT_EQ(common[1].where, "sim_server/common/bad.cpp:3");
  fs::remove_all(root);
}

}  // namespace
}  // namespace tongue::layering
