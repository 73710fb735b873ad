// ServerLoop driven through an in-memory bus (FakeServerBus): the messages a controller would
// send are queued encoded, and the model and states published are read back; no network, a
// small box scene, each test well under a second.
#include "server/server_loop.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"
#include "scene_run/scene_run.hpp"
#include "server/fake_server_bus.hpp"
#include "support/box_scenes.hpp"
#include "support/run_file.hpp"
#include "support/temp_dir_test.hpp"

namespace tongue::server {
namespace {

using tongue_lcm::lcmt_tongue_state;
using Channel = bus::IncomingMessage::Channel;
using testing::FakeServerBus;

constexpr double kDt = 0.002;  // s, the box scenes'
// A test whose loop has not ended after this long [s] is stopped (common::kExitInterrupted).
constexpr double kLongestRun = 30.0;

// The bytes of an lcmt_tongue_command whose string has the given length field (NUL included on
// the wire) followed by body: what a hostile or broken sender may put on the command channel.
std::vector<std::uint8_t> command_bytes(std::int32_t length,
                                        const std::vector<std::uint8_t>& body) {
  std::vector<std::uint8_t> bytes;
  const auto put = [&bytes](std::uint64_t value, int count) {
    for (int i = count - 1; i >= 0; --i) bytes.push_back(static_cast<std::uint8_t>(value >> 8 * i));
  };
  put(static_cast<std::uint64_t>(tongue_lcm::lcmt_tongue_command::getHash()), 8);
  put(0, 8);  // utime
  put(static_cast<std::uint32_t>(length), 4);
  bytes.insert(bytes.end(), body.begin(), body.end());
  return bytes;
}

class ServerLoopTest : public tongue::testing::TempDirTest {
 protected:
  // Runs a server on scene_text with options until it ends, on bus_ as queued (and answered by
  // bus_.on_state).
  ExitStatus run(ServerOptions options = {}, const char* scene_text = tongue::testing::kBoxScene) {
    scene_ = std::make_unique<scene::Scene>(scene::parse_scene(scene_text, "", "box.yaml"));
    const auto start = std::chrono::steady_clock::now();
    ServerLoop loop(*scene_, scene::build_scene(*scene_), bus_, std::move(options), [start] {
      return std::chrono::steady_clock::now() - start > std::chrono::duration<double>(kLongestRun);
    });
    return loop.run();
  }

  ServerOptions with_run_file() const {
    ServerOptions options;
    options.output = (dir_ / "run.h5").string();
    return options;
  }

  // The positions of the box stepped directly by a SceneRun with levels (one muscle), one entry
  // per step from step 1.
  std::vector<std::vector<double>> reference_positions(const std::vector<double>& levels) const {
    const scene::Scene scene = scene::parse_scene(tongue::testing::kBoxScene, "", "box.yaml");
    scene_run::SceneRun reference(scene, scene::build_scene(scene));
    EXPECT_TRUE(reference.start().converged);
    std::vector<std::vector<double>> out;
    for (const double level : levels) {
      EXPECT_TRUE(reference.step(kDt, fem::Vector::Constant(1, level)).report.converged);
      const fem::Vector x = reference.positions();
      out.emplace_back(x.data(), x.data() + x.size());
    }
    return out;
  }

  // The box scene above a floor 0.5 mm below it (a square of 100 mm in an OBJ file, facing up).
  std::string box_above_floor() const {
    const std::string floor = write("floor.obj",
                                    "v -50 -50 0\nv 50 -50 0\nv 50 50 0\nv -50 50 0\n"
                                    "f 1 2 3\nf 1 3 4\n");
    return std::string(tongue::testing::kBoxScene) +
           "obstacles:\n  - {name: floor, file: " + floor +
           ", length_scale: 0.001, rotate: [-90, 0, 0], translate: [0, -0.0005, 0]}\n";
  }

  // The steps of the states published, in order.
  std::vector<std::int64_t> published_steps() const {
    std::vector<std::int64_t> steps;
    for (const lcmt_tongue_state& s : bus_.states) steps.push_back(s.step);
    return steps;
  }

