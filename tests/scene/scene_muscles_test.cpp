// The built-in tongue mesh, muscles and activation schedules in scenes: reading, building and
// every error, each named by its key path.
#include <gtest/gtest.h>

#include "model/active_stiffening.hpp"

#include <set>
#include <string>
#include <utility>

#include "model/default_tongue.hpp"
#include "scene/activation_schedule.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_error_expectations.hpp"
#include "scene/scene_reader.hpp"

namespace tongue::scene {
namespace {

// The tongue with the paper's boundary conditions; tests append muscles and activations.
const char* const kTongue = R"(
mesh: {tongue: {}}
material: {type: mooney_rivlin5}
constraints:
  - {set: mandible, components: [x, y, z]}
  - {set: root_bottom, components: [y]}
  - {set: hyoid, components: [y, z]}
analysis: {type: static}
)";

// A 40 x 10 x 10 mm box, 4 x 1 x 1 elements; node (i, j, k) = i + 5 (j + 2 k) at 10 mm (i, j, k).
const char* const kBox = R"(
mesh: {box: {size: [0.04, 0.01, 0.01], divisions: [4, 1, 1]}}
material: {type: neo_hookean, parameters: {shear_modulus: 5000}}
analysis: {type: static}
)";

// Two muscles along x on the box: "flexor" (10 N, two fibres) and "flexor_deep" (30 N).
const char* const kBoxMuscles = R"(
muscles:
  - {name: flexor, max_force: 10, elements: [0, 1, 2],
     fibres: [{nodes: [0, 1, 2, 3]}, {nodes: [5, 6, 7], origin: [-0.01, 0.01, 0], weight: 3}]}
  - {name: flexor_deep, max_force: 30, elements: [3], fibres: [{nodes: [13, 14]}]}
)";

using scene_test::expect_build_error;
void expect_error(const std::string& text, const std::string& key_path,
                  const std::string& also = "") {
  scene_test::expect_parse_error(text, key_path, also);
}

Scene parse(const std::string& text) {
  return parse_scene(text, "", "test.yaml");
}

int muscle_index(const BuiltScene& built, const std::string& name) {
  return built.muscles->index_of(name);
}

// ---- reading ----

TEST(TongueSceneReader, TongueMeshDefaultsToRefinementOne) {
  const Scene s = parse(kTongue);
  ASSERT_TRUE(std::holds_alternative<TongueMeshSpec>(s.mesh));
  EXPECT_EQ(std::get<TongueMeshSpec>(s.mesh).refinement, 1);
  EXPECT_EQ(s.muscle_source, MuscleSource::none);
  EXPECT_TRUE(s.activations.empty());
  const Scene refined = parse(R"(
mesh: {tongue: {refinement: 2}}
material: {type: mooney_rivlin5}
analysis: {type: static}
)");
  EXPECT_EQ(std::get<TongueMeshSpec>(refined.mesh).refinement, 2);
}

TEST(TongueSceneReader, BuiltinMusclesAndActivationsOfBothKinds) {
  const Scene s = parse(std::string(kTongue) + R"(
muscles: builtin
activations:
  - {muscles: [SG_left, SG_right], level: 0.125, start: 0.01, end: 0.12}
  - {group: GGp, force: 4}
)");
  EXPECT_EQ(s.muscle_source, MuscleSource::builtin);
  ASSERT_EQ(s.activations.size(), 2u);
  const ActivationSpec& a = s.activations[0];
  EXPECT_EQ(a.muscles, (std::vector<std::string>{"SG_left", "SG_right"}));
  EXPECT_TRUE(a.group.empty());
  ASSERT_TRUE(a.level);
  EXPECT_DOUBLE_EQ(*a.level, 0.125);
  EXPECT_FALSE(a.force);
  EXPECT_DOUBLE_EQ(a.start, 0.01);
  ASSERT_TRUE(a.end);
  EXPECT_DOUBLE_EQ(*a.end, 0.12);
  EXPECT_EQ(a.line, 12);  // the line of the entry, for the builder's messages
  const ActivationSpec& b = s.activations[1];
  EXPECT_EQ(b.group, "GGp");
  EXPECT_TRUE(b.muscles.empty());
  EXPECT_FALSE(b.level);
  ASSERT_TRUE(b.force);
  EXPECT_DOUBLE_EQ(*b.force, 4.0);
  EXPECT_DOUBLE_EQ(b.start, 0.0);  // default
  EXPECT_FALSE(b.end);             // until the end of the run
}

