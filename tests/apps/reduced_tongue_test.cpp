// The reduced tongue as a user makes it, end to end (label slow: about a minute): the real
// build_reduced_model with its default training on scenes/tongue_ep.yaml, then the real
// reduced_benchmark on its held-out runs. Where the full model can be trusted (its material
// stays strongly elliptic), every held-out run of the reduced model stays within the aim of half
// a millimetre RMS of the full model's.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/run_command.hpp"
#include "support/temp_dir_test.hpp"

#if !defined(BUILD_REDUCED_MODEL_PATH) || !defined(REDUCED_BENCHMARK_PATH) || !defined(PROJECT_DIR)
#error "BUILD_REDUCED_MODEL_PATH, REDUCED_BENCHMARK_PATH and PROJECT_DIR must be defined"
#endif

namespace tongue {
namespace {

class ReducedTongue : public testing::TempDirTest {};

// The number printed after `label` in `text`, NaN when it is not there.
double number_after(const std::string& text, const std::string& label) {
  const auto at = text.find(label);
  if (at == std::string::npos) return std::nan("");
  return std::stod(text.substr(at + label.size()));
}

TEST_F(ReducedTongue, HeldOutRunsStayWithinHalfAMillimetreWhereTheFullModelCanBeTrusted) {
  const std::string scene = PROJECT_DIR "/scenes/tongue_ep.yaml";
  const std::string basis = (dir_ / "basis.h5").string();
  const testing::RunResult built = testing::run_command(
      BUILD_REDUCED_MODEL_PATH, "'" + scene + "' --output '" + basis + "'", dir_);
  ASSERT_EQ(built.exit_code, 0) << built.out << built.err;
  const testing::RunResult bench = testing::run_command(
      REDUCED_BENCHMARK_PATH,
      "'" + scene + "' '" + basis + "' --csv '" + (dir_ / "reduced.csv").string() + "'", dir_);
  ASSERT_EQ(bench.exit_code, 0) << bench.out << bench.err;
  EXPECT_NE(bench.out.find(", 0 failed runs"), std::string::npos) << bench.out;
  // The aim itself: 0.5 mm (measured with the default training: 0.415 mm, `ramp SL`, the worst
  // of the 14 runs in which the material stays elliptic; with 6 random mixes instead of 60 and
  // the other defaults, 0.92 mm, and the test fails).
  const double worst =
      number_after(bench.out, "stays strongly elliptic: 14 of 34, the worst of them ");
  EXPECT_LE(worst, 0.5) << bench.out;
}

}  // namespace
}  // namespace tongue
