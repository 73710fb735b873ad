#include "scene/scene_reader.hpp"
#include "scene/scene_error_expectations.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/box_scenes.hpp"
#include "support/temp_dir_test.hpp"

namespace tongue::scene {
namespace {

namespace fs = std::filesystem;
void expect_error(const std::string& text, const std::string& key_path,
                  const std::string& also = "") {
  scene_test::expect_parse_error(text, key_path, also);
}

// The smallest runnable scene; the error tests each break one thing in a copy of it.
const char* const kMinimal = testing::kStaticBoxScene;

// A fresh temporary directory per test, for mesh files and scene files.
class TempDir : public testing::TempDirTest {};

TEST(SceneReader, MinimalSceneGetsDefaults) {
  const Scene s = parse_scene(kMinimal, "", "test.yaml");
  const auto& box = std::get<BoxMeshSpec>(s.mesh);
  EXPECT_EQ(box.origin, fem::Vec3::Zero());
  EXPECT_EQ(box.size, fem::Vec3(0.04, 0.01, 0.01));
  EXPECT_EQ(box.divisions, (std::array<int, 3>{4, 1, 1}));
  EXPECT_EQ(s.material.type, "neo_hookean");
  EXPECT_DOUBLE_EQ(s.material.parameters.at("shear_modulus"), 5000.0);
  EXPECT_DOUBLE_EQ(s.material.density, 1000.0);
  EXPECT_EQ(s.material.formulation, fem::Formulation::mean_dilatation);  // split material
  EXPECT_TRUE(s.node_sets.empty());
  EXPECT_TRUE(s.constraints.empty());
  EXPECT_FALSE(s.gravity.has_value());
  EXPECT_TRUE(s.loads.empty());
  EXPECT_FALSE(s.damping.active());
  EXPECT_EQ(s.analysis.type, AnalysisType::static_equilibrium);
  EXPECT_FALSE(s.analysis.settle);
  EXPECT_EQ(s.analysis.load_steps, 1);
  EXPECT_DOUBLE_EQ(s.analysis.newmark.beta, 0.25);
  EXPECT_DOUBLE_EQ(s.analysis.newmark.gamma, 0.5);
  EXPECT_FALSE(s.analysis.lumped_mass);
  EXPECT_EQ(s.analysis.max_cuts, 4);
  const fem::NewtonSettings newton_defaults;
  EXPECT_EQ(s.solver.max_iterations, newton_defaults.max_iterations);
  EXPECT_DOUBLE_EQ(s.solver.residual_rtol, newton_defaults.residual_rtol);
  EXPECT_EQ(s.solver.line_search, newton_defaults.line_search);
  EXPECT_EQ(s.solver.max_tangent_reuse, newton_defaults.max_tangent_reuse);
  EXPECT_TRUE(s.solver_keys.empty());
  EXPECT_EQ(s.threads, 1);
  EXPECT_TRUE(s.output.file.empty());
  EXPECT_EQ(s.output.every, 1);
  EXPECT_FALSE(s.output.compression.has_value());
  EXPECT_EQ(s.output.deflate_level(false), 4);
  EXPECT_EQ(s.output.deflate_level(true), 0);
  EXPECT_EQ(s.source, "test.yaml");
  EXPECT_EQ(s.text, kMinimal);
}

TEST(SceneReader, FullSceneReadsEveryKey) {
  const Scene s = parse_scene(R"(
mesh:
  box: {origin: [1, 2, 3], size: [0.04, 0.01, 0.01], divisions: [8, 2, 2]}
material:
  type: linear
  parameters: {youngs_modulus: 20000, poisson_ratio: 0.3}
  density: 1100
node_sets:
  clamped: {box: {min: [-1e-9, -1, -1], max: [1e-9, 1, 1]}}
  tip: {ids: [5, 7]}
  both: {union: [clamped, tip, x_max]}
constraints:
  - {set: clamped, components: [x, y, z]}
  - {set: tip, components: [z, x], displacement: [0.001, -0.002]}
  - {set: both, components: [y], displacement: 0.003}
gravity: [0, -9.81, 0]
loads:
  - {set: x_max, total_force: [0, -0.01, 0]}
damping: {alpha: 0.5, beta: 0.028}
analysis:
  type: dynamic
  settle: true
  duration: 0.1
  dt: 0.001
  load_steps: 10
  newmark: {beta: 0.3, gamma: 0.6}
  lumped_mass: true
  max_cuts: 3
solver: {residual_rtol: 1e-7, residual_atol: 1e-10, increment_rtol: 1e-5, increment_atol: 1e-11,
         max_iterations: 12, line_search: false, max_tangent_reuse: 5, reform_ratio: 0.25,
         quasi_newton_updates: 4, displacement_tolerance: 2e-6, threads: 2}
output: {file: logs/x.h5, every: 5, compression: 9}
)",
                              "", "test.yaml");
  EXPECT_EQ(std::get<BoxMeshSpec>(s.mesh).origin, fem::Vec3(1, 2, 3));
  EXPECT_EQ(s.material.formulation, fem::Formulation::standard);  // linear has no split
  EXPECT_DOUBLE_EQ(s.material.density, 1100.0);
  ASSERT_EQ(s.node_sets.size(), 3u);
  EXPECT_EQ(s.node_sets[0].kind, NodeSetSpec::Kind::box);
  EXPECT_EQ(s.node_sets[0].box_max, fem::Vec3(1e-9, 1, 1));
  EXPECT_EQ(s.node_sets[1].ids, (std::vector<long>{5, 7}));
  EXPECT_EQ(s.node_sets[2].members, (std::vector<std::string>{"clamped", "tip", "x_max"}));
  ASSERT_EQ(s.constraints.size(), 3u);
  EXPECT_EQ(s.constraints[0].components, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(s.constraints[0].displacements, (std::vector<double>{0, 0, 0}));
  EXPECT_EQ(s.constraints[1].components, (std::vector<int>{2, 0}));
  EXPECT_EQ(s.constraints[1].displacements, (std::vector<double>{0.001, -0.002}));
  EXPECT_EQ(s.constraints[2].displacements, (std::vector<double>{0.003}));
  ASSERT_TRUE(s.gravity);
  EXPECT_EQ(*s.gravity, fem::Vec3(0, -9.81, 0));
  ASSERT_EQ(s.loads.size(), 1u);
  EXPECT_EQ(s.loads[0].force, fem::Vec3(0, -0.01, 0));
  EXPECT_DOUBLE_EQ(s.damping.mass_coefficient, 0.5);
  EXPECT_DOUBLE_EQ(s.damping.stiffness_coefficient, 0.028);
  EXPECT_EQ(s.analysis.type, AnalysisType::dynamic);
  EXPECT_TRUE(s.analysis.settle);
  EXPECT_DOUBLE_EQ(s.analysis.duration, 0.1);
  EXPECT_DOUBLE_EQ(s.analysis.dt, 0.001);
  EXPECT_EQ(s.analysis.load_steps, 10);
  EXPECT_DOUBLE_EQ(s.analysis.newmark.beta, 0.3);
  EXPECT_DOUBLE_EQ(s.analysis.newmark.gamma, 0.6);
  EXPECT_TRUE(s.analysis.lumped_mass);
  EXPECT_EQ(s.analysis.max_cuts, 3);
  EXPECT_DOUBLE_EQ(s.solver.residual_rtol, 1e-7);
  EXPECT_DOUBLE_EQ(s.solver.residual_atol, 1e-10);
  EXPECT_DOUBLE_EQ(s.solver.increment_rtol, 1e-5);
  EXPECT_DOUBLE_EQ(s.solver.increment_atol, 1e-11);
  EXPECT_EQ(s.solver.max_iterations, 12);
  EXPECT_FALSE(s.solver.line_search);
  EXPECT_EQ(s.solver.max_tangent_reuse, 5);
  EXPECT_DOUBLE_EQ(s.solver.reform_ratio, 0.25);
  EXPECT_EQ(s.solver.quasi_newton_updates, 4);
  EXPECT_DOUBLE_EQ(s.solver.displacement_tolerance, 2e-6);
  EXPECT_EQ(s.threads, 2);
  EXPECT_EQ(s.solver_keys.size(), 11u);  // every key given
  EXPECT_EQ(s.output.file, "logs/x.h5");
  EXPECT_EQ(s.output.every, 5);
  EXPECT_EQ(s.output.deflate_level(true), 9);  // given: whatever the model
}

TEST(SceneReader, EmptyValueCountsAsOmitted) {
  const Scene s = parse_scene(std::string(kMinimal) + "gravity:\nloads:\n", "", "test.yaml");
  EXPECT_FALSE(s.gravity.has_value());
  EXPECT_TRUE(s.loads.empty());
}

TEST(SceneReader, ShippedDemoSceneParses) {
  // Tests run in the source directory of this test (tongue_add_test's WORKING_DIRECTORY).
  const Scene s = read_scene("../../scenes/cantilever_gravity.yaml");
  EXPECT_EQ(s.material.type, "mooney_rivlin5");
  EXPECT_EQ(s.analysis.type, AnalysisType::dynamic);
  EXPECT_FALSE(s.analysis.settle);
  EXPECT_DOUBLE_EQ(s.analysis.duration, 0.2);
  EXPECT_DOUBLE_EQ(s.analysis.dt, 0.001);
  EXPECT_DOUBLE_EQ(s.damping.stiffness_coefficient, 0.028);
  ASSERT_TRUE(s.gravity);
  EXPECT_DOUBLE_EQ((*s.gravity)[1], -9.81);
}

// ---- errors: one test per case, each naming the key path ----

TEST(SceneErrors, UnknownTopLevelKey) {
  expect_error(std::string(kMinimal) + "materal: {}\n", "materal");
}

TEST(SceneErrors, UnknownNestedKey) {
  expect_error(R"(
mesh: {box: {size: [1, 1, 1], divisions: [1, 1, 1], sise: [1, 1, 1]}}
material: {type: neo_hookean, parameters: {shear_modulus: 1}}
analysis: {type: static}
)",
               "mesh.box.sise", "unknown key");
}

TEST(SceneErrors, UnknownMaterialParameter) {
  expect_error(R"(
mesh: {box: {size: [1, 1, 1], divisions: [1, 1, 1]}}
material: {type: mooney_rivlin5, parameters: {c99: 1}}
analysis: {type: static}
)",
               "material.parameters.c99", "unknown parameter");
}