TEST(TongueSceneReader, MuscleListReadsEveryKey) {
  const Scene s = parse(std::string(kBox) + kBoxMuscles);
  EXPECT_EQ(s.muscle_source, MuscleSource::list);
  ASSERT_EQ(s.muscles.size(), 2u);
  const MuscleSpec& m = s.muscles[0];
  EXPECT_EQ(m.name, "flexor");
  EXPECT_DOUBLE_EQ(m.max_force, 10.0);
  EXPECT_EQ(m.elements, (std::vector<long>{0, 1, 2}));
  ASSERT_EQ(m.fibres.size(), 2u);
  EXPECT_EQ(m.fibres[0].nodes, (std::vector<long>{0, 1, 2, 3}));
  EXPECT_FALSE(m.fibres[0].origin);
  EXPECT_DOUBLE_EQ(m.fibres[0].weight, 1.0);  // default
  ASSERT_TRUE(m.fibres[1].origin);
  EXPECT_EQ(*m.fibres[1].origin, fem::Vec3(-0.01, 0.01, 0.0));
  EXPECT_DOUBLE_EQ(m.fibres[1].weight, 3.0);  // normalized by the builder
}

TEST(TongueSceneReader, TongueAndMuscleSetsCanBeNamed) {
  // Tongue sets in constraints (kTongue) and a union; a listed muscle's name as a node set.
  parse(std::string(kTongue) + "node_sets:\n  front: {union: [tip, blade, SG_left]}\n");
  parse(std::string(kBox) + kBoxMuscles + "constraints:\n  - {set: flexor, components: [z]}\n");
}

TEST(TongueSceneReader, ShippedTongueScenesParse) {
  // Tests run in the source directory of this test (tongue_add_test's WORKING_DIRECTORY).
  for (const char* name : {"tongue_rest", "tongue_sg_3n", "tongue_ggp_4n", "tongue_sl_1n",
                           "tongue_all_max", "tongue_i", "tongue_k"}) {
    SCOPED_TRACE(name);
    const Scene s = read_scene(std::string("../../scenes/") + name + ".yaml");
    EXPECT_TRUE(std::holds_alternative<TongueMeshSpec>(s.mesh));
    EXPECT_EQ(s.muscle_source, MuscleSource::builtin);
    EXPECT_EQ(s.analysis.type, AnalysisType::dynamic);
    EXPECT_TRUE(s.analysis.settle);
    EXPECT_DOUBLE_EQ(s.damping.stiffness_coefficient, 0.028);
    EXPECT_EQ(s.constraints.size(), 3u);
    EXPECT_EQ(s.output.file, std::string("logs/") + name + ".h5");
  }
}

// ---- reader errors ----

TEST(TongueSceneErrors, RefinementBelowOne) {
  expect_error(R"(
mesh: {tongue: {refinement: 0}}
material: {type: mooney_rivlin5}
analysis: {type: static}
)",
               "mesh.tongue.refinement", "at least 1");
}

TEST(TongueSceneErrors, RefinementTooLarge) {
  expect_error(R"(
mesh: {tongue: {refinement: 9}}
material: {type: mooney_rivlin5}
analysis: {type: static}
)",
               "mesh.tongue.refinement", "at most 8");
}

TEST(TongueSceneErrors, UnknownTongueKey) {
  expect_error(R"(
mesh: {tongue: {refinment: 2}}
material: {type: mooney_rivlin5}
analysis: {type: static}
)",
               "mesh.tongue.refinment", "unknown key");
}

