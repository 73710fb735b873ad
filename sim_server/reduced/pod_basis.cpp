#include "reduced/pod_basis.hpp"

#include <Eigen/SVD>
#include <stdexcept>

namespace tongue::reduced {

int modes_for(const fem::Vector& singular_values, double energy_fraction) {
  const double goal = energy_fraction * singular_values.squaredNorm();
  double sum = 0.0;
  int k = 0;
  while (k < singular_values.size() && sum < goal)
    sum += singular_values[k] * singular_values[k], ++k;
  return k;
}

PodBasis pod_basis(const Eigen::MatrixXd& snapshots, double energy_fraction) {
  if (snapshots.size() == 0) throw std::invalid_argument("POD: no snapshots");
  if (!(energy_fraction > 0.0 && energy_fraction <= 1.0))
    throw std::invalid_argument("POD: the energy fraction must lie in (0, 1]");
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(snapshots, Eigen::ComputeThinU);
  PodBasis b;
  b.singular_values = svd.singularValues();
  const double total = b.singular_values.squaredNorm();
  if (!(total > 0.0)) throw std::invalid_argument("POD: every snapshot is zero");
  const int k = modes_for(b.singular_values, energy_fraction);
  b.modes = svd.matrixU().leftCols(k);
  b.captured = b.singular_values.head(k).squaredNorm() / total;
  return b;
}

}  // namespace tongue::reduced
