#pragma once
// Frictionless contact of a solid's surface nodes against rigid obstacles, by a penalty on the
// penetration (Wriggers 2006, Computational Contact Mechanics, sec. 6.3; node-to-surface with a
// rigid master surface). A surface node i at signed distance phi from an obstacle, penetration
// p = -phi > 0, is pushed out along the obstacle's normal n by the force psi'(p) n, the
// derivative of the energy psi(p) whose stiffness psi'' grows linearly from 0 to eps_i over the
// first w of penetration and stays eps_i beyond:
//     psi''(p) = eps_i min(p / w, 1),   eps_i = kappa A_i,
// with A_i the node's share of the contact surface's area in the reference state (a quarter of
// each of its faces the node is a corner of; the surface is the solid's whole boundary unless
// given, as FEBio's contact surfaces are) and kappa the penalty [Pa/m]. A pressure P then
// penetrates w / 2 + P / kappa (P >= kappa w / 2). The smooth start keeps Newton's iteration from
// cycling on nodes at the edge of the contact zone, which a force with a kink at p = 0 makes
// jump between a stiff spring and none (a smoothed penalty in the spirit of Wriggers 2006,
// sec. 10.3). With faceted normals the consistent tangent is psi'' n n^T + (psi' / p) C,
// C = phi dn/dx the obstacle's curvature term (zero inside a triangle, obstacle.hpp). With smooth
// normals (obstacle.hpp's Normals) p is the gap along the interpolated normal n and the tangent
// psi'' n n^T alone: the force is then not the gradient of an energy, and the symmetric part of
// its derivative is indefinite where n leans from the facet's normal (docs/contact.md). A node
// touching several obstacles gets the sum.
//
// Augmented Lagrangian (Simo & Laursen 1992, Computers & Structures 42; Wriggers 2006, sec. 6.3):
// when a step's converged state has a node deeper than the tolerance t, each pair's multiplier
// lambda = eps_i s is updated by Uzawa's rule for the constraint p <= t / 2,
//     lambda <- max(0, lambda + eps_i (p - t / 2)),
// and the step is solved again: the penalty then acts on p + s instead of p, as if the
// obstacle's surface stood s in front of where it is, and a node that was deeper settles near
// t / 2 with nearly the same force (each update shrinks the excess by about the ratio of the
// stiffness behind the node to eps_i). The target is t / 2, not the surface: near an edge or a
// vertex of the faceted obstacle the normal turns through 1 / |phi| radians per metre, and nodes
// held at phi = 0 there made Newton's iteration cycle (the full-force push, docs/contact.md).
// The multipliers start every step at zero, so a step whose nodes stay within the tolerance is
// the plain penalty's.
//
// The force does not scale with a load factor: contact is part of the solid, not a load.
#include <memory>
#include <mutex>
#include <vector>

#include "fem/assembly/dof_map.hpp"
#include "fem/assembly/loads.hpp"
#include "fem/contact/obstacle.hpp"
#include "fem/mesh/boundary_faces.hpp"
#include "fem/mesh/mesh.hpp"

