#include "scene/scene_builder.hpp"
#include "scene/scene_error_expectations.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "fem/assembly/loads.hpp"
#include "scene/scene_reader.hpp"
#include "support/box_scenes.hpp"
#include "support/temp_dir_test.hpp"

namespace tongue::scene {
namespace {

namespace fs = std::filesystem;

const char* const kBox = testing::kStaticBoxScene;

BuiltScene build(const std::string& extra) {
  return build_scene(parse_scene(std::string(kBox) + extra, "", "test.yaml"));
}

void expect_build_error(const std::string& extra, const std::string& key_path,
                        const std::string& also = "") {
  scene_test::expect_build_error(std::string(kBox) + extra, key_path, also);
}

fem::Vec3 total(const fem::Vector& f) {
  fem::Vec3 sum = fem::Vec3::Zero();
  for (int n = 0; n < f.size() / 3; ++n) sum += f.segment<3>(3 * n);
  return sum;
}

const fem::ConstantForce& constant_load(const BuiltScene& built, std::size_t i) {
  const auto* load = dynamic_cast<const fem::ConstantForce*>(built.system->loads().at(i).get());
  if (!load) throw std::logic_error("not a ConstantForce");
  return *load;
}

TEST(SceneBuilder, ClampedFaceAndPartialConstraintGiveTheRightPrescribedDofs) {
  const BuiltScene built = build(R"(
constraints:
  - {set: x_min, components: [x, y, z]}
  - {set: x_max, components: [y]}
)");
  // 4 nodes per x face: 4 x 3 clamped + 4 x 1 on the far face.
  EXPECT_EQ(built.prescribed.size(), 16u);
  EXPECT_EQ(built.solid->dofs().num_free(), 3 * 20 - 16);
  for (const auto& p : built.prescribed) EXPECT_EQ(p.value, 0.0);
}

TEST(SceneBuilder, OverlappingSetsWithEqualValuesPrescribeEachDofOnce) {
  const BuiltScene built = build(R"(
constraints:
  - {set: x_min, components: [x, y, z]}
  - {set: y_min, components: [y]}
)");
  // y_min has 10 nodes, 2 of them on x_min whose y is already fixed.
  EXPECT_EQ(built.prescribed.size(), 12u + 8u);
}

TEST(SceneBuilder, PrescribedDisplacementValuesPerComponent) {
  const BuiltScene built = build(R"(
constraints:
  - {set: x_max, components: [x, z], displacement: [0.002, -0.001]}
)");
  ASSERT_EQ(built.prescribed.size(), 8u);
  for (const auto& p : built.prescribed) EXPECT_EQ(p.value, p.component == 0 ? 0.002 : -0.001);
}

TEST(SceneBuilder, GravityLoadTotalsMassTimesG) {
  const BuiltScene built = build("gravity: [0, -9.81, 0]\n");
  ASSERT_EQ(built.system->loads().size(), 1u);
  const double mass = 1000.0 * 0.04 * 0.01 * 0.01;  // kg
  EXPECT_NEAR(built.solid->total_mass(), mass, 1e-15);
  const fem::Vec3 f = total(constant_load(built, 0).force());
  EXPECT_NEAR(f.x(), 0.0, 1e-15);
  EXPECT_NEAR(f.y(), -mass * 9.81, 1e-14);
  EXPECT_NEAR(f.z(), 0.0, 1e-15);
}

TEST(SceneBuilder, SurfaceLoadTotalsTheGivenForceOnTheSetOnly) {
  const BuiltScene built = build(R"(
gravity: [0, -9.81, 0]
loads:
  - {set: x_max, total_force: [0.001, -0.01, 0.002]}
)");
  ASSERT_EQ(built.system->loads().size(), 2u);  // gravity first, then the loads in order
  const fem::Vector& f = constant_load(built, 1).force();
  const fem::Vec3 sum = total(f);
  EXPECT_NEAR(sum.x(), 0.001, 1e-15);
  EXPECT_NEAR(sum.y(), -0.01, 1e-15);
  EXPECT_NEAR(sum.z(), 0.002, 1e-15);
  const auto& face = built.solid->mesh().node_set("x_max");
  for (int n = 0; n < built.solid->mesh().num_nodes(); ++n) {
    const bool on_face = std::binary_search(face.begin(), face.end(), n);
    if (!on_face) {
      EXPECT_EQ(f.segment<3>(3 * n).norm(), 0.0) << "node " << n;
    }
  }
}

TEST(SceneBuilder, ForcePerNodeActsOnEveryNodeOfTheSet) {
  const BuiltScene built = build(R"(
loads:
  - {set: x_max, force_per_node: [0, 0, 0.003]}
)");
  const fem::Vector& f = constant_load(built, 0).force();
  const auto& face = built.solid->mesh().node_set("x_max");
  for (int n = 0; n < built.solid->mesh().num_nodes(); ++n) {
    const bool on_face = std::binary_search(face.begin(), face.end(), n);
    EXPECT_EQ(f.segment<3>(3 * n), on_face ? fem::Vec3(0, 0, 0.003) : fem::Vec3::Zero())
        << "node " << n;
  }
}

TEST(SceneBuilder, SceneNodeSetsAreResolvedIntoTheMesh) {
  const BuiltScene built = build(R"(
node_sets:
  both: {union: [clamped, tip]}       # refers to sets defined below it
  clamped: {box: {min: [0, -1, -1], max: [0, 1, 1]}}
  tip: {ids: [4, 9, 4]}
constraints:
  - {set: both, components: [x]}
)");
  const fem::Mesh& mesh = built.solid->mesh();
  EXPECT_EQ(mesh.node_set("clamped"), mesh.node_set("x_min"));
  EXPECT_EQ(mesh.node_set("tip"), (std::vector<int>{4, 9}));  // sorted, unique
  EXPECT_EQ(mesh.node_set("both"), (std::vector<int>{0, 4, 5, 9, 10, 15}));
  EXPECT_EQ(mesh.node_set("all").size(), 20u);
  EXPECT_EQ(built.prescribed.size(), 6u);
}

TEST(SceneBuilder, SettingsFollowTheScene) {
  const Scene scene = parse_scene(R"(
mesh: {box: {size: [0.04, 0.01, 0.01], divisions: [4, 1, 1]}}
material: {type: mooney_rivlin5}
damping: {alpha: 0.5, beta: 0.028}
analysis: {type: dynamic, duration: 0.1, dt: 0.001, load_steps: 7, max_cuts: 2, lumped_mass: true,
           newmark: {beta: 0.3, gamma: 0.6}}
solver: {max_iterations: 11, max_tangent_reuse: 3}
)",
                                  "", "test.yaml");
  const BuiltScene built = build_scene(scene);
  EXPECT_EQ(built.solid->formulation(), fem::Formulation::mean_dilatation);
  EXPECT_EQ(built.static_settings.load_steps, 7);
  EXPECT_EQ(built.static_settings.max_cuts, 2);
  EXPECT_EQ(built.static_settings.newton.max_iterations, 11);
  EXPECT_EQ(built.dynamic_settings.max_cuts, 2);
  EXPECT_TRUE(built.dynamic_settings.lumped_mass);
  EXPECT_DOUBLE_EQ(built.dynamic_settings.newmark.beta, 0.3);
  EXPECT_DOUBLE_EQ(built.dynamic_settings.newmark.gamma, 0.6);
  EXPECT_DOUBLE_EQ(built.dynamic_settings.damping.mass_coefficient, 0.5);
  EXPECT_DOUBLE_EQ(built.dynamic_settings.damping.stiffness_coefficient, 0.028);
  EXPECT_EQ(built.dynamic_settings.newton.max_tangent_reuse, 3);
  EXPECT_TRUE(built.system->loads().empty());
  // Keys not given take the dynamic defaults in the steps, fem's in the settling.
  EXPECT_DOUBLE_EQ(built.dynamic_settings.newton.residual_rtol, 1e-4);
  EXPECT_EQ(built.dynamic_settings.newton.quasi_newton_updates, 8);
  EXPECT_DOUBLE_EQ(built.dynamic_settings.newton.displacement_tolerance,
                   scene::kDynamicAccelerationTolerance * 0.3 * scene.analysis.dt *
                       scene.analysis.dt);  // beta = 0.3 in this scene
  EXPECT_EQ(built.static_settings.newton.displacement_tolerance, 0.0);
  EXPECT_DOUBLE_EQ(built.static_settings.newton.residual_rtol, fem::NewtonSettings{}.residual_rtol);
  EXPECT_EQ(built.static_settings.newton.max_tangent_reuse, 3);
  EXPECT_EQ(built.solid->threads(), 1);
}

TEST(SceneBuilder, DynamicStepsDefaultToAReusedFactorization) {
  const Scene scene = parse_scene(R"(
mesh: {box: {size: [0.04, 0.01, 0.01], divisions: [4, 1, 1]}}
material: {type: mooney_rivlin5}
analysis: {type: dynamic, duration: 0.1, dt: 0.001}
solver: {threads: 2}
)",
                                  "", "test.yaml");
  const BuiltScene built = build_scene(scene);
  const fem::NewtonSettings& d = built.dynamic_settings.newton;
  EXPECT_EQ(d.max_tangent_reuse, 100);
  EXPECT_DOUBLE_EQ(d.reform_ratio, 0.8);
  EXPECT_DOUBLE_EQ(d.increment_rtol, 1e-4);
  EXPECT_EQ(built.static_settings.newton.max_tangent_reuse, 0);  // statics: full Newton
  EXPECT_EQ(built.solid->threads(), 2);
}

