#include "model/ansys_muscle_macro_writer.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <set>
#include <stdexcept>

namespace tongue::model {

namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File open_for_writing(const std::string& path) {
  File f(std::fopen(path.c_str(), "wb"));
  if (!f) throw std::runtime_error(path + ": cannot be written");
  return f;
}

void close_checked(File f, const std::string& path) {
  const bool failed = std::ferror(f.get()) != 0;
  if (std::fclose(f.release()) != 0 || failed) throw std::runtime_error(path + ": write error");
}

bool valid_name(const std::string& name) {
  if (name.empty() || name.size() > 32 || !std::isalpha(static_cast<unsigned char>(name[0])))
    return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

void check(const std::vector<MacroMuscle>& muscles) {
  std::set<std::string> names;
  for (const MacroMuscle& m : muscles) {
    const std::string label = "write_ansys_muscle_macros: muscle '" + m.name + "'";
    if (!valid_name(m.name))
      throw std::invalid_argument(label +
                                  ": the name is not a letter followed by letters, digits or '_' "
                                  "(at most 32 characters)");
    if (!names.insert(upper(m.name)).second)
      throw std::invalid_argument(label + " is given twice (names are case-insensitive)");
    if (m.element_ids.empty()) throw std::invalid_argument(label + " has no elements");
    if (m.fibres.empty()) throw std::invalid_argument(label + " has no fibres");
    if (!(m.max_force > 0.0) || !std::isfinite(m.max_force))
      throw std::invalid_argument(label + ": the max force is not finite and positive");
    for (long id : m.element_ids)
      if (id <= 0) throw std::invalid_argument(label + ": element id " + std::to_string(id));
    for (std::size_t f = 0; f < m.fibres.size(); ++f) {
      if (m.fibres[f].size() < 2)
        throw std::invalid_argument(label + ": fibre " + std::to_string(f + 1) +
                                    " has fewer than 2 points");
      for (long id : m.fibres[f])
        if (id <= 0)
          throw std::invalid_argument(label + ": fibre " + std::to_string(f + 1) +
                                      " has point id " + std::to_string(id));
    }
  }
  if (muscles.empty()) throw std::invalid_argument("write_ansys_muscle_macros: no muscles");
}

// "ESEL,S,ELEM,,a,b" for the first run of consecutive ids, "ESEL,A,..." for the others.
void write_selection(std::FILE* out, const std::vector<long>& element_ids) {
  const std::set<long> ids(element_ids.begin(), element_ids.end());
  bool first = true;
  for (auto it = ids.begin(); it != ids.end();) {
    const long start = *it;
    long end = start;
    for (++it; it != ids.end() && *it == end + 1; ++it) end = *it;
    std::fprintf(out, "ESEL,%s,ELEM,,%ld,%ld\r\n", first ? "S" : "A", start, end);
    first = false;
  }
}

}  // namespace

void write_ansys_muscle_macros(const std::vector<MacroMuscle>& muscles,
                               const std::string& elements_path, const std::string& fibres_path,
                               const std::string& max_force_path) {
  check(muscles);

  File elements = open_for_writing(elements_path);
  std::fprintf(elements.get(), "! The muscles' elements: one element component per bundle\r\n");
  std::fprintf(elements.get(), "/PREP7\r\n");
  for (const MacroMuscle& m : muscles) {
    write_selection(elements.get(), m.element_ids);
    std::fprintf(elements.get(), "CM,%s,ELEM\r\n", m.name.c_str());
  }
  std::fprintf(elements.get(), "ESEL,NONE\r\nCM,NO_MUSCLE,ELEM\r\nALLSEL\r\n");
  close_checked(std::move(elements), elements_path);

  File fibres = open_for_writing(fibres_path);
  std::fprintf(fibres.get(),
               "! FIBER(k,f,m): point k of fibre f of muscle m (the m-th CM of the elements "
               "macro)\r\n");
  for (std::size_t m = 0; m < muscles.size(); ++m) {
    std::fprintf(fibres.get(), "! %s\r\n", muscles[m].name.c_str());
    for (std::size_t f = 0; f < muscles[m].fibres.size(); ++f) {
      const std::vector<long>& points = muscles[m].fibres[f];
      std::fprintf(fibres.get(), "NB_NODES_FIBER(%zu,%zu)=%zu\r\n", f + 1, m + 1, points.size());
      for (std::size_t k = 0; k < points.size(); ++k)
        std::fprintf(fibres.get(), "FIBER(%zu,%zu,%zu)=%ld\r\n", k + 1, f + 1, m + 1, points[k]);
    }
  }
  close_checked(std::move(fibres), fibres_path);

  File forces = open_for_writing(max_force_path);
  for (const MacroMuscle& m : muscles)
    std::fprintf(forces.get(), "%s %.17g\n", m.name.c_str(), m.max_force);
  close_checked(std::move(forces), max_force_path);
}

}  // namespace tongue::model
