// run_experiment end to end: the real runner starts the real sim_server, lcm-logger and
// controller processes on a udpm bus of the test's own port, and the test reads what the run
// left in its folder. Ports 7872-7879.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "support/run_command.hpp"
#include "support/run_file.hpp"
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef RUN_EXPERIMENT_PATH
#error "RUN_EXPERIMENT_PATH must name the run_experiment executable"
#endif

namespace tongue::runner {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::run_command;
using testing::RunFile;

class RunExperiment : public testing::TempDirTest {
 protected:
  // Writes the box scene and an experiment around it with the given controllers section.
  std::string experiment(const std::string& name, const std::string& controllers,
                         const std::string& extra = "") {
    write("box.yaml", testing::kBoxScene);
    return write(name + ".yaml", "name: " + name +
                                     "\nscene: box.yaml\nduration: 0.02\ntimeout: 60\n" + extra +
                                     "controllers:\n" + controllers);
  }
  testing::RunResult run(const std::string& file, int port) {
    return run_command(RUN_EXPERIMENT_PATH,
                       "'" + file + "' --no-plots --quiet --logs '" + (dir_ / "logs").string() +
                           "' --port " + std::to_string(port),
                       dir_);
  }
  fs::path latest(const std::string& name) const {
    return fs::canonical(dir_ / "logs" / (name + "-latest"));
  }
};

// The whole path: sequence_player drives the box through the runner; everything is collected and
// the figures in the summary are the run file's.
TEST_F(RunExperiment, CompletesAndCollectsEverything) {
  write("steps.yaml", "entries:\n  - {muscle: flexor, start: 0.0, end: 0.01, level: 0.5}\n");
  const std::string file = experiment(
      "played", "  - {name: player, program: sequence_player, args: [--schedule, steps.yaml]}\n");
  const auto r = run(file, 7877);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const fs::path folder = latest("played");
  const std::string summary = read_text(folder / "summary.txt");
  EXPECT_NE(summary.find("result: completed"), std::string::npos) << summary;
  EXPECT_NE(summary.find("status 'completed', 10 steps"), std::string::npos) << summary;
  // States: 0 to 10, plus state 0 again for the controller's describe (it joins late).
  EXPECT_NE(summary.find(" states, 10 activations"), std::string::npos) << summary;
  const RunFile f(folder / "run.h5");
  ASSERT_TRUE(f.ok());
  const std::vector<double> a = f.doubles("/activations");
  ASSERT_EQ(a.size(), 11u);  // step 0 and the 10 steps of 2 ms
  EXPECT_EQ(a[0], 0.0);
  EXPECT_EQ(a[5], 0.5);   // t = 10 ms, inside the step
  EXPECT_EQ(a[10], 0.0);  // t = 20 ms, after it
  for (const char* name : {"bus.lcmlog", "run.xmf", "sim_server.err", "player.err", "scene.yaml"}) {
    EXPECT_TRUE(fs::exists(folder / name)) << name;
  }
}

// A controller that dies (here: a shell killing itself with SIGSEGV while the server waits for
// it) is named in the summary, the server is stopped cleanly and what was logged is kept.
TEST_F(RunExperiment, ControllerCrashIsReportedAndEverythingKept) {
  const std::string file = experiment(
      "crash",
      "  - {name: crasher, program: /bin/sh, args: [-c, 'sleep 0.5; kill -SEGV $$', sh]}\n");
  const auto r = run(file, 7872);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // a failed run (was 2)
  const fs::path folder = latest("crash");
  const std::string summary = read_text(folder / "summary.txt");
  EXPECT_NE(summary.find("controller 'crasher' ended before the run was done (killed by signal "
                         "11"),
            std::string::npos)
      << summary;
  EXPECT_NE(summary.find("sim_server: exit status 130, stopped by the runner with SIGTERM"),
            std::string::npos)
      << summary;
  const RunFile f(folder / "run.h5");
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.string_attribute("/", "status"), "interrupted");
  EXPECT_TRUE(fs::exists(folder / "bus.lcmlog"));
  EXPECT_TRUE(fs::exists(folder / "sim_server.err"));
  EXPECT_TRUE(fs::exists(folder / "experiment.yaml"));
}

TEST_F(RunExperiment, BadExperimentFileIsAClearError) {
  const std::string file =
      experiment("typo", "  - {name: c, program: /bin/true}\n", "lcm_lgo: false\n");
  const auto r = run(file, 7873);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("typo.yaml: lcm_lgo: unknown key"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "logs")) << "nothing is started for a bad file";
}

TEST_F(RunExperiment, MissingProgramIsAClearError) {
  const std::string file = experiment("missing", "  - {name: c, program: ./no_such_controller}\n");
  const auto r = run(file, 7874);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // a failed run (was 2)
  const std::string summary = read_text(latest("missing") / "summary.txt");
  EXPECT_NE(summary.find("no_such_controller"), std::string::npos) << summary;
}

}  // namespace
}  // namespace tongue::runner