  std::unique_ptr<scene::Scene> scene_;
  FakeServerBus bus_;
};

int status(ExitStatus s) {
  return static_cast<int>(s);
}

TEST_F(ServerLoopTest, PublishesTheModelThenStateZero) {
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run()), status(common::kExitOk));
  EXPECT_EQ(bus_.published.substr(0, 2), "ms");
  ASSERT_EQ(bus_.models.size(), 1u);
  EXPECT_EQ(bus_.models[0].num_nodes, 20);
  EXPECT_EQ(bus_.models[0].muscle_names, (std::vector<std::string>{"flexor"}));
  // The flexor's one fibre, through nodes 2, 3, 4, with no bony origin (for drawing).
  EXPECT_EQ(bus_.models[0].fibre_muscles, (std::vector<std::int32_t>{0}));
  EXPECT_EQ(bus_.models[0].fibre_offsets, (std::vector<std::int32_t>{0, 3}));
  EXPECT_EQ(bus_.models[0].fibre_nodes, (std::vector<std::int32_t>{2, 3, 4}));
  EXPECT_EQ(bus_.models[0].fibre_has_origin, (std::vector<int8_t>{0}));
  EXPECT_EQ(bus_.models[0].num_fibre_origins, 3);
  EXPECT_DOUBLE_EQ(bus_.models[0].dt, kDt);
  ASSERT_EQ(bus_.states.size(), 1u);
  const lcmt_tongue_state& s0 = bus_.states[0];
  EXPECT_EQ(s0.step, 0);
  EXPECT_EQ(s0.positions, bus_.models[0].rest_positions);  // not settled: starts at rest
  EXPECT_EQ(s0.activations, (std::vector<double>{0.0}));
  EXPECT_DOUBLE_EQ(s0.muscle_lengths.at(0), 0.02);  // two 10 mm segments
  EXPECT_EQ(s0.status, "ok");
}

TEST_F(ServerLoopTest, LockStepStepsOnTheActivationTaggedTheNextStep) {
  const std::vector<double> levels{0.2, 0.5, 0.9, 0.1};
  for (std::size_t k = 0; k < levels.size(); ++k)
    bus_.send_activation(static_cast<std::int64_t>(k) + 1, {"flexor"}, {levels[k]});
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run()), status(common::kExitOk));
  ASSERT_EQ(published_steps(), (std::vector<std::int64_t>{0, 1, 2, 3, 4}));
  // The same as stepping the scene directly with the same levels, bit for bit.
  const auto expected = reference_positions(levels);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const lcmt_tongue_state& s = bus_.states[k + 1];
    EXPECT_EQ(s.activations, (std::vector<double>{levels[k]}));
    EXPECT_NEAR(s.time, static_cast<double>(k + 1) * kDt, 1e-12);
    EXPECT_EQ(s.positions, expected[k]) << "step " << k + 1;
    EXPECT_TRUE(s.converged);
    EXPECT_GT(s.newton_iterations, 0);
    EXPECT_EQ(s.rejected_messages, 0);
  }
}

