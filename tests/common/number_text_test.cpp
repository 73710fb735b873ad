#include "common/number_text.hpp"

#include <gtest/gtest.h>

namespace tongue::common {
namespace {

TEST(NumberText, ShortestTextThatReadsBack) {
  EXPECT_EQ(number_text(0.002), "0.002");
  EXPECT_EQ(number_text(1.0 / 3.0), "0.3333333333333333");
  EXPECT_EQ(number_text(-4.0), "-4");
  EXPECT_EQ(number_text(1e-12), "1e-12");
}

TEST(ParseNumber, WholeFiniteDecimalOnly) {
  EXPECT_EQ(parse_number("12.5"), 12.5);
  EXPECT_EQ(parse_number("-1"), -1.0);
  EXPECT_EQ(parse_number("1e-3"), 1e-3);
  EXPECT_EQ(parse_number("0"), 0.0);
  for (const char* bad :
       {"", "12ms", "inf", "-inf", "nan", "1e999", " 5", "5 ", "+5", "0x10", "1,5", "--1"})
    EXPECT_FALSE(parse_number(bad)) << "'" << bad << "'";
}

TEST(ParseInteger, DecimalDigitsOnly) {
  EXPECT_EQ(parse_integer("0"), 0);
  EXPECT_EQ(parse_integer("-1"), -1);
  EXPECT_EQ(parse_integer("1000000"), 1000000);
  for (const char* bad : {"", "3.5", "two", "1e3", "+5", " 5", "99999999999999999999"})
    EXPECT_FALSE(parse_integer(bad)) << "'" << bad << "'";
}

}  // namespace
}  // namespace tongue::common
