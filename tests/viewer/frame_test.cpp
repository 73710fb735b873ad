// A frame's JSON: positions rounded to 10 nm, no NaN reaching the page.
#include "viewer/frame.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace tongue::viewer {
namespace {

TEST(FrameJson, PositionsRoundedTo10Nanometres) {
  Frame f;
  f.positions = {0.012345678912, -0.0000000049, 0.1};
  const auto j = nlohmann::json::parse(frame_json(f));
  EXPECT_DOUBLE_EQ(j["positions"][0].get<double>(), 0.01234568);
  EXPECT_DOUBLE_EQ(j["positions"][1].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(j["positions"][2].get<double>(), 0.1);
  // The rounding moves a position by at most half the step.
  for (double x : {0.0123456789, -0.04444444449, 1.0 / 3.0})
    EXPECT_LE(std::abs(rounded_position(x) - x), 0.5e-8 + 1e-17);
}

TEST(FrameJson, ANumberThatIsNotFiniteIsNull) {
  Frame f;
  f.residual = std::numeric_limits<double>::quiet_NaN();
  f.real_time_factor = std::numeric_limits<double>::infinity();
  const auto j = nlohmann::json::parse(frame_json(f, 4));
  EXPECT_TRUE(j["residual"].is_null());
  EXPECT_TRUE(j["real_time_factor"].is_null());
  EXPECT_EQ(j["dropped"], 4);
  EXPECT_TRUE(j["nodes"].is_null());  // every node, in order
  EXPECT_TRUE(j["index"].is_null());  // live
}

TEST(FrameFromState, CarriesTheStatesFields) {
  tongue_lcm::lcmt_tongue_state s{};
  s.step = 12;
  s.time = 0.048;
  s.node_indices = {3};
  s.positions = {0.01, 0.02, 0.03};
  s.activations = {0.5};
  s.newton_iterations = 4;
  s.status = "ok";
  s.contact_nodes = {3};
  s.contact_obstacles = {0};
  s.contact_forces = {0, -0.1, 0};
  const Frame f = frame_from_state(s);
  const auto j = nlohmann::json::parse(frame_json(f));
  EXPECT_EQ(j["step"], 12);
  EXPECT_EQ(j["nodes"], (std::vector<int>{3}));
  EXPECT_EQ(j["iterations"], 4);
  EXPECT_EQ(j["contacts"]["obstacles"], (std::vector<int>{0}));
}

}  // namespace
}  // namespace tongue::viewer