TEST(SceneErrors, KeyGivenTwice) {
  expect_error(std::string(kMinimal) + "gravity: [0, 0, 0]\ngravity: [0, -9.81, 0]\n", "gravity",
               "twice");
}

TEST(SceneErrors, StringWhereNumber) {
  expect_error(R"(
mesh: {box: {size: [1, 1, 1], divisions: [1, 1, 1]}}
material: {type: neo_hookean, parameters: {shear_modulus: 1}, density: heavy}
analysis: {type: static}
)",
               "material.density", "expected a number");
}

TEST(SceneErrors, NumberInListIsText) {
  expect_error(std::string(kMinimal) + "gravity: [0, down, 0]\n", "gravity[1]",
               "expected a number");
}

TEST(SceneErrors, ListOfWrongLength) {
  expect_error(R"(
mesh: {box: {size: [1, 1], divisions: [1, 1, 1]}}
material: {type: neo_hookean, parameters: {shear_modulus: 1}}
analysis: {type: static}
)",
               "mesh.box.size", "3 numbers");
}

TEST(SceneErrors, FractionalInteger) {
  expect_error(R"(
mesh: {box: {size: [1, 1, 1], divisions: [1, 2.5, 1]}}
material: {type: neo_hookean, parameters: {shear_modulus: 1}}
analysis: {type: static}
)",
               "mesh.box.divisions[1]", "integer");
}

