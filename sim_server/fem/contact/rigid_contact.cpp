#include "fem/contact/rigid_contact.hpp"

#include <algorithm>
#include <stdexcept>

namespace tongue::fem {

RigidContact::RigidContact(std::vector<std::shared_ptr<const Obstacle>> obstacles, const Mesh& mesh,
                           const DofMap& dofs, ContactSettings settings, std::vector<Quad4> surface)
    : obstacles_(std::move(obstacles)), dofs_(dofs), settings_(settings) {
  if (obstacles_.empty()) throw std::invalid_argument("contact: no obstacles");
  if (!(settings_.penalty > 0.0))
    throw std::invalid_argument("contact: penalty must be positive [Pa/m]");
  if (!(settings_.search_depth > 0.0))
    throw std::invalid_argument("contact: search_depth must be positive [m]");

  if (surface.empty()) surface = boundary_faces(mesh);
  // A quarter of each face's area to each of its corners (|d1 x d2| / 2 with d1, d2 the
  // diagonals is a planar quad's area, and the mean of a warped one's).
  std::vector<double> area(mesh.num_nodes(), 0.0);
  for (const Quad4& f : surface) {
    const Vec3 d1 = mesh.nodes[f[2]] - mesh.nodes[f[0]], d2 = mesh.nodes[f[3]] - mesh.nodes[f[1]];
    const double quarter = d1.cross(d2).norm() / 8.0;
    for (int n : f) area[n] += quarter;
  }
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    if (area[n] == 0.0) continue;  // not on the contact surface
    const bool moves = dofs.is_free(3 * n) || dofs.is_free(3 * n + 1) || dofs.is_free(3 * n + 2);
    if (!moves) continue;
    nodes_.push_back(n);
    rest_.push_back(mesh.nodes[n]);
    node_penalty_.push_back(settings_.penalty * area[n]);
  }
}

template <typename Visit>
void RigidContact::for_each_contact(const Vector& u, Visit&& visit) const {
  for (int i = 0; i < static_cast<int>(nodes_.size()); ++i) {
    const Vec3 x = rest_[i] + u.segment<3>(3 * nodes_[i]);
    for (int o = 0; o < static_cast<int>(obstacles_.size()); ++o) {
      const Obstacle& obstacle = *obstacles_[o];
      // Outside the bounding box a point is outside a closed obstacle, and at least that far
      // from any surface: skip the tree when that settles it.
      const double box = obstacle.box_distance(x);
      if (box > 0.0 && (obstacle.closed() || box >= settings_.search_depth)) continue;
      const SurfacePoint s = obstacle.closest(x);
      if (!s.valid || !(s.distance < 0.0) || s.distance <= -settings_.search_depth) continue;
      visit(i, o, s);
    }
  }
}

void RigidContact::add(const Vector& u, double /*load_factor*/, Vector& force,
                       SymmetricMatrix* stiffness) const {
  for_each_contact(u, [&](int i, int, const SurfacePoint& s) {
    const double eps = node_penalty_[i];
    force.segment<3>(3 * nodes_[i]) -= (eps * s.distance) * s.normal;
    if (stiffness != nullptr) {
      const Mat3 block = eps * (s.normal * s.normal.transpose() + s.curvature);
      add_node_block(*stiffness, dofs_, nodes_[i], nodes_[i], block);
    }
  });
}

ContactReport RigidContact::report(const Vector& u) const {
  ContactReport r;
  r.obstacle_force.assign(obstacles_.size(), Vec3::Zero());
  for_each_contact(u, [&](int i, int o, const SurfacePoint& s) {
    const double eps = node_penalty_[i];
    const Vec3 f = (-eps * s.distance) * s.normal;
    r.contacts.push_back({nodes_[i], o, s.distance, f, s.point});
    r.obstacle_force[o] -= f;
    r.max_penetration = std::max(r.max_penetration, -s.distance);
    r.energy += 0.5 * eps * s.distance * s.distance;
  });
  return r;
}

}  // namespace tongue::fem
