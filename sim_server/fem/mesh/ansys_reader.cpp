#include "fem/mesh/ansys_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string_view>
#include <system_error>
#include <vector>

#include "fem/mesh/mesh_quality.hpp"

namespace tongue::fem {

namespace {

std::string format_message(const std::string& path, int line, const std::string& reason) {
  if (line > 0) return path + ", line " + std::to_string(line) + ": " + reason;
  return path + ": " + reason;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> tokens;
  const auto is_space = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
  };
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

// from_chars rejects a leading '+', which Fortran formatted output may write.
std::string_view strip_plus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  return token;
}

bool parse_integer(std::string_view token, long& value) {
  token = strip_plus(token);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

bool parse_real(std::string_view token, double& value) {
  token = strip_plus(token);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size() && std::isfinite(value);
}

// Calls on_line(line_number, tokens) for every non-blank line; throws for a missing, unreadable
// or data-free file.
void for_each_data_line(
    const std::string& path, const char* what,
    const std::function<void(int, const std::vector<std::string_view>&)>& on_line) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw MeshReadError(path, 0, std::string("cannot read ") + what + " file: is a directory");
  }
  // A device or a pipe (/dev/zero) could be read for ever; a mesh file of more than 1 GiB
  // (some 10 million nodes) is a wrong path, not a tongue.
  constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t{1} << 30;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec)) {
    throw MeshReadError(path, 0, std::string("cannot read ") + what + " file: not a regular file");
  }
  if (const auto size = std::filesystem::file_size(path, ec); !ec && size > kMaxMeshFileBytes) {
    throw MeshReadError(path, 0, std::string(what) + " file is larger than 1 GiB");
  }
  std::ifstream in(path);
  if (!in) throw MeshReadError(path, 0, std::string("cannot open ") + what + " file");
  std::string line;
  int line_number = 0;
  int data_lines = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const auto tokens = split(line);
    if (tokens.empty()) continue;
    ++data_lines;
    on_line(line_number, tokens);
  }
  if (in.bad()) throw MeshReadError(path, 0, std::string("read error in ") + what + " file");
  if (data_lines == 0) {
    throw MeshReadError(path, 0, std::string(what) + " file is empty (no data lines)");
  }
}

std::string quoted(std::string_view token) {
  return "'" + std::string(token) + "'";
}

void read_nodes(const std::string& path, double scale, ImportedMesh& out) {
  for_each_data_line(path, "node", [&](int line, const std::vector<std::string_view>& tokens) {
    // id, then up to X Y Z THXY THYZ THZX (NWRITE format (I9, 6G21.13E3)).
    if (tokens.size() > 7) {
      throw MeshReadError(path, line,
                          "expected a node id and at most 6 numbers, got " +
                              std::to_string(tokens.size()) + " fields");
    }
    long id = 0;
    if (!parse_integer(tokens[0], id)) {
      throw MeshReadError(path, line, "node id " + quoted(tokens[0]) + " is not an integer");
    }
    if (id <= 0) throw MeshReadError(path, line, "node id " + std::to_string(id) + " not positive");
    double values[6] = {0, 0, 0, 0, 0, 0};
    for (std::size_t t = 1; t < tokens.size(); ++t) {
      if (!parse_real(tokens[t], values[t - 1])) {
        throw MeshReadError(
            path, line,
            "field " + std::to_string(t + 1) + " " + quoted(tokens[t]) + " is not a finite number");
      }
    }
    const auto [it, inserted] = out.node_index_of_id.emplace(id, out.mesh.num_nodes());
    if (!inserted) {
      throw MeshReadError(path, line, "duplicate node id " + std::to_string(id));
    }
    out.mesh.nodes.emplace_back(scale * values[0], scale * values[1], scale * values[2]);
  });
}

