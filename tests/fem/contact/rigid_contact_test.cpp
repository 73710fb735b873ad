// Penalty contact against rigid obstacles: the tangent against finite differences, with and
// without the augmented Lagrangian's multipliers, a contact patch test (a block pressed onto a
// plane by a uniform pressure) and a block dropped onto a plane under gravity, on the default
// penalty and on one soft enough that the multipliers must hold the impact.
#include "fem/contact/rigid_contact.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "fem/integrator/newmark_integrator.hpp"
#include "fem/integrator/static_solver.hpp"
#include "fem/material/material_factory.hpp"
#include "fem/mesh/boundary_faces.hpp"
#include "fem/mesh/box_generator.hpp"
#include "surfaces.hpp"

namespace tongue::fem {
namespace {

std::shared_ptr<const Obstacle> obstacle(const std::string& name, TriangleSurface s) {
  return std::make_shared<const Obstacle>(name, std::move(s));
}

std::shared_ptr<SolidModel> make_solid(const Mesh& mesh,
                                       std::vector<PrescribedDof> prescribed = {}) {
  return std::make_shared<SolidModel>(mesh, make_material("mooney_rivlin5", {}),
                                      Formulation::mean_dilatation, 1000.0, prescribed);
}

// The largest difference between the tangent at u and -d f / du by central differences,
// relative to the largest penalty eps_i.
double tangent_error(const RigidContact& contact, const SolidModel& solid, const Vector& u) {
  SymmetricMatrix K(solid.pattern());
  Vector f = Vector::Zero(u.size());
  contact.add(u, 1.0, f, &K);
  const Eigen::MatrixXd dense = K.to_dense();
  const double h = 1e-8;  // m; forces ~eps phi ~ 1e5 * 1e-3 N: round-off 1e-14 / h
  double worst = 0.0;
  for (int j = 0; j < u.size(); ++j) {
    Vector up = u, um = u, fp = Vector::Zero(u.size()), fm = Vector::Zero(u.size());
    up[j] += h;
    um[j] -= h;
    contact.add(up, 1.0, fp, nullptr);
    contact.add(um, 1.0, fm, nullptr);
    const Vector column = -(fp - fm) / (2.0 * h);
    worst = std::max(worst, (column - dense.col(j)).cwiseAbs().maxCoeff());
  }
  return worst / *std::max_element(contact.node_penalty().begin(), contact.node_penalty().end());
}

// Nodes of a 2 x 2 x 2 box shaken by up to 1 mm and pressed into a coarse sphere (closest points
// on its faces, edges and vertices) and a tilted plane at once.
struct ShakenBox {
  Mesh mesh = make_box(Vec3(-0.01, -0.01, -0.01), Vec3(0.02, 0.02, 0.02), 2, 2, 2);
  std::shared_ptr<SolidModel> solid = make_solid(mesh);
  Vector u;
  ShakenBox() {
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> shake(-0.001, 0.001);
    u.resize(solid->num_dofs());
    for (int i = 0; i < u.size(); ++i) u[i] = shake(rng);
  }
  RigidContact contact() const {
    return RigidContact(
        {obstacle("ball", test::icosphere(Vec3(0.0, 0.0, 0.022), 0.015, 0)),
         obstacle("wall", test::square(Vec3(-0.008, 0, 0), Vec3(1, 0.2, 0.1), 0.05))},
        mesh, solid->dofs());
  }
};

// Truncation is zero inside a feature region (phi n is affine or quadratic there), round-off
// ~1e-14 N / 1e-8 m = 1e-6 N/m on entries ~1e4 N/m: 1e-8 of the largest penalty.
constexpr double kTangentTolerance = 1e-8;

TEST(RigidContact, TangentIsTheDerivativeOfTheForce) {
  const ShakenBox box;
  const RigidContact contact = box.contact();
  ASSERT_GE(contact.report(box.u).contacts.size(), 6u);  // both obstacles touched
  EXPECT_LT(tangent_error(contact, *box.solid, box.u), kTangentTolerance);
}

// With the augmented Lagrangian's multipliers: a pair p deep (more than half the tolerance t)
// gets the shift s = p - t / 2, and then the force psi'(s + p) = eps (2 p - t / 2 - w / 2)
// along its normal; the tangent stays the force's derivative; a new step drops the multipliers.
TEST(RigidContact, MultipliersShiftThePenaltyAndKeepItsTangent) {
  const ShakenBox box;
  RigidContact contact = box.contact();
  const ContactReport plain = contact.report(box.u);
  ASSERT_EQ(contact.augment(box.u), Augmentation::solve_again);  // nodes millimetres deep
  const ContactReport augmented = contact.report(box.u);
  ASSERT_EQ(augmented.contacts.size(), plain.contacts.size());
  const ContactSettings& s = contact.settings();
  for (const NodeContact& c : augmented.contacts) {
    const auto i =
        std::find(contact.nodes().begin(), contact.nodes().end(), c.node) - contact.nodes().begin();
    const double p = -c.distance, eps = contact.node_penalty()[i];
    ASSERT_GT(p, s.penetration_tolerance);  // the shaken box's contacts are all this deep
    const double expected = eps * (2.0 * p - s.penetration_tolerance / 2.0 - s.smoothing / 2.0);
    EXPECT_NEAR(c.force.norm(), expected, 1e-12 * expected) << "node " << c.node;
  }
  EXPECT_LT(tangent_error(contact, *box.solid, box.u), kTangentTolerance);

  contact.begin_step();
  const RigidContact fresh = box.contact();
  Vector f = Vector::Zero(box.u.size()), expected = f;
  contact.add(box.u, 1.0, f, nullptr);
  fresh.add(box.u, 1.0, expected, nullptr);
  EXPECT_EQ(f, expected);
}

// The contacts found at the last positions are reused when asked again at the same ones (a
// Newton iteration asks for the force and the springs at one u): the force and springs at u,
// asked again after other positions, equal those of a contact that never saw anything else.
TEST(RigidContact, AskedAgainAtTheSamePositionsGivesTheSameContacts) {
  const Mesh mesh = make_box(Vec3(-0.01, -0.01, -0.01), Vec3(0.02, 0.02, 0.02), 2, 2, 2);
  const auto solid = make_solid(mesh);
  auto make = [&] {
    return RigidContact({obstacle("ball", test::icosphere(Vec3(0.0, 0.0, 0.022), 0.015, 0))}, mesh,
                        solid->dofs());
  };
  const RigidContact reused = make(), fresh = make();
  Vector u = Vector::Zero(solid->num_dofs()), v = u;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    u[3 * n + 2] = 0.001;   // the top face (z = 10 mm) 4 mm into the ball (lowest at 7 mm)
    v[3 * n + 2] = -0.004;  // 1 mm below it
  }
  auto force = [&](const RigidContact& c, const Vector& at) {
    Vector f = Vector::Zero(at.size());
    c.add(at, 1.0, f, nullptr);
    return f;
  };
  auto springs = [&](const RigidContact& c, const Vector& at) {
    std::vector<NodeSpring> s;
    c.add_springs(at, s);
    return s;
  };
  const Vector first = force(reused, u);
  ASSERT_GT(first.norm(), 0.0);
  EXPECT_EQ(force(reused, u), first);       // again at u
  EXPECT_EQ(force(reused, v).norm(), 0.0);  // elsewhere: out of contact
  const std::vector<NodeSpring> again = springs(reused, u), expected = springs(fresh, u);
  ASSERT_EQ(again.size(), expected.size());
  for (std::size_t i = 0; i < again.size(); ++i) {
    EXPECT_EQ(again[i].node, expected[i].node);
    EXPECT_EQ(again[i].direction, expected[i].direction);
    EXPECT_EQ(again[i].stiffness, expected[i].stiffness);
  }
  EXPECT_EQ(force(reused, u), force(fresh, u));
}

// A node that skips its query (it cannot have come within reach of the obstacle since its last
// one) finds what a query would: a block slid past the rim of an open sheet, once on the sheet's
// front side (over it, then pressed into it) and once on its back side (under it, coming round
// the rim into its back within the search depth), gets at every position the forces of a contact
// that never saw another position.
TEST(RigidContact, SkippedQueriesFindWhatAQueryWould) {
  const Mesh mesh = make_box(Vec3::Zero(), Vec3(0.01, 0.01, 0.01), 2, 2, 2);
  const auto solid = make_solid(mesh);
  // The sheet z = -1 mm for x < -3 mm: the block starts 3 mm beyond its rim.
  const auto sheet = [] {
    return std::vector{
        obstacle("sheet", test::square(Vec3(-0.053, 0.005, -0.001), Vec3::UnitZ(), 0.05, 4))};
  };
  for (const double side : {1.0, -1.0}) {  // in front of the sheet's plane, behind it
    const RigidContact reused(sheet(), mesh, solid->dofs());
    // From 1 mm above the plane (the block's bottom), or from the block's top 1 mm below it.
    const Vec3 start(0.0, 0.0, side > 0.0 ? 0.0 : -0.012);
    std::vector<Vec3> path;
    for (int k = 0; k <= 40; ++k) path.push_back(start + Vec3(-0.00025 * k, 0.0, 0.0));
    for (int k = 1; k <= 30; ++k) path.push_back(path[40] + Vec3(0.0, 0.0, -side * 0.00005 * k));
    double largest = 0.0;
    for (const Vec3& move : path) {
      Vector u(solid->num_dofs());
      for (int n = 0; n < mesh.num_nodes(); ++n) u.segment<3>(3 * n) = move;
      Vector f = Vector::Zero(u.size()), expected = f;
      reused.add(u, 1.0, f, nullptr);
      RigidContact(sheet(), mesh, solid->dofs()).add(u, 1.0, expected, nullptr);
      // The same closest points, found from other hints: round-off of the 0.05 m geometry
      // (~1e-17 m) times the penalties (~1e4 N/m).
      EXPECT_LT((f - expected).norm(), 1e-11) << "side " << side << ", at " << move.transpose();
      largest = std::max(largest, expected.norm());
    }
    EXPECT_GT(largest, 1.0) << "side " << side;  // N: the path ends in contact
  }
}

// A node asked again at every iterate (in contact) is answered from the triangles listed near
// it, and from the nearest of them alone while it cannot have changed: the shaken box, pressed
// into a faceted ball, then slid to and fro by about 0.1 mm a step, each node jittered, for 400
// steps, gets at every position the forces of a contact that never saw another position.
TEST(RigidContact, NearTrianglesFindWhatAQueryWould) {
  const ShakenBox box;
  // A ball whose facets are about 2 mm wide (a walk crosses many of them), the box's top face
  // 0.4-4 mm into it.
  const auto contact = [&] {
    return RigidContact({obstacle("ball", test::icosphere(Vec3(0.0, 0.0, 0.036), 0.03, 4))},
                        box.mesh, box.solid->dofs());
  };
  const RigidContact walked = contact();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-3e-5, 3e-5);
  Vector u = box.u;
  std::size_t fewest = 1000;
  for (int k = 0; k < 400; ++k) {
    // Slid to and fro by about 0.1 mm a step (within the lists' slack), some steps standing
    // still, each node jittered by up to 0.05 mm.
    const Vec3 slide =
        k % 7 == 6 ? Vec3::Zero() : Vec3(1e-4 * std::cos(k / 20.0), 1e-4 * std::sin(k / 31.0), 0.0);
    for (int n = 0; n < box.mesh.num_nodes(); ++n)
      u.segment<3>(3 * n) += slide + Vec3(jitter(rng), jitter(rng), jitter(rng));
    Vector f = Vector::Zero(u.size()), expected = f;
    walked.add(u, 1.0, f, nullptr);
    const RigidContact fresh = contact();
    fresh.add(u, 1.0, expected, nullptr);
    fewest = std::min(fewest, fresh.report(u).contacts.size());
    // The same triangle's closest point, computed alike: equal but for a tie between triangles
    // sharing an edge (the same point either way, to round-off ~1e-17 m times ~1e5 N/m).
    EXPECT_LT((f - expected).norm(), 1e-11) << "step " << k;
  }
  EXPECT_GE(fewest, 4u);  // nodes in contact all along
}

