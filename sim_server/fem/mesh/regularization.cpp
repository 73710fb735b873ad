#include "fem/mesh/regularization.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>  // cross()

#include "fem/mesh/mesh_quality.hpp"

namespace tongue::fem {

namespace {

void check_corner(int corner) {
  if (corner < 0 || corner >= 8) {
    throw std::out_of_range("hex8 corner " + std::to_string(corner) + " out of range [0, 8)");
  }
}

// Edge neighbours of every corner, derived from the reference coordinates so that they follow
// the node order of hex8_shape.hpp: neighbour k differs from the corner in coordinate k only.
constexpr std::array<std::array<int, 3>, 8> make_neighbour_table() {
  std::array<std::array<int, 3>, 8> table{};
  for (int a = 0; a < 8; ++a) {
    const auto& s = hex8::kNodeCoords[a];
    for (int k = 0; k < 3; ++k) {
      for (int b = 0; b < 8; ++b) {
        const auto& t = hex8::kNodeCoords[b];
        bool differs_in_k_only = true;
        for (int j = 0; j < 3; ++j) differs_in_k_only &= (j == k) ? t[j] != s[j] : t[j] == s[j];
        if (differs_in_k_only) table[a][k] = b;
      }
    }
  }
  return table;
}
constexpr auto kNeighbours = make_neighbour_table();
static_assert(kNeighbours[0][0] == 1 && kNeighbours[0][1] == 3 && kNeighbours[0][2] == 4);
static_assert(kNeighbours[6][0] == 7 && kNeighbours[6][1] == 5 && kNeighbours[6][2] == 2);

// -(s_1 s_2 s_3) / 8 of corner a: the factor between D_a and the triple product of its edges.
double corner_sign_factor(int corner) {
  const auto& s = hex8::kNodeCoords[corner];
  return -(s[0] * s[1] * s[2]) / 8.0;
}

// Mean edge length along each reference direction: the 4 edges along xi_k join the corners with
// s_k = -1 to their neighbour along k.
Vec3 edge_scales(const hex8::ElementCoords& X) {
  Vec3 L = Vec3::Zero();
  for (int a = 0; a < 8; ++a) {
    for (int k = 0; k < 3; ++k) {
      const int b = kNeighbours[a][k];
      if (hex8::kNodeCoords[a][k] < 0) L[k] += (X.row(b) - X.row(a)).norm() / 4.0;
    }
  }
  return L;
}

std::string format_mm(double metres) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.4g mm", metres * 1e3);
  return buffer;
}

void check_settings(const RegularizationSettings& s) {
  if (!(s.max_displacement >= 0)) {
    throw std::invalid_argument("regularize: max_displacement must be >= 0");
  }
  if (s.max_iterations < 0) throw std::invalid_argument("regularize: max_iterations must be >= 0");
  if (!(s.step > 0 && s.step <= 1))
    throw std::invalid_argument("regularize: step must be in (0, 1]");
  if (!(s.min_det_ratio > 0 && s.min_det_ratio < 1)) {
    throw std::invalid_argument("regularize: min_det_ratio must be in (0, 1)");
  }
  if (!(s.max_step_ratio > 0 && std::isfinite(s.max_step_ratio))) {
    throw std::invalid_argument("regularize: max_step_ratio must be positive and finite");
  }
}

// By is_regular, so that the report agrees with check_quality to the last bit.
std::vector<int> irregular_elements(const Mesh& mesh) {
  std::vector<int> out;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    if (!is_regular(mesh, e)) out.push_back(e);
  }
  return out;
}

}  // namespace

std::array<int, 3> corner_neighbours(int corner) {
  check_corner(corner);
  return kNeighbours[corner];
}

double nodal_jacobian_determinant(const hex8::ElementCoords& X, int corner) {
  const auto n = corner_neighbours(corner);  // checks the corner
  const Vec3 xa = X.row(corner).transpose();
  const Vec3 e1 = X.row(n[0]).transpose() - xa;
  const Vec3 e2 = X.row(n[1]).transpose() - xa;
  const Vec3 e3 = X.row(n[2]).transpose() - xa;
  return corner_sign_factor(corner) * e1.dot(e2.cross(e3));
}

