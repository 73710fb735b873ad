#include "common/yaml_reader.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

namespace tongue::common {
namespace {

// The error of action, which must throw one.
KeyPathError error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const KeyPathError& e) {
    return e;
  }
  ADD_FAILURE() << "no KeyPathError";
  return KeyPathError("", "", "");
}

TEST(KeyPathError, NamesFileKeyAndLine) {
  const KeyPathError e("a.yaml", "b.c[1]", "must be positive", 7);
  EXPECT_STREQ(e.what(), "a.yaml: b.c[1]: must be positive (line 7)");
  EXPECT_EQ(e.key_path(), "b.c[1]");
  EXPECT_EQ(e.reason(), "must be positive");
  EXPECT_STREQ(KeyPathError("a.yaml", "", "cannot open the file").what(),
               "a.yaml: cannot open the file");
}

TEST(YamlReader, ErrorsNameTheKeyPathAndTheLine) {
  const YamlReader y = YamlReader::parse("a:\n  b: [1, x]\n  c: -2\n", "t.yaml");
  const YAML::Node& a = y.root()["a"];
  const KeyPathError number = error_of([&] { y.numbers(a["b"], "a.b"); });
  EXPECT_EQ(number.key_path(), "a.b[1]");
  EXPECT_EQ(number.line(), 2);
  EXPECT_NE(std::string(number.what()).find("expected a number, got 'x'"), std::string::npos);
  const KeyPathError negative = error_of([&] { y.non_negative(a["c"], "a.c", "N"); });
  EXPECT_STREQ(negative.what(), "t.yaml: a.c: must not be negative, got -2 N (line 3)");
  const KeyPathError unknown = error_of([&] { y.check_keys(a, "a", {"b"}); });
  EXPECT_EQ(unknown.key_path(), "a.c");
  EXPECT_NE(std::string(unknown.what()).find("unknown key (known: b)"), std::string::npos);
  EXPECT_EQ(error_of([&] { y.required(a, "a", "d"); }).key_path(), "a.d");
}

TEST(YamlReader, WholeFileErrors) {
  EXPECT_EQ(error_of([] { YamlReader::parse("", "e.yaml"); }).reason(), "the file is empty");
  EXPECT_EQ(error_of([] { YamlReader::load("/nonexistent/x.yaml"); }).reason(),
            "cannot open the file");
  const KeyPathError syntax = error_of([] { YamlReader::parse("a: [1\n", "s.yaml"); });
  EXPECT_EQ(syntax.reason().rfind("YAML syntax error", 0), 0u) << syntax.what();
  EXPECT_GT(syntax.line(), 0);
}

TEST(YamlReader, EmptyValueCountsAsOmitted) {
  const YamlReader y = YamlReader::parse("a:\nb: 1\n", "t.yaml");
  EXPECT_FALSE(present(y.root()["a"]));
  EXPECT_TRUE(present(y.root()["b"]));
  EXPECT_FALSE(present(y.root()["c"]));
}

}  // namespace
}  // namespace tongue::common
