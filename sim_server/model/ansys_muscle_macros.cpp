#include "model/ansys_muscle_macros.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <string_view>
#include <system_error>

namespace tongue::model {

namespace {

std::string format_message(const std::string& path, int line, const std::string& reason) {
  if (line > 0) return path + ", line " + std::to_string(line) + ": " + reason;
  return path + ": " + reason;
}

std::string_view trim(std::string_view s) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return s;
}

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

bool starts_with_ci(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() && upper(s.substr(0, prefix.size())) == prefix;
}

std::string shown(std::string_view token) {
  return "'" + std::string(token.substr(0, 64)) + (token.size() > 64 ? "...'" : "'");
}

std::vector<std::string_view> split(std::string_view s, char separator) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = s.find(separator, start);
    out.push_back(trim(s.substr(start, end - start)));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return out;
}

std::optional<long> integer(std::string_view token) {
  long value = 0;
  if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || token.empty()) return std::nullopt;
  return value;
}

std::optional<double> real(std::string_view token) {
  double value = 0;
  if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || token.empty() ||
      !std::isfinite(value))
    return std::nullopt;
  return value;
}

// Calls on_line(line number, content) for every line with content once comments are removed;
// checks that only comments hold bytes outside ASCII.
void for_each_line(const std::string& path, const char* what,
                   const std::function<void(int, std::string_view)>& on_line) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw MacroReadError(path, 0, std::string("cannot read the ") + what + " file: not found");
  // A muscle macro of the Grenoble tongue is some 100 kB; 256 MiB is a wrong file.
  constexpr std::uintmax_t kMaxBytes = std::uintmax_t{256} << 20;
  if (const auto size = std::filesystem::file_size(path, ec); !ec && size > kMaxBytes)
    throw MacroReadError(path, 0, std::string("the ") + what + " file is larger than 256 MiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MacroReadError(path, 0, std::string("cannot open the ") + what + " file");
  std::string raw;
  int number = 0;
  while (std::getline(in, raw)) {
    ++number;
    std::string_view line = raw;
    if (const auto bang = line.find('!'); bang != std::string_view::npos)
      line = line.substr(0, bang);
    line = trim(line);
    if (line.empty() || starts_with_ci(line, "/COM") || starts_with_ci(line, "C***")) continue;
    for (const char c : line) {
      const auto byte = static_cast<unsigned char>(c);
      if (byte >= 0x80 || (byte < 0x20 && c != '\t')) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "0x%02X", byte);
        throw MacroReadError(path, number,
                             std::string("byte ") + hex +
                                 " outside a comment (only comments may hold non-ASCII text)");
      }
    }
    on_line(number, line);
  }
  if (in.bad()) throw MacroReadError(path, 0, std::string("read error in the ") + what + " file");
}

// Commands that set ANSYS up or print, with no effect on the definitions read here.
bool is_neutral_command(const std::string& command) {
  return command == "/PREP7" || command == "FINISH" || command == "ALLSEL" || command == "/NOPR" ||
         command == "/GOPR" || command == "*DIM";
}

