// The checked decoders of the server's publications (decode_state, decode_model): whole messages
// decode, and every truncation, every hostile count or string length and random bytes after the
// fingerprint fail with a reason instead of throwing or reading out of bounds.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "bus/messages.hpp"
#include "bus/published_decode.hpp"
#include "wire_bytes.hpp"

namespace tongue::bus {
namespace {

using testing::encoded;
using testing::put_int32;
using tongue_lcm::lcmt_tongue_model;
using tongue_lcm::lcmt_tongue_state;

lcmt_tongue_state a_state() {
  lcmt_tongue_state s{};
  s.step = 7;
  s.time = 0.014;
  s.num_nodes = 2;
  s.node_indices = {0, 5};
  s.num_positions = 6;
  s.positions = {0.0, 0.1, 0.2, 0.3, 0.4, 0.5};
  s.num_muscles = 1;
  s.muscle_lengths = {0.02};
  s.muscle_velocities = {0.0};
  s.activations = {0.5};
  s.converged = true;
  s.status = "ok";
  s.num_contacts = 1;
  s.contact_nodes = {5};
  s.contact_obstacles = {0};
  s.num_contact_forces = 3;
  s.contact_forces = {0.0, -0.2, 0.0};
  s.num_obstacle_forces = 3;
  s.obstacle_forces = {0.0, 0.2, 0.0};
  s.max_penetration = 1e-5;
  s.reduced_model_correction = 2e-4;
  return s;
}

// Bytes after a_state()'s status: rejected_messages, overruns, the contact fields, then the
// reduced model's correction.
constexpr std::size_t kStateTail = 8 + 8 + (4 + 4 + 4) + (4 + 3 * 8) + (4 + 3 * 8) + 8 + 8;

lcmt_tongue_model a_model() {
  lcmt_tongue_model m{};
  m.num_nodes = 1;
  m.num_rest_positions = 3;
  m.rest_positions = {0.0, 0.0, 0.0};
  m.num_elements = 1;
  m.num_element_nodes = 8;
  m.elements = {0, 0, 0, 0, 0, 0, 0, 0};
  m.num_muscles = 2;
  m.muscle_names = {"GGp", "SG"};
  m.muscle_max_forces = {1.0, 2.0};
  m.num_landmarks = 1;
  m.landmark_names = {"tip"};
  m.landmark_nodes = {0};
  m.dt = 0.002;
  m.scene = "mesh: {}";
  m.num_obstacles = 1;
  m.obstacle_names = {"hard_palate"};
  m.num_fibres = 1;
  m.fibre_muscles = {1};
  m.num_fibre_offsets = 2;
  m.fibre_offsets = {0, 1};
  m.num_fibre_nodes = 1;
  m.fibre_nodes = {0};
  m.fibre_has_origin = {true};
  m.num_fibre_origins = 3;
  m.fibre_origins = {0.0, -0.01, 0.0};
  m.obstacle_vertex_counts = {3};
  m.obstacle_triangle_counts = {1};
  m.num_obstacle_vertex_values = 9;
  m.obstacle_vertices = {0.0, 0.02, 0.0, 0.01, 0.02, 0.0, 0.0, 0.02, 0.01};
  m.num_obstacle_triangle_values = 3;
  m.obstacle_triangles = {0, 1, 2};
  return m;
}

// Offsets of the int32 fields (after the 8-byte fingerprint), from the .lcm layouts.
constexpr std::size_t kStateNumNodes = 8 + 8 + 8 + 8;
constexpr std::size_t kModelNumNodes = 8 + 8;

bool state_decodes(const std::vector<std::uint8_t>& bytes, std::string& reason) {
  lcmt_tongue_state out;
  return decode_state(bytes.data(), static_cast<int>(bytes.size()), out, reason);
}
bool model_decodes(const std::vector<std::uint8_t>& bytes, std::string& reason) {
  lcmt_tongue_model out;
  return decode_model(bytes.data(), static_cast<int>(bytes.size()), out, reason);
}

TEST(DecodeState, DecodesAWholeMessage) {
  const auto bytes = encoded(a_state());
  lcmt_tongue_state out;
  std::string reason;
  ASSERT_TRUE(decode_state(bytes.data(), static_cast<int>(bytes.size()), out, reason)) << reason;
  EXPECT_EQ(out.step, 7);
  EXPECT_EQ(out.node_indices, (std::vector<std::int32_t>{0, 5}));
  EXPECT_EQ(out.status, "ok");
}

TEST(DecodeModel, DecodesAWholeMessage) {
  const auto bytes = encoded(a_model());
  lcmt_tongue_model out;
  std::string reason;
  ASSERT_TRUE(decode_model(bytes.data(), static_cast<int>(bytes.size()), out, reason)) << reason;
  EXPECT_EQ(out.muscle_names, (std::vector<std::string>{"GGp", "SG"}));
  EXPECT_EQ(out.scene, "mesh: {}");
}

TEST(DecodeState, EveryTruncationFailsWithAReason) {
  const auto whole = encoded(a_state());
  for (std::size_t size = 0; size < whole.size(); ++size) {
    const std::vector<std::uint8_t> bytes(whole.begin(), whole.begin() + size);
    std::string reason;
    EXPECT_FALSE(state_decodes(bytes, reason)) << size;
    EXPECT_FALSE(reason.empty()) << size;
  }
}

TEST(DecodeModel, EveryTruncationFailsWithAReason) {
  const auto whole = encoded(a_model());
  for (std::size_t size = 0; size < whole.size(); ++size) {
    const std::vector<std::uint8_t> bytes(whole.begin(), whole.begin() + size);
    std::string reason;
    EXPECT_FALSE(model_decodes(bytes, reason)) << size;
    EXPECT_FALSE(reason.empty()) << size;
  }
}

// The forged state that used to end ep_controller: its status string of length 0 (lcm-gen's
// decoder throws on it), and the other hostile lengths.
TEST(DecodeState, BadStatusLengthsFail) {
  const auto whole = encoded(a_state());
  const std::size_t status_offset = whole.size() - kStateTail - (4 + 3);  // "ok" + NUL
  for (const std::int32_t length : {0, -1, std::numeric_limits<std::int32_t>::min(), 100,
                                    std::numeric_limits<std::int32_t>::max()}) {
    auto bytes = whole;
    put_int32(bytes, status_offset, length);
    std::string reason;
    EXPECT_FALSE(state_decodes(bytes, reason)) << length;
    EXPECT_NE(reason.find("status"), std::string::npos) << reason;
  }
}

TEST(DecodeState, ContactCountsThatDoNotMatchFail) {
  const auto whole = encoded(a_state());
  // num_contact_forces: 4 + 3 * 8 + 4 + 3 * 8 + 8 + 8 bytes before the end.
  const std::size_t contact_forces = whole.size() - (4 + 3 * 8) - (4 + 3 * 8) - 8 - 8;
  auto bytes = whole;
  put_int32(bytes, contact_forces, 0);  // 3 * num_contacts expected; the rest no longer fits
  std::string reason;
  EXPECT_FALSE(state_decodes(bytes, reason));
  EXPECT_FALSE(reason.empty());
  lcmt_tongue_state two_forces = a_state();
  two_forces.num_contact_forces = 2;
  two_forces.contact_forces = {0.0, -0.2};
  EXPECT_FALSE(state_decodes(encoded(two_forces), reason));
  EXPECT_NE(reason.find("num_contact_forces = 2 is not 3 * num_contacts"), std::string::npos)
      << reason;
  lcmt_tongue_state four = a_state();
  four.num_obstacle_forces = 4;
  four.obstacle_forces = {0.0, 0.2, 0.0, 1.0};
  EXPECT_FALSE(state_decodes(encoded(four), reason));
  EXPECT_NE(reason.find("num_obstacle_forces = 4 is not a multiple of 3"), std::string::npos)
      << reason;
}

// Every int32 of the message overwritten with an absurd value: a count or length among them
// must fail the check (or still decode when the field is not a count), never throw.
template <typename Decodes>
void expect_no_throw_with_absurd_int32s(const std::vector<std::uint8_t>& whole, Decodes decodes) {
  for (std::size_t at = 8; at + 4 <= whole.size(); ++at) {
    for (const std::int32_t v : {-1, 0, 3, 1 << 20, std::numeric_limits<std::int32_t>::min(),
                                 std::numeric_limits<std::int32_t>::max()}) {
      auto bytes = whole;
      put_int32(bytes, at, v);
      std::string reason;
      EXPECT_NO_THROW(decodes(bytes, reason)) << at << " " << v;
    }
  }
}

TEST(DecodeState, AbsurdValuesInEveryInt32Position) {
  expect_no_throw_with_absurd_int32s(encoded(a_state()), state_decodes);
}

TEST(DecodeModel, AbsurdValuesInEveryInt32Position) {
  expect_no_throw_with_absurd_int32s(encoded(a_model()), model_decodes);
}

TEST(DecodeState, HugeCountFailsWithoutAllocating) {
  auto bytes = encoded(a_state());
  put_int32(bytes, kStateNumNodes, std::numeric_limits<std::int32_t>::max());
  std::string reason;
  EXPECT_FALSE(state_decodes(bytes, reason));
  EXPECT_NE(reason.find("num_nodes = 2147483647 needs at least"), std::string::npos) << reason;
}

TEST(DecodeState, PositionsMustBeThreePerNode) {
  lcmt_tongue_state s = a_state();
  s.num_positions = 3;
  s.positions.resize(3);
  std::string reason;
  EXPECT_FALSE(state_decodes(encoded(s), reason));
  EXPECT_NE(reason.find("num_positions = 3 is not 3 * num_nodes (2)"), std::string::npos) << reason;
}

TEST(DecodeModel, RestPositionsAndElementsMustFitTheirCounts) {
  lcmt_tongue_model m = a_model();
  m.num_nodes = 2;
  std::string reason;
  EXPECT_FALSE(model_decodes(encoded(m), reason));
  EXPECT_NE(reason.find("num_rest_positions"), std::string::npos) << reason;
  m = a_model();
  m.num_elements = 2;
  EXPECT_FALSE(model_decodes(encoded(m), reason));
  EXPECT_NE(reason.find("num_element_nodes"), std::string::npos) << reason;
}

TEST(DecodeModel, FibresAndObstacleSurfacesMustFitTheirCounts) {
  lcmt_tongue_model m = a_model();
  std::string reason;
  m.num_fibre_origins = 6;
  m.fibre_origins.resize(6);
  EXPECT_FALSE(model_decodes(encoded(m), reason));
  EXPECT_NE(reason.find("num_fibre_origins = 6 is not 3 * num_fibres (1)"), std::string::npos)
      << reason;
  m = a_model();
  m.num_fibre_offsets = 1;
  m.fibre_offsets = {0};
  EXPECT_FALSE(model_decodes(encoded(m), reason));
  EXPECT_NE(reason.find("num_fibre_offsets = 1 is not num_fibres + 1 (2)"), std::string::npos)
      << reason;
  m = a_model();
  m.num_obstacle_triangle_values = 2;
  m.obstacle_triangles = {0, 1};
  EXPECT_FALSE(model_decodes(encoded(m), reason));
  EXPECT_NE(reason.find("must be multiples of 3"), std::string::npos) << reason;
}

TEST(DecodeModel, NegativeNodeCountFails) {
  auto bytes = encoded(a_model());
  put_int32(bytes, kModelNumNodes, -1);
  std::string reason;
  EXPECT_FALSE(model_decodes(bytes, reason));
  EXPECT_NE(reason.find("num_nodes = -1 is negative"), std::string::npos) << reason;
}

TEST(DecodePublished, TrailingBytesFail) {
  auto state = encoded(a_state());
  state.push_back(0);
  std::string reason;
  EXPECT_FALSE(state_decodes(state, reason));
  EXPECT_NE(reason.find("1 trailing bytes"), std::string::npos) << reason;
  auto model = encoded(a_model());
  model.push_back(0);
  EXPECT_FALSE(model_decodes(model, reason));
  EXPECT_NE(reason.find("1 trailing bytes"), std::string::npos) << reason;
}

TEST(DecodePublished, AnotherTypeFailsOnTheFingerprint) {
  std::string reason;
  EXPECT_FALSE(state_decodes(encoded(a_model()), reason));
  EXPECT_NE(reason.find("fingerprint"), std::string::npos) << reason;
  EXPECT_FALSE(model_decodes(encoded(a_state()), reason));
  EXPECT_NE(reason.find("fingerprint"), std::string::npos) << reason;
}

// Random bytes after a valid fingerprint, of random lengths (seeded: the same cases every run).
TEST(DecodePublished, RandomBytesAfterTheFingerprintNeverThrow) {
  std::mt19937 random(15);
  const auto state = encoded(a_state());
  const auto model = encoded(a_model());
  for (int i = 0; i < 4000; ++i) {
    const auto& base = i % 2 == 0 ? state : model;
    std::vector<std::uint8_t> bytes(base.begin(), base.begin() + 8);
    const std::size_t extra = random() % 400;
    for (std::size_t k = 0; k < extra; ++k) bytes.push_back(static_cast<std::uint8_t>(random()));
    std::string reason;
    EXPECT_NO_THROW(i % 2 == 0 ? state_decodes(bytes, reason) : model_decodes(bytes, reason));
  }
}

TEST(DecodePublished, NullOrNegativeSizeFails) {
  lcmt_tongue_state s;
  lcmt_tongue_model m;
  std::string reason;
  EXPECT_FALSE(decode_state(nullptr, 10, s, reason));
  EXPECT_FALSE(decode_model("x", -1, m, reason));
}

}  // namespace
}  // namespace tongue::bus
