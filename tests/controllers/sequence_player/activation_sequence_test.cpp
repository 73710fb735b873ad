#include "sequence_player/activation_sequence.hpp"

#include <gtest/gtest.h>

#include <string>

#include "builtin_tongue_muscles.hpp"
#include "controller/input_error.hpp"
#include "sequence_player/sequence_player.hpp"

#ifndef CONTROLLERS_DIR
#error "CONTROLLERS_DIR must name the controllers source directory"
#endif

namespace tongue::sequence_player {
namespace {

const testing::MuscleList kTongue = testing::builtin_tongue_muscles();

ActivationSequence resolve(const std::string& text) {
  return ActivationSequence(parse_sequence(text, "seq.yaml"), kTongue.names, kTongue.max_forces_n);
}

// Level of one muscle in the levels at t.
double level_of(const ActivationSequence& s, double t, const std::string& name) {
  const controller::MuscleLevels l = s.levels_at(t);
  for (std::size_t i = 0; i < l.names.size(); ++i)
    if (l.names[i] == name) return l.levels[i];
  ADD_FAILURE() << name << " is not sent";
  return -1.0;
}

double max_force(const std::string& name) {
  for (std::size_t m = 0; m < kTongue.names.size(); ++m)
    if (kTongue.names[m] == name) return kTongue.max_forces_n[m];
  return 0.0;
}

TEST(ActivationSequence, StepInNewtonsIsSplitByMaxForceOverTheGroup) {
  const ActivationSequence s =
      resolve("entries: [{muscle: SG, start: 0.0, end: 0.12, force: 3.0}]");
  const double level = 3.0 / (max_force("SG_left") + max_force("SG_right"));
  EXPECT_EQ(level_of(s, 0.004, "SG_left"), level);
  EXPECT_EQ(level_of(s, 0.004, "SG_right"), level);
  // Active on [start, end] with the scene's round-off tolerance: 30 * 0.004 is not exactly 0.12.
  EXPECT_EQ(level_of(s, 30 * 0.004, "SG_left"), level);
  EXPECT_EQ(level_of(s, 0.0, "SG_left"), level);
  EXPECT_EQ(level_of(s, 0.124, "SG_left"), 0.0);  // after the end: off again
  // Only the named muscles are sent.
  EXPECT_EQ(s.levels_at(0.01).names, (std::vector<std::string>{"SG_left", "SG_right"}));
}

TEST(ActivationSequence, StepWithoutEndLastsAndLaterEntriesOverride) {
  const ActivationSequence s = resolve(R"(
entries:
  - {muscle: GGp, start: 0.1, level: 0.2}
  - {muscle: GGp_left, start: 0.2, end: 0.3, level: 0.7}
)");
  EXPECT_EQ(level_of(s, 0.05, "GGp_left"), 0.0);
  EXPECT_EQ(level_of(s, 0.15, "GGp_left"), 0.2);
  EXPECT_EQ(level_of(s, 0.25, "GGp_left"), 0.7);
  EXPECT_EQ(level_of(s, 0.25, "GGp_right"), 0.2);
  EXPECT_EQ(level_of(s, 100.0, "GGp_left"), 0.2);
}

TEST(ActivationSequence, RampsGoLinearlyFromStartToEnd) {
  const ActivationSequence s = resolve(R"(
entries:
  - {muscle: GGa_left, start: 0.1, end: 0.2, level_from: 0.1, level_to: 0.5}
  - {muscle: HG, start: 0.0, end: 0.05, force_from: 0, force_to: 6.5}
)");
  EXPECT_EQ(level_of(s, 0.05, "GGa_left"), 0.0);  // before the ramp
  EXPECT_NEAR(level_of(s, 0.1, "GGa_left"), 0.1, 1e-12);
  EXPECT_NEAR(level_of(s, 0.15, "GGa_left"), 0.3, 1e-12);
  EXPECT_NEAR(level_of(s, 0.2, "GGa_left"), 0.5, 1e-12);
  EXPECT_EQ(level_of(s, 0.21, "GGa_left"), 0.0);  // after: off, as every entry
  const double hg_total = max_force("HG_left") + max_force("HG_right");
  EXPECT_NEAR(level_of(s, 0.025, "HG_right"), 3.25 / hg_total, 1e-12);
}

TEST(ActivationSequence, PlayerSendsTheLevelsAtTheEndOfTheStep) {
  SequencePlayer player(parse_sequence(
      "duration: 0.1\nentries: [{muscle: SL, start: 0.0, end: 0.1, level_from: 0, level_to: 1}]",
      "seq.yaml"));
  controller::Model m;
  m.muscle_names = kTongue.names;
  m.muscle_max_forces = kTongue.max_forces_n;
  m.num_muscles = static_cast<int>(kTongue.names.size());
  m.dt = 0.004;
  player.start(m);
  EXPECT_EQ(player.last_step(), 25);                     // 0.1 s / 4 ms
  const controller::MuscleLevels l = player.command(5);  // the step from 16 to 20 ms
  ASSERT_EQ(l.names, (std::vector<std::string>{"SL"}));
  EXPECT_NEAR(l.levels[0], 5 * 0.004 / 0.1, 1e-12);
}

TEST(ActivationSequence, StepsCoveringADurationCountLikeSimBatch) {
  EXPECT_EQ(steps_covering(0.12, 0.004), 30);  // 0.12 / 0.004 = 30.000000000000004
  EXPECT_EQ(steps_covering(0.1, 0.03), 4);     // the last step ends past the duration
  EXPECT_EQ(steps_covering(1e-6, 0.004), 1);
}

void expect_error(const std::string& text, const std::string& key_path,
                  const std::string& also = "") {
  try {
    resolve(text);
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const controller::InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), "seq.yaml");
    EXPECT_EQ(e.key_path(), key_path) << what;
    if (!also.empty()) {
      EXPECT_NE(what.find(also), std::string::npos) << what;
    }
  }
}