hex8::ElementCoords nodal_jacobian_gradient(const hex8::ElementCoords& X, int corner) {
  const auto n = corner_neighbours(corner);
  const Vec3 xa = X.row(corner).transpose();
  const Vec3 e1 = X.row(n[0]).transpose() - xa;
  const Vec3 e2 = X.row(n[1]).transpose() - xa;
  const Vec3 e3 = X.row(n[2]).transpose() - xa;
  const double c = corner_sign_factor(corner);
  hex8::ElementCoords g = hex8::ElementCoords::Zero();
  g.row(n[0]) = c * e2.cross(e3).transpose();
  g.row(n[1]) = c * e3.cross(e1).transpose();
  g.row(n[2]) = c * e1.cross(e2).transpose();
  // e_k = X_{n_k} - X_a, so X_a enters every edge with a minus sign.
  g.row(corner) = -(g.row(n[0]) + g.row(n[1]) + g.row(n[2]));
  return g;
}

hex8::ElementCoords nodal_jacobian_gradient(const Mesh& mesh, int element, int corner) {
  check_corner(corner);
  return nodal_jacobian_gradient(element_coords(mesh, element), corner);
}

namespace {

// Luboz et al. (2001) / Gerard et al. (2003) sec. II.3, one sweep per iteration:
//  1. nodal determinants D_a of every element;
//  2. irregular elements (some D_a <= 0) join the set of corrected elements;
//  3. in every corrected element, each corner below its target t moves the free nodes of its
//     corner tetrahedron along their rows g_b of the gradient of D_a, by
//         dX_b = step (2 t - D_a) / |g|^2 g_b,
//     contributions to shared nodes summed. The paper moves the offending nodes along grad D
//     weighted by |D|; 2 t - D_a = |D_a| + 2 t is that weight, and dividing by |g|^2 (the
//     linearized, Newton step) makes the step dimensionless, so neither the mesh unit nor the
//     element size changes the iteration. Aiming at 2 t rather than t: relaxed steps approach
//     their aim geometrically and would never quite reach it. All 4 nodes of which D_a depends
//     move (not the offending node alone): the joint gradient is the smallest correction for a
//     given gain in D_a, each node spends its own share of the displacement bound, and a corner
//     whose own node is fixed or at the bound is still corrected by its neighbours.
// Moves are capped per iteration and clamped to the ball of radius max_displacement about the
// start; a node on that sphere keeps only the tangential part of its gradient row (projected
// gradient), so the shortfall passes to the nodes that still can move.
class Sweeps {
 public:
  enum class Stop { done, iterations, stalled, no_progress };
  // Sweeps without progress (summed shortfall not falling) before giving up: the nodes are then
  // trading the shortfall around against the displacement bound.
  static constexpr int kPatience = 200;

  Sweeps(Mesh& mesh, const RegularizationSettings& settings, const std::vector<char>& fixed)
      : mesh_(mesh),
        settings_(settings),
        fixed_(fixed),
        start_(mesh.nodes),
        corrected_(mesh.num_elements(), 0),
        move_(mesh.num_nodes()),
        move_cap_(mesh.num_nodes()) {}

  // Sweeps until every corrected corner has D_a >= ratio * L1 L2 L3 / 8, or one of the other
  // stops, at most max_sweeps times. Returns the sweeps applied.
  int run(double ratio, int max_sweeps) {
    double best_shortfall = std::numeric_limits<double>::infinity();
    int best_sweep = 0;
    stop_ = Stop::iterations;
    for (int sweep = 0;; ++sweep) {
      const int newly_corrected = gather(ratio);
      if (below_target_ == 0) {
        stop_ = Stop::done;
        return sweep;
      }
      if (sweep == max_sweeps) return sweep;
      // A newly corrected element brings its own shortfall, so progress is measured from there.
      if (newly_corrected > 0 || shortfall_ < best_shortfall * (1.0 - 1e-6)) {
        best_shortfall = shortfall_;
        best_sweep = sweep;
      } else if (sweep - best_sweep >= kPatience) {
        stop_ = Stop::no_progress;
        return sweep;
      }
      // Nothing moves any more (every node of the offending corners fixed or held at the
      // bound): further sweeps would change nothing.
      if (!(apply() > 1e-12 * smallest_scale_)) {
        stop_ = Stop::stalled;
        return sweep + 1;
      }
    }
  }

