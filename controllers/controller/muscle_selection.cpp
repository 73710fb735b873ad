#include "controller/muscle_selection.hpp"

#include <string_view>

namespace tongue::controller {

std::vector<int> select_muscles(const std::string& name,
                                const std::vector<std::string>& muscle_names) {
  std::vector<int> out;
  if (name.empty()) return out;
  const std::string prefix = name + "_";
  for (std::size_t m = 0; m < muscle_names.size(); ++m) {
    const std::string& candidate = muscle_names[m];
    if (candidate == name || candidate.compare(0, prefix.size(), prefix) == 0)
      out.push_back(static_cast<int>(m));
  }
  return out;
}

std::string muscle_group(const std::string& muscle_name) {
  for (const std::string_view suffix : {std::string_view("_left"), std::string_view("_right")}) {
    if (muscle_name.size() > suffix.size() &&
        muscle_name.compare(muscle_name.size() - suffix.size(), suffix.size(), suffix) == 0)
      return muscle_name.substr(0, muscle_name.size() - suffix.size());
  }
  return muscle_name;
}

std::string joined_names(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace tongue::controller