TEST(SceneErrors, MissingMesh) {
  expect_error(R"(
material: {type: neo_hookean, parameters: {shear_modulus: 1}}
analysis: {type: static}
)",
               "mesh", "missing");
}

TEST(SceneErrors, MissingMaterialType) {
  expect_error(R"(
mesh: {box: {size: [1, 1, 1], divisions: [1, 1, 1]}}
material: {density: 1000}
analysis: {type: static}
)",
               "material.type", "missing");
}

TEST(SceneErrors, MissingDurationInDynamic) {
  expect_error(R"(
mesh: {box: {size: [1, 1, 1], divisions: [1, 1, 1]}}
material: {type: neo_hookean, parameters: {shear_modulus: 1}}
analysis: {type: dynamic, dt: 0.001}
)",
               "analysis.duration", "missing");
}

TEST(SceneErrors, MissingDtInDynamic) {
  expect_error(R"(
mesh: {box: {size: [1, 1, 1], divisions: [1, 1, 1]}}
material: {type: neo_hookean, parameters: {shear_modulus: 1}}
analysis: {type: dynamic, duration: 0.1}
)",
               "analysis.dt", "missing");
}

TEST(SceneErrors, MissingRequiredPerMaterialParameter) {
  // neo_hookean has no default shear modulus: the factory's message, under the parameters' path.
  expect_error(R"(
mesh: {box: {size: [1, 1, 1], divisions: [1, 1, 1]}}
material: {type: neo_hookean}
analysis: {type: static}
)",
               "material.parameters", "shear_modulus");
}