  Stop stop() const { return stop_; }
  int below_target() const { return below_target_; }
  const std::vector<Vec3>& start() const { return start_; }
  bool on_bound(int node) const {
    // Within a relative tolerance for the round-off of the projection onto the sphere.
    return (mesh_.nodes[node] - start_[node]).norm() >= settings_.max_displacement * (1.0 - 1e-9);
  }

 private:
  // Steps 1 to 3 without moving: fills move_ and move_cap_, counts the corners below target and
  // their summed shortfall. Returns the number of elements newly found irregular.
  int gather(double ratio) {
    std::fill(move_.begin(), move_.end(), Vec3::Zero());
    std::fill(move_cap_.begin(), move_cap_.end(), std::numeric_limits<double>::infinity());
    below_target_ = 0;
    shortfall_ = 0.0;
    smallest_scale_ = std::numeric_limits<double>::infinity();
    int newly_corrected = 0;
    for (int e = 0; e < mesh_.num_elements(); ++e) {
      const hex8::ElementCoords X = element_coords(mesh_, e);
      std::array<double, 8> D{};
      for (int a = 0; a < 8; ++a) D[a] = nodal_jacobian_determinant(X, a);
      if (*std::min_element(D.begin(), D.end()) <= 0 && !corrected_[e]) {
        corrected_[e] = 1;
        ++newly_corrected;
      }
      if (!corrected_[e]) continue;
      const Vec3 L = edge_scales(X);
      const double target = ratio * L.prod() / 8.0;
      const double cap = settings_.max_step_ratio * L.minCoeff();
      const Hex8& hex = mesh_.elements[e];
      for (int a = 0; a < 8; ++a) {
        if (D[a] > 0 && D[a] >= target) continue;
        ++below_target_;
        shortfall_ += target - D[a];
        hex8::ElementCoords g = nodal_jacobian_gradient(X, a);
        double norm2 = 0.0;
        for (int b = 0; b < 8; ++b) {
          const int node = hex[b];
          if (fixed_[node]) {
            g.row(b).setZero();
          } else if (on_bound(node)) {
            const Vec3 r = (mesh_.nodes[node] - start_[node]).normalized();
            const double outward = g.row(b).dot(r.transpose());
            if (outward > 0) g.row(b) -= outward * r.transpose();
          }
          norm2 += g.row(b).squaredNorm();
        }
        if (!(norm2 > 0)) continue;  // every node of the corner held
        const double factor = settings_.step * (2.0 * target - D[a]) / norm2;
        for (int b = 0; b < 8; ++b) {
          if (g.row(b).isZero(0.0)) continue;
          move_[hex[b]] += factor * g.row(b).transpose();
          move_cap_[hex[b]] = std::min(move_cap_[hex[b]], cap);
        }
        smallest_scale_ = std::min(smallest_scale_, L.minCoeff());
      }
    }
    return newly_corrected;
  }

  // Moves every node by its capped, clamped share; returns the largest move [m].
  double apply() {
    const double bound = settings_.max_displacement;
    double largest = 0.0;
    for (int node = 0; node < mesh_.num_nodes(); ++node) {
      Vec3 d = move_[node];
      const double length = d.norm();
      if (length == 0.0) continue;
      if (length > move_cap_[node]) d *= move_cap_[node] / length;
      Vec3 x = mesh_.nodes[node] + d;
      const Vec3 from_start = x - start_[node];
      if (from_start.norm() > bound) x = start_[node] + from_start * (bound / from_start.norm());
      largest = std::max(largest, (x - mesh_.nodes[node]).norm());
      mesh_.nodes[node] = x;
    }
    return largest;
  }