TEST(ActivationSequence, BadSchedulesNameTheFileAndKey) {
  expect_error("entries: [{muscle: XX, level: 0.1}]", "entries[0].muscle", "no muscle");
  expect_error("entries: [{level: 0.1}]", "entries[0].muscle", "missing");
  expect_error("entries: [{muscle: SG, level: 1.5}]", "entries[0].level", "[0, 1]");
  expect_error("entries: [{muscle: SG, force: -1}]", "entries[0].force", "negative");
  expect_error("entries: [{muscle: SG, force: 25}]", "entries[0]", "exceeds");
  expect_error("entries: [{muscle: SG, force: 1, level: 0.1}]", "entries[0]", "exactly one");
  expect_error("entries: [{muscle: SG}]", "entries[0]", "exactly one");
  expect_error("entries: [{muscle: SG, level_from: 0.1, end: 1}]", "entries[0].level_to",
               "missing");
  expect_error("entries: [{muscle: SG, level_from: 0, level_to: 0.1}]", "entries[0].end",
               "ramp needs an end");
  expect_error("entries: [{muscle: SG, start: 0.2, end: 0.1, level: 0.1}]", "entries[0].end",
               "after start");
  expect_error("entries: [{muscle: SG, start: -1, level: 0.1}]", "entries[0].start", "negative");
  expect_error("entries: [{muscle: SG, level: 0.1, colour: red}]", "entries[0].colour",
               "unknown key");
  expect_error("steps: []", "steps", "unknown key");
  expect_error("duration: 0\nentries: []", "duration", "positive");
  expect_error("entries: {muscle: SG}", "entries", "list");
  expect_error("entries: [{muscle: SG, level: x}]", "entries[0].level", "number");
}

TEST(ActivationSequence, ShippedSg3nIsThePapersStep) {
  const SequenceSpec spec = read_sequence(CONTROLLERS_DIR "/sequences/sg_3n.yaml");
  EXPECT_EQ(spec.duration_s, 0.12);
  const ActivationSequence s(spec, kTongue.names, kTongue.max_forces_n);
  // The scene's level for 3 N over SG (scene/activation_schedule.cpp: force / summed F_max).
  const double level = 3.0 / (max_force("SG_left") + max_force("SG_right"));
  for (int k = 1; k <= 30; ++k) EXPECT_EQ(level_of(s, k * 0.004, "SG_left"), level) << k;
}

}  // namespace
}  // namespace tongue::sequence_player
