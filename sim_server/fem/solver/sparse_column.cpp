#include "fem/solver/sparse_column.hpp"

#include <algorithm>

namespace tongue::fem {

namespace {
using ConstSegment = Eigen::Map<const Eigen::VectorXd>;
}  // namespace

void SparseColumn::append(int row, double value) {
  if (value == 0.0) return;
  if (!runs.empty() && runs.back().row + runs.back().length == row)
    ++runs.back().length;
  else
    runs.push_back({row, 1});
  values.push_back(value);
}

double SparseColumn::dot(const Vector& y) const {
  double sum = 0.0;
  const double* v = values.data();
  for (const Run& r : runs) {
    sum += ConstSegment(v, r.length).dot(y.segment(r.row, r.length));
    v += r.length;
  }
  return sum;
}

void SparseColumn::subtract_from(double a, Vector& y) const {
  const double* v = values.data();
  for (const Run& r : runs) {
    y.segment(r.row, r.length) -= a * ConstSegment(v, r.length);
    v += r.length;
  }
}

double dot(const SparseColumn& a, const SparseColumn& b) {
  double sum = 0.0;
  auto i = a.runs.begin(), j = b.runs.begin();
  const double *va = a.values.data(), *vb = b.values.data();
  while (i != a.runs.end() && j != b.runs.end()) {
    const int start = std::max(i->row, j->row);
    const int end_a = i->row + i->length, end_b = j->row + j->length;
    const int end = std::min(end_a, end_b);
    if (start < end)
      sum += ConstSegment(va + (start - i->row), end - start)
                 .dot(ConstSegment(vb + (start - j->row), end - start));
    // The run that ends first cannot meet another of the other column's runs.
    if (end_a <= end_b) {
      va += i->length;
      ++i;
    } else {
      vb += j->length;
      ++j;
    }
  }
  return sum;
}

}  // namespace tongue::fem
