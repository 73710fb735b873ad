#pragma once
// Frictionless contact of a solid's surface nodes against rigid obstacles, by a penalty on the
// penetration (Wriggers 2006, Computational Contact Mechanics, sec. 6.3; node-to-surface with a
// rigid master surface). A surface node i at signed distance phi < 0 from an obstacle is pushed
// out along the obstacle's normal n by
//     f_i = -eps_i phi n,     eps_i = kappa A_i,
// the gradient of the energy eps_i phi^2 / 2, with A_i the node's share of the contact surface's
// area in the reference state (a quarter of each of its faces the node is a corner of; the
// surface is the solid's whole boundary unless given, as FEBio's contact surfaces are) and kappa
// the penalty [Pa/m], the contact pressure per metre of penetration: a pressure p then penetrates
// p / kappa. The energy's Hessian eps_i (n n^T + phi dn/dx) is the consistent tangent; the
// second term is zero where the closest point lies inside a triangle and accounts for the
// normal turning around an edge or a vertex. A node touching several obstacles gets the sum.
//
// The force does not scale with a load factor: contact is part of the solid, not a load.
#include <memory>
#include <vector>

#include "fem/assembly/dof_map.hpp"
#include "fem/assembly/loads.hpp"
#include "fem/contact/obstacle.hpp"
#include "fem/mesh/boundary_faces.hpp"
#include "fem/mesh/mesh.hpp"

namespace tongue::fem {

struct ContactSettings {
  // kappa [Pa/m]. 1e9 Pa/m: 20 kPa, a firm tongue-palate contact pressure, penetrates 20 um.
  double penalty = 1e9;
  // Points deeper than this behind an obstacle's surface are not in contact with it [m]: the
  // back of a sheet seen from the other side. Well beyond any penetration the penalty allows.
  double search_depth = 0.005;
};

// One node in contact with one obstacle.
struct NodeContact {
  int node = 0;
  int obstacle = 0;
  double distance = 0.0;      // signed distance phi < 0 [m]
  Vec3 force = Vec3::Zero();  // on the node [N]
  Vec3 point = Vec3::Zero();  // closest point on the obstacle [m]
};

struct ContactReport {
  std::vector<NodeContact> contacts;  // node by node, in the order of nodes()
  std::vector<Vec3> obstacle_force;   // the total force the solid exerts on each obstacle [N]
  double max_penetration = 0.0;       // largest -phi [m], 0 without contact
  double energy = 0.0;                // sum eps phi^2 / 2 [J]
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
  // tangent eps (n n^T + phi dn/dx) to the stiffness.
  void add(const Vector& u, double load_factor, Vector& force,
           SymmetricMatrix* stiffness) const override;

  ContactReport report(const Vector& u) const;

  const std::vector<std::shared_ptr<const Obstacle>>& obstacles() const { return obstacles_; }
  const std::vector<int>& nodes() const { return nodes_; }
  // eps_i of each candidate node [N/m], in the order of nodes().
  const std::vector<double>& node_penalty() const { return node_penalty_; }
  const ContactSettings& settings() const { return settings_; }

 private:
  // Calls visit(candidate index, obstacle index, surface point) for every contact at u.
  template <typename Visit>
  void for_each_contact(const Vector& u, Visit&& visit) const;

  std::vector<std::shared_ptr<const Obstacle>> obstacles_;
  DofMap dofs_;
  ContactSettings settings_;
  std::vector<int> nodes_;
  std::vector<Vec3> rest_;  // reference positions of nodes_ [m]
  std::vector<double> node_penalty_;
};

}  // namespace tongue::fem