bool valid_component_name(std::string_view name) {
  if (name.empty() || name.size() > 32 || !std::isalpha(static_cast<unsigned char>(name[0])))
    return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

struct Bundle {
  std::string name;
  std::vector<long> elements;
  int line = 0;
};

// ---- the elements file ----

std::set<long> element_range(const std::string& path, int line,
                             const std::vector<std::string_view>& f) {
  // ESEL,Type,ELEM,Comp,VMIN,VMAX,VINC
  if (f.size() < 5 || upper(f[2]) != "ELEM")
    throw MacroReadError(path, line,
                         "expected ESEL," + upper(f[1]) +
                             ",ELEM,,first[,last[,step]] (only element ids are supported)");
  if (f.size() > 7) throw MacroReadError(path, line, "ESEL has more than 7 fields");
  if (!f[3].empty())
    throw MacroReadError(path, line, "ESEL: the 4th field (component) must be empty");
  const auto field = [&](std::size_t k, const char* name) -> std::optional<long> {
    if (k >= f.size() || f[k].empty()) return std::nullopt;
    const auto v = integer(f[k]);
    if (!v)
      throw MacroReadError(path, line,
                           std::string("ESEL: ") + name + " " + shown(f[k]) + " is not an integer");
    return v;
  };
  const long first = field(4, "first id").value_or(0);
  const long last = field(5, "last id").value_or(first);
  const long step = field(6, "step").value_or(1);
  if (first <= 0) throw MacroReadError(path, line, "ESEL: element ids must be positive");
  if (last < first)
    throw MacroReadError(
        path, line,
        "ESEL: last id " + std::to_string(last) + " is below the first, " + std::to_string(first));
  if (step <= 0) throw MacroReadError(path, line, "ESEL: the step must be positive");
  if ((last - first) / step >= 10'000'000)
    throw MacroReadError(path, line, "ESEL: a range of more than 10 million elements");
  std::set<long> ids;
  for (long id = first; id <= last; id += step) ids.insert(id);
  return ids;
}

std::pair<std::vector<Bundle>, std::vector<std::string>> read_elements(const std::string& path) {
  std::vector<Bundle> bundles;
  std::vector<std::string> ignored;
  std::set<long> selection;
  std::set<std::string> names;
  for_each_line(path, "muscle elements", [&](int line, std::string_view text) {
    const auto f = split(text, ',');
    const std::string command = upper(f[0]);
    if (command == "ESEL") {
      const std::string type = f.size() > 1 ? upper(f[1]) : "";
      if (type == "NONE") {
        if (f.size() > 2 && std::any_of(f.begin() + 2, f.end(), [](auto s) { return !s.empty(); }))
          throw MacroReadError(path, line, "ESEL,NONE takes no further fields");
        selection.clear();
        return;
      }
      if (type != "S" && type != "A" && type != "U" && type != "R")
        throw MacroReadError(path, line,
                             "ESEL type " + shown(f.size() > 1 ? f[1] : "") +
                                 " is not supported (supported: S, A, U, R, NONE)");
      const std::set<long> range = element_range(path, line, f);
      if (type == "S") {
        selection = range;
      } else if (type == "A") {
        selection.insert(range.begin(), range.end());
      } else if (type == "U") {
        for (long id : range) selection.erase(id);
      } else {
        std::set<long> kept;
        std::set_intersection(selection.begin(), selection.end(), range.begin(), range.end(),
                              std::inserter(kept, kept.end()));
        selection = std::move(kept);
      }
    } else if (command == "CM") {
      if (f.size() != 3 || upper(f[2]) != "ELEM")
        throw MacroReadError(path, line, "expected CM,NAME,ELEM");
      if (!valid_component_name(f[1]))
        throw MacroReadError(path, line,
                             "component name " + shown(f[1]) +
                                 " is not a letter followed by letters, digits or '_' (at most "
                                 "32 characters)");
      const std::string name(f[1]);
      if (!names.insert(upper(name)).second)
        throw MacroReadError(path, line, "component " + name + " is defined twice");
      if (selection.empty()) {
        ignored.push_back(name);  // no elements selected (after ESEL,NONE): not a muscle
        return;
      }
      bundles.push_back({name, std::vector<long>(selection.begin(), selection.end()), line});
    } else if (!is_neutral_command(command)) {
      throw MacroReadError(path, line,
                           "unsupported command " + shown(f[0]) +
                               " (supported: ESEL, CM; ignored: /PREP7, FINISH, ALLSEL, /NOPR, "
                               "/GOPR, *DIM)");
    }
  });
  if (bundles.empty())
    throw MacroReadError(path, 0, "defines no muscle (no CM,NAME,ELEM of a non-empty selection)");
  return {std::move(bundles), std::move(ignored)};
}

// ---- the fibres file ----

struct FibreEntry {
  long count = -1;  // NB_NODES_FIBER; -1 until given
  int count_line = 0;
  std::map<long, std::pair<long, int>> points;  // k -> (id, line)
};

// "NAME(i,j[,k])=value" -> NAME, indices, value.
void read_fibres(const std::string& path, std::map<std::pair<long, long>, FibreEntry>& fibres) {
  for_each_line(path, "fibres", [&](int line, std::string_view text) {
    const std::string command = upper(split(text, ',')[0]);
    if (is_neutral_command(command)) return;
    const auto open = text.find('('), close = text.find(')'), equals = text.find('=');
    if (open == std::string_view::npos || close == std::string_view::npos ||
        equals == std::string_view::npos || !(open < close && close < equals))
      throw MacroReadError(
          path, line, "expected FIBER(k,f,m)=node or NB_NODES_FIBER(f,m)=n, got " + shown(text));
    const std::string name = upper(trim(text.substr(0, open)));
    if (!trim(text.substr(close + 1, equals - close - 1)).empty())
      throw MacroReadError(path, line, "unexpected text between ')' and '='");
    std::vector<long> index;
    for (const auto part : split(text.substr(open + 1, close - open - 1), ',')) {
      const auto v = integer(part);
      if (!v || *v <= 0)
        throw MacroReadError(path, line, "index " + shown(part) + " is not a positive integer");
      index.push_back(*v);
    }
    const std::string_view value_text = trim(text.substr(equals + 1));
    const auto value = integer(value_text);
    if (!value || *value <= 0)
      throw MacroReadError(path, line, "value " + shown(value_text) + " is not a positive integer");
    if (name == "NB_NODES_FIBER") {
      if (index.size() != 2)
        throw MacroReadError(path, line, "NB_NODES_FIBER takes 2 indices (fibre, muscle)");
      FibreEntry& entry = fibres[{index[1], index[0]}];
      if (entry.count >= 0)
        throw MacroReadError(path, line,
                             "NB_NODES_FIBER(" + std::to_string(index[0]) + "," +
                                 std::to_string(index[1]) + ") given twice (first on line " +
                                 std::to_string(entry.count_line) + ")");
      entry.count = *value;
      entry.count_line = line;
    } else if (name == "FIBER") {
      if (index.size() != 3)
        throw MacroReadError(path, line, "FIBER takes 3 indices (point, fibre, muscle)");
      FibreEntry& entry = fibres[{index[2], index[1]}];
      const auto [it, inserted] = entry.points.emplace(index[0], std::pair{*value, line});
      if (!inserted)
        throw MacroReadError(path, line,
                             "FIBER(" + std::to_string(index[0]) + "," + std::to_string(index[1]) +
                                 "," + std::to_string(index[2]) + ") given twice (first on line " +
                                 std::to_string(it->second.second) + ")");
    } else {
      throw MacroReadError(path, line,
                           "unknown array " + shown(name) + " (known: FIBER, NB_NODES_FIBER)");
    }
  });
}

ImportedFibre make_fibre(const std::string& path, long f, long m, const std::string& muscle,
                         const FibreEntry& entry, const std::map<long, fem::Vec3>& external) {
  const std::string label =
      "fibre " + std::to_string(f) + " of muscle " + std::to_string(m) + " (" + muscle + ")";
  const int line = entry.count_line > 0 ? entry.count_line : entry.points.begin()->second.second;
  if (entry.count < 0) throw MacroReadError(path, line, label + " has no NB_NODES_FIBER");
  std::vector<long> ids;
  for (long k = 1; k <= entry.count; ++k) {
    const auto it = entry.points.find(k);
    if (it == entry.points.end())
      throw MacroReadError(path, line,
                           label + " has " + std::to_string(entry.count) + " points but no FIBER(" +
                               std::to_string(k) + "," + std::to_string(f) + "," +
                               std::to_string(m) + ")");
    ids.push_back(it->second.first);
  }
  if (const auto last = entry.points.rbegin(); last->first > entry.count)
    throw MacroReadError(path, last->second.second,
                         label + ": point " + std::to_string(last->first) + " is beyond its " +
                             std::to_string(entry.count) + " points (NB_NODES_FIBER)");
  ImportedFibre fibre;
  fibre.source = path + ", line " + std::to_string(line);
  const auto is_external = [&](long id) { return external.count(id) != 0; };
  for (std::size_t k = 1; k + 1 < ids.size(); ++k)
    if (is_external(ids[k]))
      throw MacroReadError(path, line,
                           label + ": external point " + std::to_string(ids[k]) +
                               " is inside the fibre (point " + std::to_string(k + 1) +
                               "); it may only start or end it");
  const bool starts = is_external(ids.front()), ends = ids.size() > 1 && is_external(ids.back());
  if (starts && ends)
    throw MacroReadError(path, line, label + " starts and ends at an external point");
  if (ends) {
    std::reverse(ids.begin(), ids.end());
    fibre.reversed = true;
  }
  if (starts || ends) {
    fibre.origin = external.at(ids.front());
    ids.erase(ids.begin());
  }
  if (ids.size() + (fibre.origin ? 1 : 0) < 2)
    throw MacroReadError(path, line, label + " has fewer than 2 points");
  fibre.node_ids = std::move(ids);
  return fibre;
}

// ---- the max-force file ----

std::vector<double> read_max_forces(const std::string& path, const std::vector<Bundle>& bundles) {
  std::vector<std::optional<double>> forces(bundles.size());
  std::vector<int> lines(bundles.size(), 0);
  int form = 0;  // 1: values alone, 2: "NAME value"
  std::size_t next = 0;
  for_each_line(path, "max-force", [&](int line, std::string_view text) {
    std::vector<std::string_view> fields;
    for (const auto part : split(text, ' '))
      for (const auto piece : split(part, '\t'))
        if (!piece.empty()) fields.push_back(piece);
    const int this_form = static_cast<int>(fields.size());
    if (this_form != 1 && this_form != 2)
      throw MacroReadError(path, line,
                           "expected 'NAME force' or a force alone, got " +
                               std::to_string(fields.size()) + " fields");
    if (form != 0 && this_form != form)
      throw MacroReadError(path, line, "mixes 'NAME force' lines and lines of a force alone");
    form = this_form;
    const auto value = real(fields.back());
    if (!value || *value <= 0)
      throw MacroReadError(path, line,
                           "force " + shown(fields.back()) + " is not a positive number (N)");
    std::size_t b = next;
    if (form == 2) {
      const auto it = std::find_if(bundles.begin(), bundles.end(), [&](const Bundle& x) {
        return upper(x.name) == upper(fields[0]);
      });
      if (it == bundles.end())
        throw MacroReadError(path, line, "no muscle " + shown(fields[0]) + " in the elements file");
      b = static_cast<std::size_t>(it - bundles.begin());
      if (forces[b])
        throw MacroReadError(path, line,
                             "muscle " + bundles[b].name + " given twice (first on line " +
                                 std::to_string(lines[b]) + ")");
    } else if (b >= bundles.size()) {
      throw MacroReadError(path, line,
                           "more forces than the " + std::to_string(bundles.size()) +
                               " muscles of the elements file");
    }
    forces[b] = *value;
    lines[b] = line;
    ++next;
  });
  std::vector<double> out;
  for (std::size_t b = 0; b < bundles.size(); ++b) {
    if (!forces[b]) throw MacroReadError(path, 0, "no force for muscle " + bundles[b].name);
    out.push_back(*forces[b]);
  }
  return out;
}

}  // namespace

