// The writer of ANSYS muscle macros (model/ansys_muscle_macro_writer.hpp): what it writes, the
// importer reads back as the same muscles; bad input is refused before a file is written.
#include "model/ansys_muscle_macro_writer.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "model/ansys_muscle_macros.hpp"
#include "support/temp_dir_test.hpp"

namespace tongue::model {
namespace {

class AnsysMuscleMacroWriter : public testing::TempDirTest {
 protected:
  std::string path(const char* name) const { return (dir_ / name).string(); }
  std::string text(const char* name) const {
    std::ifstream in(path(name), std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  void write(const std::vector<MacroMuscle>& muscles) const {
    write_ansys_muscle_macros(muscles, path("CreateMuscles.mac"), path("Fibers.mac"),
                              path("MuscleMaxForce.txt"));
  }
};

TEST_F(AnsysMuscleMacroWriter, ReadsBackAsTheSameMuscles) {
  const std::vector<MacroMuscle> muscles = {
      {"STY_L", {7, 1, 2, 3, 9, 8}, {{100, 1, 2, 3}, {100, 6, 7}}, 0.1 + 0.2},
      {"SL", {4}, {{16, 17}}, 19.0}};
  write(muscles);
  const std::string elements = text("CreateMuscles.mac");
  EXPECT_NE(elements.find("ESEL,S,ELEM,,1,3\r\nESEL,A,ELEM,,7,9\r\nCM,STY_L,ELEM\r\n"),
            std::string::npos)
      << elements;
  EXPECT_NE(elements.find("ESEL,NONE\r\nCM,NO_MUSCLE,ELEM\r\n"), std::string::npos) << elements;

  const ImportedMuscles back = import_ansys_muscles({path("CreateMuscles.mac"),
                                                     path("Fibers.mac"),
                                                     path("MuscleMaxForce.txt"),
                                                     {{100, fem::Vec3(-0.07, 0.075, 0.04)}}});
  EXPECT_EQ(back.ignored_components, std::vector<std::string>{"NO_MUSCLE"});
  ASSERT_EQ(back.muscles.size(), 2u);
  EXPECT_EQ(back.muscles[0].name, "STY_L");
  EXPECT_EQ(back.muscles[0].element_ids, (std::vector<long>{1, 2, 3, 7, 8, 9}));
  EXPECT_EQ(back.muscles[0].max_force, 0.1 + 0.2);  // 17 digits: the same double
  ASSERT_EQ(back.muscles[0].fibres.size(), 2u);
  EXPECT_EQ(back.muscles[0].fibres[0].node_ids, (std::vector<long>{1, 2, 3}));
  ASSERT_TRUE(back.muscles[0].fibres[1].origin.has_value());
  EXPECT_EQ(*back.muscles[0].fibres[1].origin, fem::Vec3(-0.07, 0.075, 0.04));
  EXPECT_EQ(back.muscles[1].fibres[0].node_ids, (std::vector<long>{16, 17}));
  EXPECT_EQ(back.muscles[1].max_force, 19.0);
}

TEST_F(AnsysMuscleMacroWriter, RefusesBadMuscles) {
  const auto refused = [&](const std::vector<MacroMuscle>& muscles, const std::string& why) {
    try {
      write(muscles);
      ADD_FAILURE() << "no error for: " << why;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  refused({{"1BAD", {1}, {{1, 2}}, 1.0}}, "the name is not a letter");
  refused({{"A", {1}, {{1, 2}}, 1.0}, {"a", {2}, {{1, 2}}, 1.0}}, "given twice");
  refused({{"A", {}, {{1, 2}}, 1.0}}, "has no elements");
  refused({{"A", {1}, {{1}}, 1.0}}, "fibre 1 has fewer than 2 points");
  refused({{"A", {1}, {{1, 2}}, 0.0}}, "max force is not finite and positive");
  EXPECT_FALSE(std::filesystem::exists(path("CreateMuscles.mac")));
}

}  // namespace
}  // namespace tongue::model