TEST(TongueSceneErrors, TongueAndBox) {
  expect_error(R"(
mesh: {tongue: {}, box: {size: [1, 1, 1], divisions: [1, 1, 1]}}
material: {type: mooney_rivlin5}
analysis: {type: static}
)",
               "mesh", "exactly one of 'box', 'ansys' or 'tongue'");
}

TEST(TongueSceneErrors, UnknownSetListsTheTongueSets) {
  expect_error(std::string(kTongue) + "loads:\n  - {set: tipp, force_per_node: [0, 0, 1]}\n",
               "loads[0].set", "velar_dorsum");
}

TEST(TongueSceneErrors, NodeSetShadowsATongueSet) {
  expect_error(std::string(kTongue) + "node_sets:\n  tip: {ids: [1]}\n", "node_sets.tip",
               "already taken");
}

TEST(MuscleSceneErrors, BuiltinNeedsTheTongue) {
  expect_error(std::string(kBox) + "muscles: builtin\n", "muscles", "built-in tongue");
}

TEST(MuscleSceneErrors, NeitherBuiltinNorList) {
  expect_error(std::string(kTongue) + "muscles: all\n", "muscles", "'builtin' or a list");
  expect_error(std::string(kTongue) + "muscles: {SG: 1}\n", "muscles", "'builtin' or a list");
}

TEST(MuscleSceneErrors, EmptyList) {
  expect_error(std::string(kBox) + "muscles: []\n", "muscles", "empty");
}

TEST(MuscleSceneErrors, MissingMaxForce) {
  expect_error(
      std::string(kBox) + "muscles:\n  - {name: a, elements: [0], fibres: [{nodes: [0, 1]}]}\n",
      "muscles[0].max_force", "missing");
}

TEST(MuscleSceneErrors, NonPositiveMaxForce) {
  expect_error(
      std::string(kBox) +
          "muscles:\n  - {name: a, max_force: 0, elements: [0], fibres: [{nodes: [0, 1]}]}\n",
      "muscles[0].max_force", "positive");
}

TEST(MuscleSceneErrors, NegativeElementId) {
  expect_error(
      std::string(kBox) +
          "muscles:\n  - {name: a, max_force: 1, elements: [0, -1], fibres: [{nodes: [0, 1]}]}\n",
      "muscles[0].elements[1]", "at least 0");
}

TEST(MuscleSceneErrors, NoFibres) {
  expect_error(
      std::string(kBox) + "muscles:\n  - {name: a, max_force: 1, elements: [0], fibres: []}\n",
      "muscles[0].fibres", "at least one fibre");
}

TEST(MuscleSceneErrors, FibreOfOnePoint) {
  expect_error(std::string(kBox) +
                   "muscles:\n  - {name: a, max_force: 1, elements: [0], fibres: [{nodes: [0]}]}\n",
               "muscles[0].fibres[0]", "at least 2 points");
}

TEST(MuscleSceneErrors, NonPositiveWeight) {
  expect_error(std::string(kBox) + R"(muscles:
  - {name: a, max_force: 1, elements: [0], fibres: [{nodes: [0, 1], weight: 0}]}
)",
               "muscles[0].fibres[0].weight", "positive");
}

TEST(MuscleSceneErrors, UnknownFibreKey) {
  expect_error(std::string(kBox) + R"(muscles:
  - {name: a, max_force: 1, elements: [0], fibres: [{nodes: [0, 1], weigth: 2}]}
)",
               "muscles[0].fibres[0].weigth", "unknown key");
}

TEST(MuscleSceneErrors, NameDefinedTwice) {
  expect_error(std::string(kBox) + R"(muscles:
  - {name: a, max_force: 1, elements: [0], fibres: [{nodes: [0, 1]}]}
  - {name: a, max_force: 1, elements: [1], fibres: [{nodes: [1, 2]}]}
)",
               "muscles[1].name", "defined twice");
}