TEST(SceneErrors, UnknownMaterialType) {
  expect_error(R"(
mesh: {box: {size: [1, 1, 1], divisions: [1, 1, 1]}}
material: {type: rubber}
analysis: {type: static}
)",
               "material.type", "rubber");
}

TEST(SceneErrors, PoissonRatioOneHalf) {
  expect_error(R"(
mesh: {box: {size: [1, 1, 1], divisions: [1, 1, 1]}}
material: {type: mooney_rivlin5, parameters: {poisson_ratio: 0.5}}
analysis: {type: static}
)",
               "material.parameters.poisson_ratio", "out of range");
}

TEST(SceneErrors, ConflictingMaterialParameters) {
  expect_error(R"(
mesh: {box: {size: [1, 1, 1], divisions: [1, 1, 1]}}
material: {type: exponential, parameters: {poisson_ratio: 0.45, bulk_modulus: 1e5}}
analysis: {type: static}
)",
               "material.parameters", "not both");
}

TEST(SceneErrors, MeanDilatationNeedsSplitMaterial) {
  expect_error(R"(
mesh: {box: {size: [1, 1, 1], divisions: [1, 1, 1]}}
material: {type: linear, formulation: mean_dilatation}
analysis: {type: static}
)",
               "material.formulation");
}

TEST(SceneErrors, NegativeDensity) {
  expect_error(R"(
mesh: {box: {size: [1, 1, 1], divisions: [1, 1, 1]}}
material: {type: neo_hookean, parameters: {shear_modulus: 1}, density: -1000}
analysis: {type: static}
)",
               "material.density", "positive");
}

TEST(SceneErrors, DivisionsBelowOne) {
  expect_error(R"(
mesh: {box: {size: [1, 1, 1], divisions: [4, 0, 1]}}
material: {type: neo_hookean, parameters: {shear_modulus: 1}}
analysis: {type: static}
)",
               "mesh.box.divisions[1]", "at least 1");
}

TEST(SceneErrors, NonPositiveSize) {
  expect_error(R"(
mesh: {box: {size: [0.04, 0, 0.01], divisions: [1, 1, 1]}}
material: {type: neo_hookean, parameters: {shear_modulus: 1}}
analysis: {type: static}
)",
               "mesh.box.size[1]", "positive");
}