TEST(SceneBuilder, TimeStepsCoverTheDurationExactly) {
  AnalysisSpec a;
  a.duration = 0.2;
  a.dt = 0.001;
  EXPECT_EQ(time_step_count(a), 200);
  EXPECT_EQ(time_step_length(a, 199), 0.001);  // round-off remainder keeps dt
  a.duration = 0.0105;
  EXPECT_EQ(time_step_count(a), 11);
  EXPECT_NEAR(time_step_length(a, 10), 0.0005, 1e-15);
}

// ---- errors only the built mesh reveals ----

TEST(SceneBuilderErrors, BoxSelectingNoNodes) {
  expect_build_error("node_sets:\n  far: {box: {min: [1, 1, 1], max: [2, 2, 2]}}\n",
                     "node_sets.far.box", "no nodes");
}

TEST(SceneBuilderErrors, NodeIndexOutOfRange) {
  expect_build_error("node_sets:\n  tip: {ids: [3, 20]}\n", "node_sets.tip.ids[1]", "20 nodes");
}

TEST(SceneBuilderErrors, ContradictoryPrescribedValues) {
  expect_build_error(R"(
constraints:
  - {set: x_min, components: [y]}
  - {set: y_min, components: [y], displacement: 0.001}
)",
                     "constraints[1]", "constraints[0]");
}

