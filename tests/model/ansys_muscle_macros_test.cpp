// The importer of ANSYS muscle macros (model/ansys_muscle_macros.hpp) on small files written by
// the tests in the Grenoble files' format: CRLF line ends, Latin-1 comments, the closing
// "ESEL,NONE" + "CM", fibres ending at an external point, and every error naming file and line.
#include "model/ansys_muscle_macros.hpp"

#include <gtest/gtest.h>

#include <string>

#include "support/temp_dir_test.hpp"

namespace tongue::model {
namespace {

// "\xe9" is a Latin-1 e acute, as in the Grenoble files' French comments.
const char* const kElements =
    "! Cr\xe9"
    "ation des muscles\r\n"
    "/PREP7\r\n"
    "ESEL,S,ELEM,,1,4\r\n"
    "CM,STY_L,ELEM\r\n"
    "ESEL,S,ELEM,,5,7,2   ! \xe9l\xe9ments 5 et 7\r\n"
    "esel,a,elem,,8\r\n"
    "CM,STY_R,ELEM\r\n"
    "ESEL,S,ELEM,,1,8\r\n"
    "ESEL,U,ELEM,,4,8\r\n"
    "ESEL,R,ELEM,,2,3\r\n"
    "CM,SL,ELEM\r\n"
    "ESEL,NONE\r\n"
    "CM,REST,ELEM\r\n"
    "FINISH\r\n";

const char* const kFibres =
    "/COM, Fibres (d\xe9"
    "finition)\r\n"
    "*DIM,FIBER,ARRAY,4,2,3\r\n"
    "NB_NODES_FIBER(1,1)=4\r\n"
    "FIBER(1,1,1)=1\r\n"
    "FIBER(2,1,1)=2\r\n"
    "FIBER(3,1,1)=3\r\n"
    "FIBER(4,1,1)=4037\r\n"  // ends at the styloid: reversed
    "NB_NODES_FIBER(2,1)=3\r\n"
    "FIBER(1,2,1)=4037\r\n"  // starts at it
    "FIBER(2,2,1)=6\r\n"
    "FIBER(3,2,1)=7\r\n"
    "NB_NODES_FIBER(1,2)=3\r\n"
    "FIBER(1,1,2)=11\r\n"
    "FIBER(2,1,2)=12\r\n"
    "FIBER(3,1,2)=13\r\n"
    "NB_NODES_FIBER(1,3)=2\r\n"
    "FIBER(2,1,3)=17\r\n"  // any order
    "FIBER(1,1,3)=16\r\n";

const char* const kForces =
    "! forces maximales (N), \xe9tude\r\nSTY_L 12\r\nSL 9.5\r\nSTY_R 12\r\n";

class AnsysMuscleMacros : public testing::TempDirTest {
 protected:
  AnsysMuscleFiles files(const std::string& elements = kElements,
                         const std::string& fibres = kFibres,
                         const std::string& forces = kForces) const {
    return {write("CreateMuscles.mac", elements),
            write("Fibers.mac", fibres),
            write("MuscleMaxForce.txt", forces),
            {{4037, fem::Vec3(-0.07, 0.075, 0.04)}}};
  }