TEST(SceneErrors, BothBoxAndAnsys) {
  expect_error(R"(
mesh:
  box: {size: [1, 1, 1], divisions: [1, 1, 1]}
  ansys: {nodes: a.node, elements: a.elem}
material: {type: neo_hookean, parameters: {shear_modulus: 1}}
analysis: {type: static}
)",
               "mesh", "exactly one of");
}

TEST(SceneErrors, NeitherBoxNorAnsys) {
  expect_error(R"(
mesh: {}
material: {type: neo_hookean, parameters: {shear_modulus: 1}}
analysis: {type: static}
)",
               "mesh");
}

const char* const kDynamicHead = R"(
mesh: {box: {size: [1, 1, 1], divisions: [1, 1, 1]}}
material: {type: neo_hookean, parameters: {shear_modulus: 1}}
)";

TEST(SceneErrors, NegativeDt) {
  expect_error(std::string(kDynamicHead) + "analysis: {type: dynamic, duration: 0.1, dt: -0.001}\n",
               "analysis.dt", "positive");
}

TEST(SceneErrors, NegativeDuration) {
  expect_error(std::string(kDynamicHead) + "analysis: {type: dynamic, duration: -0.1, dt: 0.001}\n",
               "analysis.duration", "positive");
}

TEST(SceneErrors, DtLongerThanDuration) {
  expect_error(std::string(kDynamicHead) + "analysis: {type: dynamic, duration: 0.1, dt: 0.2}\n",
               "analysis.dt", "longer than the duration");
}

TEST(SceneErrors, UnknownAnalysisType) {
  expect_error(std::string(kDynamicHead) + "analysis: {type: modal}\n", "analysis.type", "modal");
}

TEST(SceneErrors, NewmarkGammaBelowHalf) {
  expect_error(std::string(kDynamicHead) +
                   "analysis: {type: dynamic, duration: 0.1, dt: 0.01, newmark: {gamma: 0.4}}\n",
               "analysis.newmark.gamma");
}

TEST(SceneReader, NewmarkSpectralRadiusSetsTheAlphaMethod) {
  const Scene s = parse_scene(
      std::string(kDynamicHead) +
          "analysis: {type: dynamic, duration: 0.1, dt: 0.01, newmark: {spectral_radius: 0.8}}\n",
      ".");
  const fem::NewmarkParameters p = fem::NewmarkParameters::bossak(0.8);
  EXPECT_EQ(s.analysis.newmark.alpha, p.alpha);
  EXPECT_EQ(s.analysis.newmark.beta, p.beta);
  EXPECT_EQ(s.analysis.newmark.gamma, p.gamma);
}

TEST(SceneErrors, NewmarkSpectralRadiusOutOfRange) {
  expect_error(std::string(kDynamicHead) +
                   "analysis: {type: dynamic, duration: 0.1, dt: 0.01, newmark: "
                   "{spectral_radius: 0.3}}\n",
               "analysis.newmark.spectral_radius", "[0.5, 1]");
}

TEST(SceneErrors, NewmarkSpectralRadiusWithBetaOrGamma) {
  expect_error(std::string(kDynamicHead) +
                   "analysis: {type: dynamic, duration: 0.1, dt: 0.01, newmark: "
                   "{spectral_radius: 0.8, gamma: 0.6}}\n",
               "analysis.newmark.spectral_radius", "not both");
}

TEST(SceneErrors, BooleanExpected) {
  expect_error(std::string(kDynamicHead) +
                   "analysis: {type: dynamic, duration: 0.1, dt: 0.01, settle: maybe}\n",
               "analysis.settle", "true or false");
}

TEST(SceneErrors, NegativeDamping) {
  expect_error(std::string(kMinimal) + "damping: {beta: -0.028}\n", "damping.beta", "negative");
}