TEST(MuscleSceneErrors, NameWithSlash) {
  expect_error(std::string(kBox) + R"(muscles:
  - {name: a/b, max_force: 1, elements: [0], fibres: [{nodes: [0, 1]}]}
)",
               "muscles[0].name", "not a valid name");
}

TEST(MuscleSceneErrors, NameTakenByAMeshSet) {
  expect_error(std::string(kBox) + R"(muscles:
  - {name: x_max, max_force: 1, elements: [0], fibres: [{nodes: [0, 1]}]}
)",
               "muscles[0].name", "already taken");
}

TEST(MuscleSceneErrors, NodeSetShadowsAMuscle) {
  expect_error(std::string(kBox) + kBoxMuscles + "node_sets:\n  flexor: {ids: [1]}\n",
               "node_sets.flexor", "already taken");
}

TEST(ActivationSceneErrors, NoMuscles) {
  expect_error(std::string(kTongue) + "activations:\n  - {group: SG, level: 1}\n", "activations",
               "no muscles");
}

const std::string kBuiltin = std::string(kTongue) + "muscles: builtin\nactivations:\n";

TEST(ActivationSceneErrors, BothMusclesAndGroup) {
  expect_error(kBuiltin + "  - {muscles: [SG_left], group: SG, level: 1}\n", "activations[0]",
               "exactly one of 'muscles'");
}

TEST(ActivationSceneErrors, NeitherMusclesNorGroup) {
  expect_error(kBuiltin + "  - {level: 1}\n", "activations[0]", "exactly one of 'muscles'");
}

TEST(ActivationSceneErrors, BothLevelAndForce) {
  expect_error(kBuiltin + "  - {group: SG, level: 1, force: 2}\n", "activations[0]",
               "exactly one of 'level'");
}

TEST(ActivationSceneErrors, NeitherLevelNorForce) {
  expect_error(kBuiltin + "  - {group: SG}\n", "activations[0]", "exactly one of 'level'");
}

TEST(ActivationSceneErrors, LevelAboveOne) {
  expect_error(kBuiltin + "  - {group: SG, level: 1.5}\n", "activations[0].level", "[0, 1]");
}

TEST(ActivationSceneErrors, NegativeLevel) {
  expect_error(kBuiltin + "  - {group: SG, level: -0.1}\n", "activations[0].level", "[0, 1]");
}

TEST(ActivationSceneErrors, NanLevel) {
  expect_error(kBuiltin + "  - {group: SG, level: .nan}\n", "activations[0].level", "finite");
}

TEST(ActivationSceneErrors, NegativeForce) {
  expect_error(kBuiltin + "  - {group: SG, force: -3}\n", "activations[0].force", "negative");
}

TEST(ActivationSceneErrors, EndNotAfterStart) {
  expect_error(kBuiltin + "  - {group: SG, level: 1, start: 0.1, end: 0.1}\n", "activations[0].end",
               "later than start");
  expect_error(kBuiltin + "  - {group: SG, level: 1, start: 0.1, end: 0.05}\n",
               "activations[0].end", "later than start");
}

TEST(ActivationSceneErrors, NegativeStart) {
  expect_error(kBuiltin + "  - {group: SG, level: 1, start: -1}\n", "activations[0].start",
               "negative");
}

TEST(ActivationSceneErrors, MuscleListedTwice) {
  expect_error(kBuiltin + "  - {muscles: [SG_left, SG_left], level: 1}\n",
               "activations[0].muscles[1]", "listed twice");
}

TEST(ActivationSceneErrors, EmptyMuscleList) {
  expect_error(kBuiltin + "  - {muscles: [], level: 1}\n", "activations[0].muscles", "empty");
}

TEST(ActivationSceneErrors, UnknownKey) {
  expect_error(kBuiltin + "  - {group: SG, level: 1, stop: 2}\n", "activations[0].stop",
               "unknown key");
}

// ---- building ----

