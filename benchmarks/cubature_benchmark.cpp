// How few evaluation points can carry the reduced model's internal force: the misfit of the
// energy-conserving sample (reduced/element_sampling.hpp) against its size, for two kinds of
// candidates over the training snapshots:
//  - the mesh's elements, each integrated as the full model does (2x2x2 Gauss points, mean
//    dilatation): what build_reduced_model samples;
//  - one point per element: W(F) at the element's centre times its volume, the one-point
//    cubature of An, Kim & James 2008 (ACM Trans. Graph. 27, "Optimizing cubature for efficient
//    integration of subspace deformations"), about an eighth of an element's work, each point
//    weighed to reproduce the whole mesh's forces of the first kind.
// Prints, for each tolerance, the sampled count and misfit, and the one-point candidates' misfit
// with every weight 1 (how far the one-point mesh is from the full one). Then the same for one
// point per element plus an affine model, in the reduced coordinates, of what those points leave
// out of the whole mesh's force, the sample fitting the rest.
//
// Usage: cubature_benchmark SCENE BASIS SNAPSHOTS [--snapshots N]
//   (BASIS and SNAPSHOTS from build_reduced_model SCENE --output BASIS --snapshots SNAPSHOTS)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include "fem/element/hex8_shape.hpp"
#include "reduced/element_reduced_forces.hpp"
#include "reduced/element_sampling.hpp"
#include "reduced/reduced_basis_file.hpp"
#include "reduced/snapshot_file.hpp"
#include "scene/scene_builder.hpp"
#include "scene/scene_reader.hpp"

namespace {

using namespace tongue;
using Clock = std::chrono::steady_clock;

// As element_reduced_forces, with each element's force that of one point at its centre:
// f_a = V P(F_c) dN_a/dX (c), F_c the deformation gradient there.
Eigen::MatrixXd centre_point_reduced_forces(const fem::SolidModel& solid, const fem::Vector& origin,
                                            const Eigen::MatrixXd& modes,
                                            const Eigen::MatrixXd& snapshots) {
  const fem::Mesh& mesh = solid.mesh();
  const Eigen::Index k = modes.cols(), S = snapshots.cols();
  Eigen::MatrixXd g(S * k, mesh.num_elements());
  const fem::Vec3 centre = fem::Vec3::Zero();
  const fem::hex8::ShapeGradients dN_dxi = fem::hex8::reference_gradients(centre);
  Eigen::Matrix<double, 24, Eigen::Dynamic> phi_e(24, k);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const fem::Hex8& nodes = mesh.elements[e];
    fem::hex8::ElementCoords X;
    for (int a = 0; a < 8; ++a) X.row(a) = mesh.nodes[nodes[a]].transpose();
    const Eigen::Matrix<double, 8, 3> dN_dX = dN_dxi * fem::hex8::jacobian(X, centre).inverse();
    double volume = 0.0;
    for (const fem::hex8::QuadraturePoint& q : fem::hex8::gauss_2x2x2())
      volume += q.weight * fem::hex8::jacobian(X, q.xi).determinant();
    for (int a = 0; a < 8; ++a) phi_e.middleRows(3 * a, 3) = modes.middleRows(3 * nodes[a], 3);
    for (Eigen::Index s = 0; s < S; ++s) {
      fem::hex8::ElementCoords x = X;
      for (int a = 0; a < 8; ++a)
        x.row(a) += (origin + snapshots.col(s)).segment<3>(3 * nodes[a]).transpose();
      const fem::Mat3 F = x.transpose() * dN_dX;
      if (!(F.determinant() > 0.0))
        throw std::runtime_error("element " + std::to_string(e) + " inverted at its centre");
      const fem::Mat3 P = solid.material().response(F, false).stress;
      fem::ElementVector f;
      for (int a = 0; a < 8; ++a) f.segment<3>(3 * a) = volume * P * dN_dX.row(a).transpose();
      g.block(s * k, e, k, 1) = phi_e.transpose() * f;
    }
  }
  return g;
}

// What the one-point mesh leaves out of the whole mesh's reduced force (the elements' bending, or
// hourglass, forces), taken as affine in the reduced coordinates: its value r0 at the origin and
// its derivative H there along each mode, by central differences of step kProbe [m].
struct AffineRemainder {
  fem::Vector r0;
  Eigen::MatrixXd H;
};
AffineRemainder hourglass_remainder(const fem::SolidModel& solid, const fem::Vector& origin,
                                    const Eigen::MatrixXd& modes) {
  constexpr double kProbe = 1e-3;  // the modes are unit vectors: about 30 um at a node
  const Eigen::Index k = modes.cols();
  Eigen::MatrixXd probes = Eigen::MatrixXd::Zero(modes.rows(), 2 * k + 1);
  for (Eigen::Index j = 0; j < k; ++j) {
    probes.col(1 + 2 * j) = kProbe * modes.col(j);
    probes.col(2 + 2 * j) = -kProbe * modes.col(j);
  }
  const fem::Vector left_out = (reduced::element_reduced_forces(solid, origin, modes, probes) -
                                centre_point_reduced_forces(solid, origin, modes, probes))
                                   .rowwise()
                                   .sum();
  AffineRemainder a{left_out.head(k), Eigen::MatrixXd(k, k)};
  for (Eigen::Index j = 0; j < k; ++j)
    a.H.col(j) = (left_out.segment((1 + 2 * j) * k, k) - left_out.segment((2 + 2 * j) * k, k)) /
                 (2.0 * kProbe);
  return a;
}

