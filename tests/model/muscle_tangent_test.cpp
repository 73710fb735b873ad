// The fibre stiffness that MuscleForces assembles against central differences of its force over
// the free dofs, on a box with mixed constraints and fibres that cross the constraints, start at
// fixed origins and join nodes sharing no element: with constant tension (T d2L/dx2) and with
// the active force-length relation, on every part of its curve.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "model/muscle_forces.hpp"
#include "model/muscle_test_support.hpp"
#include "support/finite_difference.hpp"

namespace tongue::model {
namespace {

using fem::Vec3;
using fem::Vector;
using testing::fibre;
using testing::grid_box;
using testing::grid_node;
using testing::muscle;

struct TangentScene {
  std::vector<Muscle> muscles;
  std::shared_ptr<const fem::SolidModel> solid;
  Vector u;

  TangentScene() {
    // Clamped x_min face, and single components prescribed on nodes the fibres pass through.
    const fem::Mesh mesh = grid_box();
    std::vector<fem::PrescribedDof> prescribed;
    for (int n : mesh.node_set("x_min")) {
      for (int c = 0; c < 3; ++c) prescribed.push_back({n, c, 0.0});
    }
    prescribed.push_back({grid_node(2, 1, 1), 1, 0.0});
    prescribed.push_back({grid_node(4, 2, 2), 0, 0.0});
    prescribed.push_back({grid_node(3, 0, 1), 2, 0.0});

    // A fibre from the clamped face through a partly prescribed node; one from a bony origin
    // with long jumps between nodes sharing no element; a weighted pair in one muscle, one of
    // them visiting a node twice (not consecutively).
    Fibre from_bone =
        fibre({grid_node(1, 0, 0), grid_node(4, 2, 2), grid_node(1, 2, 1), grid_node(3, 0, 1)});
    from_bone.origin = Vec3(-0.015, -0.01, 0.01);
    muscles = {muscle("GGp",
                      {fibre({grid_node(0, 1, 1), grid_node(1, 1, 1), grid_node(2, 1, 1),
                              grid_node(3, 2, 1), grid_node(4, 2, 2)})},
                      37.0),
               muscle("SG", {from_bone}, 24.0),
               muscle("T",
                      {fibre({grid_node(2, 0, 0), grid_node(2, 0, 2), grid_node(3, 1, 2),
                              grid_node(2, 0, 2 - 1), grid_node(2, 0, 2)},
                             0.4),
                       fibre({grid_node(4, 0, 0), grid_node(4, 0, 1)}, 0.6)},
                      50.0)};
    solid = testing::make_solid(mesh, muscles, prescribed);

    // A random displacement of up to 2 mm (segments stay >= ~5 mm long), with the prescribed
    // dofs at their values.
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> d(-2e-3, 2e-3);
    u.resize(solid->num_dofs());
    for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = d(rng);
    for (int dof : solid->dofs().prescribed_dofs()) u[dof] = 0.0;
  }
};

// Relative Frobenius error of the assembled tangent against central differences of the force
// over the free dofs at u_at, printed under `what`; also checks that the tangent is positive
// semidefinite.
double tangent_error(const TangentScene& scene, const MuscleForces& muscles, const Vector& u_at,
                     const char* what) {
  const double load_factor = 0.9;
  const fem::DofMap& dofs = scene.solid->dofs();
  fem::SymmetricMatrix K(scene.solid->pattern());
  Vector f = Vector::Zero(scene.solid->num_dofs());
  muscles.add(u_at, load_factor, f, &K);
  const Eigen::MatrixXd K_assembled = K.to_dense();

  // The residual's load part is -f; its Jacobian over the free dofs is the tangent.
  const auto minus_force = [&](const Vector& u_free) -> Vector {
    Vector u = u_at;
    dofs.scatter_free(u_free, u);
    Vector force = Vector::Zero(u.size());
    muscles.add(u, load_factor, force, nullptr);
    return -dofs.gather_free(force);
  };
  // Central differences with h = 1e-6 m: truncation h^2 / 6 |f'''| ~ T h^2 / l^3 against
  // |K| ~ T / l, i.e. (h / l)^2 ~ 4e-8 relative for l >= 5 mm (1e-7 for the 3-4 mm segments of
  // the compressed fibre below; the force-length terms add T f'''(lambda) h^2 / l_rest^3 of the
  // same order, f''' <= 48 (1 - lambda_0)^-3 = 384); round-off eps |f| / h ~ 1e-10 T against
  // T / l ~ 100 T per m: 1e-12. 1e-6 leaves an order of magnitude.
  const Eigen::MatrixXd K_fd =
      tongue::testing::central_difference_jacobian(minus_force, dofs.gather_free(u_at), 1e-6);
  const double error = (K_assembled - K_fd).norm() / K_fd.norm();
  std::printf("  %s: relative Frobenius error %.2e\n", what, error);
  EXPECT_GT(K_fd.norm(), 0.0);

  // Each segment's block t (I - e e^T) / l + T f' / l_rest e e^T is positive semidefinite
  // (f, f' >= 0), and so is their sum (eigenvalues down to -1e-12 |K| for round-off).
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K_assembled);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-12 * eig.eigenvalues().maxCoeff());
  return error;
}