TEST(TongueSceneBuilder, TongueMeshCarriesItsSetsAndBuiltinMuscles) {
  const BuiltScene built = build_scene(parse(std::string(kTongue) + "muscles: builtin\n"));
  const fem::Mesh& mesh = built.solid->mesh();
  const model::TongueModel tongue = model::make_default_tongue(1);
  EXPECT_EQ(mesh.num_nodes(), tongue.mesh.num_nodes());
  for (const char* name : {"mandible", "root_bottom", "hyoid", "midsagittal", "all"})
    EXPECT_FALSE(mesh.node_set(name).empty()) << name;
  for (const std::string& name : model::landmark_names())
    EXPECT_EQ(mesh.node_set(name).size(), 1u) << name;
  EXPECT_EQ(mesh.element_set("all").size(), static_cast<std::size_t>(mesh.num_elements()));
  ASSERT_TRUE(built.muscles);
  EXPECT_EQ(built.muscles->num_muscles(), 19);
  for (const model::Muscle& m : built.muscles->muscles()) {
    EXPECT_EQ(mesh.element_set(m.name), m.elements) << m.name;
    EXPECT_FALSE(mesh.node_set(m.name).empty()) << m.name;
  }
  // The muscle forces come last but for the active stiffening (on by default, at 110 / 15),
  // and every activation starts at 0.
  const auto& loads = built.system->loads();
  ASSERT_GE(loads.size(), 2u);
  EXPECT_EQ(loads[loads.size() - 2].get(), built.muscles.get());
  const auto* stiffening = dynamic_cast<const model::ActiveStiffening*>(loads.back().get());
  ASSERT_NE(stiffening, nullptr);
  EXPECT_DOUBLE_EQ(stiffening->ratio(), 110.0 / 15.0);
  EXPECT_EQ(built.muscles->activations(), fem::Vector::Zero(19));
  EXPECT_EQ(built.activations.num_muscles(), 19);
  // mandible x, y, z; root_bottom y; hyoid y, z (the sets may share nodes).
  std::set<std::pair<int, int>> expected;
  for (int n : mesh.node_set("mandible"))
    for (int c = 0; c < 3; ++c) expected.insert({n, c});
  for (int n : mesh.node_set("root_bottom")) expected.insert({n, 1});
  for (int n : mesh.node_set("hyoid"))
    for (int c = 1; c < 3; ++c) expected.insert({n, c});
  EXPECT_EQ(built.prescribed.size(), expected.size());
}

TEST(TongueSceneBuilder, TongueWithoutMusclesKeepsTheMuscleElementSets) {
  const BuiltScene built = build_scene(parse(kTongue));
  EXPECT_FALSE(built.muscles);
  EXPECT_TRUE(built.system->loads().empty());
  EXPECT_FALSE(built.solid->mesh().element_set("SG_left").empty());
}

TEST(TongueSceneBuilder, GroupForceIsSplitByMaxForce) {
  // SG 3 N: SG_left and SG_right have 12 N each, so both run at 3 / 24 = 0.125.
  const BuiltScene built =
      build_scene(parse(kBuiltin + "  - {group: SG, force: 3.0, end: 0.12}\n"));
  const int left = muscle_index(built, "SG_left"), right = muscle_index(built, "SG_right");
  ASSERT_GE(left, 0);
  ASSERT_GE(right, 0);
  EXPECT_DOUBLE_EQ(built.muscles->muscles()[left].max_force, 12.0);
  for (double t : {0.0, 0.06, 0.12, 0.12 + 1e-12}) {
    const fem::Vector levels = built.activations.levels_at(t);
    EXPECT_DOUBLE_EQ(levels[left], 0.125) << t;
    EXPECT_DOUBLE_EQ(levels[right], 0.125) << t;
    EXPECT_DOUBLE_EQ(levels.sum(), 0.25) << t;  // no other muscle
  }
  EXPECT_EQ(built.activations.levels_at(0.124), fem::Vector::Zero(19));
}

TEST(TongueSceneBuilder, UnpairedGroupAndFullForce) {
  const BuiltScene built = build_scene(parse(kBuiltin + "  - {group: SL, force: 19}\n"));
  const int sl = muscle_index(built, "SL");
  EXPECT_DOUBLE_EQ(built.activations.levels_at(1e6)[sl], 1.0);  // no end: the whole run
}