namespace tongue::fem {

struct ContactSettings {
  // kappa [Pa/m]. With the default w, 20 kPa (a firm tongue-palate contact pressure)
  // penetrates 77 um. Stiffer penalties penetrate less but make Newton's iteration longer (the
  // tongue pushed by GGp into the vocal tract, docs/contact.md: 1e8, 3e8 and 1e9 Pa/m took
  // 104, 143 and 156 iterations for 30 steps, and reached 0.096, 0.043 and 0.042 mm).
  double penalty = 3e8;
  // w [m]: the penetration over which the penalty's stiffness grows from 0 to eps.
  double smoothing = 2e-5;
  // Points deeper than this behind an obstacle's surface are not in contact with it [m]: the
  // back of a sheet seen from the other side. Well beyond any penetration the penalty allows.
  double search_depth = 0.005;
  // [m]: a step whose converged state has a node deeper than this is solved again with the
  // multipliers updated, at most max_augmentations times (0: the plain penalty). Without it the
  // full-force push of the tongue strikes the palate 0.14 mm deep (docs/contact.md).
  double penetration_tolerance = 1e-4;
  int max_augmentations = 4;
};

// One node in contact with one obstacle.
struct NodeContact {
  int node = 0;
  int obstacle = 0;
  double distance = 0.0;      // signed distance phi [m]: < 0, or below the multiplier's shift
  Vec3 force = Vec3::Zero();  // on the node [N]
  Vec3 point = Vec3::Zero();  // closest point on the obstacle [m]
};

struct ContactReport {
  std::vector<NodeContact> contacts;  // node by node, in the order of nodes()
  std::vector<Vec3> obstacle_force;   // the total force the solid exerts on each obstacle [N]
  double max_penetration = 0.0;       // largest -phi [m], 0 without contact
  double energy = 0.0;                // sum of psi [J]
};

class RigidContact : public ForceContribution {
 public:
  // The candidates are the nodes of the contact surface's faces (empty: the mesh's boundary
  // faces) with at least one free dof. Throws std::invalid_argument for no obstacles or a
  // penalty or depth that is not positive.
  RigidContact(std::vector<std::shared_ptr<const Obstacle>> obstacles, const Mesh& mesh,
               const DofMap& dofs, ContactSettings settings = {}, std::vector<Quad4> surface = {});

  std::string name() const override { return "contact"; }
  // Adds the contact forces at displacement u (load_factor is ignored) and, when given, their
  // tangent to the stiffness.
  void add(const Vector& u, double load_factor, Vector& force,
           SymmetricMatrix* stiffness) const override;

  // The normal springs psi'' n n^T of the nodes in contact at u (their tangent without the
  // curvature term), and for the nodes in front of an obstacle within kCandidateGap, the spring
  // eps n n^T that would engage, with their distance (from their last query, moved along n).
  static constexpr double kCandidateGap = 0.002;  // [m]
  void add_springs(const Vector& u, std::vector<NodeSpring>& springs) const override;

  ContactReport report(const Vector& u) const;

  // The augmented Lagrangian's multipliers (ForceContribution): set to zero, and updated at u
  // when a node is deeper than the tolerance there and updates are left this step (unmet when
  // none are; held without a tolerance).
  void begin_step() override;
  Augmentation augment(const Vector& u) override;

  const std::vector<std::shared_ptr<const Obstacle>>& obstacles() const { return obstacles_; }
  const std::vector<int>& nodes() const { return nodes_; }
  // eps_i of each candidate node [N/m], in the order of nodes().
  const std::vector<double>& node_penalty() const { return node_penalty_; }
  const ContactSettings& settings() const { return settings_; }

 private:
  // psi, psi' and psi'' of candidate i at penetration p.
  struct Penalty {
    double energy, force, stiffness;
  };
  Penalty penalty(int i, double p) const;
  // The index of a (candidate, obstacle) pair in probes_ and shift_.
  int pair(int candidate, int obstacle) const {
    return candidate * static_cast<int>(obstacles_.size()) + obstacle;
  }
  // The depth the multipliers hold a node at, over the tolerance.
  static constexpr double kTargetDepth = 0.5;
  // How far a node may move from where its near triangles were listed (Probe) [m].
  static constexpr double kNearSlack = 0.5e-3;
  // Distances to two triangles closer than this count as a tie [m]: far above their round-off
  // (~1e-17 m on a tongue-sized surface), far below any gap that matters.
  static constexpr double kTie = 1e-12;
  // Calls visit(candidate index, obstacle index, surface point) for every contact at u: every
  // pair whose signed distance is below its shift (and above -search_depth).
  template <typename Visit>
  void for_each_contact(const Vector& u, Visit&& visit) const;
  // The queries' proofs and the contacts found hold for the shifts they were made with.
  void forget_queries();

