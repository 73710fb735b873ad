// run_experiment end to end: the real runner starts the real sim_server, lcm-logger and
// controller processes on a udpm bus of the test's own port, and the test reads what the run
// left in its folder. Ports 7872-7879.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/run_command.hpp"
#include "support/run_file.hpp"
#include "support/sim_server_driver.hpp"
#include "support/temp_dir_test.hpp"

#ifndef RUN_EXPERIMENT_PATH
#error "RUN_EXPERIMENT_PATH must name the run_experiment executable"
#endif

namespace tongue::experiments {
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

// A controller that dies (here: a shell killing itself with SIGSEGV while the server waits for
// it) is named in the summary, the server is stopped cleanly and what was logged is kept.
TEST_F(RunExperiment, ControllerCrashIsReportedAndEverythingKept) {
  const std::string file = experiment(
      "crash",
      "  - {name: crasher, program: /bin/sh, args: [-c, 'sleep 0.5; kill -SEGV $$', sh]}\n");
  const auto r = run(file, 7872);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
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
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  const std::string summary = read_text(latest("missing") / "summary.txt");
  EXPECT_NE(summary.find("no_such_controller"), std::string::npos) << summary;
}

}  // namespace
}  // namespace tongue::experiments