TEST(TongueSceneBuilder, LaterEntryWinsWhileActive) {
  const BuiltScene built = build_scene(parse(kBuiltin + R"(
  - {group: SG, level: 0.5, start: 0, end: 0.1}
  - {muscles: [SG_left], level: 0.2, start: 0.05, end: 0.08}
)"));
  const int left = muscle_index(built, "SG_left"), right = muscle_index(built, "SG_right");
  EXPECT_DOUBLE_EQ(built.activations.levels_at(0.01)[left], 0.5);
  EXPECT_DOUBLE_EQ(built.activations.levels_at(0.06)[left], 0.2);
  EXPECT_DOUBLE_EQ(built.activations.levels_at(0.06)[right], 0.5);
  EXPECT_DOUBLE_EQ(built.activations.levels_at(0.09)[left], 0.5);  // the later one has ended
  EXPECT_DOUBLE_EQ(built.activations.levels_at(0.2)[left], 0.0);

  // In the other order the group entry, now later, hides the single muscle's.
  const BuiltScene swapped = build_scene(parse(kBuiltin + R"(
  - {muscles: [SG_left], level: 0.2, start: 0.05, end: 0.08}
  - {group: SG, level: 0.5, start: 0, end: 0.1}
)"));
  EXPECT_DOUBLE_EQ(swapped.activations.levels_at(0.06)[left], 0.5);
}

TEST(TongueSceneBuilder, StartIsInclusiveAndLaterStartWaits) {
  const BuiltScene built =
      build_scene(parse(kBuiltin + "  - {muscles: [GGp_left], level: 0.3, start: 0.05}\n"));
  const int ggp = muscle_index(built, "GGp_left");
  EXPECT_DOUBLE_EQ(built.activations.levels_at(0.049)[ggp], 0.0);
  EXPECT_DOUBLE_EQ(built.activations.levels_at(0.05 - 1e-12)[ggp], 0.3);  // round-off
  EXPECT_DOUBLE_EQ(built.activations.levels_at(0.05)[ggp], 0.3);
}

TEST(TongueSceneBuilder, ShippedSg3nSceneDrivesSgAtOneEighth) {
  const BuiltScene built = build_scene(read_scene("../../scenes/tongue_sg_3n.yaml"));
  const fem::Vector levels = built.activations.levels_at(0.12);
  EXPECT_DOUBLE_EQ(levels[muscle_index(built, "SG_left")], 0.125);
  EXPECT_DOUBLE_EQ(levels[muscle_index(built, "SG_right")], 0.125);
  EXPECT_DOUBLE_EQ(levels.sum(), 0.25);
}

TEST(MuscleSceneBuilder, ListedMusclesOnABox) {
  const BuiltScene built = build_scene(parse(std::string(kBox) + kBoxMuscles + R"(
activations:
  - {group: flexor, force: 20}
)"));
  ASSERT_TRUE(built.muscles);
  ASSERT_EQ(built.muscles->num_muscles(), 2);
  const model::Muscle& m = built.muscles->muscles()[0];
  EXPECT_EQ(m.name, "flexor");
  EXPECT_EQ(m.elements, (std::vector<int>{0, 1, 2}));
  ASSERT_EQ(m.fibres.size(), 2u);
  EXPECT_EQ(m.fibres[0].nodes, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_DOUBLE_EQ(m.fibres[0].weight, 0.25);  // 1 and 3, normalized
  EXPECT_DOUBLE_EQ(m.fibres[1].weight, 0.75);
  ASSERT_TRUE(m.fibres[1].origin);
  const fem::Mesh& mesh = built.solid->mesh();
  EXPECT_EQ(mesh.element_set("flexor"), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(mesh.element_set("flexor_deep"), (std::vector<int>{3}));
  EXPECT_EQ(mesh.node_set("flexor_deep").size(), 8u);  // the nodes of its element
  // Group "flexor" is flexor and flexor_deep: 20 N of their 10 + 30 N, 0.5 each.
  EXPECT_EQ(built.activations.levels_at(0.0), fem::Vector::Constant(2, 0.5));

  // The muscles pull: an active one adds force to the system's residual.
  built.muscles->set_activations(built.activations.levels_at(0.0));
  fem::Vector r;
  const fem::Vector u = fem::Vector::Zero(built.solid->num_dofs());
  built.system->residual(u, 1.0, r, nullptr);
  EXPECT_GT(r.norm(), 1.0);  // N: tensions of 1.25 N and more at the fibre ends
}

TEST(MuscleSceneBuilder, GroupIsTheNameOrItsUnderscorePrefix) {
  const std::string text = std::string(kBox) + R"(
muscles:
  - {name: ab, max_force: 1, elements: [0], fibres: [{nodes: [0, 1]}]}
  - {name: a, max_force: 1, elements: [1], fibres: [{nodes: [1, 2]}]}
  - {name: a_x, max_force: 1, elements: [2], fibres: [{nodes: [2, 3]}]}
activations:
  - {group: a, level: 1}
)";
  const BuiltScene built = build_scene(parse(text));
  EXPECT_EQ(built.activations.levels_at(0.0), (fem::Vector(3) << 0.0, 1.0, 1.0).finished());
}

TEST(MuscleSceneBuilderErrors, ElementIndexOutOfRange) {
  expect_build_error(std::string(kBox) + R"(muscles:
  - {name: a, max_force: 1, elements: [0, 4], fibres: [{nodes: [0, 1]}]}
)",
                     "muscles[0].elements[1]", "element index 4 out of range");
}

TEST(MuscleSceneBuilderErrors, NodeIndexOutOfRange) {
  expect_build_error(std::string(kBox) + R"(muscles:
  - {name: a, max_force: 1, elements: [0], fibres: [{nodes: [0, 1, 20]}]}
)",
                     "muscles[0].fibres[0].nodes[2]", "node index 20 out of range");
}

TEST(MuscleSceneBuilderErrors, ValidateMessageAfterTheKeyPath) {
  expect_build_error(std::string(kBox) + R"(muscles:
  - {name: a, max_force: 1, elements: [0], fibres: [{nodes: [0, 1]}]}
  - {name: b, max_force: 1, elements: [0], fibres: [{nodes: [0, 1, 1]}]}
)",
                     "muscles[1]", "muscle 'b': fibre 0: node 1 repeats consecutively");
}

TEST(MuscleSceneBuilderErrors, ZeroLengthSegmentAtRest) {
  // The origin sits on the fibre's first node (node 0 at the origin of the box).
  expect_build_error(std::string(kBox) + R"(muscles:
  - {name: a, max_force: 1, elements: [0], fibres: [{nodes: [1, 2]}]}
  - {name: b, max_force: 1, elements: [0], fibres: [{nodes: [0, 1], origin: [0, 0, 0]}]}
)",
                     "muscles[1]", "zero-length segment");
}