TEST_F(ServerLoopTest, AControllerAnsweringEachStateDrivesTheRun) {
  bus_.on_state = [this](const lcmt_tongue_state& s) {
    if (s.step < 5)
      bus_.send_activation(s.step + 1, {"flexor"}, {0.1 * static_cast<double>(s.step)});
  };
  ServerOptions options;
  options.max_steps = 5;
  ASSERT_EQ(status(run(options)), status(common::kExitOk));
  EXPECT_EQ(published_steps(), (std::vector<std::int64_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(bus_.states.back().activations, (std::vector<double>{0.4}));
}

// Lock-step over a lossy bus: while the activation for k + 1 is late, state k goes out again
// after 10, 20, 40 ms (here), then no more; the silence rule then applies.
TEST_F(ServerLoopTest, AStateIsPublishedAgainWhileTheActivationIsLate) {
  ServerOptions options = with_run_file();
  options.repeat_ms = 10;
  options.repeats = 3;
  options.timeout_ms = 500;
  options.on_silence = OnSilence::stop;
  ASSERT_EQ(status(run(options)), status(common::kExitSilence));
  EXPECT_EQ(published_steps(), (std::vector<std::int64_t>{0, 0, 0, 0}));
  for (const lcmt_tongue_state& s : bus_.states) EXPECT_EQ(s.status, "ok");
  const tongue::testing::RunFile f(dir_ / "run.h5");
  EXPECT_EQ(f.string_attribute("/", "repeated_states"), "3");
  EXPECT_EQ(f.string_attribute("/", "repeated_activations"), "0");
}

// Two named controllers on a bus that loses the first publication of every odd state (nobody
// answers it) and that delivers some answers twice: the repeats of state k bring the answers, a
// sender's repeated message is taken once, and the run is the one of a lossless bus, bit for bit.
TEST_F(ServerLoopTest, LostStatesAndRepeatedAnswersGiveTheLosslessRun) {
  constexpr std::int64_t kSteps = 6;
  ServerOptions options;
  options.controllers = 2;
  options.repeat_ms = 5;
  options.max_steps = kSteps;
  const auto answer = [this](std::int64_t step, int copies) {
    for (int i = 0; i < copies; ++i) {
      // The same bytes each time for a step, as a controller repeats its message.
      bus_.send_activation(step, {"flexor"}, {0.1 * static_cast<double>(step)}, "a:1", step);
      bus_.send_activation(step, {"extensor"}, {0.05 * static_cast<double>(step % 3)}, "b:2", step);
    }
  };
  bus_.on_state = [&answer](const lcmt_tongue_state& s) { answer(s.step + 1, 1); };
  ASSERT_EQ(status(run(options, tongue::testing::kTwoMuscleBoxScene)), status(common::kExitOk));
  ASSERT_EQ(published_steps(), (std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6}));
  const std::vector<lcmt_tongue_state> lossless = bus_.states;

  bus_ = FakeServerBus{};
  std::vector<int> seen(kSteps + 1, 0);
  bus_.on_state = [&answer, &seen](const lcmt_tongue_state& s) {
    const int times = ++seen[static_cast<std::size_t>(s.step)];
    if (s.step % 2 == 1 && times == 1) return;  // lost
    answer(s.step + 1, s.step % 2 == 0 ? 2 : 1);
  };
  ASSERT_EQ(status(run(options, tongue::testing::kTwoMuscleBoxScene)), status(common::kExitOk));
  std::vector<lcmt_tongue_state> last_of_step(kSteps + 1);
  for (const lcmt_tongue_state& s : bus_.states) last_of_step[static_cast<std::size_t>(s.step)] = s;
  for (std::int64_t k = 1; k <= kSteps; ++k) {
    const auto i = static_cast<std::size_t>(k);
    EXPECT_EQ(last_of_step[i].positions, lossless[i].positions) << "step " << k;
    EXPECT_EQ(last_of_step[i].activations, lossless[i].activations) << "step " << k;
    EXPECT_EQ(last_of_step[i].rejected_messages, 0) << "step " << k;
    if (k % 2 == 1) {
      EXPECT_GE(seen[i], 2) << "state " << k << " was not published again";
    }
  }
}

TEST_F(ServerLoopTest, StaleAndFutureActivationsAreRejectedAndCounted) {
  bus_.send_activation(1, {"flexor"}, {0.5});
  bus_.send_activation(1, {"flexor"}, {0.9});  // stale once step 1 is taken
  bus_.send_activation(0, {"flexor"}, {0.9});  // stale
  bus_.send_activation(5, {"flexor"}, {0.9});  // future
  bus_.send_activation(2, {"flexor"}, {0.25});
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run()), status(common::kExitOk));
  ASSERT_EQ(published_steps(), (std::vector<std::int64_t>{0, 1, 2}));
  EXPECT_EQ(bus_.states[1].activations, (std::vector<double>{0.5}));
  EXPECT_EQ(bus_.states[2].activations, (std::vector<double>{0.25}));
  EXPECT_EQ(bus_.states[2].rejected_messages, 3);
}

TEST_F(ServerLoopTest, InvalidAndUndecodableActivationsAreRejectedAndCounted) {
  bus_.send_activation(1, {"flexor"}, {1.5});  // out of range
  bus_.send_activation(1, {"nobody"}, {0.5});  // not a muscle
  bus_.send_activation(1, {"flexor"}, {std::numeric_limits<double>::quiet_NaN()});
  bus_.send_raw(Channel::activation, {1, 2, 3});  // not a message
  bus_.send_activation(1, {"flexor"}, {0.5});
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run()), status(common::kExitOk));
  ASSERT_EQ(published_steps(), (std::vector<std::int64_t>{0, 1}));
  EXPECT_EQ(bus_.states[1].activations, (std::vector<double>{0.5}));
  EXPECT_EQ(bus_.states[1].rejected_messages, 4);
}