TEST(MuscleTangent, MatchesCentralDifferencesOfTheForceOverTheFreeDofs) {
  TangentScene scene;
  const Vector levels = (Vector(3) << 0.8, 0.5, 0.3).finished();
  MuscleForces constant(scene.solid, scene.muscles, ActiveForceLength::constant_tension());
  constant.set_activations(levels);
  EXPECT_LT(tangent_error(scene, constant, scene.u, "fibre tangent, constant tension"), 1e-6);
  MuscleForces hill(scene.solid, scene.muscles);
  hill.set_activations(levels);
  EXPECT_LT(tangent_error(scene, hill, scene.u, "fibre tangent, force-length"), 1e-6);
}

// The GGp fibre pushed back along x so that its segments sit below the zero-force length
// (lambda ~0.4), on the ascending limb (~0.7, ~0.9) and on the plateau: every piece of f and
// both terms of the segment block are exercised.
TEST(MuscleTangent, WithForceLengthMatchesCentralDifferencesOnEveryPartOfTheCurve) {
  TangentScene scene;
  const std::vector<int>& ggp = scene.muscles[0].fibres[0].nodes;
  Vector u = 0.25 * scene.u;  // jitter of up to 0.5 mm
  u[3 * ggp[1]] -= 0.006;     // segment 0: 10 -> ~4 mm
  u[3 * ggp[2]] -= 0.009;     // segment 1: 10 -> ~7 mm
  u[3 * ggp[3]] -= 0.0112;    // segment 2: 14.1 -> ~12.7 mm; segment 3: 14.1 -> ~23 mm
  const ActiveForceLength relation;
  const Vector rest = scene.solid->rest_positions(), x = rest + u;
  int below = 0, limb = 0, plateau = 0;
  for (size_t i = 1; i < ggp.size(); ++i) {
    const auto length = [&](const Vector& at) {
      return (at.segment<3>(3 * ggp[i]) - at.segment<3>(3 * ggp[i - 1])).norm();
    };
    const double lambda = length(x) / length(rest);
    below += lambda < relation.zero_force_length();
    limb += lambda > relation.zero_force_length() && lambda < 1.0;
    plateau += lambda > 1.0;
  }
  ASSERT_EQ(below, 1);
  ASSERT_EQ(limb, 2);
  ASSERT_EQ(plateau, 1);

  MuscleForces muscles(scene.solid, scene.muscles, relation);
  muscles.set_activations((Vector(3) << 1.0, 0.5, 0.3).finished());
  EXPECT_LT(tangent_error(scene, muscles, u, "fibre tangent, force-length, compressed GGp"), 1e-6);
}

TEST(MuscleTangent, AddsToWhatTheMatrixAlreadyHolds) {
  TangentScene scene;
  MuscleForces muscles(scene.solid, scene.muscles);
  muscles.set_activation(1, 1.0);
  fem::SymmetricMatrix alone(scene.solid->pattern()), on_top(scene.solid->pattern());
  Vector f = Vector::Zero(scene.solid->num_dofs());
  muscles.add(scene.u, 1.0, f, &alone);
  Vector internal(scene.solid->num_dofs());
  ASSERT_TRUE(scene.solid->assemble(scene.u, internal, &on_top).ok);
  const Eigen::MatrixXd solid_only = on_top.to_dense();
  muscles.add(scene.u, 1.0, f, &on_top);
  EXPECT_LT((on_top.to_dense() - solid_only - alone.to_dense()).norm(),
            1e-14 * on_top.to_dense().norm());
}

}  // namespace
}  // namespace tongue::model
