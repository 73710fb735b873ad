// Cost of the strong-ellipticity direction search (fem::check_ellipticity) that the stability
// check runs on strained elements (docs/stability.md): mooney_rivlin5 with Gerard et al.'s
// constants (the factory defaults, Poisson's ratio 0.49) under an isochoric uniaxial stretch of
// 1.3 (elliptic), a simple shear of 0.6 (elliptic) and a stretch of 1.7 (not elliptic). Prints per
// deformation the median over the repeats of the time a search takes and what it found.
//
// Usage: ellipticity_benchmark [--searches N] [--repeats K]   (defaults 2000 and 5)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "fem/material/ellipticity.hpp"
#include "fem/material/material_factory.hpp"

namespace {

using tongue::fem::Mat3;
using tongue::fem::Vec3;

Mat3 uniaxial(double stretch) {
  return Vec3(stretch, 1.0 / std::sqrt(stretch), 1.0 / std::sqrt(stretch)).asDiagonal();
}

Mat3 simple_shear(double gamma) {
  Mat3 F = Mat3::Identity();
  F(0, 1) = gamma;
  return F;
}

}  // namespace

int main(int argc, char** argv) {
  int searches = 2000, repeats = 5;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    std::size_t used = 0;
    int value = 0;
    if ((arg == "--searches" || arg == "--repeats") && i + 1 < argc) {
      try {
        value = std::stoi(argv[++i], &used);
      } catch (const std::exception&) {
        used = 0;
      }
    }
    if (used == 0 || argv[i][used] != '\0' || value < 1) {
      std::fprintf(stderr,
                   "usage: ellipticity_benchmark [--searches N] [--repeats K] (N, K >= 1)\n");
      return 2;
    }
    (arg == "--searches" ? searches : repeats) = value;
  }
  const auto material = tongue::fem::make_material("mooney_rivlin5", {{"poisson_ratio", 0.49}});
  const struct {
    const char* name;
    Mat3 F;
  } cases[] = {{"uniaxial stretch 1.3", uniaxial(1.3)},
               {"simple shear 0.6", simple_shear(0.6)},
               {"uniaxial stretch 1.7", uniaxial(1.7)}};
  std::printf("mooney_rivlin5 (Gerard et al. 2003, nu 0.49): %d searches, median of %d repeats\n",
              searches, repeats);
  for (const auto& c : cases) {
    std::vector<double> us;
    for (int r = 0; r < repeats; ++r) {
      const auto start = std::chrono::steady_clock::now();
      for (int s = 0; s < searches; ++s) tongue::fem::check_ellipticity(*material, c.F);
      us.push_back(
          std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
              .count() /
          searches);
    }
    std::sort(us.begin(), us.end());
    const tongue::fem::EllipticityCheck found = tongue::fem::check_ellipticity(*material, c.F);
    std::printf("%-22s %7.2f us a search; smallest eigenvalue %.6g Pa (%s)\n", c.name,
                us[us.size() / 2], found.min_eigenvalue,
                found.elliptic() ? "elliptic" : "not elliptic");
  }
  return 0;
}