void check_element_shape(const std::string& path, int line, long id, const Mesh& mesh,
                         int element) {
  // Zero volume is judged relative to the element's size, so the test is unit independent.
  Vec3 lo = mesh.nodes[mesh.elements[element][0]], hi = lo;
  for (int n : mesh.elements[element]) {
    lo = lo.cwiseMin(mesh.nodes[n]);
    hi = hi.cwiseMax(mesh.nodes[n]);
  }
  const double extent = (hi - lo).maxCoeff();
  const double volume = element_volume(mesh, element);
  if (!(std::abs(volume) > 1e-12 * extent * extent * extent)) {
    throw MeshReadError(path, line,
                        "element " + std::to_string(id) + " has no volume (flat or collapsed)");
  }
  const auto dets = nodal_jacobian_determinants(mesh, element);
  if (volume < 0 || std::all_of(dets.begin(), dets.end(), [](double d) { return d <= 0; })) {
    throw MeshReadError(path, line,
                        "element " + std::to_string(id) +
                            " is inside out: negative volume or Jacobian determinant "
                            "non-positive at all 8 nodes (expected SOLID185 node order)");
  }
}

void read_elements(const std::string& path, ImportedMesh& out) {
  std::map<long, std::vector<int>> by_material;
  for_each_data_line(path, "element", [&](int line, const std::vector<std::string_view>& tokens) {
    if (tokens.size() != 14) {
      throw MeshReadError(path, line,
                          "expected 14 integers (8 nodes, mat, type, real, secnum, esys, id), "
                          "got " +
                              std::to_string(tokens.size()) + " fields");
    }
    long fields[14];
    for (int t = 0; t < 14; ++t) {
      if (!parse_integer(tokens[t], fields[t])) {
        throw MeshReadError(
            path, line,
            "field " + std::to_string(t + 1) + " " + quoted(tokens[t]) + " is not an integer");
      }
    }
    const long id = fields[13];
    const long material = fields[8];
    if (id <= 0) {
      throw MeshReadError(path, line, "element id " + std::to_string(id) + " not positive");
    }
    Hex8 hex;
    for (int a = 0; a < 8; ++a) {
      const auto it = out.node_index_of_id.find(fields[a]);
      if (it == out.node_index_of_id.end()) {
        throw MeshReadError(path, line,
                            "element " + std::to_string(id) + " refers to node " +
                                std::to_string(fields[a]) + ", which is not in the node file");
      }
      hex[a] = it->second;
    }
    for (int a = 0; a < 8; ++a)
      for (int b = a + 1; b < 8; ++b)
        if (hex[a] == hex[b]) {
          // ANSYS writes prisms and tetrahedra as SOLID185 with repeated nodes; not supported.
          throw MeshReadError(path, line,
                              "element " + std::to_string(id) + " is degenerate: node " +
                                  std::to_string(fields[a]) + " appears twice");
        }
    const int index = out.mesh.num_elements();
    if (!out.element_index_of_id.emplace(id, index).second) {
      throw MeshReadError(path, line, "duplicate element id " + std::to_string(id));
    }
    out.mesh.elements.push_back(hex);
    check_element_shape(path, line, id, out.mesh, index);
    by_material[material].push_back(index);
  });
  std::vector<int> all(out.mesh.num_elements());
  for (int e = 0; e < out.mesh.num_elements(); ++e) all[e] = e;
  out.mesh.element_sets["all"] = std::move(all);
  for (auto& [material, elements] : by_material) {
    out.mesh.element_sets["mat_" + std::to_string(material)] = std::move(elements);
  }
}

}  // namespace

MeshReadError::MeshReadError(const std::string& path, int line, const std::string& reason)
    : std::runtime_error(format_message(path, line, reason)), path_(path), line_(line) {}

ImportedMesh read_ansys_mesh(const std::string& nodes_path, const std::string& elements_path,
                             double length_scale) {
  if (!(length_scale > 0) || !std::isfinite(length_scale)) {
    throw std::invalid_argument("length_scale must be positive and finite");
  }
  ImportedMesh result;
  read_nodes(nodes_path, length_scale, result);
  read_elements(elements_path, result);
  return result;
}

}  // namespace tongue::fem