TEST(ActivationSceneBuilderErrors, UnknownMuscle) {
  expect_build_error(kBuiltin + "  - {muscles: [SG_left, SG_lft], level: 0.5}\n",
                     "activations[0].muscles[1]", "unknown muscle 'SG_lft'");
}

TEST(ActivationSceneBuilderErrors, UnknownGroup) {
  expect_build_error(kBuiltin + "  - {group: SK, level: 0.5}\n", "activations[0].group",
                     "no muscle is named 'SK'");
}

TEST(ActivationSceneBuilderErrors, ForceBeyondMaxForce) {
  expect_build_error(kBuiltin + "  - {group: SG, force: 24.5}\n", "activations[0].force",
                     "24.5 N exceeds the muscles' summed max_force, 24 N");
}

TEST(ActivationSceneBuilderErrors, MessageGivesTheLine) {
  const Scene scene = parse(kBuiltin + "  - {group: SG, level: 0.5}\n  - {group: XX, level: 1}\n");
  try {
    build_scene(scene);
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), scene.activations[1].line) << e.what();
    EXPECT_GT(e.line(), 0);
  }
}

}  // namespace
}  // namespace tongue::scene

namespace tongue::scene {
namespace {

TEST(MuscleStiffeningScene, DefaultIsThePapersRatioAndOneTurnsItOff) {
  const std::string head = R"(
mesh: {tongue: {refinement: 1}}
material: {type: mooney_rivlin5}
muscles: builtin
analysis: {type: static}
)";
  EXPECT_DOUBLE_EQ(parse_scene(head, "", "t.yaml").muscle_stiffening, 110.0 / 15.0);
  EXPECT_DOUBLE_EQ(parse_scene(head + "muscle_stiffening: 1\n", "", "t.yaml").muscle_stiffening,
                   1.0);
  for (const char* bad :
       {"muscle_stiffening: 0.5\n", "muscle_stiffening: -2\n", "muscle_stiffening: abc\n"}) {
    try {
      parse_scene(head + bad, "", "t.yaml");
      ADD_FAILURE() << "accepted " << bad;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("muscle_stiffening"), std::string::npos) << e.what();
    }
  }
}