TEST_F(ServerLoopTest, TwoControllersAreMergedAndAnOverlapIsRejected) {
  ServerOptions options;
  options.controllers = 2;
  bus_.send_activation(1, {"flexor"}, {0.5});
  bus_.send_activation(1, {"flexor"}, {0.3});  // flexor is already set for step 1
  bus_.send_command("describe");               // still at step 0: one of two arrived
  bus_.send_activation(1, {"extensor"}, {0.25});
  bus_.send_activation(2, {"extensor"}, {0.75});  // flexor keeps 0.5, named by nobody
  bus_.send_activation(2, {}, {});
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run(options, tongue::testing::kTwoMuscleBoxScene)), status(common::kExitOk));
  ASSERT_EQ(published_steps(), (std::vector<std::int64_t>{0, 0, 1, 2}));
  EXPECT_EQ(bus_.states[1].rejected_messages, 1);
  EXPECT_EQ(bus_.states[2].activations, (std::vector<double>{0.5, 0.25}));  // not the 0.3
  EXPECT_EQ(bus_.states[3].activations, (std::vector<double>{0.5, 0.75}));
}

TEST_F(ServerLoopTest, PauseHoldsACompleteRoundUntilResume) {
  bus_.send_command("pause");
  bus_.send_activation(1, {"flexor"}, {0.5});
  bus_.send_command("describe");
  bus_.send_command("resume");
  bus_.send_activation(2, {"flexor"}, {0.6});
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run()), status(common::kExitOk));
  ASSERT_EQ(published_steps(), (std::vector<std::int64_t>{0, 0, 0, 1, 2}));
  EXPECT_EQ(bus_.states[1].status, "paused");
  EXPECT_EQ(bus_.states[2].status, "paused");  // describe while paused, still at step 0
  EXPECT_EQ(bus_.states[3].status, "ok");
  EXPECT_EQ(bus_.states[3].activations, (std::vector<double>{0.5}));
  EXPECT_EQ(bus_.states[4].activations, (std::vector<double>{0.6}));
}

TEST_F(ServerLoopTest, WhilePausedTheLatestActivationForTheNextStepIsTheOneTaken) {
  bus_.send_command("pause");
  bus_.send_activation(1, {"flexor"}, {0.5});
  bus_.send_activation(1, {"flexor"}, {0.7});
  bus_.send_command("resume");
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run()), status(common::kExitOk));
  ASSERT_EQ(published_steps(), (std::vector<std::int64_t>{0, 0, 1}));
  EXPECT_EQ(bus_.states[2].activations, (std::vector<double>{0.7}));
  EXPECT_EQ(bus_.states[2].rejected_messages, 0);
}

TEST_F(ServerLoopTest, ResetRepeatsTheRunBitForBit) {
  const std::vector<double> levels{0.3, 1.0, 0.6};
  for (int round = 0; round < 2; ++round) {
    for (std::size_t k = 0; k < levels.size(); ++k)
      bus_.send_activation(static_cast<std::int64_t>(k) + 1, {"flexor"}, {levels[k]});
    bus_.send_activation(9, {"flexor"}, {0.5});  // a rejection, cleared by the reset
    if (round == 0) bus_.send_command("reset");
  }
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run(with_run_file())), status(common::kExitOk));
  ASSERT_EQ(published_steps(), (std::vector<std::int64_t>{0, 1, 2, 3, 0, 1, 2, 3}));
  EXPECT_EQ(bus_.states[4].rejected_messages, 0);
  EXPECT_EQ(bus_.states[4].positions, bus_.states[0].positions);
  for (std::size_t k = 0; k < 4; ++k) {
    const lcmt_tongue_state& first = bus_.states[k];
    const lcmt_tongue_state& again = bus_.states[k + 4];
    EXPECT_EQ(again.time, first.time);
    EXPECT_EQ(again.positions, first.positions) << "step " << k;
    EXPECT_EQ(again.muscle_lengths, first.muscle_lengths);
    EXPECT_EQ(again.muscle_velocities, first.muscle_velocities);
    EXPECT_EQ(again.activations, first.activations);
    EXPECT_EQ(again.newton_iterations, first.newton_iterations);
    EXPECT_EQ(again.residual_norm, first.residual_norm);
  }
  // The run file has every frame, the reset's step 0 included.
  const tongue::testing::RunFile f(dir_ / "run.h5");
  ASSERT_TRUE(f.ok());
  const std::vector<double> time = f.doubles("/time");
  ASSERT_EQ(time.size(), 8u);
  EXPECT_EQ(time[4], 0.0);
  EXPECT_EQ(f.doubles("/activations"),
            (std::vector<double>{0.0, 0.3, 1.0, 0.6, 0.0, 0.3, 1.0, 0.6}));
  const std::vector<double> lengths = f.doubles("/muscles/length");
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(lengths[k + 4], lengths[k]);
    // Logged from the same lengths as published.
    EXPECT_EQ(lengths[k], bus_.states[k].muscle_lengths.at(0));
  }
  EXPECT_EQ(f.string_attribute("/", "resets"), "1");
  EXPECT_EQ(f.string_attribute("/", "status"), "completed");
}

