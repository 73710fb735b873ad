#include "reduced/training_sequences.hpp"

#include <algorithm>
#include <random>
#include <stdexcept>

namespace tongue::reduced {
namespace {

// A number in [0, 1) from the generator's raw 32-bit output: the same on every platform.
double uniform(std::mt19937& g) {
  return (static_cast<double>(g()) + 0.5) / 4294967296.0;
}

struct Builder {
  const std::vector<MuscleGroup>& groups;
  int num_muscles;
  const TrainingOptions& o;
  std::mt19937 random;

  double level() { return o.min_level + (1.0 - o.min_level) * uniform(random); }

  fem::Vector off() const { return fem::Vector::Zero(num_muscles); }
  fem::Vector on(const std::vector<std::pair<int, double>>& group_levels) const {
    fem::Vector v = off();
    for (const auto& [g, a] : group_levels)
      for (int m : groups[g].muscles) v[m] = a;
    return v;
  }

  // Off, up to `levels` over the rise, held, and released over the rise at mid-duration.
  TrainingSequence step(std::string name, const fem::Vector& levels) const {
    const double half = 0.5 * o.duration;
    return {std::move(name),
            {0.0, o.rise, half, half + o.rise},
            {off(), levels, levels, off()},
            o.duration};
  }
  // Up to `levels` over the first half, back down over the second.
  TrainingSequence ramp(std::string name, const fem::Vector& levels) const {
    return {
        std::move(name), {0.0, 0.5 * o.duration, o.duration}, {off(), levels, off()}, o.duration};
  }
};

}  // namespace

fem::Vector TrainingSequence::at(double t) const {
  if (t <= times.front()) return levels.front();
  for (std::size_t k = 1; k < times.size(); ++k)
    if (t <= times[k]) {
      const double s = (t - times[k - 1]) / (times[k] - times[k - 1]);
      return (1.0 - s) * levels[k - 1] + s * levels[k];
    }
  return levels.back();
}

std::vector<MuscleGroup> muscle_groups(const std::vector<std::string>& muscles) {
  std::vector<MuscleGroup> groups;
  for (int m = 0; m < static_cast<int>(muscles.size()); ++m) {
    std::string name = muscles[m];
    for (const std::string side : {"_left", "_right"})
      if (name.size() > side.size() && name.ends_with(side)) name.resize(name.size() - side.size());
    auto g = std::find_if(groups.begin(), groups.end(),
                          [&](const MuscleGroup& x) { return x.name == name; });
    if (g == groups.end()) g = groups.insert(groups.end(), MuscleGroup{name, {}});
    g->muscles.push_back(m);
  }
  return groups;
}

std::vector<TrainingSequence> training_sequences(const std::vector<std::string>& muscles,
                                                 const TrainingOptions& o) {
  if (muscles.empty()) throw std::invalid_argument("training sequences need muscles");
  if (!(o.duration > 0.0) || !(o.rise > 0.0) || !(2.0 * o.rise < o.duration))
    throw std::invalid_argument("training sequences: need 0 < 2 x rise < duration [s]");
  if (!(o.min_level >= 0.0 && o.min_level <= 1.0))
    throw std::invalid_argument("training sequences: min_level must lie in [0, 1]");
  if (o.pairs < 0 || o.mixes < 0)
    throw std::invalid_argument("training sequences: pairs and mixes must be >= 0");
  const std::vector<MuscleGroup> groups = muscle_groups(muscles);
  Builder b{groups, static_cast<int>(muscles.size()), o, std::mt19937(o.seed)};
  const int n = static_cast<int>(groups.size());
  std::vector<TrainingSequence> out;
  for (int g = 0; g < n; ++g) {
    out.push_back(b.step("step " + groups[g].name, b.on({{g, b.level()}})));
    out.push_back(b.ramp("ramp " + groups[g].name, b.on({{g, b.level()}})));
  }
  for (int k = 0; k < o.pairs && n > 1; ++k) {
    const int a = static_cast<int>(uniform(b.random) * n);
    const int c = (a + 1 + static_cast<int>(uniform(b.random) * (n - 1))) % n;  // another group
    out.push_back(b.step("pair " + groups[a].name + "+" + groups[c].name,
                         b.on({{a, b.level()}, {c, b.level()}})));
  }
  for (int k = 0; k < o.mixes; ++k) {
    std::vector<std::pair<int, double>> on;
    for (int g = 0; g < n; ++g) {
      const bool active = uniform(b.random) < 0.5;
      const double a = b.level();
      if (active) on.push_back({g, a});
    }
    out.push_back(b.step("mix " + std::to_string(k + 1), b.on(on)));
  }
  return out;
}

}  // namespace tongue::reduced