  // The error's message, which must name the file and the line.
  std::string error(const AnsysMuscleFiles& f, const std::string& file, int line) const {
    try {
      import_ansys_muscles(f);
    } catch (const MacroReadError& e) {
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_NE(std::string(e.what()).find((dir_ / file).string()), std::string::npos) << e.what();
      return e.what();
    }
    ADD_FAILURE() << "no MacroReadError";
    return "";
  }
};

TEST_F(AnsysMuscleMacros, ReadsBundlesFibresAndForces) {
  const ImportedMuscles imported = import_ansys_muscles(files());
  ASSERT_EQ(imported.muscles.size(), 3u);
  const ImportedMuscle& sty_l = imported.muscles[0];
  EXPECT_EQ(sty_l.name, "STY_L");
  EXPECT_EQ(sty_l.element_ids, (std::vector<long>{1, 2, 3, 4}));
  EXPECT_DOUBLE_EQ(sty_l.max_force, 12.0);
  ASSERT_EQ(sty_l.fibres.size(), 2u);
  // The first fibre ended at the styloid: it now starts there.
  EXPECT_EQ(sty_l.fibres[0].node_ids, (std::vector<long>{3, 2, 1}));
  EXPECT_TRUE(sty_l.fibres[0].reversed);
  ASSERT_TRUE(sty_l.fibres[0].origin);
  EXPECT_EQ(*sty_l.fibres[0].origin, fem::Vec3(-0.07, 0.075, 0.04));
  EXPECT_EQ(sty_l.fibres[1].node_ids, (std::vector<long>{6, 7}));
  EXPECT_FALSE(sty_l.fibres[1].reversed);
  EXPECT_TRUE(sty_l.fibres[1].origin);
  EXPECT_NE(sty_l.source.find("CreateMuscles.mac, line 4"), std::string::npos) << sty_l.source;
  EXPECT_NE(sty_l.fibres[1].source.find("Fibers.mac, line 8"), std::string::npos);

  EXPECT_EQ(imported.muscles[1].name, "STY_R");
  EXPECT_EQ(imported.muscles[1].element_ids, (std::vector<long>{5, 7, 8}));
  EXPECT_EQ(imported.muscles[1].fibres[0].node_ids, (std::vector<long>{11, 12, 13}));
  EXPECT_FALSE(imported.muscles[1].fibres[0].origin);
  EXPECT_EQ(imported.muscles[2].name, "SL");
  EXPECT_EQ(imported.muscles[2].element_ids, (std::vector<long>{2, 3}));
  EXPECT_DOUBLE_EQ(imported.muscles[2].max_force, 9.5);
  EXPECT_EQ(imported.muscles[2].fibres[0].node_ids, (std::vector<long>{16, 17}));
  // The CM after ESEL,NONE is no muscle.
  EXPECT_EQ(imported.ignored_components, (std::vector<std::string>{"REST"}));
}

TEST_F(AnsysMuscleMacros, ForcesMayBeValuesInBundleOrder) {
  const ImportedMuscles imported = import_ansys_muscles(files(kElements, kFibres, "12\n12\n9.5\n"));
  EXPECT_DOUBLE_EQ(imported.muscles[2].max_force, 9.5);
}

TEST_F(AnsysMuscleMacros, ErrorsNameFileAndLine) {
  const std::string elements = kElements;
  EXPECT_NE(error(files("ESEL,S,ELEM,,1\nNSEL,S,NODE,,1\n"), "CreateMuscles.mac", 2)
                .find("unsupported command 'NSEL'"),
            std::string::npos);
  EXPECT_NE(error(files("ESEL,S,ELEM,,1\nCM,\xe9,ELEM\n"), "CreateMuscles.mac", 2)
                .find("byte 0xE9 outside a comment"),
            std::string::npos);
  EXPECT_NE(error(files("ESEL,S,ELEM,,4,2\n"), "CreateMuscles.mac", 1).find("below the first"),
            std::string::npos);
  EXPECT_NE(
      error(files(elements + "CM,STY_L,ELEM\r\n"), "CreateMuscles.mac", 15).find("defined twice"),
      std::string::npos);
  EXPECT_NE(error(files("ESEL,NONE\nCM,X,ELEM\n"), "CreateMuscles.mac", 0).find("no muscle"),
            std::string::npos);

  const std::string fibres = kFibres;
  EXPECT_NE(error(files(kElements, fibres + "FIBER(3,1,3)=18\r\n"), "Fibers.mac", 19)
                .find("beyond its 2 points"),
            std::string::npos);
  EXPECT_NE(error(files(kElements, fibres + "FIBER(1,1,3)=18\r\n"), "Fibers.mac", 19)
                .find("given twice (first on line 18)"),
            std::string::npos);
  EXPECT_NE(error(files(kElements, fibres + "NB_NODES_FIBER(1,4)=2\r\n"), "Fibers.mac", 19)
                .find("muscle 4 does not exist"),
            std::string::npos);
  EXPECT_NE(error(files(kElements, fibres + "NB_NODES_FIBER(3,3)=2\r\n"), "Fibers.mac", 19)
                .find("no fibre 2"),
            std::string::npos);
  EXPECT_NE(error(files(kElements, fibres + "NB_FIBERS(3)=2\r\n"), "Fibers.mac", 19)
                .find("unknown array 'NB_FIBERS'"),
            std::string::npos);
  EXPECT_NE(error(files(kElements,
                        "NB_NODES_FIBER(1,1)=3\nFIBER(1,1,1)=1\nFIBER(2,1,1)=4037\n"
                        "FIBER(3,1,1)=2\n"),
                  "Fibers.mac", 1)
                .find("inside the fibre"),
            std::string::npos);
  EXPECT_NE(error(files(kElements, "NB_NODES_FIBER(1,1)=3\nFIBER(1,1,1)=1\nFIBER(3,1,1)=2\n"),
                  "Fibers.mac", 1)
                .find("no FIBER(2,1,1)"),
            std::string::npos);
  EXPECT_NE(error(files(kElements, "NB_NODES_FIBER(1,1)=2\nFIBER(1,1,1)=1\nFIBER(2,1,1)=2\n"),
                  "Fibers.mac", 0)
                .find("muscle 2 (STY_R"),
            std::string::npos);

  EXPECT_NE(error(files(kElements, kFibres, "STY_L 12\nSTY_R 12\n"), "MuscleMaxForce.txt", 0)
                .find("no force for muscle SL"),
            std::string::npos);
  EXPECT_NE(
      error(files(kElements, kFibres, "STY_L 12\n12\n"), "MuscleMaxForce.txt", 2).find("mixes"),
      std::string::npos);
  EXPECT_NE(
      error(files(kElements, kFibres, "GG 12\n"), "MuscleMaxForce.txt", 1).find("no muscle 'GG'"),
      std::string::npos);
  EXPECT_NE(error(files(kElements, kFibres, "STY_L -1\n"), "MuscleMaxForce.txt", 1)
                .find("not a positive number"),
            std::string::npos);
}

}  // namespace
}  // namespace tongue::model
