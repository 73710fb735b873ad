// The factory: defaults, parameter tables, and errors that name the offending key.
#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "material_test_support.hpp"

namespace tongue::fem::testing {
namespace {

// The message of the std::invalid_argument thrown by make_material, or "" if none.
std::string error_of(const std::string& type, const std::map<std::string, double>& p) {
  try {
    make_material(type, p);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

double bulk_from_poisson(double mu, double nu) {
  return 2.0 * mu * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu));
}

TEST(MaterialFactory, MooneyRivlin5Defaults) {
  const auto m = make_material("mooney_rivlin5", {});
  ASSERT_NE(m->as_uncoupled(), nullptr);
  EXPECT_EQ(m->name(), "mooney_rivlin5");
  const double mu0 = 2.0 * (4367.0 - 1908.0);
  EXPECT_DOUBLE_EQ(m->initial_shear_modulus(), mu0);
  EXPECT_DOUBLE_EQ(m->bulk_modulus(), bulk_from_poisson(mu0, 0.49));
  EXPECT_NEAR(m->bulk_modulus(), 244.3e3, 0.05e3);  // docs/physics.md
  const auto& c = dynamic_cast<const MooneyRivlin5&>(*m).coefficients();
  EXPECT_EQ(c.c10, 4367.0);
  EXPECT_EQ(c.c01, -1908.0);
  EXPECT_EQ(c.c20, 2077.0);
  EXPECT_EQ(c.c11, -1851.0);
  EXPECT_EQ(c.c02, 530.0);
  // The default constructor is the same law.
  EXPECT_DOUBLE_EQ(MooneyRivlin5().bulk_modulus(), m->bulk_modulus());
}

TEST(MaterialFactory, OtherDefaults) {
  const auto e = make_material("exponential", {});
  EXPECT_DOUBLE_EQ(e->initial_shear_modulus(), 5000.0);
  EXPECT_DOUBLE_EQ(e->bulk_modulus(), bulk_from_poisson(5000.0, 0.49));
  EXPECT_EQ(dynamic_cast<const Exponential&>(*e).b(), 0.2526);

  const auto lin = make_material("linear", {});
  EXPECT_EQ(lin->as_uncoupled(), nullptr);
  EXPECT_DOUBLE_EQ(lin->initial_shear_modulus(), 15e3 / (2.0 * 1.49));
  EXPECT_DOUBLE_EQ(lin->bulk_modulus(), 15e3 / (3.0 * (1.0 - 2.0 * 0.49)));
}

TEST(MaterialFactory, ParametersPassThrough) {
  const auto m = make_material("mooney_rivlin5", {{"c10", 1000.0},
                                                  {"c01", 200.0},
                                                  {"c20", 0.0},
                                                  {"c11", 0.0},
                                                  {"c02", 0.0},
                                                  {"bulk_modulus", 1e6}});
  EXPECT_DOUBLE_EQ(m->initial_shear_modulus(), 2400.0);
  EXPECT_DOUBLE_EQ(m->bulk_modulus(), 1e6);

  const auto nh = make_material("neo_hookean", {{"shear_modulus", 2e3}, {"poisson_ratio", 0.3}});
  EXPECT_DOUBLE_EQ(nh->bulk_modulus(), bulk_from_poisson(2e3, 0.3));

  const auto lin = make_material("linear", {{"shear_modulus", 1e3}, {"bulk_modulus", 5e3}});
  EXPECT_DOUBLE_EQ(lin->initial_shear_modulus(), 1e3);
  EXPECT_DOUBLE_EQ(lin->bulk_modulus(), 5e3);
}

TEST(MaterialFactory, UnknownParameterNamesTheKey) {
  EXPECT_EQ(error_of("neo_hookean", {{"shear_modulus", 1e3}, {"mu2", 1.0}}),
            "material 'neo_hookean': unknown parameter 'mu2' (known: shear_modulus, "
            "bulk_modulus, poisson_ratio)");
  // Density belongs to the scene, not to the material.
  EXPECT_NE(error_of("mooney_rivlin5", {{"density", 1000.0}}).find("'density'"), std::string::npos);
}

TEST(MaterialFactory, BulkModulusAndPoissonRatioAreExclusive) {
  for (const auto& type : {"mooney_rivlin5", "exponential", "neo_hookean"}) {
    std::map<std::string, double> p{{"bulk_modulus", 1e5}, {"poisson_ratio", 0.45}};
    if (std::string(type) == "neo_hookean") p["shear_modulus"] = 1e3;
    const std::string msg = error_of(type, p);
    EXPECT_NE(msg.find("'bulk_modulus'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'poisson_ratio'"), std::string::npos) << msg;
  }
  const std::string msg = error_of("linear", {{"shear_modulus", 1e3}, {"youngs_modulus", 3e3}});
  EXPECT_NE(msg.find("'youngs_modulus'"), std::string::npos) << msg;
}

TEST(MaterialFactory, OutOfRangeNamesTheKey) {
  for (const auto& type : material_types()) {
    for (double nu : {0.5, 0.6, -1.0, std::nan("")}) {
      std::map<std::string, double> p{{"poisson_ratio", nu}};
      if (type == "neo_hookean") p["shear_modulus"] = 1e3;
      const std::string msg = error_of(type, p);
      EXPECT_NE(msg.find("'poisson_ratio'"), std::string::npos) << type << " nu=" << nu;
      EXPECT_NE(msg.find("out of range"), std::string::npos) << msg;
    }
  }
  EXPECT_EQ(error_of("neo_hookean", {{"shear_modulus", -5.0}}),
            "material 'neo_hookean': parameter 'shear_modulus' = -5 Pa out of range (0, inf)");
  EXPECT_NE(error_of("exponential", {{"b", 0.0}}).find("'b'"), std::string::npos);
  EXPECT_NE(error_of("mooney_rivlin5", {{"bulk_modulus", 0.0}}).find("'bulk_modulus'"),
            std::string::npos);
}

TEST(MaterialFactory, MissingOrInconsistentParameters) {
  const std::string msg = error_of("neo_hookean", {});
  EXPECT_NE(msg.find("'shear_modulus'"), std::string::npos) << msg;
  EXPECT_NE(error_of("linear", {{"shear_modulus", 1e3}}).find("'bulk_modulus'"), std::string::npos);
  // Unstable at rest: mu0 = 2 (c10 + c01) <= 0.
  EXPECT_NE(error_of("mooney_rivlin5", {{"c10", 1000.0},
                                        {"c01", -1000.0},
                                        {"c20", 0.0},
                                        {"c11", 0.0},
                                        {"c02", 0.0}})
                .find("'c10'"),
            std::string::npos);
}

// Some of the five coefficients given: the others would silently be Gerard et al.'s (c01 =
// -1908 Pa with c10 = 2459 Pa gave a far softer material that did not converge).
TEST(MaterialFactory, MooneyRivlinCoefficientsComeAllFiveOrNone) {
  EXPECT_EQ(error_of("mooney_rivlin5", {{"c10", 2459.0}, {"bulk_modulus", 244267.0}}),
            "material 'mooney_rivlin5': give all five coefficients c10, c01, c20, c11, c02 or "
            "none (Gerard et al. 2003's set); c10 given without c01, c20, c11, c02");
  EXPECT_NO_THROW(make_material("mooney_rivlin5", {{"bulk_modulus", 244267.0}}));
}

TEST(MaterialFactory, UnknownTypeListsKnownTypes) {
  const std::string expected =
      "unknown material type 'ogden' (known: mooney_rivlin5, exponential, neo_hookean, linear)";
  EXPECT_EQ(error_of("ogden", {}), expected);
  try {
    material_parameters("ogden");
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), expected);
  }
}

