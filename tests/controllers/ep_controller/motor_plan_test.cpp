#include "ep_controller/motor_plan.hpp"

#include <gtest/gtest.h>

#include <string>

#include "builtin_tongue_muscles.hpp"
#include "controller/input_error.hpp"

#ifndef CONTROLLERS_DIR
#error "CONTROLLERS_DIR must name the controllers source directory"
#endif

namespace tongue::ep_controller {
namespace {

const std::vector<std::string> kTongue = testing::builtin_tongue_muscles().names;

int index_of(const std::string& name) {
  for (std::size_t m = 0; m < kTongue.size(); ++m)
    if (kTongue[m] == name) return static_cast<int>(m);
  ADD_FAILURE() << name << " is not a muscle of the built-in tongue";
  return 0;
}

// Times are compared to round-off of the interpolation (a few ulps of mm).
constexpr double kTol = 1e-12;

TEST(DeltaLambdaTrack, MovesLinearlyThenHoldsEachTargetInTurn) {
  const DeltaLambdaTrack t{{-10.0, 20.0}, 0.05, 0.1, 0.0};
  EXPECT_EQ(t.at(-1.0), 0.0);
  EXPECT_EQ(t.at(0.0), 0.0);               // rest until the start
  EXPECT_NEAR(t.at(0.025), -5.0, kTol);    // halfway to the first target
  EXPECT_NEAR(t.at(0.05), -10.0, kTol);    // reached after the transition
  EXPECT_NEAR(t.at(0.1), -10.0, kTol);     // held
  EXPECT_NEAR(t.at(0.1499), -10.0, kTol);  // still held just before the next move
  EXPECT_NEAR(t.at(0.175), 5.0, kTol);     // halfway from -10 to 20
  EXPECT_NEAR(t.at(0.2), 20.0, kTol);      // second target reached
  EXPECT_EQ(t.at(10.0), 20.0);             // the last target stays
  // Linear: equal steps in time give equal steps in Delta-lambda during a transition.
  EXPECT_NEAR(t.at(0.16) - t.at(0.155), t.at(0.165) - t.at(0.16), kTol);
}

TEST(DeltaLambdaTrack, StartDelaysAndZeroTransitionJumps) {
  const DeltaLambdaTrack delayed{{4.0}, 0.02, 0.0, 0.1};
  EXPECT_EQ(delayed.at(0.1), 0.0);
  EXPECT_NEAR(delayed.at(0.11), 2.0, kTol);
  EXPECT_EQ(delayed.at(0.5), 4.0);
  const DeltaLambdaTrack jump{{3.0, -3.0}, 0.0, 0.1, 0.0};
  EXPECT_EQ(jump.at(1e-6), 3.0);
  EXPECT_EQ(jump.at(0.1 + 1e-6), -3.0);
}

const char* const kPlan = R"(
transition: 0.04
hold: 0.06
delta_lambda_mm:
  GGp: [-10]
  SG_left: {targets: [2, 4], transition: 0.02, hold: 0.0, start: 0.01}
rho: {GGp: 6.0}
)";

TEST(MotorPlan, ReadsDefaultsAndPerEntryDurations) {
  const MotorPlanSpec spec = parse_motor_plan(kPlan, "plan.yaml");
  ASSERT_EQ(spec.entries.size(), 2u);
  EXPECT_EQ(spec.entries[0].name, "GGp");
  EXPECT_EQ(spec.entries[0].track.transition_s, 0.04);
  EXPECT_EQ(spec.entries[0].track.hold_s, 0.06);
  EXPECT_EQ(spec.entries[0].track.start_s, 0.0);
  EXPECT_EQ(spec.entries[1].track.targets_mm, (std::vector<double>{2.0, 4.0}));
  EXPECT_EQ(spec.entries[1].track.transition_s, 0.02);
  EXPECT_EQ(spec.entries[1].track.hold_s, 0.0);
  EXPECT_EQ(spec.entries[1].track.start_s, 0.01);
  ASSERT_EQ(spec.rho.size(), 1u);
  EXPECT_EQ(spec.rho[0].rho_n, 6.0);
}

TEST(MotorPlan, DefaultDurationsAreFiftyAndHundredMilliseconds) {
  const MotorPlanSpec spec = parse_motor_plan("delta_lambda_mm: {SG: [1]}", "p.yaml");
  EXPECT_EQ(spec.entries[0].track.transition_s, 0.05);
  EXPECT_EQ(spec.entries[0].track.hold_s, 0.1);
  EXPECT_EQ(spec.entries[0].track.start_s, 0.0);
}

TEST(MotorPlan, GroupsExpandToTheirHalvesAndOthersStayAtRest) {
  const MotorPlan plan(parse_motor_plan(kPlan, "plan.yaml"), kTongue);
  const double t = 0.02;  // halfway through GGp's transition
  EXPECT_NEAR(plan.delta_lambda_mm(index_of("GGp_left"), t), -5.0, kTol);
  EXPECT_NEAR(plan.delta_lambda_mm(index_of("GGp_right"), t), -5.0, kTol);
  EXPECT_NEAR(plan.delta_lambda_mm(index_of("SG_left"), t), 1.0, kTol);
  EXPECT_EQ(plan.delta_lambda_mm(index_of("SG_right"), t), 0.0);
  EXPECT_EQ(plan.delta_lambda_mm(index_of("SL"), t), 0.0);
  EXPECT_EQ(plan.delta_lambda_mm(index_of("HG_left"), 1.0), 0.0);
}

// An InputError whose message names the file and the key path.
void expect_error(const std::string& text, const std::string& key_path,
                  const std::string& also = "") {
  try {
    const MotorPlan plan(parse_motor_plan(text, "bad_plan.yaml"), kTongue);
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const controller::InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), "bad_plan.yaml");
    EXPECT_EQ(e.key_path(), key_path) << what;
    EXPECT_EQ(what.rfind("bad_plan.yaml: " + key_path, 0), 0u) << what;
    if (!also.empty()) {
      EXPECT_NE(what.find(also), std::string::npos) << what;
    }
  }
}