TEST_F(ServerLoopTest, DescribePublishesTheModelThenTheCurrentState) {
  bus_.send_activation(1, {"flexor"}, {0.4});
  bus_.send_command("describe");
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run()), status(common::kExitOk));
  EXPECT_EQ(bus_.published, "mssms");  // start: model, state 0; step 1; describe
  ASSERT_EQ(bus_.models.size(), 2u);
  EXPECT_EQ(bus_.models[1].rest_positions, bus_.models[0].rest_positions);
  ASSERT_EQ(published_steps(), (std::vector<std::int64_t>{0, 1, 1}));
  EXPECT_EQ(bus_.states[2].positions, bus_.states[1].positions);
  EXPECT_EQ(bus_.states[2].muscle_lengths, bus_.states[1].muscle_lengths);
  EXPECT_EQ(bus_.states[2].status, "ok");
}

TEST_F(ServerLoopTest, ShutdownEndsTheRunAndLeavesTheRestUnread) {
  bus_.send_activation(1, {"flexor"}, {0.4});
  bus_.send_command("shutdown");
  bus_.send_activation(2, {"flexor"}, {0.4});
  ASSERT_EQ(status(run(with_run_file())), status(common::kExitOk));
  EXPECT_EQ(published_steps(), (std::vector<std::int64_t>{0, 1}));
  const tongue::testing::RunFile f(dir_ / "run.h5");
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.doubles("/time").size(), 2u);
  EXPECT_EQ(f.string_attribute("/", "status"), "completed");
  EXPECT_EQ(f.string_attribute("/", "resets"), "0");
}

TEST_F(ServerLoopTest, MaxStepsEndsTheRun) {
  ServerOptions options;
  options.max_steps = 2;
  for (int k = 1; k <= 4; ++k) bus_.send_activation(k, {"flexor"}, {0.4});
  ASSERT_EQ(status(run(options)), status(common::kExitOk));
  EXPECT_EQ(published_steps(), (std::vector<std::int64_t>{0, 1, 2}));
}

// A 43-byte command whose string length is 0: lcm-gen's decoder reads before the buffer.
TEST_F(ServerLoopTest, ACommandWithAZeroStringLengthIsRejected) {
  const std::vector<std::uint8_t> bytes = command_bytes(0, std::vector<std::uint8_t>(23, 'x'));
  ASSERT_EQ(bytes.size(), 43u);
  bus_.send_raw(Channel::command, bytes);
  bus_.send_command("describe");
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run()), status(common::kExitOk));
  ASSERT_EQ(bus_.states.size(), 2u);
  EXPECT_EQ(bus_.states[1].rejected_messages, 1);
}

