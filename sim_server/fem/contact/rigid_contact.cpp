#include "fem/contact/rigid_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tongue::fem {

RigidContact::RigidContact(std::vector<std::shared_ptr<const Obstacle>> obstacles, const Mesh& mesh,
                           const DofMap& dofs, ContactSettings settings, std::vector<Quad4> surface)
    : obstacles_(std::move(obstacles)), dofs_(dofs), settings_(settings) {
  if (obstacles_.empty()) throw std::invalid_argument("contact: no obstacles");
  if (!(settings_.penalty > 0.0))
    throw std::invalid_argument("contact: penalty must be positive [Pa/m]");
  if (!(settings_.smoothing > 0.0))
    throw std::invalid_argument("contact: smoothing must be positive [m]");
  if (!(settings_.search_depth > 0.0))
    throw std::invalid_argument("contact: search_depth must be positive [m]");
  if (!(settings_.penetration_tolerance >= 0.0))
    throw std::invalid_argument("contact: penetration_tolerance must not be negative [m]");
  if (settings_.max_augmentations < 0)
    throw std::invalid_argument("contact: max_augmentations must not be negative");

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
  shift_.assign(nodes_.size() * obstacles_.size(), 0.0);
}

template <typename Visit>
void RigidContact::for_each_contact(const Vector& u, Visit&& visit) const {
  const std::lock_guard lock(probes_mutex_);
  const int num_candidates = static_cast<int>(nodes_.size());
  bool same = static_cast<int>(found_at_.size()) == num_candidates;
  for (int i = 0; same && i < num_candidates; ++i)
    same = found_at_[i] == rest_[i] + u.segment<3>(3 * nodes_[i]);
  if (same) {
    for (const Found& f : found_) visit(f.candidate, f.obstacle, f.point);
    return;
  }
  found_at_.clear();  // valid again once every candidate is done
  found_.clear();
  std::vector<Vec3> at(num_candidates);
  const int num_obstacles = static_cast<int>(obstacles_.size());
  probes_.resize(nodes_.size() * obstacles_.size());
  candidates_.resize(nodes_.size());
  const double depth = settings_.search_depth;
  for (int i = 0; i < num_candidates; ++i) {
    const Vec3 x = rest_[i] + u.segment<3>(3 * nodes_[i]);
    at[i] = x;
    Candidate& candidate = candidates_[i];
    if ((x - candidate.at).norm() < candidate.reach) continue;
    candidate = {x, std::numeric_limits<double>::infinity(), false};
    for (int o = 0; o < num_obstacles; ++o) {
      Probe& probe = probes_[pair(i, o)];
      // What the probe, kept (x `moved` from where it was asked) or asked again at x, leaves the
      // candidate.
      const auto hold = [&](double moved) {
        candidate.reach = std::min(candidate.reach, probe.reach - moved);
        candidate.in_front = candidate.in_front || probe.in_front;
      };
      if (const double moved = (x - probe.at).norm(); moved < probe.reach) {
        hold(moved);
        continue;
      }
      const Obstacle& obstacle = *obstacles_[o];
      const double shift = shift_[pair(i, o)];
      probe.at = x;
      probe.in_front = false;
      // Outside the bounding box a point is outside a closed obstacle, and at least that far
      // from any surface, so out of reach of an open one while farther than the search depth.
      const double box = obstacle.box_distance(x);
      probe.reach = obstacle.closed() ? box - shift : box - std::max(depth, shift);
      if (probe.reach > 0.0) {
        hold(0.0);
        continue;
      }
      const SurfacePoint s = closest(obstacle, probe, x);
      probe.triangle = s.triangle;
      probe.point = s.point;
      if (!s.valid) {
        // Beyond an open sheet's rim. On the rim's front side, out of reach until it comes as
        // near as a node in front of the sheet (with the same escape, Probe); on its back side
        // once within the depth of it.
        probe.reach = s.distance >= 0.0 ? s.distance - shift : -s.distance - depth;
      } else if (s.distance >= shift) {  // in front
        probe.reach = s.distance - shift;
        probe.in_front = true;
        probe.phi = s.gap;
        probe.normal = s.normal;
      } else {
        probe.reach = s.distance > -depth ? -1.0 : -s.distance - depth;
        if (s.distance > -depth) {
          visit(i, o, s);
          found_.push_back({i, o, s});
        }
      }
      if (probe.reach < 0.0 && probe.near.empty()) list_near(obstacle, probe, x, s);
      hold(0.0);
    }
  }
  found_at_.swap(at);
}

SurfacePoint RigidContact::closest(const Obstacle& obstacle, Probe& probe, const Vec3& x) const {
  if ((x - probe.kept_at).norm() < probe.keep) return obstacle.closest_on(x, probe.triangle);
  const double moved = (x - probe.near_at).norm();
  if (probe.near.empty() || moved > kNearSlack) {
    probe.near.clear();
    probe.keep = -1.0;
  } else if (keep_nearest(obstacle, probe, x, probe.near_half_width - moved)) {
    return obstacle.closest_on(x, probe.triangle);
  }
  return obstacle.closest(x, probe.triangle, probe.point);
}

bool RigidContact::keep_nearest(const Obstacle& obstacle, Probe& probe, const Vec3& x,
                                double unlisted) const {
  const Obstacle::Nearest n = obstacle.nearest_among(x, probe.near);
  const double next = std::min(n.next, unlisted);
  // Two triangles about as near (x on the surface's medial axis, e.g. deep behind a fold or
  // in the symmetry plane of one) each hold a closest point, which round-off chooses between:
  // the tree's choice, as a query without the list would make it.
  if (!(next - n.distance > kTie)) {
    probe.keep = -1.0;
    return false;
  }
  probe.triangle = n.triangle;
  probe.kept_at = x;
  probe.keep = 0.5 * (next - n.distance);
  return true;
}