// A node between two sheets of one obstacle, nearer one of them, that moves across to the other
// in steps shorter than the lists' slack: its nearest triangle changes sheets half-way, and
// with the other sheet off its first list (3 mm away) only the bound on unlisted triangles
// says when. The forces at every position are a fresh contact's.
TEST(RigidContact, NearTrianglesLetGoOfTheNearestWhenAnotherCouldBeNearer) {
  // Off the sheets' triangle edges, where two triangles tie.
  const Mesh mesh = make_box(Vec3(0.0013, 0.0021, 0.0), Vec3(0.001, 0.001, 0.0005), 1, 1, 1);
  const auto solid = make_solid(mesh);
  // The sheets z = -0.6 mm (normal -z) and z = 3.4 mm (normal +z): the block's nodes are behind
  // both, within the search depth of each.
  TriangleSurface slot = test::square(Vec3(0.0, 0.0, -0.0006), -Vec3::UnitZ(), 0.01, 2);
  const TriangleSurface upper = test::square(Vec3(0.0, 0.0, 0.0034), Vec3::UnitZ(), 0.01, 2);
  const int offset = static_cast<int>(slot.vertices.size());
  slot.vertices.insert(slot.vertices.end(), upper.vertices.begin(), upper.vertices.end());
  for (auto t : upper.triangles)
    slot.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  const auto contact = [&] { return RigidContact({obstacle("slot", slot)}, mesh, solid->dofs()); };
  const RigidContact moved = contact();
  Vector u = Vector::Zero(solid->num_dofs());
  for (int k = 0; k <= 40; ++k) {
    // Up to 2.9 mm, never where a node is as far from both sheets (a tie either may win).
    for (int n = 0; n < mesh.num_nodes(); ++n) u[3 * n + 2] = 0.000073 * k;
    Vector f = Vector::Zero(u.size()), expected = f;
    moved.add(u, 1.0, f, nullptr);
    contact().add(u, 1.0, expected, nullptr);
    EXPECT_LT((f - expected).norm(), 1e-11) << "step " << k;
    EXPECT_GT(expected.norm(), 0.0);
  }
}

