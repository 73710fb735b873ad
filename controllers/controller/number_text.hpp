#pragma once
// Numbers in messages: the shortest text that reads back as the same double.
#include <charconv>
#include <string>

namespace tongue::controller {

inline std::string number_text(double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

}  // namespace tongue::controller