TEST(SceneErrors, SolverMaxIterationsZero) {
  expect_error(std::string(kMinimal) + "solver: {max_iterations: 0}\n", "solver.max_iterations");
}

TEST(SceneErrors, SolverThreadsOutOfRange) {
  expect_error(std::string(kMinimal) + "solver: {threads: 0}\n", "solver.threads");
  expect_error(std::string(kMinimal) + "solver: {threads: 3}\n", "solver.threads", "1 or 2");
  expect_error(std::string(kMinimal) + "solver: {quasi_newton_updates: -1}\n",
               "solver.quasi_newton_updates");
}

TEST(SceneErrors, OutputEveryZeroOrCompressionOutOfRange) {
  expect_error(std::string(kMinimal) + "output: {every: 0}\n", "output.every");
  expect_error(std::string(kMinimal) + "output: {compression: 10}\n", "output.compression");
  expect_error(std::string(kMinimal) + "output: {compression: -1}\n", "output.compression");
}

TEST(SceneErrors, UnknownComponentLetter) {
  expect_error(std::string(kMinimal) + "constraints:\n  - {set: x_min, components: [x, w]}\n",
               "constraints[0].components[1]", "unknown component 'w'");
}

TEST(SceneErrors, ComponentListedTwice) {
  expect_error(std::string(kMinimal) + "constraints:\n  - {set: x_min, components: [x, x]}\n",
               "constraints[0].components[1]", "twice");
}

TEST(SceneErrors, DisplacementListOfWrongLength) {
  expect_error(std::string(kMinimal) +
                   "constraints:\n  - {set: x_min, components: [x, y], displacement: [0, 0, 0]}\n",
               "constraints[0].displacement");
}

TEST(SceneErrors, UnknownSetInConstraint) {
  expect_error(std::string(kMinimal) + "constraints:\n  - {set: x_min, components: [x]}\n" +
                   "  - {set: clampd, components: [x]}\n",
               "constraints[1].set", "unknown node set 'clampd'");
}

TEST(SceneErrors, UnknownSetInLoad) {
  expect_error(std::string(kMinimal) + "loads:\n  - {set: tip, total_force: [0, -1, 0]}\n",
               "loads[0].set", "unknown node set 'tip'");
}

TEST(SceneErrors, LoadWithBothOrNeitherForceKind) {
  expect_error(std::string(kMinimal) +
                   "loads:\n  - {set: x_max, total_force: [0, -1, 0], force_per_node: [0, 1, 0]}\n",
               "loads[0]", "exactly one of total_force");
  expect_error(std::string(kMinimal) + "loads:\n  - {set: x_max}\n", "loads[0]",
               "exactly one of total_force");
}

TEST(SceneErrors, UnknownSetInUnion) {
  expect_error(std::string(kMinimal) + "node_sets:\n  both: {union: [x_min, tipp]}\n",
               "node_sets.both.union[1]", "unknown node set 'tipp'");
}

TEST(SceneErrors, UnionCycle) {
  expect_error(std::string(kMinimal) + "node_sets:\n  a: {union: [b]}\n  b: {union: [x_min, a]}\n",
               "node_sets.a.union", "cycle: a -> b -> a");
}

TEST(SceneErrors, EmptyIdList) {
  expect_error(std::string(kMinimal) + "node_sets:\n  tip: {ids: []}\n", "node_sets.tip.ids",
               "empty");
}

TEST(SceneErrors, EmptyUnion) {
  expect_error(std::string(kMinimal) + "node_sets:\n  none: {union: []}\n", "node_sets.none.union",
               "empty");
}

TEST(SceneErrors, NodeSetWithTwoDefinitions) {
  expect_error(std::string(kMinimal) + "node_sets:\n  tip: {ids: [1], union: [x_max]}\n",
               "node_sets.tip", "exactly one");
}

TEST(SceneErrors, NodeSetShadowsMeshSet) {
  expect_error(std::string(kMinimal) + "node_sets:\n  x_min: {ids: [1]}\n", "node_sets.x_min",
               "taken");
}

