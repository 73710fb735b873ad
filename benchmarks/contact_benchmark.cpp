// What contact costs (docs/contact.md): each scene as it is and the same scene without its
// obstacles, stepped in turn --repeats times in this process, the stepping alone timed (building
// and settling are a start-up). Prints for each scene the medians of the stepping's wall time
// with and without obstacles and their ratio, the median of each repeat's own ratio (two runs
// made one after the other, under the same load from others on this shared machine), and the
// Newton iterations and factorizations of each.
//
// Usage: contact_benchmark [--repeats N] [SCENE.yaml ...]
//        (default: scenes/tongue_i.yaml, tongue_k.yaml and tongue_t.yaml, 7 repeats)
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "dynamic_scene_run.hpp"
#include "median.hpp"
#include "scene/scene_reader.hpp"

namespace {

using namespace tongue;

using benchmarks::median;

void measure(const std::string& path, int repeats) {
  const scene::Scene with = scene::read_scene(path);
  if (with.obstacles.empty()) throw std::runtime_error(path + ": the scene has no obstacles");
  scene::Scene without = with;
  without.obstacles = scene::ObstaclesSpec{};
  std::vector<double> wall_with, wall_without, paired, own_with, own_without;
  benchmarks::DynamicRun a, b;
  for (int k = 0; k < repeats; ++k) {
    a = benchmarks::run_dynamic_scene(with);
    b = benchmarks::run_dynamic_scene(without);
    wall_with.push_back(a.wall_seconds);
    wall_without.push_back(b.wall_seconds);
    paired.push_back(a.wall_seconds / b.wall_seconds);
    own_with.push_back(a.integrator_seconds);
    own_without.push_back(b.integrator_seconds);
  }
  const double m_with = median(wall_with), m_without = median(wall_without);
  const double own_m_with = median(own_with), own_m_without = median(own_without);
  std::printf(
      "%s: %d steps; stepping with obstacles %.4f s (%d iterations, %d residuals, %d "
      "factorizations), without %.4f s (%d, %d, %d): %.2fx; the repeats' own ratios %.2fx "
      "(%.2f-%.2f); medians of %d\n",
      path.c_str(), a.steps, m_with, a.iterations, a.residual_evaluations, a.factorizations,
      m_without, b.iterations, b.residual_evaluations, b.factorizations, m_with / m_without,
      median(paired), *std::min_element(paired.begin(), paired.end()),
      *std::max_element(paired.begin(), paired.end()), repeats);
  std::printf(
      "  the integrator's steps alone (sim_batch's \"stepping\"): %.4f s against %.4f s: %.2fx\n",
      own_m_with, own_m_without, own_m_with / own_m_without);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 7;
  std::vector<std::string> scenes;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--repeats" && i + 1 < argc) {
      repeats = std::max(1, std::stoi(argv[++i]));
    } else if (arg.rfind("--", 0) == 0) {
      std::fprintf(stderr, "usage: contact_benchmark [--repeats N] [SCENE.yaml ...]\n");
      return 2;
    } else {
      scenes.push_back(arg);
    }
  }
  if (scenes.empty())
    for (const char* name : {"tongue_i.yaml", "tongue_k.yaml", "tongue_t.yaml"})
      scenes.push_back(std::string(TONGUE_SOURCE_DIR) + "/scenes/" + name);
  try {
    for (const std::string& path : scenes) measure(path, repeats);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "contact_benchmark: %s\n", e.what());
    return 1;
  }
  return 0;
}