// The penetration under a contact pressure P: psi'(p) = eps p^2 / (2 w) up to p = w, then
// eps (p - w / 2), per unit area (rigid_contact.hpp).
double penetration(double P, const ContactSettings& s) {
  const double w = s.smoothing;
  return P <= s.penalty * w / 2.0 ? std::sqrt(2.0 * w * P / s.penalty) : w / 2.0 + P / s.penalty;
}

// A 20 x 20 x 10 mm block on a rigid plane, its top pressed down by a uniform pressure p, sliding
// freely (symmetry rollers on x = 0 and y = 0): the homogeneous uniaxial state is the exact
// discrete solution, so every bottom node carries p times its area and sinks the same depth into
// the plane, and the contact forces add up to the load.
TEST(RigidContact, PatchTestCarriesTheLoadWithUniformPressure) {
  const Mesh mesh = make_box(Vec3::Zero(), Vec3(0.02, 0.02, 0.01), 4, 4, 2);
  std::vector<PrescribedDof> rollers;
  for (int n = 0; n < mesh.num_nodes(); ++n) {
    if (mesh.nodes[n].x() < 1e-9) rollers.push_back({n, 0, 0.0});
    if (mesh.nodes[n].y() < 1e-9) rollers.push_back({n, 1, 0.0});
  }
  const auto solid = make_solid(mesh, rollers);
  const double p = 5e3;       // Pa
  const double start = 1e-6;  // m: the plane starts 1 um into the block, so that contact
                              // holds the block from the first iteration
  ContactSettings settings;
  settings.penalty = 1e9;  // Pa/m: p / kappa = 5 um
  std::vector<Quad4> top, bottom;
  for (const Quad4& face : boundary_faces(mesh)) {
    bool at_top = true, at_bottom = true;
    for (int n : face) {
      at_top = at_top && mesh.nodes[n].z() > 0.01 - 1e-9;
      at_bottom = at_bottom && mesh.nodes[n].z() < 1e-9;
    }
    if (at_top) top.push_back(face);
    if (at_bottom) bottom.push_back(face);
  }
  // The bottom is the contact surface: the sides' area does not bear on the plane.
  auto contact = std::make_shared<RigidContact>(
      std::vector{obstacle("floor", test::square(Vec3(0.01, 0.01, start), Vec3::UnitZ(), 0.05))},
      mesh, solid->dofs(), settings, bottom);
  Vector load = Vector::Zero(solid->num_dofs());
  for (const Quad4& face : top) {
    const double quarter = (mesh.nodes[face[2]] - mesh.nodes[face[0]])
                               .cross(mesh.nodes[face[3]] - mesh.nodes[face[1]])
                               .norm() /
                           8.0;
    for (int n : face) load[3 * n + 2] -= p * quarter;
  }
  MechanicalSystem system(solid);
  system.add_load(std::make_shared<ConstantForce>("pressure", load));
  system.add_load(contact);
  StaticSettings static_settings;
  static_settings.require_held = false;  // the plane holds the block in z
  static_settings.newton.residual_rtol = 1e-12;
  static_settings.newton.residual_atol = 1e-13;  // N; the load is 2 N
  Vector u = Vector::Zero(solid->num_dofs());
  const StaticReport solved = solve_static(system, u, static_settings);
  ASSERT_TRUE(solved.converged) << solved.message;

  const ContactReport report = contact->report(u);
  ASSERT_EQ(report.contacts.size(), 25u);  // the 5 x 5 bottom nodes
  const double total = p * 0.02 * 0.02;
  // The force balance holds to the residual tolerance (1e-13 N on 2 N); the pressure and the
  // penetration of each node to that over the smallest nodal area (a corner's 6 mm^2).
  EXPECT_NEAR(-report.obstacle_force[0].z(), total, 1e-10 * total);
  for (const NodeContact& c : report.contacts) {
    const int i =
        static_cast<int>(std::find(contact->nodes().begin(), contact->nodes().end(), c.node) -
                         contact->nodes().begin());
    const double area = contact->node_penalty()[i] / settings.penalty;
    EXPECT_NEAR(c.force.z() / area, p, 1e-8 * p);
    EXPECT_NEAR(-c.distance, penetration(p, settings), 1e-8 * penetration(p, settings));
    EXPECT_NEAR(c.force.x(), 0.0, 1e-12);
  }
  EXPECT_NEAR(report.max_penetration, penetration(p, settings), 1e-8 * penetration(p, settings));
  EXPECT_LT(report.max_penetration, 1e-4);  // the bound the scenes are held to
}