MacroReadError::MacroReadError(const std::string& path, int line, const std::string& reason)
    : std::runtime_error(format_message(path, line, reason)), path_(path), line_(line) {}

ImportedMuscles import_ansys_muscles(const AnsysMuscleFiles& files) {
  for (const auto& [id, point] : files.external_points)
    if (!point.allFinite())
      throw std::invalid_argument("external point " + std::to_string(id) + " is not finite");
  auto [bundles, ignored] = read_elements(files.elements);
  std::map<std::pair<long, long>, FibreEntry> entries;  // (muscle, fibre) -> entry
  read_fibres(files.fibres, entries);
  const std::vector<double> forces = read_max_forces(files.max_force, bundles);

  ImportedMuscles result;
  result.ignored_components = std::move(ignored);
  for (std::size_t b = 0; b < bundles.size(); ++b) {
    ImportedMuscle muscle;
    muscle.name = bundles[b].name;
    muscle.element_ids = std::move(bundles[b].elements);
    muscle.max_force = forces[b];
    muscle.source = files.elements + ", line " + std::to_string(bundles[b].line);
    result.muscles.push_back(std::move(muscle));
  }
  const long num_muscles = static_cast<long>(result.muscles.size());
  long expected_fibre = 1, current_muscle = 0;
  for (const auto& [key, entry] : entries) {
    const auto [m, f] = key;
    const int line = entry.count_line > 0 ? entry.count_line : entry.points.begin()->second.second;
    if (m > num_muscles)
      throw MacroReadError(files.fibres, line,
                           "muscle " + std::to_string(m) + " does not exist: the elements file " +
                               files.elements + " defines " + std::to_string(num_muscles) +
                               " muscles");
    if (m != current_muscle) current_muscle = m, expected_fibre = 1;
    if (f != expected_fibre)
      throw MacroReadError(files.fibres, line,
                           "muscle " + std::to_string(m) + " has fibre " + std::to_string(f) +
                               " but no fibre " + std::to_string(expected_fibre) +
                               " (fibres are numbered from 1 without gaps)");
    ++expected_fibre;
    ImportedMuscle& muscle = result.muscles[m - 1];
    muscle.fibres.push_back(
        make_fibre(files.fibres, f, m, muscle.name, entry, files.external_points));
  }
  for (long m = 0; m < num_muscles; ++m)
    if (result.muscles[m].fibres.empty())
      throw MacroReadError(files.fibres, 0,
                           "muscle " + std::to_string(m + 1) + " (" + result.muscles[m].name +
                               ", " + result.muscles[m].source + ") has no fibre");
  return result;
}

}  // namespace tongue::model
