"""Feldman's lambda model of muscle force, as the C++ controller has it
(controllers/ep_controller/lambda_model.hpp, which gives the equations and their sources):

    A = [l(t - d) - lambda(t) + mu l'(t - d)]^+          mm, mu = 0.01 s
    M = rho (exp(c A) - 1)                               c = 0.112 / mm
    M' = M max(0, f1 + f2 atan(f3 + f4 l'/l0) + f5 l'/l0)
    level = min(M' / F_max, 1)
"""
import math

C_PER_MM = 0.112  # 1/mm
MU_S = 0.01  # s
F1, F2, F3 = 0.80, 0.5, 0.43
F4 = 0.8 / 1.5  # s
F5 = 0.023 / 0.7  # s


class MuscleLaw:
    def __init__(self, rho_n, max_force_n):
        self.rho_n = rho_n
        self.max_force_n = max_force_n
        self.rest_length_mm = 0.0  # l0, for the velocity factor


def velocity_factor(relative_velocity_per_s):
    r = relative_velocity_per_s
    return max(0.0, F1 + F2 * math.atan(F3 + F4 * r) + F5 * r)


def muscle_level(law, lambda_mm, length_mm, velocity_mm_s, use_velocity_factor):
    """The level [0, 1] the law gives one muscle; lengths in mm, velocity in mm/s."""
    stretch_mm = max(0.0, length_mm - lambda_mm + MU_S * velocity_mm_s)
    force_n = law.rho_n * math.expm1(C_PER_MM * stretch_mm)  # expm1: small forces exact
    if use_velocity_factor:
        force_n *= velocity_factor(velocity_mm_s / law.rest_length_mm)
    return min(max(force_n / law.max_force_n, 0.0), 1.0)