TEST_F(ServerLoopTest, HostileCommandBytesAreRejectedWithoutThrowing) {
  const std::vector<std::uint8_t> reset{'r', 'e', 's', 'e', 't', 0};
  std::vector<std::uint8_t> cut_in_the_length = command_bytes(6, reset);
  cut_in_the_length.resize(18);
  const std::vector<std::vector<std::uint8_t>> hostile{
      command_bytes(-1, reset),
      command_bytes(std::numeric_limits<std::int32_t>::min(), reset),
      command_bytes(std::numeric_limits<std::int32_t>::max(), reset),
      command_bytes(7, reset),                            // longer than the bytes left
      command_bytes(5, reset),                            // the NUL not where it says
      command_bytes(6, {'r', 'e', 's', 'e', 't', 0, 0}),  // a trailing byte
      command_bytes(6, {'r', 'e', 's'}),                  // cut off
      cut_in_the_length,
      {},
  };
  bus_.send_activation(1, {"flexor"}, {0.4});
  for (const auto& bytes : hostile) bus_.send_raw(Channel::command, bytes);
  bus_.send_raw(Channel::command, command_bytes(6, reset));  // well formed: a real reset
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run()), status(common::kExitOk));
  ASSERT_EQ(published_steps(), (std::vector<std::int64_t>{0, 1, 0}));
  EXPECT_EQ(bus_.states[1].rejected_messages, 0);
  EXPECT_EQ(bus_.states[2].rejected_messages, 0);  // the reset cleared the count
}

TEST_F(ServerLoopTest, RandomBytesAfterTheCommandFingerprintAreRejected) {
  std::mt19937 random(2024);
  constexpr int kTrials = 500;
  for (int trial = 0; trial < kTrials; ++trial) {
    std::vector<std::uint8_t> bytes = command_bytes(0, {});
    bytes.resize(8 + random() % 60);
    for (std::size_t i = 8; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(random());
    bus_.send_raw(Channel::command, bytes);
  }
  bus_.send_command("describe");
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run()), status(common::kExitOk));
  ASSERT_EQ(bus_.states.size(), 2u);
  EXPECT_EQ(bus_.states[1].rejected_messages, kTrials);  // undecodable, or no command's name
}

TEST_F(ServerLoopTest, AnUnknownCommandIsRejected) {
  bus_.send_command("jump");
  bus_.send_command("Shutdown");
  bus_.send_command("describe");
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run()), status(common::kExitOk));
  ASSERT_EQ(bus_.states.size(), 2u);
  EXPECT_EQ(bus_.states[1].rejected_messages, 2);
}

TEST_F(ServerLoopTest, LockStepSilenceStopsWhenAskedTo) {
  ServerOptions options = with_run_file();
  options.timeout_ms = 50;
  options.on_silence = OnSilence::stop;
  bus_.send_activation(1, {"flexor"}, {0.4});
  ASSERT_EQ(status(run(options)), status(common::kExitSilence));
  EXPECT_EQ(published_steps(), (std::vector<std::int64_t>{0, 1}));
  const tongue::testing::RunFile f(dir_ / "run.h5");
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.string_attribute("/", "status"), "stopped: no activation for 50 ms");
}

TEST_F(ServerLoopTest, FastModeHoldsTheLatestActivationAndPublishesEveryKth) {
  ServerOptions options = with_run_file();
  options.mode = Mode::fast;
  options.publish_every = 2;
  options.max_steps = 5;
  bus_.send_activation(-1, {"flexor"}, {0.7});  // any step number, held from the first step
  ASSERT_EQ(status(run(options)), status(common::kExitOk));
  EXPECT_EQ(published_steps(), (std::vector<std::int64_t>{0, 2, 4, 5}));
  for (std::size_t k = 1; k < bus_.states.size(); ++k)
    EXPECT_EQ(bus_.states[k].activations, (std::vector<double>{0.7}));
  // Every step is logged, and it is the run of the held level.
  const tongue::testing::RunFile f(dir_ / "run.h5");
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.doubles("/activations"), (std::vector<double>{0.0, 0.7, 0.7, 0.7, 0.7, 0.7}));
  EXPECT_EQ(bus_.states.back().positions, reference_positions(std::vector<double>(5, 0.7)).back());
}

TEST_F(ServerLoopTest, RealTimeDecaysTheActivationAfterSilence) {
  ServerOptions options;
  options.mode = Mode::realtime;
  options.silence_s = 0.04;  // 20 steps of 2 ms
  options.on_silence = OnSilence::decay;
  options.max_steps = 40;
  bus_.send_activation(-1, {"flexor"}, {0.8});
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(status(run(options)), status(common::kExitOk));
  const double took =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(took, 39 * kDt);  // paced: step 40 starts no earlier than 39 dt after the start
  ASSERT_EQ(bus_.states.size(), 41u);
  EXPECT_EQ(bus_.states[1].activations, (std::vector<double>{0.8}));
  EXPECT_EQ(bus_.states.back().activations, (std::vector<double>{0.0}));
}

