#pragma once
// A hyperelastic material is its strain-energy density W(F) per unit reference volume.
// Every material returns W, the first Piola-Kirchhoff stress P = dW/dF and the consistent
// tangent A = d2W/dF dF, so that the element needs nothing else (Holzapfel 2000, sec. 6.1).
#include <memory>
#include <string>

#include "fem/types.hpp"

namespace tongue::fem {

struct PointResponse {
  double energy = 0.0;  // W [Pa = J/m^3]
  Mat3 stress;          // P = dW/dF [Pa]
  Mat9 tangent;         // A_{iJkL} = d2W / dF_iJ dF_kL [Pa], symmetric
};

// U(J) and its first two derivatives.
struct VolumetricResponse {
  double energy = 0.0;  // U [Pa]
  double first = 0.0;   // dU/dJ [Pa]; the pressure is -dU/dJ
  double second = 0.0;  // d2U/dJ2 [Pa]
};

class UncoupledMaterial;

class Material {
 public:
  virtual ~Material() = default;
  virtual std::string name() const = 0;
  // The full response at deformation gradient F (det F > 0). Without the tangent (a residual
  // evaluation) `tangent` is left unset, which saves most of the work.
  virtual PointResponse response(const Mat3& F, bool with_tangent = true) const = 0;
  // Non-null when W splits into W_iso(C_bar) + U(J): such materials can use mean dilatation.
  virtual const UncoupledMaterial* as_uncoupled() const { return nullptr; }
  // Small-strain shear and bulk moduli at the rest state [Pa], for wave speeds and checks.
  virtual double initial_shear_modulus() const = 0;
  virtual double bulk_modulus() const = 0;
};

// Derivatives of W_iso with respect to the isochoric invariants I1_bar, I2_bar of
// C_bar = J^{-2/3} C (Holzapfel 2000, sec. 6.4).
struct InvariantDerivatives {
  double energy = 0.0;
  double d1 = 0.0, d2 = 0.0;               // dW/dI1b, dW/dI2b
  double d11 = 0.0, d12 = 0.0, d22 = 0.0;  // second derivatives
};

// W(F) = W_iso(I1_bar, I2_bar) + U(J) with U(J) = K/2 (J - 1)^2.
// Concrete materials supply only W_iso's invariant derivatives; this class turns them into
// P and A with one shared kernel, so every uncoupled material is verified by the same tests.
class UncoupledMaterial : public Material {
 public:
  explicit UncoupledMaterial(double bulk_modulus);

  virtual InvariantDerivatives isochoric_derivatives(double I1_bar, double I2_bar) const = 0;
  // W_iso, dW/dI1b and dW/dI2b at n points at once, for the residual kernel (it needs no second
  // derivatives); every pointer holds n values. The default calls isochoric_derivatives point by
  // point; a law overrides it when a loop over its formula is cheaper than n virtual calls.
  virtual void isochoric_first_derivatives(int n, const double* I1_bar, const double* I2_bar,
                                           double* energy, double* d1, double* d2) const;
  // The same with the second derivatives d2W/dI1b2, d2W/dI1b dI2b, d2W/dI2b2, for the tangent
  // kernel; every pointer holds n values. The default calls isochoric_derivatives point by point.
  virtual void isochoric_second_derivatives(int n, const double* I1_bar, const double* I2_bar,
                                            double* energy, double* d1, double* d2, double* d11,
                                            double* d12, double* d22) const;

  PointResponse response(const Mat3& F, bool with_tangent = true) const override;
  const UncoupledMaterial* as_uncoupled() const override { return this; }
  double bulk_modulus() const override { return bulk_modulus_; }

  // The isochoric part alone: W_iso, dW_iso/dF, d2W_iso/dF2.
  PointResponse isochoric_response(const Mat3& F, bool with_tangent = true) const;
  // U(J) = K/2 (J - 1)^2 and its derivatives.
  VolumetricResponse volumetric(double J) const;

 private:
  double bulk_modulus_;
};

// The small-strain Poisson's ratio of every material whose K is not given: nearly
// incompressible tissue, the paper's value (Gerard et al. 2003 sec. III.2).
inline constexpr double kDefaultPoissonRatio = 0.49;

// K from the small-strain shear modulus and Poisson's ratio: K = 2 mu (1 + nu) / (3 (1 - 2 nu)).
double bulk_modulus_from_poisson(double shear_modulus, double poisson_ratio);

}  // namespace tongue::fem
