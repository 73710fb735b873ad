#include "viewer/drawing_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "fem/mesh/boundary_faces.hpp"
#include "model/default_tongue.hpp"

namespace tongue::viewer {
namespace {

namespace L = run_file::layout;

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// Every index in [0, size).
void check_indices(const std::vector<int>& indices, std::size_t size, const std::string& what) {
  for (int i : indices)
    require(i >= 0 && static_cast<std::size_t>(i) < size,
            what + " names index " + std::to_string(i) + " of " + std::to_string(size));
}

void check_finite(const std::vector<double>& values, const std::string& what) {
  for (double v : values) require(std::isfinite(v), what + " holds a value that is not finite");
}

// Boundary quads of the hex8 mesh, through the finite-element core's own definition.
std::vector<int> surface_of(const std::vector<double>& rest, const std::vector<int>& elements) {
  fem::Mesh mesh;
  for (std::size_t i = 0; i + 2 < rest.size(); i += 3)
    mesh.nodes.emplace_back(rest[i], rest[i + 1], rest[i + 2]);
  for (std::size_t e = 0; e + 7 < elements.size(); e += 8) {
    fem::Hex8 hex;
    for (int k = 0; k < 8; ++k) hex[k] = elements[e + k];
    mesh.elements.push_back(hex);
  }
  std::vector<int> surface;
  for (const fem::Quad4& q : fem::boundary_faces(mesh))
    surface.insert(surface.end(), q.begin(), q.end());
  return surface;
}

// The relations every source must satisfy before the page sees the model.
void check(const DrawingModel& m) {
  const auto nodes = static_cast<std::size_t>(m.num_nodes());
  require(m.rest_positions.size() % 3 == 0 && m.elements.size() % 8 == 0,
          "rest positions or elements are not whole nodes and hexahedra");
  check_finite(m.rest_positions, "rest positions");
  check_indices(m.elements, nodes, "elements");
  const std::size_t fibres = m.fibre_muscles.size();
  check_indices(m.fibre_muscles, m.muscles.size(), "fibre muscles");
  require(m.fibre_offsets.size() == (fibres > 0 ? fibres + 1 : 0) &&
              m.fibre_has_origin.size() == fibres && m.fibre_origins.size() == 3 * fibres,
          "fibre counts disagree");
  for (std::size_t f = 0; f < fibres; ++f)
    require(m.fibre_offsets[f] >= 0 && m.fibre_offsets[f] <= m.fibre_offsets[f + 1],
            "fibre offsets decrease at fibre " + std::to_string(f));
  require(fibres == 0 || (m.fibre_offsets.front() == 0 &&
                          static_cast<std::size_t>(m.fibre_offsets.back()) == m.fibre_nodes.size()),
          "fibre offsets do not span the fibre nodes");
  check_indices(m.fibre_nodes, nodes, "fibre nodes");
  check_finite(m.fibre_origins, "fibre origins");
  for (const auto& l : m.landmarks) check_indices({l.node}, nodes, "landmark " + l.name);
  for (const auto& o : m.obstacles) {
    require(o.vertices.size() % 3 == 0 && o.triangles.size() % 3 == 0,
            "obstacle " + o.name + " is not whole vertices and triangles");
    check_finite(o.vertices, "obstacle " + o.name);
    check_indices(o.triangles, o.vertices.size() / 3, "obstacle " + o.name + "'s triangles");
  }
  require(std::isfinite(m.dt), "dt is not finite");
}

}  // namespace

DrawingModel drawing_model(const tongue_lcm::lcmt_tongue_model& msg) {
  DrawingModel m;
  m.rest_positions = msg.rest_positions;
  m.elements = msg.elements;
  for (std::size_t i = 0; i < msg.muscle_names.size(); ++i)
    m.muscles.push_back({msg.muscle_names[i], msg.muscle_max_forces[i]});
  m.fibre_muscles = msg.fibre_muscles;
  m.fibre_offsets = msg.fibre_offsets;
  m.fibre_nodes = msg.fibre_nodes;
  m.fibre_has_origin.assign(msg.fibre_has_origin.begin(), msg.fibre_has_origin.end());
  m.fibre_origins = msg.fibre_origins;
  for (std::size_t i = 0; i < msg.landmark_names.size(); ++i)
    m.landmarks.push_back({msg.landmark_names[i], msg.landmark_nodes[i]});
  // The obstacles' surfaces lie one after another in the flat columns.
  require(msg.obstacle_vertex_counts.size() == msg.obstacle_names.size() &&
              msg.obstacle_triangle_counts.size() == msg.obstacle_names.size(),
          "obstacle counts disagree with the obstacle names");
  std::size_t vertex = 0, triangle = 0;
  for (std::size_t i = 0; i < msg.obstacle_names.size(); ++i) {
    const std::int64_t v = msg.obstacle_vertex_counts[i], t = msg.obstacle_triangle_counts[i];
    require(v >= 0 && t >= 0 && vertex + 3 * v <= msg.obstacle_vertices.size() &&
                triangle + 3 * t <= msg.obstacle_triangles.size(),
            "obstacle " + msg.obstacle_names[i] + " runs past the vertices or triangles sent");
    DrawingModel::Obstacle o{msg.obstacle_names[i], {}, {}};
    o.vertices.assign(msg.obstacle_vertices.begin() + vertex,
                      msg.obstacle_vertices.begin() + vertex + 3 * v);
    o.triangles.assign(msg.obstacle_triangles.begin() + triangle,
                       msg.obstacle_triangles.begin() + triangle + 3 * t);
    vertex += 3 * v;
    triangle += 3 * t;
    m.obstacles.push_back(std::move(o));
  }
  require(vertex == msg.obstacle_vertices.size() && triangle == msg.obstacle_triangles.size(),
          "more obstacle vertices or triangles than the counts say");
  m.dt = msg.dt;
  m.scene = msg.scene;
  check(m);
  m.surface = surface_of(m.rest_positions, m.elements);
  return m;
}

DrawingModel drawing_model(const run_file::RunFileReader& file) {
  DrawingModel m;
  m.rest_positions = file.doubles(L::kRestPositions);
  m.elements = file.ints(L::kElements);
  if (file.exists(L::kMuscleNames)) {
    const std::vector<std::string> names = file.strings(L::kMuscleNames);
    const std::vector<double> forces = file.doubles(L::kMaxForce);
    require(forces.size() == names.size(),
            file.path() + ": " + L::kMaxForce + " has not one value per muscle");
    for (std::size_t i = 0; i < names.size(); ++i) m.muscles.push_back({names[i], forces[i]});
  }
  if (file.exists(L::kFibreMuscle)) {
    m.fibre_muscles = file.ints(L::kFibreMuscle);
    m.fibre_offsets = file.ints(L::kFibreNodeOffsets);
    m.fibre_nodes = file.ints(L::kFibreNodes);
    // NaN marks a fibre without a bony origin in the file.
    m.fibre_origins = file.doubles(L::kFibreOrigin);
    for (std::size_t f = 0; 3 * f < m.fibre_origins.size(); ++f) {
      m.fibre_has_origin.push_back(!std::isnan(m.fibre_origins[3 * f]));
      if (!m.fibre_has_origin.back())
        std::fill_n(m.fibre_origins.begin() + static_cast<std::ptrdiff_t>(3 * f), 3, 0.0);
    }
  }
  // A landmark is the first node of its node set (the built-in tongue's names).
  for (const std::string& name : model::landmark_names()) {
    if (!file.exists(L::node_set(name))) continue;
    const std::vector<int> nodes = file.ints(L::node_set(name));
    if (!nodes.empty()) m.landmarks.push_back({name, nodes.front()});
  }
  if (file.exists(L::kObstacleNames))
    for (const std::string& name : file.strings(L::kObstacleNames))
      m.obstacles.push_back(
          {name, file.doubles(L::obstacle_vertices(name)), file.ints(L::obstacle_triangles(name))});
  const std::vector<double> time = file.doubles(L::kTime);
  m.dt = time.size() >= 2 ? time[1] - time[0] : 0.0;
  m.scene = file.string_attribute(L::kRoot, L::kSceneTextAttribute);
  try {
    check(m);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(file.path() + ": " + e.what());
  }
  m.surface = surface_of(m.rest_positions, m.elements);
  return m;
}

std::string model_json(const DrawingModel& m, int version) {
  using nlohmann::json;
  json muscles = json::array();
  for (const auto& muscle : m.muscles)
    muscles.push_back({{"name", muscle.name}, {"max_force", muscle.max_force}});
  json origins = json::array();
  for (std::size_t f = 0; f < m.fibre_has_origin.size(); ++f)
    for (int k = 0; k < 3; ++k)
      origins.push_back(m.fibre_has_origin[f] ? json(m.fibre_origins[3 * f + k]) : json(nullptr));
  json landmarks = json::array();
  for (const auto& l : m.landmarks) landmarks.push_back({{"name", l.name}, {"node", l.node}});
  json obstacles = json::array();
  for (const auto& o : m.obstacles)
    obstacles.push_back({{"name", o.name}, {"vertices", o.vertices}, {"triangles", o.triangles}});
  const json j = {{"version", version},
                  {"num_nodes", m.num_nodes()},
                  {"rest_positions", m.rest_positions},
                  {"elements", m.elements},
                  {"surface", m.surface},
                  {"muscles", muscles},
                  {"fibres",
                   {{"muscle", m.fibre_muscles},
                    {"offsets", m.fibre_offsets},
                    {"nodes", m.fibre_nodes},
                    {"origins", origins}}},
                  {"landmarks", landmarks},
                  {"obstacles", obstacles},
                  {"dt", m.dt},
                  {"scene", m.scene}};
  // Scene text from the bus may hold bytes that are not UTF-8: replaced, not thrown.
  return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace tongue::viewer
