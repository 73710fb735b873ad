// Training sequences for the reduced basis: the muscle groups, the sequences' shapes, their
// range and their reproducibility.
#include "reduced/training_sequences.hpp"

#include <gtest/gtest.h>

#include <set>

namespace tongue::reduced {
namespace {

const std::vector<std::string> kMuscles = {"GGp_left", "GGp_right", "SG_left", "SG_right", "SL"};

TEST(TrainingSequences, LeftAndRightHalvesFormOneGroup) {
  const std::vector<MuscleGroup> g = muscle_groups(kMuscles);
  ASSERT_EQ(g.size(), 3u);
  EXPECT_EQ(g[0].name, "GGp");
  EXPECT_EQ(g[0].muscles, (std::vector<int>{0, 1}));
  EXPECT_EQ(g[1].name, "SG");
  EXPECT_EQ(g[2].name, "SL");
  EXPECT_EQ(g[2].muscles, (std::vector<int>{4}));
}

TEST(TrainingSequences, EachGroupIsSteppedAndRampedThenPairedAndMixed) {
  TrainingOptions o;
  o.pairs = 4;
  o.mixes = 2;
  const std::vector<TrainingSequence> s = training_sequences(kMuscles, o);
  ASSERT_EQ(s.size(), 3u * 2u + 4u + 2u);
  EXPECT_EQ(s[0].name, "step GGp");
  EXPECT_EQ(s[1].name, "ramp GGp");
  EXPECT_EQ(s[6].name.rfind("pair ", 0), 0u);
  EXPECT_EQ(s[10].name, "mix 1");
  // A step: off at 0, at its level after the rise (both halves alike, the others off), off again
  // after the release at mid-duration.
  const fem::Vector held = s[2].at(0.1);  // step SG
  EXPECT_EQ(s[2].at(0.0).norm(), 0.0);
  EXPECT_GE(held[2], o.min_level);
  EXPECT_EQ(held[2], held[3]);
  EXPECT_EQ(held[0] + held[1] + held[4], 0.0);
  EXPECT_EQ(s[2].at(0.5 * o.duration + o.rise).norm(), 0.0);
  // A ramp: its top at mid-duration, half of it a quarter of the way.
  const fem::Vector top = s[3].at(0.5 * o.duration);
  EXPECT_NEAR(s[3].at(0.25 * o.duration)[2], 0.5 * top[2], 1e-15);
  EXPECT_EQ(s[3].at(o.duration).norm(), 0.0);
  // A pair drives two groups, never one twice.
  for (int k = 6; k < 10; ++k) {
    std::set<int> on;
    const fem::Vector v = s[k].at(0.1);
    for (int m = 0; m < v.size(); ++m)
      if (v[m] > 0.0) on.insert(m == 1 ? 0 : m == 3 ? 2 : m);
    EXPECT_EQ(on.size(), 2u) << s[k].name;
  }
}

TEST(TrainingSequences, LevelsStayInRangeAndTheSeedRepeatsThem) {
  const auto a = training_sequences(kMuscles), b = training_sequences(kMuscles);
  TrainingOptions other;
  other.seed = 2;
  const auto c = training_sequences(kMuscles, other);
  bool differs = false;
  for (std::size_t k = 0; k < a.size(); ++k)
    for (std::size_t i = 0; i < a[k].levels.size(); ++i) {
      EXPECT_EQ(a[k].levels[i], b[k].levels[i]);
      EXPECT_GE(a[k].levels[i].minCoeff(), 0.0);
      EXPECT_LE(a[k].levels[i].maxCoeff(), 1.0);
      differs |= a[k].levels[i] != c[k].levels[i];
    }
  EXPECT_TRUE(differs);
}

TEST(TrainingSequences, RefusesNoMusclesAndBadOptions) {
  EXPECT_THROW(training_sequences({}), std::invalid_argument);
  TrainingOptions o;
  o.rise = 0.2;  // two rises longer than the 0.3 s sequence
  EXPECT_THROW(training_sequences(kMuscles, o), std::invalid_argument);
  o = {};
  o.min_level = 1.5;
  EXPECT_THROW(training_sequences(kMuscles, o), std::invalid_argument);
}

}  // namespace
}  // namespace tongue::reduced
