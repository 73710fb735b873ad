#include "fem/mesh/mesh.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace tongue::fem {
namespace {

Mesh two_set_mesh() {
  Mesh m;
  m.nodes = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0.5, 0.5), Vec3(2, 2, 2)};
  m.node_sets["fixed"] = {0, 1};
  m.node_sets["load"] = {3};
  m.element_sets["tongue"] = {};
  return m;
}

TEST(Mesh, NodeSetLookupReturnsTheStoredSet) {
  const Mesh m = two_set_mesh();
  EXPECT_EQ(m.node_set("fixed"), (std::vector<int>{0, 1}));
  EXPECT_EQ(m.node_set("load"), (std::vector<int>{3}));
  EXPECT_TRUE(m.element_set("tongue").empty());
}

TEST(Mesh, MissingNodeSetNamesItAndListsAvailableOnes) {
  const Mesh m = two_set_mesh();
  try {
    m.node_set("fixd");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("'fixd'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'fixed'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'load'"), std::string::npos) << msg;
  }
}

TEST(Mesh, MissingElementSetNamesItAndListsAvailableOnes) {
  const Mesh m = two_set_mesh();
  try {
    m.element_set("muscle");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("'muscle'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'tongue'"), std::string::npos) << msg;
  }
  EXPECT_THROW(Mesh().element_set("all"), std::invalid_argument);
}

TEST(Mesh, NodesInBoxIsInclusiveWithTolerance) {
  const Mesh m = two_set_mesh();
  EXPECT_EQ(nodes_in_box(m, Vec3(0, 0, 0), Vec3(1, 1, 1)), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(nodes_in_box(m, Vec3(0.6, -1, -1), Vec3(3, 3, 3)), (std::vector<int>{1, 3}));
  // Node 1 sits 1e-9 outside the box: caught only with a large enough tolerance.
  EXPECT_EQ(nodes_in_box(m, Vec3(1 + 1e-9, -1, -1), Vec3(3, 3, 3)), (std::vector<int>{3}));
  EXPECT_EQ(nodes_in_box(m, Vec3(1 + 1e-9, -1, -1), Vec3(3, 3, 3), 1e-8), (std::vector<int>{1, 3}));
  EXPECT_TRUE(nodes_in_box(m, Vec3(5, 5, 5), Vec3(6, 6, 6)).empty());
}

}  // namespace
}  // namespace tongue::fem