TEST_F(ServerLoopTest, RefusesScenesAndOptionsItCannotRun) {
  ServerOptions options;
  options.timeout_ms = 0;
  EXPECT_THROW(run(options), std::invalid_argument);
  options = {};
  options.controllers = 2;
  options.mode = Mode::fast;
  EXPECT_THROW(run(options), std::invalid_argument);
  options = {};
  options.on_silence = OnSilence::decay;
  EXPECT_THROW(run(options), std::invalid_argument);
  options = {};
  options.nodes = Nodes::landmarks;  // the box has no landmark sets
  EXPECT_THROW(run(options), std::invalid_argument);
  EXPECT_TRUE(bus_.published.empty());
}

TEST_F(ServerLoopTest, StatesCarryTheSelectedNodes) {
  ServerOptions options;
  options.nodes = Nodes::surface;
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run(options)), status(common::kExitOk));
  ASSERT_EQ(bus_.states.size(), 1u);
  const lcmt_tongue_state& s = bus_.states[0];
  EXPECT_EQ(s.num_nodes, 20);  // every node of a 4 x 1 x 1 box is on its surface
  EXPECT_EQ(s.positions.size(), 3 * s.node_indices.size());
}

// The box falling onto a floor 0.5 mm below it (a square of 100 mm, facing up): once it lands,
// every state names the obstacle, the nodes it pushes and the forces, and they agree with the
// run file's frame of the same step: the contact forces sum to the force on the floor (its
// opposite), and the nodes in contact are those with a force in /contact/node_force.
TEST_F(ServerLoopTest, StatesCarryTheContactWithTheObstacles) {
  constexpr std::int64_t kSteps = 15;  // 30 ms: a free fall of 0.5 mm takes about 10 ms
  const std::string scene = box_above_floor();
  for (std::int64_t k = 1; k <= kSteps; ++k) bus_.send_activation(k, {"flexor"}, {0.0});
  bus_.send_command("shutdown");
  ServerOptions options = with_run_file();
  ASSERT_EQ(status(run(options, scene.c_str())), status(common::kExitOk));
  ASSERT_FALSE(bus_.models.empty());
  EXPECT_EQ(bus_.models.back().obstacle_names, (std::vector<std::string>{"floor"}));
  // The floor's surface as the OBJ file has it: 4 vertices, 2 triangles, in metres.
  EXPECT_EQ(bus_.models.back().obstacle_vertex_counts, (std::vector<std::int32_t>{4}));
  EXPECT_EQ(bus_.models.back().obstacle_triangle_counts, (std::vector<std::int32_t>{2}));
  EXPECT_EQ(bus_.models.back().num_obstacle_vertex_values, 12);
  EXPECT_EQ(bus_.models.back().obstacle_triangles.size(), 6u);
  for (double v : bus_.models.back().obstacle_vertices) EXPECT_LE(std::abs(v), 0.05 + 1e-12);
  ASSERT_EQ(bus_.states.size(), static_cast<std::size_t>(kSteps + 1));
  EXPECT_EQ(bus_.states.front().num_contacts, 0);  // at rest, 0.5 mm above the floor
  const lcmt_tongue_state& last = bus_.states.back();
  ASSERT_GT(last.num_contacts, 0) << "the box did not land";
  ASSERT_EQ(last.contact_forces.size(), 3u * last.num_contacts);
  ASSERT_EQ(last.num_obstacle_forces, 3);
  double sum_y = 0.0;
  for (int k = 0; k < last.num_contacts; ++k) {
    EXPECT_EQ(last.contact_obstacles[k], 0);
    EXPECT_GT(last.contact_forces[3 * k + 1], 0.0);  // the floor pushes up
    sum_y += last.contact_forces[3 * k + 1];
  }
  EXPECT_NEAR(last.obstacle_forces[1], -sum_y, 1e-12 * std::abs(sum_y));
  EXPECT_GE(last.max_penetration, 0.0);
  EXPECT_LT(last.max_penetration, 5e-4);  // below the floor's start: not through it

  const tongue::testing::RunFile f(dir_ / "run.h5");
  ASSERT_TRUE(f.ok());
  const std::vector<double> node_force = f.doubles("/contact/node_force");
  const std::size_t per_frame = node_force.size() / (kSteps + 1);
  for (int k = 0; k < last.num_contacts; ++k) {
    const std::size_t at = kSteps * per_frame + 3 * static_cast<std::size_t>(last.contact_nodes[k]);
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(node_force.at(at + c), last.contact_forces[3 * k + c]) << "contact " << k;
  }
  EXPECT_EQ(f.doubles("/contact/max_penetration").back(), last.max_penetration);
}

