#include "model/muscle_forces.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

namespace tongue::model {

using fem::Mat3;
using fem::Vec3;
using fem::Vector;

namespace {

Vec3 node_position(const Vector& x, int node) {
  return x.segment<3>(3 * node);
}

// Calls visit(from_node, to_node, from, to) for each segment of the fibre in order; from_node is
// -1 for the segment that starts at the fixed origin.
template <typename Visit>
void for_each_segment(const Fibre& fibre, const Vector& x, Visit&& visit) {
  size_t first = 0;
  int from_node = -1;
  Vec3 from;
  if (fibre.origin) {
    from = *fibre.origin;
  } else {
    from_node = fibre.nodes[0];
    from = node_position(x, from_node);
    first = 1;
  }
  for (size_t i = first; i < fibre.nodes.size(); ++i) {
    const int to_node = fibre.nodes[i];
    const Vec3 to = node_position(x, to_node);
    visit(from_node, to_node, from, to);
    from_node = to_node;
    from = to;
  }
}

// True when every free dof of node a is coupled to every free dof of node b in the pattern
// (vacuously when one of them has no free dof).
bool coupled(const fem::SparsityPattern& pattern, const fem::DofMap& dofs, int a, int b) {
  for (int c = 0; c < 3; ++c) {
    const int i = dofs.free_index(3 * a + c);
    for (int d = 0; d < 3 && i >= 0; ++d) {
      const int j = dofs.free_index(3 * b + d);
      if (j >= 0 && pattern.find(std::min(i, j), std::max(i, j)) < 0) return false;
    }
  }
  return true;
}

void check_level(double level, const std::string& muscle) {
  if (!std::isfinite(level) || level < 0.0 || level > 1.0) {
    throw std::invalid_argument("activation " + std::to_string(level) + " of muscle '" + muscle +
                                "' is outside [0, 1]");
  }
}

}  // namespace

double fibre_length(const Fibre& fibre, const Vector& x) {
  double length = 0.0;
  for_each_segment(
      fibre, x, [&](int, int, const Vec3& from, const Vec3& to) { length += (to - from).norm(); });
  return length;
}

FibreKinematics fibre_kinematics(const Fibre& fibre, const Vector& x, const Vector& v) {
  // dl/dt = e . (v_to - v_from) per segment; the origin does not move.
  FibreKinematics k;
  for_each_segment(fibre, x, [&](int from_node, int to_node, const Vec3& from, const Vec3& to) {
    const double l = (to - from).norm();
    k.length += l;
    if (l == 0.0) return;
    Vec3 dv = v.segment<3>(3 * to_node);
    if (from_node >= 0) dv -= v.segment<3>(3 * from_node);
    k.rate += (to - from).dot(dv) / l;
  });
  return k;
}

MuscleForces::MuscleForces(std::shared_ptr<const fem::SolidModel> solid,
                           std::vector<Muscle> muscles, ActiveForceLength force_length)
    : solid_(std::move(solid)),
      muscles_(std::move(muscles)),
      activations_(Vector::Zero(static_cast<Eigen::Index>(muscles_.size()))),
      force_length_(force_length),
      first_segment_(muscles_.size()) {
  const fem::Mesh& mesh = solid_->mesh();
  const Vector& rest = solid_->rest_positions();
  std::set<std::string> names;
  for (size_t m = 0; m < muscles_.size(); ++m) {
    const Muscle& muscle = muscles_[m];
    validate(muscle, mesh.num_nodes(), mesh.num_elements());
    if (!names.insert(muscle.name).second) {
      throw std::invalid_argument("muscle '" + muscle.name + "' is defined twice");
    }
    for (size_t f = 0; f < muscle.fibres.size(); ++f) {
      const std::string where = "muscle '" + muscle.name + "': fibre " + std::to_string(f);
      first_segment_[m].push_back(static_cast<int>(rest_lengths_.size()));
      for_each_segment(muscle.fibres[f], rest,
                       [&](int from_node, int to_node, const Vec3& from, const Vec3& to) {
                         rest_lengths_.push_back((to - from).norm());
                         if (rest_lengths_.back() == 0.0) {
                           throw std::invalid_argument(where +
                                                       " has a zero-length segment at "
                                                       "rest ending at node " +
                                                       std::to_string(to_node));
                         }
                         if (from_node >= 0 &&
                             !coupled(*solid_->pattern(), solid_->dofs(), from_node, to_node)) {
                           throw std::invalid_argument(
                               where + ": nodes " + std::to_string(from_node) + " and " +
                               std::to_string(to_node) +
                               " are not coupled in the solid's sparsity pattern; build the "
                               "SolidModel with fibre_node_pairs(muscles) as extra_node_pairs");
                         }
                       });
    }
  }
}

int MuscleForces::index_of(const std::string& name) const {
  for (size_t m = 0; m < muscles_.size(); ++m) {
    if (muscles_[m].name == name) return static_cast<int>(m);
  }
  return -1;
}

void MuscleForces::set_activation(int index, double level) {
  if (index < 0 || index >= num_muscles()) {
    throw std::invalid_argument("muscle index " + std::to_string(index) + " is outside 0.." +
                                std::to_string(num_muscles() - 1));
  }
  check_level(level, muscles_[index].name);
  activations_[index] = level;
}

void MuscleForces::set_activations(const Vector& levels) {
  if (levels.size() != num_muscles()) {
    throw std::invalid_argument(std::to_string(levels.size()) + " activation levels given for " +
                                std::to_string(num_muscles()) + " muscles");
  }
  // All checked before any is set, so a bad vector changes nothing.
  for (int m = 0; m < num_muscles(); ++m) check_level(levels[m], muscles_[m].name);
  activations_ = levels;
}

Vector MuscleForces::muscle_forces() const {
  Vector t(num_muscles());
  for (int m = 0; m < num_muscles(); ++m) t[m] = activations_[m] * muscles_[m].max_force;
  return t;
}

Vector MuscleForces::positions(const Vector& u) const {
  return solid_->rest_positions() + u;
}

void MuscleForces::add(const Vector& u, double load_factor, Vector& force,
                       fem::SymmetricMatrix* stiffness) const {
  const fem::DofMap& dofs = solid_->dofs();
  Vector x;  // formed only when some muscle is active
  for (int m = 0; m < num_muscles(); ++m) {
    const Muscle& muscle = muscles_[m];
    const double muscle_tension = load_factor * activations_[m] * muscle.max_force;
    if (muscle_tension == 0.0) continue;
    if (x.size() == 0) x = positions(u);
    for (size_t f = 0; f < muscle.fibres.size(); ++f) {
      const Fibre& fibre = muscle.fibres[f];
      const double T = muscle_tension * fibre.weight;
      const double* rest_length = &rest_lengths_[first_segment_[m][f]];
      for_each_segment(fibre, x, [&](int from_node, int to_node, const Vec3& from, const Vec3& to) {
        const double l_rest = *rest_length++;
        const double l = (to - from).norm();
        const double stretch = l / l_rest;
        const double t = T * force_length_.value(stretch);  // this segment's tension
        if (l == 0.0 || t == 0.0) return;
        const Vec3 e = (to - from) / l;
        // F = -t dl/dx with dl/dx_to = e, dl/dx_from = -e: the ends are pulled together.
        force.segment<3>(3 * to_node) -= t * e;
        if (from_node >= 0) force.segment<3>(3 * from_node) += t * e;
        if (stiffness == nullptr) return;
        // d(t e)/dx_to: t (I - e e^T) / l from the turning direction, plus the change of the
        // tension with length, T f'(l / l_rest) / l_rest along e.
        const Mat3 B = t * (Mat3::Identity() - e * e.transpose()) / l +
                       (T * force_length_.slope(stretch) / l_rest) * e * e.transpose();
        fem::add_node_block(*stiffness, dofs, to_node, to_node, B);
        if (from_node >= 0) {
          fem::add_node_block(*stiffness, dofs, from_node, from_node, B);
          fem::add_node_block(*stiffness, dofs, from_node, to_node, -B);
        }
      });
    }
  }
}

Vector MuscleForces::muscle_lengths(const Vector& u) const {
  const Vector x = positions(u);
  Vector lengths = Vector::Zero(num_muscles());
  for (int m = 0; m < num_muscles(); ++m) {
    for (const Fibre& fibre : muscles_[m].fibres)
      lengths[m] += fibre.weight * fibre_length(fibre, x);
  }
  return lengths;
}

void MuscleForces::muscle_kinematics(const Vector& u, const Vector& v, Vector& lengths,
                                     Vector& velocities) const {
  const Vector x = positions(u);
  lengths = Vector::Zero(num_muscles());
  velocities = Vector::Zero(num_muscles());
  for (int m = 0; m < num_muscles(); ++m) {
    for (const Fibre& fibre : muscles_[m].fibres) {
      const FibreKinematics k = fibre_kinematics(fibre, x, v);
      lengths[m] += fibre.weight * k.length;
      velocities[m] += fibre.weight * k.rate;
    }
  }
}

}  // namespace tongue::model
