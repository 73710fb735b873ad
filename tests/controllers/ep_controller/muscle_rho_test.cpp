#include "ep_controller/muscle_rho.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "builtin_tongue_muscles.hpp"

namespace tongue::ep_controller {
namespace {

TEST(MuscleRho, PublishedValuesPerGroup) {
  // Payan & Perrier 1997, SPEECHart (docs/controllers.md), N.
  EXPECT_EQ(default_group_rho("GGp"), 5.2);
  EXPECT_EQ(default_group_rho("GGm"), 5.2);
  EXPECT_EQ(default_group_rho("GGa"), 5.2);
  EXPECT_EQ(default_group_rho("HG"), 21.7);
  EXPECT_EQ(default_group_rho("SG"), 4.4);
  EXPECT_EQ(default_group_rho("V"), 2.4);
  EXPECT_EQ(default_group_rho("SL"), 14.3);
  EXPECT_EQ(default_group_rho("IL"), 19.4);
  EXPECT_FALSE(default_group_rho("flexor").has_value());
}

// Our T and MH: F_max times the median rho / F_max of the eight muscles with a published rho.
TEST(MuscleRho, TransversalisAndMylohyoidFollowTheMedianRatio) {
  const auto tongue = testing::builtin_tongue_muscles();
  std::vector<double> ratios;
  double t_max = 0.0, mh_max = 0.0;
  for (const model::MuscleGroup& g : model::muscle_groups()) {
    if (g.name == "T") t_max = g.max_force;
    if (g.name == "MH") mh_max = g.max_force;
    if (g.name == "T" || g.name == "MH") continue;
    ratios.push_back(*default_group_rho(g.name) / g.max_force);
  }
  ASSERT_EQ(ratios.size(), 8u);
  std::sort(ratios.begin(), ratios.end());
  const double median = 0.5 * (ratios[3] + ratios[4]);
  // The table holds them to 0.1 N.
  EXPECT_NEAR(*default_group_rho("T"), median * t_max, 0.05);
  EXPECT_NEAR(*default_group_rho("MH"), median * mh_max, 0.05);
}

TEST(MuscleRho, GroupRhoIsSplitOverItsHalvesByMaxForce) {
  const auto tongue = testing::builtin_tongue_muscles();
  const std::vector<double> rho = muscle_rhos(tongue.names, tongue.max_forces_n, {});
  for (std::size_t m = 0; m < tongue.names.size(); ++m) {
    const std::string group =
        tongue.names[m] == "SL" ? "SL" : tongue.names[m].substr(0, tongue.names[m].find('_'));
    const double share = tongue.names[m] == "SL" ? 1.0 : 0.5;  // halves of equal F_max
    EXPECT_DOUBLE_EQ(rho[m], share * *default_group_rho(group)) << tongue.names[m];
  }
}

TEST(MuscleRho, OverridesWinAndUnknownMusclesNeedOne) {
  const std::vector<std::string> names = {"flexor", "SG_left", "SG_right"};
  const std::vector<double> max_forces = {0.01, 6.0, 18.0};  // unequal halves
  EXPECT_THROW(muscle_rhos(names, max_forces, {}), std::invalid_argument);
  const std::vector<double> rho = muscle_rhos(names, max_forces, {{"flexor", 0.005}});
  EXPECT_EQ(rho[0], 0.005);
  EXPECT_DOUBLE_EQ(rho[1], 4.4 * 6.0 / 24.0);
  EXPECT_DOUBLE_EQ(rho[2], 4.4 * 18.0 / 24.0);
  const std::vector<double> over =
      muscle_rhos(names, max_forces, {{"flexor", 0.005}, {"SG_left", 1.0}});
  EXPECT_EQ(over[1], 1.0);
  EXPECT_DOUBLE_EQ(over[2], 4.4 * 18.0 / 24.0);
}

}  // namespace
}  // namespace tongue::ep_controller
