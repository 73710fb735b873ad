// Stability under the worst a user can do, each run by the real sim_batch on the
// built-in tongue: all muscles at full force, bang-bang switching of antagonists every 10 ms,
// time steps up to 20 ms, Poisson's ratio up to 0.499. Pass: the run completes, no frame has a
// non-finite position or an inverted element (checked here from the run file alone), and step
// cuts are reported rather than hidden. Built twice: a quick version for CI (label integration)
// and a long one (STRESS_FULL, label slow).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "stress_support.hpp"
#include "support/run_command.hpp"
#include "support/run_file.hpp"
#include "support/temp_dir_test.hpp"

#ifndef SIM_BATCH_PATH
#error "SIM_BATCH_PATH must name the sim_batch executable"
#endif
#ifndef STRESS_FULL
#define STRESS_FULL 0
#endif

namespace tongue::stress {
namespace {

using testing::RunFile;

// Simulated seconds of each scenario: quick for CI, long for the slow label.
constexpr double kScale = STRESS_FULL ? 10.0 : 1.0;

// Activation entries setting each of groups to level over [start, end] s.
std::string steps(const std::vector<std::string>& groups, double level, double start, double end) {
  std::string text;
  for (const std::string& g : groups) {
    char line[160];
    std::snprintf(line, sizeof line, "  - {group: %s, level: %.3f, start: %.4f, end: %.4f}\n",
                  g.c_str(), level, start, end);
    text += line;
  }
  return text;
}

std::string analysis(double duration, double dt) {
  return "analysis: {type: dynamic, settle: true, duration: " + std::to_string(duration) +
         ", dt: " + std::to_string(dt) + "}\n";
}

class Stress : public testing::TempDirTest {
 protected:
  // Runs the scene (head + body) and checks every frame of its run file.
  void run_and_check(const std::string& body, const std::string& what) {
    const std::string scene = write("scene.yaml", testing::tongue_scene_head(nu_) + body);
    const auto r = testing::run_command(
        SIM_BATCH_PATH, "'" + scene + "' --quiet --output '" + (dir_ / "run.h5").string() + "'",
        dir_);
    ASSERT_EQ(r.exit_code, 0) << what << "\n" << r.out << r.err;
    const RunFile f(dir_ / "run.h5");
    ASSERT_TRUE(f.ok()) << r.out << r.err;
    EXPECT_EQ(f.string_attribute("/", "status"), "completed");
    const std::vector<double> rest = f.doubles("/rest_positions");
    const std::vector<double> positions = f.doubles("/positions");
    const std::vector<int> elements = f.ints("/elements");
    const std::size_t frame = rest.size();
    ASSERT_GT(frame, 0u);
    double worst = 1e300;
    for (std::size_t k = 0; k + frame <= positions.size(); k += frame) {
      const std::vector<double> x(positions.begin() + k, positions.begin() + k + frame);
      worst = std::min(worst, testing::min_relative_jacobian(rest, x, elements));
    }
    EXPECT_GT(worst, 0.0) << what << ": an inverted element or a non-finite position";
    int cuts = 0;
    for (const int c : f.ints("/solver/cuts")) cuts += c;
    std::printf("%s: %zu frames, smallest det J / det J0 %.3f, %d step cuts (reported)\n",
                what.c_str(), positions.size() / frame, worst, cuts);
  }
  double nu_ = 0.49;
};

TEST_F(Stress, AllMusclesAtFullForce) {
  const double end = 0.12 * kScale;
  run_and_check(
      "activations:\n" +
          steps({"GGp", "GGm", "GGa", "HG", "SG", "SL", "IL", "T", "V", "MH"}, 1.0, 0.0, end) +
          analysis(end, 0.004),
      "all muscles at full force");
}

// Antagonists at full force, swapped every 10 ms: the hardest input a controller can send.
TEST_F(Stress, BangBangSwitchingEvery10ms) {
  const double end = 0.2 * kScale;
  std::string body = "activations:\n";
  int k = 0;
  for (double t = 0.0; t < end - 1e-9; t += 0.01, ++k) {
    body += k % 2 == 0 ? steps({"GGp", "GGm", "HG", "IL"}, 1.0, t, t + 0.01)
                       : steps({"SG", "SL", "GGa", "T", "V"}, 1.0, t, t + 0.01);
  }
  run_and_check(body + analysis(end, 0.002), "bang-bang every 10 ms");
}

TEST_F(Stress, TimeStepsUpTo20ms) {
  const double end = 0.2 * kScale;
  for (const double dt : {0.01, 0.02}) {
    run_and_check("activations:\n" + steps({"SG"}, 0.5, 0.0, 0.1) + steps({"GGp"}, 0.5, 0.1, end) +
                      analysis(end, dt),
                  "dt " + std::to_string(dt) + " s");
  }
}

TEST_F(Stress, NearlyIncompressible) {
  const double end = 0.12 * kScale;
  for (const double nu : {0.495, 0.499}) {
    nu_ = nu;
    run_and_check("activations:\n" + steps({"SG"}, 0.5, 0.0, end) + analysis(end, 0.004),
                  "nu " + std::to_string(nu));
  }
}

}  // namespace
}  // namespace tongue::stress
