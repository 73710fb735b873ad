// Muscle data: validation names the muscle and the problem, weights normalise to 1, and the
// fibre node pairs are exactly the consecutive fibre nodes.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "model/muscle.hpp"

namespace tongue::model {
namespace {

Muscle valid_muscle() {
  Muscle m;
  m.name = "GGp_left";
  m.elements = {0, 3, 5};
  m.max_force = 18.5;
  Fibre a;
  a.nodes = {1, 2, 3};
  a.weight = 0.25;
  Fibre b;
  b.nodes = {4};
  b.origin = fem::Vec3(0.01, -0.02, 0.0);
  b.weight = 0.75;
  m.fibres = {a, b};
  return m;
}

constexpr int kNodes = 10, kElements = 6;

// Expects validate() to throw std::invalid_argument whose message names the muscle and contains
// every given fragment.
void expect_rejected(const std::function<void(Muscle&)>& spoil,
                     const std::vector<std::string>& fragments) {
  Muscle m = valid_muscle();
  spoil(m);
  try {
    validate(m, kNodes, kElements);
    ADD_FAILURE() << "accepted; expected an error containing '" << fragments.front() << "'";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'" + m.name + "'"), std::string::npos) << what;
    for (const std::string& f : fragments) EXPECT_NE(what.find(f), std::string::npos) << what;
  }
}

TEST(MuscleValidation, AcceptsAValidMuscle) {
  EXPECT_NO_THROW(validate(valid_muscle(), kNodes, kElements));
}

TEST(MuscleValidation, ErrorsNameTheMuscleAndTheProblem) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  expect_rejected([](Muscle& m) { m.fibres.clear(); }, {"no fibres"});
  expect_rejected([](Muscle& m) { m.fibres[0].nodes = {1}; }, {"fibre 0", "at least 2"});
  expect_rejected([](Muscle& m) { m.fibres[1].nodes.clear(); }, {"fibre 1", "at least 2"});
  expect_rejected([](Muscle& m) { m.fibres[0].nodes[1] = kNodes; }, {"fibre 0", "node 10"});
  expect_rejected([](Muscle& m) { m.fibres[1].nodes[0] = -1; }, {"fibre 1", "node -1"});
  expect_rejected([](Muscle& m) { m.elements.push_back(kElements); }, {"element 6"});
  expect_rejected([](Muscle& m) { m.elements.push_back(-2); }, {"element -2"});
  expect_rejected(
      [](Muscle& m) {
        m.fibres[0].nodes = {1, 2, 2, 3};
      },
      {"fibre 0", "node 2", "repeats"});
  expect_rejected([&](Muscle& m) { m.fibres[1].origin = fem::Vec3(0, nan, 0); },
                  {"fibre 1", "origin"});
  expect_rejected([](Muscle& m) { m.fibres[0].weight = -0.25; }, {"fibre 0", "weight"});
  expect_rejected([](Muscle& m) { m.fibres[0].weight = 0.0; }, {"fibre 0", "weight"});
  expect_rejected([&](Muscle& m) { m.fibres[1].weight = nan; }, {"fibre 1", "weight"});
  expect_rejected([](Muscle& m) { m.fibres[1].weight = 0.5; }, {"sum to", "normalize_weights"});
  expect_rejected([](Muscle& m) { m.max_force = -1.0; }, {"max_force"});
  expect_rejected([&](Muscle& m) { m.max_force = inf; }, {"max_force"});
  expect_rejected([&](Muscle& m) { m.max_force = nan; }, {"max_force"});
}

TEST(MuscleValidation, RejectsAnEmptyName) {
  Muscle m = valid_muscle();
  m.name.clear();
  EXPECT_THROW(validate(m, kNodes, kElements), std::invalid_argument);
}

TEST(MuscleValidation, WeightsWithinToleranceOfOneAreAccepted) {
  Muscle m = valid_muscle();
  m.fibres[0].weight += 0.5 * kWeightSumTolerance;
  EXPECT_NO_THROW(validate(m, kNodes, kElements));
  m.fibres[0].weight += kWeightSumTolerance;
  EXPECT_THROW(validate(m, kNodes, kElements), std::invalid_argument);
}

TEST(NormalizeWeights, ScalesPositiveWeightsToSumOne) {
  Muscle m = valid_muscle();
  m.fibres[0].weight = 2.0;
  m.fibres[1].weight = 6.0;
  normalize_weights(m);
  EXPECT_DOUBLE_EQ(m.fibres[0].weight, 0.25);
  EXPECT_DOUBLE_EQ(m.fibres[1].weight, 0.75);
  EXPECT_NO_THROW(validate(m, kNodes, kElements));
}

TEST(NormalizeWeights, RejectsNonPositiveWeightsAndNoFibres) {
  Muscle m = valid_muscle();
  m.fibres[1].weight = 0.0;
  EXPECT_THROW(normalize_weights(m), std::invalid_argument);
  m.fibres.clear();
  EXPECT_THROW(normalize_weights(m), std::invalid_argument);
}

TEST(FibreNodePairs, AreTheConsecutiveNodesOrderedAndUnique) {
  Muscle a = valid_muscle();  // fibres 1-2-3 and origin-4
  Muscle b = valid_muscle();
  b.name = "other";
  b.fibres[0].nodes = {3, 2, 7, 1};  // 3-2 repeats 2-3 reversed
  const auto pairs = fibre_node_pairs({a, b});
  const std::vector<std::pair<int, int>> expected = {{1, 2}, {1, 7}, {2, 3}, {2, 7}};
  EXPECT_EQ(pairs, expected);
}

}  // namespace
}  // namespace tongue::model
