#pragma once
// Numbers in error messages: the shortest text that reads back as the same double.
#include <charconv>
#include <string>

namespace tongue::scene {

inline std::string format(double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

}  // namespace tongue::scene
