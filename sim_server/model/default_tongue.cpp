#include "model/default_tongue.hpp"

#include <algorithm>

namespace tongue::model {

namespace {

void add_node_set(fem::Mesh& mesh, const std::string& name, std::vector<int> nodes) {
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  mesh.node_sets[name] = std::move(nodes);
}

}  // namespace

TongueModel make_default_tongue(int refinement) {
  TongueModel model;
  model.grid = make_tongue_grid(default_tongue_shape(), refinement);
  const TongueGrid& g = model.grid;
  const int m = refinement, A = g.size.angular, Rj = g.size.radial, K = g.size.lateral;
  fem::Mesh mesh = g.mesh;

  // Boundary conditions (sec. III.3.1). The arc around the insertion and the lowest part of the
  // front face are attached to the mandible; the floor behind the insertion (the last angular
  // face) carries the root bottom and, at its far end, the hyoid.
  std::vector<int> mandible, root_bottom, hyoid, midsagittal;
  for (int k = 0; k <= K; ++k) {
    for (int i = 0; i <= A; ++i) mandible.push_back(g.node(i, 0, k));
    for (int j = 1; j <= m; ++j) mandible.push_back(g.node(0, j, k));
    for (int j = 2 * m; j <= 4 * m; ++j) root_bottom.push_back(g.node(A, j, k));
    for (int j = 4 * m + 1; j <= Rj; ++j) hyoid.push_back(g.node(A, j, k));
  }
  for (int j = 0; j <= Rj; ++j)
    for (int i = 0; i <= A; ++i) midsagittal.push_back(g.node(i, j, g.midline()));
  add_node_set(mesh, "mandible", mandible);
  add_node_set(mesh, "root_bottom", root_bottom);
  add_node_set(mesh, "hyoid", hyoid);
  add_node_set(mesh, "midsagittal", midsagittal);

  // Landmarks on the midsagittal dorsum, at base-grid angular indices.
  const int mid = g.midline();
  const std::pair<const char*, int> dorsum_points[] = {
      {"tip", 0}, {"blade", 2}, {"palatal_dorsum", 4}, {"velar_dorsum", 7}, {"root", 10}};
  for (const auto& [name, i] : dorsum_points) add_node_set(mesh, name, {g.node(i * m, Rj, mid)});
  add_node_set(mesh, "gg_insertion", {g.node(A / 2, 0, mid)});

  std::vector<int> all(mesh.num_elements());
  for (int e = 0; e < mesh.num_elements(); ++e) all[e] = e;
  mesh.element_sets["all"] = std::move(all);
  model.muscles = place_muscles(g);
  for (const Muscle& mu : model.muscles) mesh.element_sets[mu.name] = mu.elements;
  model.mesh = std::move(mesh);
  return model;
}

std::vector<fem::PrescribedDof> tongue_boundary_conditions(const fem::Mesh& mesh) {
  std::vector<fem::PrescribedDof> out;
  for (int n : mesh.node_set("mandible"))
    for (int c = 0; c < 3; ++c) out.push_back({n, c, 0.0});
  for (int n : mesh.node_set("root_bottom")) out.push_back({n, 1, 0.0});
  for (int n : mesh.node_set("hyoid"))
    for (int c = 1; c < 3; ++c) out.push_back({n, c, 0.0});
  return out;
}

}  // namespace tongue::model