TEST(SceneErrors, InvertedSelectionBox) {
  expect_error(std::string(kMinimal) + "node_sets:\n  b: {box: {min: [1, 0, 0], max: [0, 1, 1]}}\n",
               "node_sets.b.box");
}

TEST(SceneErrors, YamlSyntaxErrorGivesLine) {
  try {
    parse_scene("mesh:\n  box: {size: [1, 1, 1]\nmaterial: {}\n", "", "test.yaml");
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("test.yaml"), std::string::npos) << what;
    EXPECT_NE(what.find("YAML syntax error"), std::string::npos) << what;
    EXPECT_GT(e.line(), 0) << what;
    EXPECT_NE(what.find("(line " + std::to_string(e.line()) + ")"), std::string::npos) << what;
  }
}

TEST(SceneErrors, LineOfOffendingValueIsReported) {
  try {
    parse_scene(std::string(kMinimal) + "gravity: [0, -9.81]\n", "", "test.yaml");
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 9) << e.what();  // kMinimal starts with a newline: 8 lines, then gravity
  }
}

TEST(SceneErrors, EmptyScene) {
  expect_error("", "", "empty");
}

TEST(SceneErrors, TopLevelNotAMapping) {
  expect_error("- 1\n- 2\n", "(top level)");
}

TEST_F(TempDir, MissingSceneFileNamesThePath) {
  const std::string path = (dir_ / "nope.yaml").string();
  try {
    read_scene(path);
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST_F(TempDir, MissingMeshFileNamesThePath) {
  write("tongue.node", "1 0 0 0\n");
  const std::string scene_path = write("scene.yaml", R"(
mesh: {ansys: {nodes: tongue.node, elements: tongue.elem, length_scale: 0.001}}
material: {type: neo_hookean, parameters: {shear_modulus: 1}}
analysis: {type: static}
)");
  try {
    read_scene(scene_path);
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.key_path(), "mesh.ansys.elements") << what;
    EXPECT_NE(what.find(scene_path), std::string::npos) << what;
    // The path as resolved against the scene file's directory.
    EXPECT_NE(what.find((dir_ / "tongue.elem").string()), std::string::npos) << what;
  }
}

TEST_F(TempDir, AnsysPathsResolveAgainstTheSceneDirectory) {
  write("t.node", "1 0 0 0\n");
  write("t.elem", "1 1 1 1 1 1 1 1 1 1 1 1 0 1\n");
  const Scene s = read_scene(write("scene.yaml", R"(
mesh: {ansys: {nodes: t.node, elements: t.elem, length_scale: 0.001}}
material: {type: neo_hookean, parameters: {shear_modulus: 1}}
node_sets:
  region: {union: [mat_1]}
analysis: {type: static}
)"));
  const auto& ansys = std::get<AnsysMeshSpec>(s.mesh);
  EXPECT_EQ(fs::path(ansys.nodes_path), dir_ / "t.node");
  EXPECT_EQ(fs::path(ansys.elements_path), dir_ / "t.elem");
  EXPECT_DOUBLE_EQ(ansys.length_scale, 0.001);
}

// length_scale is a factor (metres per unit of the file), not a length: no unit in its message.
TEST_F(TempDir, AZeroLengthScaleIsRefusedWithoutAUnit) {
  write("t.node", "1 0 0 0\n");
  write("t.elem", "1 1 1 1 1 1 1 1 1 1 1 1 0 1\n");
  try {
    read_scene(write("scene.yaml", R"(
mesh: {ansys: {nodes: t.node, elements: t.elem, length_scale: 0}}
material: {type: neo_hookean, parameters: {shear_modulus: 1}}
analysis: {type: static}
)"));
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key_path(), "mesh.ansys.length_scale");
    EXPECT_NE(std::string(e.what()).find("must be positive, got 0 (line"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tongue::scene