TEST(MuscleStiffeningScene, NeedsMuscles) {
  try {
    parse_scene(
        "mesh: {box: {size: [0.01, 0.01, 0.01], divisions: [1, 1, 1]}}\n"
        "material: {type: mooney_rivlin5}\n"
        "muscle_stiffening: 2\nanalysis: {type: static}\n",
        "", "t.yaml");
    ADD_FAILURE() << "accepted muscle_stiffening without muscles";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("muscle_stiffening: needs muscles"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tongue::scene

namespace tongue::scene {
namespace {

const char* const kBuiltinMusclesHead = R"(
mesh: {tongue: {refinement: 1}}
material: {type: mooney_rivlin5}
muscles: builtin
analysis: {type: static}
)";

TEST(MuscleForceLengthScene, DefaultIsZajacsHalfRestLengthAndConstantTurnsItOff) {
  const std::string head = kBuiltinMusclesHead;
  const auto relation = [&](const std::string& line) {
    return parse_scene(head + line, "", "t.yaml").muscle_force_length;
  };
  EXPECT_FALSE(relation("").is_constant());
  EXPECT_EQ(relation("").zero_force_length(), 0.5);
  EXPECT_EQ(relation("muscle_force_length: 0.3\n").zero_force_length(), 0.3);
  EXPECT_EQ(relation("muscle_force_length: 0\n").zero_force_length(), 0.0);
  EXPECT_TRUE(relation("muscle_force_length: constant\n").is_constant());
  for (const char* bad :
       {"muscle_force_length: 1\n", "muscle_force_length: -0.1\n", "muscle_force_length: abc\n",
        "muscle_force_length: [0.5]\n", "muscle_force_length: .nan\n"}) {
    try {
      parse_scene(head + bad, "", "t.yaml");
      ADD_FAILURE() << "accepted " << bad;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("t.yaml: muscle_force_length: expected a zero-force "
                                           "length in [0, 1)"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(MuscleForceLengthScene, NeedsMusclesAndReachesTheBuiltMuscles) {
  try {
    parse_scene(
        "mesh: {box: {size: [0.01, 0.01, 0.01], divisions: [1, 1, 1]}}\n"
        "material: {type: mooney_rivlin5}\n"
        "muscle_force_length: 0.5\nanalysis: {type: static}\n",
        "", "t.yaml");
    ADD_FAILURE() << "accepted muscle_force_length without muscles";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("muscle_force_length: needs muscles"), std::string::npos)
        << e.what();
  }
  const BuiltScene built = build_scene(
      parse_scene(std::string(kBuiltinMusclesHead) + "muscle_force_length: 0.4\n", "", "t.yaml"));
  EXPECT_EQ(built.muscles->force_length().zero_force_length(), 0.4);
}

}  // namespace
}  // namespace tongue::scene