  Mesh& mesh_;
  const RegularizationSettings& settings_;
  const std::vector<char>& fixed_;
  const std::vector<Vec3> start_;
  std::vector<char> corrected_;
  std::vector<Vec3> move_;
  std::vector<double> move_cap_;
  Stop stop_ = Stop::iterations;
  int below_target_ = 0;    // corners of corrected elements below their target
  double shortfall_ = 0.0;  // sum of target - D_a over those corners [m^3]
  double smallest_scale_ = 0.0;
};

std::string describe(Sweeps::Stop stop) {
  switch (stop) {
    case Sweeps::Stop::done:
      return "target reached";
    case Sweeps::Stop::stalled:
      return "no node can move further";
    case Sweeps::Stop::no_progress:
      return "no progress in " + std::to_string(Sweeps::kPatience) + " iterations";
    case Sweeps::Stop::iterations:
      break;
  }
  return "iteration limit reached";
}

}  // namespace

// Two phases share the iteration budget. The first only makes the mesh regular, with a tenth
// of the margin, spending as little of the displacement bound as it can; the second then
// raises the corrected corners to the full margin with what is left. Chasing the full margin
// from the start can spend the bound on corners that are merely thin and leave a fold unfixed;
// a second phase that makes things worse (an element irregular again) is undone.
RegularizationReport regularize(Mesh& mesh, const RegularizationSettings& settings,
                                const std::vector<int>& fixed_nodes) {
  check_settings(settings);
  std::vector<char> fixed(mesh.num_nodes(), 0);
  for (int n : fixed_nodes) {
    if (n < 0 || n >= mesh.num_nodes()) {
      throw std::invalid_argument("regularize: fixed node " + std::to_string(n) +
                                  " out of range [0, " + std::to_string(mesh.num_nodes()) + ")");
    }
    fixed[n] = 1;
  }
  for (int e = 0; e < mesh.num_elements(); ++e)
    (void)element_coords(mesh, e);  // node indices valid

  RegularizationReport report;
  report.irregular_before = static_cast<int>(irregular_elements(mesh).size());
  Sweeps sweeps(mesh, settings, fixed);
  report.iterations = sweeps.run(settings.min_det_ratio / 10.0, settings.max_iterations);
  const Sweeps::Stop stop = sweeps.stop();
  std::string margin;
  if (report.irregular_before > 0 && irregular_elements(mesh).empty()) {
    const std::vector<Vec3> regular = mesh.nodes;
    report.iterations +=
        sweeps.run(settings.min_det_ratio, settings.max_iterations - report.iterations);
    if (!irregular_elements(mesh).empty()) {
      mesh.nodes = regular;
      margin = "; raising the margin broke regularity and was undone";
    } else if (sweeps.stop() != Sweeps::Stop::done) {
      margin = "; " + std::to_string(sweeps.below_target()) +
               " nodal determinants below the target margin (" + describe(sweeps.stop()) + ")";
    }
  }

  report.still_irregular = irregular_elements(mesh);
  report.irregular_after = static_cast<int>(report.still_irregular.size());
  report.success = report.still_irregular.empty();
  int at_bound = 0;
  for (int node = 0; node < mesh.num_nodes(); ++node) {
    const double d = (mesh.nodes[node] - sweeps.start()[node]).norm();
    report.max_node_displacement = std::max(report.max_node_displacement, d);
    if (d > 0 && sweeps.on_bound(node)) ++at_bound;
  }

  const std::string after = std::to_string(report.iterations) + " iterations";
  const std::string moved =
      "; largest node displacement " + format_mm(report.max_node_displacement) + " (bound " +
      format_mm(settings.max_displacement) + ", " + std::to_string(at_bound) + " nodes at it)";
  if (report.irregular_before == 0) {
    report.message = "mesh already regular, nothing moved";
  } else if (report.success) {
    report.message = "every element regular after " + after + margin + moved;
  } else {
    report.message = std::to_string(report.irregular_after) + " elements still irregular after " +
                     after + " (" + describe(stop) + ")" + moved;
  }
  return report;
}

}  // namespace tongue::fem
