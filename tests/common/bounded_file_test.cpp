// Input files are read up to a limit: a path that never ends (/dev/zero) or is too large gives an
// error naming it instead of reading until memory runs out.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "common/bounded_file.hpp"
#include "common/key_path_error.hpp"
#include "common/yaml_reader.hpp"
#include "support/temp_dir_test.hpp"

namespace tongue::common {
namespace {

class BoundedFile : public tongue::testing::TempDirTest {};

TEST_F(BoundedFile, AFileWithinTheLimitIsReadWhole) {
  const std::string path = write("a.yaml", "a: 1\n");
  EXPECT_EQ(read_bounded_file(path, 5), "a: 1\n");
}

TEST_F(BoundedFile, ALargerFileFailsNamingTheLimit) {
  const std::string path = write("a.yaml", "a: 12\n");
  try {
    read_bounded_file(path, 5);
    FAIL() << "no error";
  } catch (const KeyPathError& e) {
    EXPECT_NE(std::string(e.what()).find("larger than 5 bytes"), std::string::npos) << e.what();
  }
}

TEST(BoundedFileDevice, DevZeroAsASceneFailsClearly) {
  try {
    YamlReader::load("/dev/zero");
    FAIL() << "no error";
  } catch (const KeyPathError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("/dev/zero"), std::string::npos) << message;
    EXPECT_NE(message.find("larger than " + std::to_string(kMaxInputFileBytes) + " bytes"),
              std::string::npos)
        << message;
  }
}

TEST(BoundedFileDevice, ADirectoryOrAMissingFileFails) {
  EXPECT_THROW(read_bounded_file("/"), KeyPathError);
  EXPECT_THROW(read_bounded_file("/no/such/file.yaml"), KeyPathError);
}

}  // namespace
}  // namespace tongue::common
