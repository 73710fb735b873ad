#include "fem/material/material_factory.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "fem/material/exponential.hpp"
#include "fem/material/linear_elastic.hpp"
#include "fem/material/mooney_rivlin5.hpp"
#include "fem/material/neo_hookean.hpp"

namespace tongue::fem {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

// Shortest round-trip text of a double, so messages show exactly what was given.
std::string format(double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

ParameterSpec bulk_modulus_spec() {
  return {"bulk_modulus", "Pa",
          kNone,          0.0,
          kInf,           "K of U(J) = K/2 (J-1)^2; default: from poisson_ratio and mu0"};
}
ParameterSpec poisson_ratio_spec(double default_value) {
  return {"poisson_ratio",
          "1",
          default_value,
          -1.0,
          0.5,
          "small-strain Poisson's ratio; sets K = 2 mu0 (1+nu) / (3 (1-2nu))"};
}

const std::map<std::string, std::vector<ParameterSpec>>& tables() {
  static const std::map<std::string, std::vector<ParameterSpec>> t = [] {
    const MooneyRivlin5::Coefficients mr;
    std::map<std::string, std::vector<ParameterSpec>> m;
    m["mooney_rivlin5"] = {
        {"c10", "Pa", mr.c10, -kInf, kInf, "coefficient of (I1b-3)"},
        {"c01", "Pa", mr.c01, -kInf, kInf, "coefficient of (I2b-3); mu0 = 2 (c10 + c01) > 0"},
        {"c20", "Pa", mr.c20, -kInf, kInf, "coefficient of (I1b-3)^2"},
        {"c11", "Pa", mr.c11, -kInf, kInf, "coefficient of (I1b-3)(I2b-3)"},
        {"c02", "Pa", mr.c02, -kInf, kInf, "coefficient of (I2b-3)^2"},
        bulk_modulus_spec(),
        poisson_ratio_spec(kDefaultPoissonRatio),
    };
    m["exponential"] = {
        {"a", "Pa", Exponential::kDefaultA, 0.0, kInf, "stiffness; mu0 = 2 a"},
        {"b", "1", Exponential::kDefaultB, 0.0, kInf, "exponential stiffening rate"},
        bulk_modulus_spec(),
        poisson_ratio_spec(kDefaultPoissonRatio),
    };
    m["neo_hookean"] = {
        {"shear_modulus", "Pa", kNone, 0.0, kInf, "mu (required)"},
        bulk_modulus_spec(),
        poisson_ratio_spec(kDefaultPoissonRatio),
    };
    m["linear"] = {
        // E of the tongue at rest, about 15 kPa (Gerard et al. 2003 sec. III.2).
        {"youngs_modulus", "Pa", 15e3, 0.0, kInf, "E; give with poisson_ratio"},
        {"poisson_ratio", "1", kDefaultPoissonRatio, -1.0, 0.5, "nu; give with youngs_modulus"},
        {"shear_modulus", "Pa", kNone, 0.0, kInf, "mu; instead of E and nu, give with K"},
        {"bulk_modulus", "Pa", kNone, 0.0, kInf, "K; instead of E and nu, give with mu"},
    };
    return m;
  }();
  return t;
}

std::string join_names(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// The given parameters, checked against the table, with defaults filled in.
class Params {
 public:
  Params(const std::string& type, const std::map<std::string, double>& given)
      : type_(type), given_(given), specs_(material_parameters(type)) {
    for (const auto& [key, value] : given) {
      const ParameterSpec* spec = find(key);
      if (!spec) {
        std::vector<std::string> known;
        for (const auto& s : specs_) known.push_back(s.name);
        fail("unknown parameter '" + key + "' (known: " + join_names(known) + ")");
      }
      if (!spec->in_range(value))
        fail("parameter '" + key + "' = " + format(value) + " " + spec->unit + " out of range (" +
             format(spec->min) + ", " + format(spec->max) + ")");
    }
  }

  bool given(const std::string& key) const { return given_.count(key) != 0; }

  // The given value, else the default; fails if there is neither.
  double get(const std::string& key) const {
    if (const auto it = given_.find(key); it != given_.end()) return it->second;
    const ParameterSpec* spec = find(key);
    if (!spec || !spec->has_default()) fail("missing required parameter '" + key + "'");
    return spec->default_value;
  }

  void exclusive(const std::string& a, const std::string& b) const {
    if (given(a) && given(b)) fail("give either '" + a + "' or '" + b + "', not both");
  }

  // K given directly or from nu and mu0.
  double bulk_modulus(double mu0) const {
    exclusive("bulk_modulus", "poisson_ratio");
    if (given("bulk_modulus")) return get("bulk_modulus");
    if (!(mu0 > 0.0)) fail("initial shear modulus mu0 = " + format(mu0) + " Pa must be positive");
    return bulk_modulus_from_poisson(mu0, get("poisson_ratio"));
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument("material '" + type_ + "': " + what);
  }

 private:
  const ParameterSpec* find(const std::string& key) const {
    for (const auto& s : specs_)
      if (s.name == key) return &s;
    return nullptr;
  }

  std::string type_;
  const std::map<std::string, double>& given_;
  const std::vector<ParameterSpec>& specs_;
};

std::unique_ptr<Material> make_linear(const Params& p) {
  const bool moduli = p.given("shear_modulus") || p.given("bulk_modulus");
  if (!moduli)
    return std::make_unique<LinearElastic>(
        LinearElastic::from_youngs_modulus(p.get("youngs_modulus"), p.get("poisson_ratio")));
  p.exclusive("shear_modulus", "youngs_modulus");
  p.exclusive("shear_modulus", "poisson_ratio");
  p.exclusive("bulk_modulus", "youngs_modulus");
  p.exclusive("bulk_modulus", "poisson_ratio");
  return std::make_unique<LinearElastic>(p.get("shear_modulus"), p.get("bulk_modulus"));
}

}  // namespace

std::vector<std::string> material_types() {
  return {"mooney_rivlin5", "exponential", "neo_hookean", "linear"};
}

const std::vector<ParameterSpec>& material_parameters(const std::string& type) {
  const auto it = tables().find(type);
  if (it == tables().end())
    throw std::invalid_argument("unknown material type '" + type +
                                "' (known: " + join_names(material_types()) + ")");
  return it->second;
}

std::unique_ptr<Material> make_material(const std::string& type,
                                        const std::map<std::string, double>& params) {
  const Params p(type, params);
  if (type == "mooney_rivlin5") {
    // The coefficients make one law together: some of them given with the others taken from
    // Gerard et al.'s set is a different (and mostly unstable) material, never what was meant.
    std::vector<std::string> given, missing;
    for (const char* key : {"c10", "c01", "c20", "c11", "c02"})
      (p.given(key) ? given : missing).push_back(key);
    if (!given.empty() && !missing.empty())
      p.fail("give all five coefficients c10, c01, c20, c11, c02 or none (Gerard et al. 2003's "
             "set); " + join_names(given) + " given without " + join_names(missing));
    MooneyRivlin5::Coefficients c;
    c.c10 = p.get("c10");
    c.c01 = p.get("c01");
    c.c20 = p.get("c20");
    c.c11 = p.get("c11");
    c.c02 = p.get("c02");
    const double mu0 = MooneyRivlin5::initial_shear_modulus(c);
    if (!(mu0 > 0.0))
      p.fail("parameters 'c10' + 'c01' give mu0 = 2 (c10 + c01) = " + format(mu0) +
             " Pa; it must be positive");
    return std::make_unique<MooneyRivlin5>(c, p.bulk_modulus(mu0));
  }
  if (type == "exponential") {
    const double a = p.get("a");
    return std::make_unique<Exponential>(a, p.get("b"), p.bulk_modulus(2.0 * a));
  }
  if (type == "neo_hookean") {
    const double mu = p.get("shear_modulus");
    return std::make_unique<NeoHookean>(mu, p.bulk_modulus(mu));
  }
  if (type == "linear") return make_linear(p);
  p.fail("no constructor");  // unreachable: Params rejected unknown types
}

}  // namespace tongue::fem
