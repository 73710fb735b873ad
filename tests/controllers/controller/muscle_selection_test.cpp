#include "controller/muscle_selection.hpp"

#include <gtest/gtest.h>

namespace tongue::controller {
namespace {

const std::vector<std::string> kNames = {"GGp_left", "GGp_right", "SG_left",
                                         "SG_right", "SL",        "SLX"};

TEST(MuscleSelection, AGroupSelectsItsHalvesAndAMuscleItself) {
  EXPECT_EQ(select_muscles("GGp", kNames), (std::vector<int>{0, 1}));
  EXPECT_EQ(select_muscles("SG_right", kNames), (std::vector<int>{3}));
  EXPECT_EQ(select_muscles("SL", kNames), (std::vector<int>{4}));  // not SLX: no '_' after SL
}

TEST(MuscleSelection, UnknownAndPartialNamesSelectNothing) {
  EXPECT_TRUE(select_muscles("GG", kNames).empty());
  EXPECT_TRUE(select_muscles("HG", kNames).empty());
  EXPECT_TRUE(select_muscles("", kNames).empty());
}

TEST(MuscleSelection, GroupOfAMuscleDropsTheSide) {
  EXPECT_EQ(muscle_group("GGp_left"), "GGp");
  EXPECT_EQ(muscle_group("SG_right"), "SG");
  EXPECT_EQ(muscle_group("SL"), "SL");
  EXPECT_EQ(muscle_group("_left"), "_left");  // nothing would be left of the name
}

}  // namespace
}  // namespace tongue::controller
