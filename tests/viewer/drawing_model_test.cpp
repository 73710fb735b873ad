// The page's model from a model message: the boundary of the mesh, and a forged message refused
// with the field named.
#include "viewer/drawing_model.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace tongue::viewer {
namespace {

// One unit hexahedron with a fibre along x and a one-triangle obstacle.
tongue_lcm::lcmt_tongue_model one_hex() {
  tongue_lcm::lcmt_tongue_model m{};
  m.rest_positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  m.num_nodes = 8;
  m.num_rest_positions = 24;
  m.elements = {0, 1, 2, 3, 4, 5, 6, 7};
  m.num_elements = 1;
  m.num_element_nodes = 8;
  m.muscle_names = {"SG"};
  m.muscle_max_forces = {2.5};
  m.num_muscles = 1;
  m.landmark_names = {"tip"};
  m.landmark_nodes = {1};
  m.num_landmarks = 1;
  m.dt = 0.004;
  m.fibre_muscles = {0};
  m.num_fibres = 1;
  m.fibre_offsets = {0, 2};
  m.num_fibre_offsets = 2;
  m.fibre_nodes = {0, 1};
  m.num_fibre_nodes = 2;
  m.fibre_has_origin = {false};
  m.fibre_origins = {0, 0, 0};
  m.num_fibre_origins = 3;
  m.obstacle_names = {"palate"};
  m.num_obstacles = 1;
  m.obstacle_vertex_counts = {3};
  m.obstacle_triangle_counts = {1};
  m.obstacle_vertices = {0, 2, 0, 1, 2, 0, 0, 2, 1};
  m.num_obstacle_vertex_values = 9;
  m.obstacle_triangles = {0, 1, 2};
  m.num_obstacle_triangle_values = 3;
  return m;
}

TEST(DrawingModel, OneHexahedronHasSixBoundaryQuads) {
  const DrawingModel d = drawing_model(one_hex());
  EXPECT_EQ(d.num_nodes(), 8);
  EXPECT_EQ(d.surface.size(), 6u * 4u);
  const auto j = nlohmann::json::parse(model_json(d, 7));
  EXPECT_EQ(j["version"], 7);
  EXPECT_EQ(j["muscles"][0]["name"], "SG");
  EXPECT_EQ(j["fibres"]["nodes"], (std::vector<int>{0, 1}));
  EXPECT_TRUE(j["fibres"]["origins"][0].is_null());  // no bony origin
  EXPECT_EQ(j["obstacles"][0]["triangles"], (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(j["landmarks"][0]["node"], 1);
}

void expect_refused(const tongue_lcm::lcmt_tongue_model& m, const std::string& words) {
  try {
    drawing_model(m);
    ADD_FAILURE() << "accepted; expected: " << words;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(DrawingModel, AForgedMessageIsRefusedNamingTheField) {
  auto m = one_hex();
  m.fibre_nodes = {0, 8};
  expect_refused(m, "fibre nodes names index 8 of 8");
  m = one_hex();
  m.fibre_offsets = {0, 3};
  expect_refused(m, "fibre offsets do not span the fibre nodes");
  m = one_hex();
  m.obstacle_vertex_counts = {4};
  expect_refused(m, "obstacle palate runs past");
  m = one_hex();
  m.obstacle_triangles = {0, 1, 3};
  expect_refused(m, "obstacle palate's triangles names index 3 of 3");
  m = one_hex();
  m.landmark_nodes = {-1};
  expect_refused(m, "landmark tip names index -1");
  m = one_hex();
  m.rest_positions[4] = std::numeric_limits<double>::quiet_NaN();
  expect_refused(m, "rest positions holds a value that is not finite");
}

}  // namespace
}  // namespace tongue::viewer
