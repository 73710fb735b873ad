#include "reduced/element_sampling.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vigra/matrix.hxx>
#include <vigra/regression.hxx>

namespace tongue::reduced {

ElementSample sample_elements(const Eigen::MatrixXd& g, int k, double tolerance) {
  return sample_elements(g, k, tolerance, g.rowwise().sum());
}

ElementSample sample_elements(const Eigen::MatrixXd& g, int k, double tolerance,
                              const fem::Vector& goal) {
  if (k <= 0 || g.rows() == 0 || g.rows() % k != 0)
    throw std::invalid_argument("element sampling: " + std::to_string(g.rows()) +
                                " rows are not a whole number of snapshots of " +
                                std::to_string(k) + " modes");
  if (g.cols() == 0) throw std::invalid_argument("element sampling: no element");
  if (!(tolerance > 0.0 && tolerance < 1.0))
    throw std::invalid_argument("element sampling: the tolerance must lie in (0, 1)");
  if (goal.size() != g.rows())
    throw std::invalid_argument("element sampling: the target has " + std::to_string(goal.size()) +
                                " values for " + std::to_string(g.rows()) + " rows");
  const Eigen::Index E = g.cols(), S = g.rows() / k;
  // [G t], each snapshot's rows scaled by the norm of its target.
  Eigen::MatrixXd scaled(g.rows(), E + 1);
  for (Eigen::Index s = 0; s < S; ++s) {
    const double norm = goal.segment(s * k, k).norm();
    // A snapshot without force has nothing to reproduce and drops out.
    const double scale = norm > 0.0 ? 1.0 / norm : 0.0;
    scaled.block(s * k, 0, k, E) = scale * g.middleRows(s * k, k);
    scaled.block(s * k, E, k, 1) = scale * goal.segment(s * k, k);
  }
  // With [G t] = Q R, || G w - t || = || R_G w - R_t ||: the path is found on R's at most E + 1
  // rows instead of G's S k (the correlations G^T r = R^T Q^T r and the columns' norms are the
  // same), with the same result.
  Eigen::MatrixXd r;
  if (scaled.rows() > E + 1) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(scaled);
    r = qr.matrixQR().topRows(E + 1).triangularView<Eigen::Upper>();
  } else {
    r = scaled;
  }
  const Eigen::Index rows = r.rows();
  const Eigen::VectorXd target = r.col(E);
  r.conservativeResize(Eigen::NoChange, E);
  const double target_norm = target.norm();
  if (!(target_norm > 0.0))
    throw std::invalid_argument("element sampling: every snapshot's force is 0");
  vigra::linalg::Matrix<double> a(rows, E), b(rows, 1);
  for (Eigen::Index i = 0; i < rows; ++i) {
    for (Eigen::Index e = 0; e < E; ++e) a(i, e) = r(i, e);
    b(i, 0) = target[i];
  }

  vigra::ArrayVector<vigra::ArrayVector<vigra::MultiArrayIndex>> active;
  vigra::ArrayVector<vigra::linalg::Matrix<double>> lasso;
  // The LASSO weights alone: asking VIGRA for the least-squares ones too runs a path of its own
  // for each point (60 times slower on the tongue); they are solved here instead.
  const unsigned points = vigra::linalg::leastAngleRegression(
      a, b, active, lasso,
      vigra::linalg::LeastAngleRegressionOptions().nnlasso().leastSquaresSolutions(false));
  ElementSample best;
  best.relative_error = 1.0;  // w = 0
  for (unsigned p = 0; p < points; ++p) {
    // On each active set the least-squares weights fit best; the LASSO's, shrunk towards 0,
    // stand in when those are not all positive.
    const auto& set = active[p];
    const Eigen::Index m = static_cast<Eigen::Index>(set.size());
    Eigen::MatrixXd columns(rows, m);
    for (Eigen::Index j = 0; j < m; ++j) columns.col(j) = r.col(set[static_cast<unsigned>(j)]);
    Eigen::VectorXd w = columns.colPivHouseholderQr().solve(target);
    if (!(w.array() > 0.0).all())
      for (Eigen::Index j = 0; j < m; ++j) w[j] = lasso[p](j, 0);
    const double error = (columns * w - target).norm() / target_norm;
    if (error >= best.relative_error && p + 1 < points) continue;
    if (error < best.relative_error) {
      best.elements.assign(set.begin(), set.end());
      best.weights = w;
      best.relative_error = error;
    }
    if (error <= tolerance) {
      best.within_tolerance = true;
      break;
    }
  }
  // Zero weights (the LASSO's at a knot where an element leaves) are no sample; then ascending.
  std::vector<std::pair<int, double>> kept;
  for (std::size_t j = 0; j < best.elements.size(); ++j)
    if (best.weights[static_cast<Eigen::Index>(j)] > 0.0)
      kept.emplace_back(best.elements[j], best.weights[static_cast<Eigen::Index>(j)]);
  std::sort(kept.begin(), kept.end());
  best.elements.clear();
  best.weights.resize(static_cast<Eigen::Index>(kept.size()));
  for (std::size_t j = 0; j < kept.size(); ++j) {
    best.elements.push_back(kept[j].first);
    best.weights[static_cast<Eigen::Index>(j)] = kept[j].second;
  }
  return best;
}

}  // namespace tongue::reduced