// A 10 mm cube dropped 5 mm onto a plane under gravity, the plane as the contact's obstacle.
struct DroppedBlock {
  Mesh mesh = make_box(Vec3::Zero(), Vec3(0.01, 0.01, 0.01), 2, 2, 2);
  std::shared_ptr<SolidModel> solid = make_solid(mesh);
  std::shared_ptr<RigidContact> contact;
  Vector weight = solid->body_force(Vec3(0, 0, -9.81));
  MechanicalSystem system{solid};

  explicit DroppedBlock(const ContactSettings& settings = {}) {
    const double drop = 0.005;
    contact = std::make_shared<RigidContact>(
        std::vector{
            obstacle("floor", test::square(Vec3(0.005, 0.005, -drop), Vec3::UnitZ(), 0.05))},
        mesh, solid->dofs(), settings);
    system.add_load(std::make_shared<ConstantForce>("gravity", weight));
    system.add_load(contact);
  }
  // The plane carries the weight at rest; what is left is the damping force alpha M v of the
  // residual motion (< 1e-4 m/s x 40 1/s x 1e-3 kg = 4e-6 N on 1e-2 N).
  void expect_at_rest(const NewmarkIntegrator& integrator) const {
    EXPECT_LT(integrator.velocity().cwiseAbs().maxCoeff(), 1e-4);  // m/s
    const ContactReport rest = contact->report(integrator.displacement());
    const double mg = solid->total_mass() * 9.81;
    EXPECT_NEAR(-rest.obstacle_force[0].z(), mg, 1e-3 * mg);
    EXPECT_GT(rest.contacts.size(), 0u);
  }
};