TEST(MotorPlan, BadPlansNameTheFileAndKey) {
  expect_error("delta_lambda_mm: {XX: [1]}", "delta_lambda_mm.XX", "no muscle is named 'XX'");
  expect_error("delta_lambda_mm: {GG: [1]}", "delta_lambda_mm.GG", "GGp_left");  // lists muscles
  expect_error("delta_lambda_mm: {SG: [1], SG_left: [2]}", "delta_lambda_mm.SG_left",
               "also set by delta_lambda_mm.SG");
  expect_error("delta_lambda_mm: {SG: [1], SG: [2]}", "delta_lambda_mm.SG", "twice");
  expect_error("delta_lambda: {SG: [1]}", "delta_lambda", "unknown key");
  expect_error("hold: 0.1", "delta_lambda_mm", "missing");
  expect_error("delta_lambda_mm: {SG: []}", "delta_lambda_mm.SG", "at least one");
  expect_error("delta_lambda_mm: {SG: [1, x]}", "delta_lambda_mm.SG[1]", "number");
  expect_error("delta_lambda_mm: {SG: 3}", "delta_lambda_mm.SG", "list");
  expect_error("delta_lambda_mm: {SG: {targets: [1], speed: 2}}", "delta_lambda_mm.SG.speed",
               "unknown key");
  expect_error("delta_lambda_mm: {SG: {hold: 0.1}}", "delta_lambda_mm.SG.targets", "missing");
  expect_error("hold: -0.1\ndelta_lambda_mm: {SG: [1]}", "hold", "negative");
  expect_error("delta_lambda_mm: {SG: {targets: [1, 2], transition: 0, hold: 0}}",
               "delta_lambda_mm.SG", "both 0");
  expect_error("delta_lambda_mm: {SG: [1]}\nrho: {SG: 0}", "rho.SG", "positive");
  expect_error("delta_lambda_mm: {SG: [.nan]}", "delta_lambda_mm.SG[0]", "finite");
  expect_error("delta_lambda_mm: [SG, 1]", "delta_lambda_mm", "mapping");
  expect_error("delta_lambda_mm: {SG: [1}", "", "YAML syntax error");
}

TEST(MotorPlan, ErrorsCarryTheLine) {
  try {
    parse_motor_plan("hold: 0.1\ndelta_lambda_mm:\n  SG: [1, q]\n", "p.yaml");
    ADD_FAILURE() << "accepted";
  } catch (const controller::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("(line 3)"), std::string::npos) << e.what();
  }
}

TEST(MotorPlan, MissingFileIsNamed) {
  try {
    read_motor_plan("/nonexistent/plan.yaml");
    ADD_FAILURE() << "accepted";
  } catch (const controller::InputError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/plan.yaml");
  }
}

// The shipped plans read and fit the built-in tongue; /ai/ holds docs/controllers.md's.
TEST(MotorPlan, ShippedPlansFitTheBuiltInTongue) {
  const std::string dir = CONTROLLERS_DIR "/plans/";
  const MotorPlanSpec ai = read_motor_plan(dir + "ai.yaml");
  const MotorPlan ai_plan(ai, kTongue);
  EXPECT_EQ(ai_plan.delta_lambda_mm(index_of("GGa_left"), 0.05), -10.0);
  EXPECT_EQ(ai_plan.delta_lambda_mm(index_of("GGa_right"), 1.0), 20.0);
  EXPECT_EQ(ai_plan.delta_lambda_mm(index_of("GGp_left"), 0.1), 20.0);
  EXPECT_EQ(ai_plan.delta_lambda_mm(index_of("GGp_right"), 1.0), -15.0);
  EXPECT_EQ(ai_plan.delta_lambda_mm(index_of("SG_left"), 0.1), 0.0);
  EXPECT_EQ(ai_plan.delta_lambda_mm(index_of("SG_right"), 1.0), -15.0);
  const MotorPlan ku_plan(read_motor_plan(dir + "ku.yaml"), kTongue);
  EXPECT_LT(ku_plan.delta_lambda_mm(index_of("SG_left"), 0.1), 0.0);  // SG pulls for /k/
}

}  // namespace
}  // namespace tongue::ep_controller
