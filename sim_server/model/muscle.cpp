#include "model/muscle.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tongue::model {

namespace {

[[noreturn]] void fail(const Muscle& muscle, const std::string& problem) {
  throw std::invalid_argument("muscle '" + muscle.name + "': " + problem);
}

std::string fibre_label(size_t f) {
  return "fibre " + std::to_string(f);
}

void check_weight(const Muscle& muscle, size_t f) {
  const double w = muscle.fibres[f].weight;
  if (!std::isfinite(w) || w <= 0.0) {
    fail(muscle, fibre_label(f) + " has weight " + std::to_string(w) +
                     "; weights must be finite and positive");
  }
}

}  // namespace

void validate(const Muscle& muscle, int num_nodes, int num_elements,
              const fem::MeshNumbering& numbering) {
  if (muscle.name.empty()) fail(muscle, "the name is empty");
  if (!std::isfinite(muscle.max_force) || muscle.max_force < 0.0) {
    fail(muscle,
         "max_force " + std::to_string(muscle.max_force) + " N must be finite and non-negative");
  }
  for (int e : muscle.elements) {
    if (e < 0 || e >= num_elements) {
      fail(muscle, numbering.element(e) + " is outside 0.." + std::to_string(num_elements - 1));
    }
  }
  if (muscle.fibres.empty()) fail(muscle, "has no fibres");
  double weight_sum = 0.0;
  for (size_t f = 0; f < muscle.fibres.size(); ++f) {
    const Fibre& fibre = muscle.fibres[f];
    const size_t points = fibre.nodes.size() + (fibre.origin ? 1 : 0);
    if (points < 2) {
      fail(muscle, fibre_label(f) + " has " + std::to_string(points) +
                       " point(s) counting its origin; a fibre needs at least 2");
    }
    if (fibre.origin && !fibre.origin->allFinite()) {
      fail(muscle, fibre_label(f) + " has a non-finite origin");
    }
    for (size_t i = 0; i < fibre.nodes.size(); ++i) {
      const int n = fibre.nodes[i];
      if (n < 0 || n >= num_nodes) {
        fail(muscle, fibre_label(f) + ": " + numbering.node(n) + " is outside 0.." +
                         std::to_string(num_nodes - 1));
      }
      if (i > 0 && n == fibre.nodes[i - 1]) {
        fail(muscle, fibre_label(f) + ": " + numbering.node(n) +
                         " repeats consecutively (zero-length segment)");
      }
    }
    check_weight(muscle, f);
    weight_sum += fibre.weight;
  }
  if (std::abs(weight_sum - 1.0) > kWeightSumTolerance) {
    fail(muscle,
         "fibre weights sum to " + std::to_string(weight_sum) + ", not 1 (see normalize_weights)");
  }
}

void normalize_weights(Muscle& muscle) {
  if (muscle.fibres.empty()) fail(muscle, "has no fibres");
  double sum = 0.0;
  for (size_t f = 0; f < muscle.fibres.size(); ++f) {
    check_weight(muscle, f);
    sum += muscle.fibres[f].weight;
  }
  for (Fibre& fibre : muscle.fibres) fibre.weight /= sum;
}

std::vector<std::pair<int, int>> fibre_node_pairs(const std::vector<Muscle>& muscles) {
  std::vector<std::pair<int, int>> pairs;
  for (const Muscle& muscle : muscles) {
    for (const Fibre& fibre : muscle.fibres) {
      for (size_t i = 1; i < fibre.nodes.size(); ++i) {
        const int a = fibre.nodes[i - 1], b = fibre.nodes[i];
        pairs.emplace_back(std::min(a, b), std::max(a, b));
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace tongue::model