TEST(SceneBuilderErrors, LoadOnSetWithoutBoundaryFace) {
  expect_build_error(R"(
node_sets:
  corner: {ids: [0]}
loads:
  - {set: corner, total_force: [0, -1, 0]}
)",
                     "loads[0].set", "boundary face");
}

class AnsysScene : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    // Two unit-mm cubes along x, node ids 100.., element 1 of material 1 and 2 of material 2.
    std::ostringstream nodes, elements;
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i)
          nodes << id(i, j, k) << " " << i << " " << j << " " << k << "\n";
    for (int e = 0; e < 2; ++e) {
      for (int k = 0; k < 2; ++k)
        elements << id(e, 0, k) << " " << id(e + 1, 0, k) << " " << id(e + 1, 1, k) << " "
                 << id(e, 1, k) << " ";
      elements << (e + 1) << " 1 1 0 0 " << (e + 1) << "\n";
    }
    write("t.node", nodes.str());
    write("t.elem", elements.str());
  }
  static int id(int i, int j, int k) { return 100 + i + 3 * (j + 2 * k); }

  Scene scene(const std::string& extra) const {
    return parse_scene(R"(
mesh: {ansys: {nodes: t.node, elements: t.elem, length_scale: 0.001}}
material: {type: neo_hookean, parameters: {shear_modulus: 5000}}
analysis: {type: static}
)" + extra,
                       dir_.string(), "ansys.yaml");
  }
};