// A step accepted with a node deeper than the contact's tolerance, its multipliers' updates spent
// (none allowed here, and a tolerance of 0.1 um that the landing box's weight exceeds), is
// warned of on stderr.
TEST_F(ServerLoopTest, AStepLeftDeeperThanTheContactToleranceIsWarnedOf) {
  constexpr std::int64_t kSteps = 15;
  const std::string scene =
      box_above_floor() + "contact: {penetration_tolerance: 1.0e-7, max_augmentations: 0}\n";
  for (std::int64_t k = 1; k <= kSteps; ++k) bus_.send_activation(k, {"flexor"}, {0.0});
  bus_.send_command("shutdown");
  ::testing::internal::CaptureStderr();
  const ExitStatus exit = run({}, scene.c_str());
  const std::string err = ::testing::internal::GetCapturedStderr();
  ASSERT_EQ(status(exit), status(common::kExitOk)) << err;
  ASSERT_GT(bus_.states.back().max_penetration, 1e-7) << "the box did not land";
  const std::string warning = "deeper than the contact's penetration tolerance";
  EXPECT_NE(err.find(warning), std::string::npos) << err;
}

TEST_F(ServerLoopTest, TheRunFileCarriesThePerStepTiming) {
  constexpr std::int64_t kSteps = 6;
  for (std::int64_t k = 1; k <= kSteps; ++k) bus_.send_activation(k, {"flexor"}, {0.3});
  bus_.send_command("shutdown");
  ASSERT_EQ(status(run(with_run_file())), status(common::kExitOk));
  const tongue::testing::RunFile f(dir_ / "run.h5");
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.string_attribute("/", "timing_steps"), std::to_string(kSteps));
  for (const char* part : {"physics", "run_file", "state_message", "loop"}) {
    for (const char* figure : {"_ms", "_max_ms"}) {
      const std::string name = std::string("timing_") + part + figure;
      const std::string text = f.string_attribute("/", name);
      ASSERT_NE(text, "<missing>") << name;
      const double value = std::stod(text);
      EXPECT_TRUE(std::isfinite(value)) << name << " = " << text;
      EXPECT_GE(value, 0.0) << name << " = " << text;
    }
  }
  const double span = std::stod(f.string_attribute("/", "timing_span_s"));
  EXPECT_TRUE(std::isfinite(span));
  EXPECT_GE(span, 1e-3 * kSteps * std::stod(f.string_attribute("/", "timing_physics_ms")));
  // Every step solves, so its physics takes some time, and the max is at least the mean.
  EXPECT_GT(std::stod(f.string_attribute("/", "timing_physics_ms")), 0.0);
  EXPECT_GE(std::stod(f.string_attribute("/", "timing_physics_max_ms")),
            std::stod(f.string_attribute("/", "timing_physics_ms")));
  // The solver's means per step: the iterations are those the frames count (frame 0 is the
  // start, every later frame one step), and the physics time is split into non-negative parts.
  const std::vector<int> iterations = f.ints("/solver/iterations");
  ASSERT_EQ(iterations.size(), static_cast<std::size_t>(kSteps + 1));
  double sum = 0.0;
  for (std::size_t k = 1; k < iterations.size(); ++k) sum += iterations[k];
  EXPECT_NEAR(std::stod(f.string_attribute("/", "timing_iterations")), sum / kSteps, 1e-5);
  for (const char* name : {"timing_factorizations", "timing_assembly_ms", "timing_factorization_ms",
                           "timing_solve_ms"}) {
    const std::string text = f.string_attribute("/", name);
    ASSERT_NE(text, "<missing>") << name;
    EXPECT_GE(std::stod(text), 0.0) << name << " = " << text;
  }
}

}  // namespace
}  // namespace tongue::server