  std::vector<std::shared_ptr<const Obstacle>> obstacles_;
  DofMap dofs_;
  ContactSettings settings_;
  std::vector<int> nodes_;
  std::vector<Vec3> rest_;  // reference positions of nodes_ [m]
  std::vector<double> node_penalty_;
  // s of each (candidate, obstacle) pair [m], candidate-major: the multiplier over eps_i.
  std::vector<double> shift_;
  bool shifted_ = false;   // some shift is not zero
  int augmentations_ = 0;  // this step's
  // What the last closest-point query of each (node, obstacle) pair proved: no contact while the
  // node stays within `reach` of where it was (|phi| changes no faster than the node moves).
  // Most nodes are millimetres from every obstacle and move micrometres an iteration, so most
  // queries are skipped. One case escapes the proof: a node in front of an open sheet, or beyond
  // its rim on the front side, that slips around the rim to the sheet's back in less than its
  // distance from it counts as out of contact until it is queried again (a contact from behind a
  // sheet is spurious anyway). Beyond the rim on the back side a node is in reach once within
  // the search depth of the rim.
  struct Probe {
    Vec3 at = Vec3::Zero();
    double reach = -1.0;    // < 0: query again
    bool in_front = false;  // valid and phi >= 0 at `at`: then phi and normal below
    double phi = 0.0;       // the gap along the normal (SurfacePoint::gap)
    Vec3 normal = Vec3::Zero();
    int triangle = -1;  // the closest point at `at`, the next query's hint
    Vec3 point = Vec3::Zero();
    // A node asked again at every iterate (in contact, or behind a rim within the search depth)
    // is asked without the tree: its triangles within near_half_width of near_at (every other
    // one is farther) serve while it stays within kNearSlack of near_at, and the nearest of them
    // alone while it stays within `keep` of kept_at (distances to triangles change no faster
    // than the node moves, so the nearest stays so while it moves less than half the margin
    // to the next). Empty: none listed.
    std::vector<int> near;
    Vec3 near_at = Vec3::Zero(), kept_at = Vec3::Zero();
    double near_half_width = 0.0, keep = -1.0;
  };
  mutable std::vector<Probe> probes_;  // [candidate * obstacles + obstacle]
  // What a candidate's probes prove together: no contact with any obstacle while the node stays
  // within `reach` of `at` (the least reach its probes have left from there; < 0 when one is to
  // be asked again), and whether one of them is in front. Most candidates are passed over by
  // this one test on a compact array, instead of one per obstacle on probes_, whose entries are
  // 192 bytes (on scenes/tongue_i.yaml 12 % of the probes are in front of an obstacle, and most
  // nodes are far from all four).
  struct Candidate {
    Vec3 at = Vec3::Zero();
    double reach = -1.0;
    bool in_front = false;
  };
  mutable std::vector<Candidate> candidates_;
  // The closest point of `obstacle` to x, from the probe's near triangles when they hold it.
  SurfacePoint closest(const Obstacle& obstacle, Probe& probe, const Vec3& x) const;
  // The nearest of the probe's listed triangles to x into probe.triangle, and how far x may move
  // while it stays the nearest into keep; false (and no keep) when another is about as near.
  // `unlisted`: how near to x a triangle off the list can be [m].
  bool keep_nearest(const Obstacle& obstacle, Probe& probe, const Vec3& x, double unlisted) const;
  // Lists the triangles near x for a probe that will be asked again, s its closest point.
  void list_near(const Obstacle& obstacle, Probe& probe, const Vec3& x,
                 const SurfacePoint& s) const;
  // The contacts found at the last u, by candidate position: a Newton iteration asks for the
  // force and for the springs at the same u, and the line search's last trial is the next
  // iterate.
  struct Found {
    int candidate, obstacle;
    SurfacePoint point;
  };
  mutable std::vector<Vec3> found_at_;
  mutable std::vector<Found> found_;
  mutable std::mutex probes_mutex_;
};

}  // namespace tongue::fem