TEST_F(AnsysScene, IdsMaterialSetsAndLengthScale) {
  const BuiltScene built = build_scene(scene(R"(
node_sets:
  tip: {ids: [102, 105, 108, 111]}
constraints:
  - {set: mat_1, components: [x]}
  - {set: tip, components: [y, z]}
)"));
  const fem::Mesh& mesh = built.solid->mesh();
  EXPECT_EQ(mesh.num_nodes(), 12);
  EXPECT_NEAR(built.solid->reference_volume(), 2e-9, 1e-21);  // two 1 mm cubes, in m^3
  EXPECT_EQ(mesh.node_set("mat_1").size(), 8u);
  EXPECT_EQ(mesh.node_set("mat_2").size(), 8u);
  EXPECT_EQ(mesh.node_set("all").size(), 12u);
  for (int n : mesh.node_set("tip")) EXPECT_DOUBLE_EQ(mesh.nodes[n].x(), 0.002);
  EXPECT_EQ(built.node_index_of_id.at(100), 0);
  EXPECT_EQ(built.prescribed.size(), 8u + 8u);
}

// A length unit off by a thousand: two cubes of 1 um, 2e-18 m^3, is no body to simulate.
TEST_F(AnsysScene, AVanishingVolumeBlamesTheLengthScale) {
  Scene s = scene("");
  std::get<AnsysMeshSpec>(s.mesh).length_scale = 1e-6;
  try {
    build_scene(s);
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key_path(), "mesh.ansys.length_scale") << e.what();
    EXPECT_NE(std::string(e.what()).find("volume is 2e-18 m^3 (less than 1 mm^3) in a bounding "
                                         "box of 2e-06 x 1e-06 x 1e-06 m"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(AnsysScene, UnknownNodeId) {
  try {
    build_scene(scene("node_sets:\n  tip: {ids: [102, 7]}\n"));
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key_path(), "node_sets.tip.ids[1]") << e.what();
    EXPECT_NE(std::string(e.what()).find("id 7"), std::string::npos) << e.what();
  }
}

TEST_F(AnsysScene, MissingMaterialSet) {
  try {
    build_scene(scene("constraints:\n  - {set: mat_7, components: [x]}\n"));
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key_path(), "constraints[0].set") << e.what();
    EXPECT_NE(std::string(e.what()).find("mat_7"), std::string::npos) << e.what();
  }
}

TEST_F(AnsysScene, MuscleElementsAndFibreNodesByFileIds) {
  const BuiltScene built = build_scene(scene(R"(
muscles:
  - {name: m, max_force: 2, elements: [2], fibres: [{nodes: [100, 101, 102]}]}
)"));
  EXPECT_EQ(built.element_index_of_id.at(2), 1);
  ASSERT_TRUE(built.muscles);
  const auto& m = built.muscles->muscles().at(0);
  EXPECT_EQ(m.elements, (std::vector<int>{1}));
  EXPECT_EQ(m.fibres.at(0).nodes, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(built.solid->mesh().element_set("m"), (std::vector<int>{1}));
}

// The muscle checks name the nodes of an imported mesh by the file's ids, with their index.
TEST_F(AnsysScene, MuscleMessagesNameNodesByFileIds) {
  try {
    build_scene(scene(R"(
muscles:
  - {name: m, max_force: 2, elements: [2], fibres: [{nodes: [100, 101, 101, 102]}]}
)"));
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("node 101 (index 1) repeats consecutively"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(AnsysScene, UnknownMuscleElementId) {
  try {
    build_scene(scene(R"(
muscles:
  - {name: m, max_force: 2, elements: [7], fibres: [{nodes: [100, 101]}]}
)"));
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key_path(), "muscles[0].elements[0]") << e.what();
    EXPECT_NE(std::string(e.what()).find("no element with id 7"), std::string::npos) << e.what();
  }
}

TEST_F(AnsysScene, MalformedMeshFileIsASceneError) {
  std::ofstream(dir_ / "t.elem") << "1 2 3\n";
  try {
    build_scene(scene(""));
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key_path(), "mesh.ansys") << e.what();
    EXPECT_NE(std::string(e.what()).find("t.elem"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tongue::scene