// Mass-proportional damping: the motion decays as exp(-20 t).
DynamicSettings damped(NewmarkParameters newmark) {
  DynamicSettings settings;
  settings.damping.mass_coefficient = 40.0;  // 1/s
  settings.newmark = newmark;
  settings.newton.residual_rtol = 1e-10;
  settings.newton.residual_atol = 1e-12;
  return settings;
}

// The energy (kinetic + strain + contact - work of gravity) never grows, no node passes through
// the plane, and the block ends at rest on it, the plane carrying its weight.
TEST(RigidContact, DroppedBlockComesToRestOnThePlane) {
  DroppedBlock block;
  // Newmark with numerical dissipation, gamma = 3/4 and beta = (gamma + 1/2)^2 / 4 (Hughes
  // 2000, sec. 9.1): the average-acceleration rule (gamma = 1/2) gains energy whenever a node
  // leaves contact within a step, its trapezoid of the contact force over the step counting
  // eps delta (phi_{n+1}) / 2 of work the spring never did; at this penalty (omega dt ~ 12)
  // the block then bounces higher and higher.
  NewmarkIntegrator integrator(block.system, damped({0.390625, 0.75, 0.0}));
  const SolidModel& solid = *block.solid;
  const int n = solid.num_dofs();
  integrator.initialize(Vector::Zero(n), Vector::Zero(n));
  const SymmetricMatrix M = solid.mass_matrix(false);

  const auto energy = [&]() {
    const Vector& u = integrator.displacement();
    const Vector& v = integrator.velocity();
    Vector f = Vector::Zero(n);
    double strain = 0.0;
    solid.assemble(u, f, nullptr, &strain);
    return 0.5 * v.dot(M.multiply(v)) + strain + block.contact->report(u).energy -
           block.weight.dot(u);
  };
  double last = energy(), deepest = 0.0;
  const double dt = 1e-3;
  for (int step = 0; step < 400; ++step) {
    const StepReport r = integrator.step(dt);
    ASSERT_TRUE(r.converged) << "step " << step << ": " << r.message;
    EXPECT_EQ(r.augmentations, 0);  // never deeper than the tolerance
    const double e = energy();
    // Damping only takes energy out; 1e-9 J allows the solver's tolerance (1e-12 N residual on
    // displacements of ~1e-2 m) and the round-off of sums of ~5e-5 J.
    EXPECT_LE(e, last + 1e-9) << "step " << step;
    last = e;
    deepest = std::max(deepest, block.contact->report(integrator.displacement()).max_penetration);
  }
  // The impact, 0.31 m/s onto the default 3e8 Pa/m, penetrates 12 um; never tunnels.
  EXPECT_LT(deepest, 1e-4);
  block.expect_at_rest(integrator);
}