// || G w + o - t || / || t || with each snapshot's block scaled by its target's norm, as the
// sampling measures it; o an offset (S k values) or none.
double misfit(const Eigen::MatrixXd& g, int k, const fem::Vector& w, const fem::Vector& target,
              const fem::Vector* offset = nullptr) {
  double sum = 0.0, norm = 0.0;
  for (Eigen::Index s = 0; s < g.rows() / k; ++s) {
    const fem::Vector t = target.segment(s * k, k);
    if (!(t.norm() > 0.0)) continue;
    fem::Vector fit = g.middleRows(s * k, k) * w;
    if (offset) fit += offset->segment(s * k, k);
    sum += (fit - t).squaredNorm() / t.squaredNorm();
    norm += 1.0;
  }
  return std::sqrt(sum / norm);
}

void report(const char* kind, const Eigen::MatrixXd& g, int k, double tolerance,
            const fem::Vector& target) {
  const auto started = Clock::now();
  const reduced::ElementSample sample = reduced::sample_elements(g, k, tolerance, target);
  std::printf("%-22s %9.2f %8zu %9.4f %s %7.1f\n", kind, tolerance, sample.elements.size(),
              sample.relative_error, sample.within_tolerance ? "yes" : "no ",
              std::chrono::duration<double>(Clock::now() - started).count());
  std::fflush(stdout);
}

int run(int argc, char** argv) {
  if (argc != 4 && !(argc == 6 && std::string(argv[4]) == "--snapshots")) {
    std::fprintf(stderr, "usage: cubature_benchmark SCENE BASIS SNAPSHOTS [--snapshots N]\n");
    return 2;
  }
  const int wanted = argc == 6 ? std::stoi(argv[5]) : 200;  // as build_reduced_model
  const scene::Scene scene = scene::read_scene(argv[1]);
  const scene::BuiltScene built = scene::build_scene(scene);
  const fem::SolidModel& solid = *built.solid;
  const reduced::ReducedBasis basis = reduced::read_reduced_basis(argv[2]);
  reduced::check_fits(basis, argv[2], solid.mesh(), scene::material_text(scene.material));
  const reduced::SnapshotSet set = reduced::read_snapshots(argv[3]);
  const Eigen::Index stride = (set.snapshots.cols() + wanted - 1) / wanted;
  Eigen::MatrixXd snapshots(set.snapshots.rows(), (set.snapshots.cols() + stride - 1) / stride);
  for (Eigen::Index j = 0; j < snapshots.cols(); ++j)
    snapshots.col(j) = set.snapshots.col(j * stride);
  const int k = static_cast<int>(basis.modes.cols());
  const Eigen::MatrixXd elements =
      reduced::element_reduced_forces(solid, basis.origin, basis.modes, snapshots);
  const Eigen::MatrixXd points =
      centre_point_reduced_forces(solid, basis.origin, basis.modes, snapshots);
  const fem::Vector target = elements.rowwise().sum();
  std::printf("%s: %d modes, %ld snapshots, %d elements\n", argv[1], k,
              static_cast<long>(snapshots.cols()), solid.mesh().num_elements());
  std::printf("one point per element, every weight 1: misfit %.4f\n",
              misfit(points, k, fem::Vector::Ones(points.cols()), target));
  std::printf("%-22s %9s %8s %9s %s %7s\n", "candidates", "tolerance", "sampled", "misfit", "met",
              "time[s]");
  for (const double tolerance : {0.3, 0.2, 0.1, 0.05})
    report("elements (8 points)", elements, k, tolerance, target);
  // Its path is run once: it is searched to its end whenever a tolerance is not met.
  report("one point per element", points, k, 0.1, target);

  // One point per element plus the affine model of what it leaves out, over all elements: the
  // sample then fits what the model does not explain.
  const AffineRemainder hourglass = hourglass_remainder(solid, basis.origin, basis.modes);
  fem::Vector modelled(target.size());
  for (Eigen::Index s = 0; s < snapshots.cols(); ++s)
    modelled.segment(s * k, k) =
        hourglass.r0 + hourglass.H * (basis.modes.transpose() * snapshots.col(s));
  const fem::Vector ones = fem::Vector::Ones(points.cols());
  std::printf("one point per element and the affine remainder, every weight 1: misfit %.4f\n",
              misfit(points, k, ones, target, &modelled));
  std::printf("%-30s %9s %8s %9s\n", "candidates", "tolerance", "sampled", "misfit");
  for (const double tolerance : {0.5, 0.3, 0.2}) {
    const reduced::ElementSample sample =
        reduced::sample_elements(points, k, tolerance, target - modelled);
    fem::Vector w = fem::Vector::Zero(points.cols());
    for (std::size_t j = 0; j < sample.elements.size(); ++j)
      w[sample.elements[j]] = sample.weights[static_cast<Eigen::Index>(j)];
    std::printf("%-30s %9.2f %8zu %9.4f\n", "one point + affine remainder", tolerance,
                sample.elements.size(), misfit(points, k, w, target, &modelled));
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cubature_benchmark: %s\n", e.what());
    return 1;
  }
}
