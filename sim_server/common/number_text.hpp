#pragma once
// Numbers as text, one rule for every program.
//
// Formatting: the shortest text that reads back as the same double (std::to_chars), so that a
// message repeats exactly what was written ("0.002", not "0.0020000000000000001").
//
// Parsing (command-line values): the whole text is one number in plain decimal or exponent
// notation with an optional leading '-' ("12.5", "-1", "1e-3"); no leading '+' or whitespace, no
// trailing characters ("12ms"), no hexadecimal, and never infinite or NaN ("inf", "nan", "1e999"
// are refused). Integers are decimal digits with an optional leading '-' within long long.
#include <optional>
#include <string>
#include <string_view>

namespace tongue::common {

std::string number_text(double v);

// nullopt when text is not one finite number by the rule above.
std::optional<double> parse_number(std::string_view text);
// nullopt when text is not one integer by the rule above ("3.5", "two", "" are not).
std::optional<long long> parse_integer(std::string_view text);

}  // namespace tongue::common