// The nodes in contact start each step from their last step's displacement carried on, not from
// their velocity (NewmarkIntegrator's predictor): where Newton starts must not change where it
// ends. The block's drop and rest, stepped both ways, pass through the same states to 1e-12 m:
// Newton's residual tolerance (1e-12 N) on a stiffness of at least eps ~ 1e4 N/m leaves 1e-16 m
// per step, and the 400 steps measured 3e-14 m apart.
TEST(RigidContact, HeldNodesCarryingOnTheirLastStepReachTheSameStates) {
  DroppedBlock following, velocity;
  DynamicSettings settings = damped({0.390625, 0.75, 0.0});
  NewmarkIntegrator a(following.system, settings);
  settings.held_nodes_follow_increment = false;
  NewmarkIntegrator b(velocity.system, settings);
  const int n = following.solid->num_dofs();
  a.initialize(Vector::Zero(n), Vector::Zero(n));
  b.initialize(Vector::Zero(n), Vector::Zero(n));
  int in_contact = 0;
  for (int step = 0; step < 400; ++step) {
    const StepReport ra = a.step(1e-3), rb = b.step(1e-3);
    ASSERT_TRUE(ra.converged && rb.converged) << "step " << step;
    ASSERT_LT((a.displacement() - b.displacement()).cwiseAbs().maxCoeff(), 1e-12)
        << "step " << step;
    if (!following.contact->report(a.displacement()).contacts.empty()) ++in_contact;
  }
  EXPECT_GT(in_contact, 300);  // the predictor of held nodes was at work for most steps
  following.expect_at_rest(a);
}