TEST(MaterialFactory, ParameterTablesAreConsistent) {
  for (const auto& type : material_types()) {
    const auto& specs = material_parameters(type);
    EXPECT_FALSE(specs.empty());
    for (const auto& s : specs) {
      EXPECT_FALSE(s.name.empty());
      EXPECT_FALSE(s.unit.empty()) << s.name;
      EXPECT_FALSE(s.help.empty()) << s.name;
      EXPECT_LT(s.min, s.max) << s.name;
      if (s.has_default()) {
        EXPECT_TRUE(s.in_range(s.default_value)) << type << "." << s.name;
      }
    }
    // Every type builds from its table's defaults (plus the one required neo-Hookean modulus).
    std::map<std::string, double> p;
    if (type == "neo_hookean") p["shear_modulus"] = 1e3;
    EXPECT_EQ(make_material(type, p)->name(), type);
  }
}

TEST(MaterialFactory, BulkModulusFromPoissonValidates) {
  EXPECT_DOUBLE_EQ(bulk_modulus_from_poisson(1.0, 0.25), bulk_from_poisson(1.0, 0.25));
  EXPECT_THROW(bulk_modulus_from_poisson(1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(bulk_modulus_from_poisson(0.0, 0.3), std::invalid_argument);
}

}  // namespace
}  // namespace tongue::fem::testing
