// Every message type encodes and decodes to the same values.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "bus/messages.hpp"

namespace tongue::bus {
namespace {

// Encodes msg, checks the size, and decodes the bytes into a fresh message.
template <typename Message>
Message round_trip(const Message& msg) {
  const int size = msg.getEncodedSize();
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  EXPECT_EQ(msg.encode(bytes.data(), 0, size), size);
  Message decoded;
  EXPECT_EQ(decoded.decode(bytes.data(), 0, size), size);
  return decoded;
}

TEST(LcmtypesRoundTrip, Activation) {
  tongue_lcm::lcmt_tongue_activation msg;
  msg.utime = 1'700'000'000'123'456;
  msg.step = 42;
  msg.num_muscles = 3;
  msg.names = {"GGp_left", "SG_right", "SL"};
  msg.levels = {0.0, 0.25, 1.0};
  const auto out = round_trip(msg);
  EXPECT_EQ(out.utime, msg.utime);
  EXPECT_EQ(out.step, msg.step);
  EXPECT_EQ(out.num_muscles, msg.num_muscles);
  EXPECT_EQ(out.names, msg.names);
  EXPECT_EQ(out.levels, msg.levels);
}

TEST(LcmtypesRoundTrip, ActivationEmptyApplyNow) {
  tongue_lcm::lcmt_tongue_activation msg;
  msg.utime = 1;
  msg.step = -1;
  msg.num_muscles = 0;
  const auto out = round_trip(msg);
  EXPECT_EQ(out.step, -1);
  EXPECT_EQ(out.num_muscles, 0);
  EXPECT_TRUE(out.names.empty());
  EXPECT_TRUE(out.levels.empty());
}

TEST(LcmtypesRoundTrip, State) {
  tongue_lcm::lcmt_tongue_state msg;
  msg.utime = 123'456'789;
  msg.step = 120;
  msg.time = 0.12;
  msg.num_nodes = 2;
  msg.node_indices = {7, 945};
  msg.num_positions = 6;
  msg.positions = {0.01, 0.02, -0.003, 0.045, 0.031, 0.0};
  msg.num_muscles = 2;
  msg.muscle_lengths = {0.061, 0.034};
  msg.muscle_velocities = {-0.002, 0.0005};
  msg.activations = {0.3, 0.0};
  msg.newton_iterations = 3;
  msg.residual_norm = 1.5e-9;
  msg.step_wall_time = 0.0008;
  msg.step_cuts = 1;
  msg.converged = true;
  msg.status = "ok";
  msg.rejected_messages = 5;
  msg.overruns = 2;
  const auto out = round_trip(msg);
  EXPECT_EQ(out.utime, msg.utime);
  EXPECT_EQ(out.step, msg.step);
  EXPECT_EQ(out.time, msg.time);
  EXPECT_EQ(out.num_nodes, msg.num_nodes);
  EXPECT_EQ(out.node_indices, msg.node_indices);
  EXPECT_EQ(out.num_positions, msg.num_positions);
  EXPECT_EQ(out.positions, msg.positions);
  EXPECT_EQ(out.num_muscles, msg.num_muscles);
  EXPECT_EQ(out.muscle_lengths, msg.muscle_lengths);
  EXPECT_EQ(out.muscle_velocities, msg.muscle_velocities);
  EXPECT_EQ(out.activations, msg.activations);
  EXPECT_EQ(out.newton_iterations, msg.newton_iterations);
  EXPECT_EQ(out.residual_norm, msg.residual_norm);
  EXPECT_EQ(out.step_wall_time, msg.step_wall_time);
  EXPECT_EQ(out.step_cuts, msg.step_cuts);
  EXPECT_EQ(out.converged, msg.converged);
  EXPECT_EQ(out.status, msg.status);
  EXPECT_EQ(out.rejected_messages, msg.rejected_messages);
  EXPECT_EQ(out.overruns, msg.overruns);
}

TEST(LcmtypesRoundTrip, Model) {
  tongue_lcm::lcmt_tongue_model msg{};
  msg.utime = 99;
  msg.num_nodes = 8;
  msg.num_rest_positions = 24;
  msg.rest_positions.resize(24);
  for (int i = 0; i < 24; ++i) msg.rest_positions[i] = 0.001 * i;
  msg.num_elements = 1;
  msg.num_element_nodes = 8;
  msg.elements = {0, 1, 3, 2, 4, 5, 7, 6};
  msg.num_muscles = 2;
  msg.muscle_names = {"GGp_left", "SL"};
  msg.muscle_max_forces = {18.5, 19.0};
  msg.num_landmarks = 1;
  msg.landmark_names = {"tip"};
  msg.landmark_nodes = {5};
  msg.dt = 0.001;
  msg.scene = "mesh:\n  box: {size: [0.01, 0.01, 0.01]}\n";
  msg.num_obstacles = 1;
  msg.obstacle_names = {"floor"};
  msg.num_fibres = 2;
  msg.fibre_muscles = {0, 1};
  msg.num_fibre_offsets = 3;
  msg.fibre_offsets = {0, 2, 3};
  msg.num_fibre_nodes = 3;
  msg.fibre_nodes = {0, 4, 7};
  msg.fibre_has_origin = {false, true};
  msg.num_fibre_origins = 6;
  msg.fibre_origins = {0.0, 0.0, 0.0, 0.01, -0.02, 0.0};
  msg.obstacle_vertex_counts = {3};
  msg.obstacle_triangle_counts = {1};
  msg.num_obstacle_vertex_values = 9;
  msg.obstacle_vertices = {0.0, -0.01, 0.0, 0.01, -0.01, 0.0, 0.0, -0.01, 0.01};
  msg.num_obstacle_triangle_values = 3;
  msg.obstacle_triangles = {0, 2, 1};
  const auto out = round_trip(msg);
  EXPECT_EQ(out.utime, msg.utime);
  EXPECT_EQ(out.num_nodes, msg.num_nodes);
  EXPECT_EQ(out.num_rest_positions, msg.num_rest_positions);
  EXPECT_EQ(out.rest_positions, msg.rest_positions);
  EXPECT_EQ(out.num_elements, msg.num_elements);
  EXPECT_EQ(out.num_element_nodes, msg.num_element_nodes);
  EXPECT_EQ(out.elements, msg.elements);
  EXPECT_EQ(out.num_muscles, msg.num_muscles);
  EXPECT_EQ(out.muscle_names, msg.muscle_names);
  EXPECT_EQ(out.muscle_max_forces, msg.muscle_max_forces);
  EXPECT_EQ(out.num_landmarks, msg.num_landmarks);
  EXPECT_EQ(out.landmark_names, msg.landmark_names);
  EXPECT_EQ(out.landmark_nodes, msg.landmark_nodes);
  EXPECT_EQ(out.dt, msg.dt);
  EXPECT_EQ(out.scene, msg.scene);
  EXPECT_EQ(out.obstacle_names, msg.obstacle_names);
  EXPECT_EQ(out.fibre_muscles, msg.fibre_muscles);
  EXPECT_EQ(out.fibre_offsets, msg.fibre_offsets);
  EXPECT_EQ(out.fibre_nodes, msg.fibre_nodes);
  EXPECT_EQ(out.fibre_has_origin, msg.fibre_has_origin);
  EXPECT_EQ(out.fibre_origins, msg.fibre_origins);
  EXPECT_EQ(out.obstacle_vertex_counts, msg.obstacle_vertex_counts);
  EXPECT_EQ(out.obstacle_triangle_counts, msg.obstacle_triangle_counts);
  EXPECT_EQ(out.obstacle_vertices, msg.obstacle_vertices);
  EXPECT_EQ(out.obstacle_triangles, msg.obstacle_triangles);
}

TEST(LcmtypesRoundTrip, Command) {
  for (const char* command : {"reset", "pause", "resume", "shutdown", "describe"}) {
    tongue_lcm::lcmt_tongue_command msg;
    msg.utime = 7;
    msg.command = command;
    const auto out = round_trip(msg);
    EXPECT_EQ(out.utime, msg.utime);
    EXPECT_EQ(out.command, msg.command);
  }
}

}  // namespace
}  // namespace tongue::bus