// The predictor itself: once the block rests on the plane, the free dofs of its nodes in contact
// in the last two states start the next step at u_n + (u_n - u_n-1), the others (those that
// have just struck among them) at u_n + dt v_n; a step of another length, or the first after
// initialize(), starts every node at u_n + dt v_n.
TEST(RigidContact, HeldNodesArePredictedFromTheirLastStep) {
  DroppedBlock block;
  NewmarkIntegrator integrator(block.system, damped({0.390625, 0.75, 0.0}));
  const int n = block.solid->num_dofs();
  integrator.initialize(Vector::Zero(n), Vector::Zero(n));
  const DofMap& dofs = block.solid->dofs();
  const double dt = 1e-3;
  const auto by_velocity = [&](double h) {
    return Vector(dofs.gather_free(integrator.displacement()) +
                  h * dofs.gather_free(integrator.velocity()));
  };
  const auto held = [&]() {
    std::vector<RankOneTerm> terms;
    block.system.rank_one_terms(integrator.displacement(), terms);
    std::vector<char> marks(dofs.num_free(), 0);
    for (const RankOneTerm& t : terms)
      if (t.engaged())
        for (int i : t.index)
          if (i >= 0) marks[i] = 1;
    return marks;
  };
  EXPECT_EQ(integrator.predictor(dt), by_velocity(dt));  // no last step yet
  // Stepped until some nodes have been in contact for two states and others have just struck
  // (the block lands after about 32 ms, a corner first).
  Vector before;
  std::vector<char> held_before, held_now = held(), both(dofs.num_free(), 0);
  int in_both = 0, just_struck = 0;
  for (int step = 0; step < 400 && (in_both == 0 || just_struck == 0); ++step) {
    before = integrator.displacement();
    ASSERT_TRUE(integrator.step(dt).converged);
    held_before = held_now;
    held_now = held();
    in_both = just_struck = 0;
    for (int i = 0; i < dofs.num_free(); ++i) {
      both[i] = held_before[i] && held_now[i];
      in_both += both[i];
      just_struck += held_now[i] && !held_before[i];
    }
  }
  ASSERT_GT(in_both, 0);
  ASSERT_GT(just_struck, 0);

  const Vector x = integrator.predictor(dt), velocity = by_velocity(dt);
  const Vector u_n = dofs.gather_free(integrator.displacement()), u_p = dofs.gather_free(before);
  for (int i = 0; i < dofs.num_free(); ++i) {
    const double expected = both[i] ? 2.0 * u_n[i] - u_p[i] : velocity[i];
    EXPECT_EQ(x[i], expected) << "free dof " << i << (both[i] ? " (held)" : "");
  }
  EXPECT_NE(x, velocity);  // the held nodes' two predictions differ
  EXPECT_EQ(integrator.predictor(2.0 * dt), by_velocity(2.0 * dt));  // another step length
  integrator.initialize(integrator.displacement(), integrator.velocity());
  EXPECT_EQ(integrator.predictor(dt), by_velocity(dt));  // no last step since initialize()
}

// On a penalty a hundred times softer the same impact goes deeper than the tolerance: the steps
// that do are solved again with the multipliers, and no converged step leaves a node deeper
// (0.096 mm measured, 18 such solves); without them (tolerance 0) the strike goes 0.25 mm deep,
// and with a tolerance but no updates allowed, the steps that leave a node deeper say so. At
// rest the penalty alone holds the weight within the tolerance (98 Pa: 43 um).
TEST(RigidContact, MultipliersHoldASofterPenaltysImpactWithinTheTolerance) {
  struct Case {
    double tolerance;
    int max_augmentations;
  };
  for (const Case c : {Case{1e-4, 4}, Case{0.0, 4}, Case{1e-4, 0}}) {
    ContactSettings settings;
    settings.penalty = 3e6;  // Pa/m
    settings.penetration_tolerance = c.tolerance;
    settings.max_augmentations = c.max_augmentations;
    DroppedBlock block(settings);
    NewmarkIntegrator integrator(block.system, damped(NewmarkParameters::bossak(0.6)));
    const int n = block.solid->num_dofs();
    integrator.initialize(Vector::Zero(n), Vector::Zero(n));
    double deepest = 0.0;
    int augmentations = 0, unmet = 0;
    for (int step = 0; step < 800; ++step) {  // the softer bounce takes longer to die out
      const StepReport r = integrator.step(1e-3);
      ASSERT_TRUE(r.converged) << "step " << step << ": " << r.message;
      augmentations += r.augmentations;
      const double depth = block.contact->report(integrator.displacement()).max_penetration;
      // A step is flagged exactly when it leaves a node deeper than a tolerance it has.
      EXPECT_EQ(r.constraint_unmet, c.tolerance > 0.0 && depth > c.tolerance) << "step " << step;
      unmet += r.constraint_unmet ? 1 : 0;
      deepest = std::max(deepest, depth);
    }
    if (c.tolerance > 0.0 && c.max_augmentations > 0) {
      EXPECT_GT(augmentations, 0);
      EXPECT_LE(deepest, c.tolerance);
    } else {
      EXPECT_EQ(augmentations, 0);
      EXPECT_GT(deepest, 2e-4);
    }
    if (c.tolerance > 0.0 && c.max_augmentations == 0) {
      EXPECT_GT(unmet, 0);
    }
    block.expect_at_rest(integrator);
  }
}

}  // namespace
}  // namespace tongue::fem