void RigidContact::list_near(const Obstacle& obstacle, Probe& probe, const Vec3& x,
                             const SurfacePoint& s) const {
  // The closest point q at any x' within the slack of x has |q - x'| <= |x' - s.point|, so
  // |q - x| <= |x - s.point| + 2 slack: its triangle is on the list.
  probe.near_half_width = (x - s.point).norm() + 2.0 * kNearSlack;
  probe.near = obstacle.triangles_near(x, probe.near_half_width);
  probe.near_at = x;
  keep_nearest(obstacle, probe, x, probe.near_half_width);
}

RigidContact::Penalty RigidContact::penalty(int i, double p) const {
  const double eps = node_penalty_[i], w = settings_.smoothing;
  // A smooth normal's gap may lie in front of the surface where the distance is behind it (in
  // the wedge behind an edge or a vertex, nearly along the surface): no force there.
  if (!(p > 0.0)) return {0.0, 0.0, 0.0};
  if (p <= w) return {eps * p * p * p / (6.0 * w), eps * p * p / (2.0 * w), eps * p / w};
  return {eps * (p * p / 2.0 - w * p / 2.0 + w * w / 6.0), eps * (p - w / 2.0), eps};
}

void RigidContact::add(const Vector& u, double /*load_factor*/, Vector& force,
                       SymmetricMatrix* stiffness) const {
  for_each_contact(u, [&](int i, int o, const SurfacePoint& s) {
    const double shift = shift_[pair(i, o)];
    const Penalty psi = penalty(i, shift - s.gap);
    force.segment<3>(3 * nodes_[i]) += psi.force * s.normal;
    if (stiffness != nullptr) {
      // -psi' dn/dx = -(psi' / phi) C, zero with smooth normals: their tangent is psi'' n n^T
      // alone (docs/contact.md says why). Without a shift psi' vanishes as phi^2 at the surface;
      // with one, a node near an edge or a vertex would see dn/dx grow without bound as it
      // nears the surface, and |phi| is held at w there (the tangent of such nodes then no
      // longer exact).
      double phi = s.distance;
      if (shift > 0.0 && std::abs(phi) < settings_.smoothing)
        phi = phi > 0.0 ? settings_.smoothing : -settings_.smoothing;
      const Mat3 block =
          psi.stiffness * s.normal * s.normal.transpose() - (psi.force / phi) * s.curvature;
      add_node_block(*stiffness, dofs_, nodes_[i], nodes_[i], block);
    }
  });
}

void RigidContact::add_springs(const Vector& u, std::vector<NodeSpring>& springs) const {
  const int num_obstacles = static_cast<int>(obstacles_.size());
  for_each_contact(u, [&](int i, int o, const SurfacePoint& s) {
    const double shift = shift_[pair(i, o)];
    const double stiffness = penalty(i, shift - s.gap).stiffness;
    if (stiffness > 0.0) springs.push_back({nodes_[i], s.normal, stiffness, 0.0});
  });
  const std::lock_guard lock(probes_mutex_);
  for (int i = 0; i < static_cast<int>(nodes_.size()); ++i) {
    if (!candidates_[i].in_front) continue;
    const Vec3 x = rest_[i] + u.segment<3>(3 * nodes_[i]);
    for (int o = 0; o < num_obstacles; ++o) {
      const Probe& probe = probes_[pair(i, o)];
      if (!probe.in_front) continue;
      const double gap = probe.phi + probe.normal.dot(x - probe.at) - shift_[pair(i, o)];
      if (gap > 0.0 && gap < kCandidateGap)
        springs.push_back({nodes_[i], probe.normal, node_penalty_[i], gap});
    }
  }
}

ContactReport RigidContact::report(const Vector& u) const {
  ContactReport r;
  r.obstacle_force.assign(obstacles_.size(), Vec3::Zero());
  for_each_contact(u, [&](int i, int o, const SurfacePoint& s) {
    const Penalty psi = penalty(i, shift_[pair(i, o)] - s.gap);
    const Vec3 f = psi.force * s.normal;
    r.contacts.push_back({nodes_[i], o, s.distance, f, s.point});
    r.obstacle_force[o] -= f;
    r.max_penetration = std::max(r.max_penetration, -s.distance);
    r.energy += psi.energy;
  });
  return r;
}

void RigidContact::forget_queries() {
  const std::lock_guard lock(probes_mutex_);
  found_at_.clear();
  for (Probe& probe : probes_) probe.reach = -1.0;
  for (Candidate& candidate : candidates_) candidate.reach = -1.0;
}

void RigidContact::begin_step() {
  augmentations_ = 0;
  if (!shifted_) return;
  std::fill(shift_.begin(), shift_.end(), 0.0);
  shifted_ = false;
  forget_queries();
}

Augmentation RigidContact::augment(const Vector& u) {
  const double tolerance = settings_.penetration_tolerance;
  if (!(tolerance > 0.0)) return Augmentation::held;
  double deepest = 0.0;
  std::vector<double> next(shift_.size(), 0.0);  // zero for pairs out of contact
  for_each_contact(u, [&](int i, int o, const SurfacePoint& s) {
    deepest = std::max(deepest, -s.distance);
    next[pair(i, o)] = std::max(0.0, shift_[pair(i, o)] - s.gap - kTargetDepth * tolerance);
  });
  if (!(deepest > tolerance)) return Augmentation::held;
  if (augmentations_ >= settings_.max_augmentations) return Augmentation::unmet;
  shift_.swap(next);
  shifted_ = true;
  ++augmentations_;
  forget_queries();
  return Augmentation::solve_again;
}

}  // namespace tongue::fem
