"""The equilibrium-point controller: every muscle driven by the lambda model in closed loop on
the lengths and velocities the server publishes, lambda = rest length + the plan's Delta-lambda,
the feedback seen through the reflex delay, the levels through the force lag
(controllers/ep_controller/ep_controller.hpp says why each part is as it is)."""
import math

import tongue

from tongue_controllers.delay_buffer import DelayBuffer
from tongue_controllers.force_lag import ForceLag
from tongue_controllers.lambda_model import MuscleLaw, muscle_level
from tongue_controllers.motor_plan import MotorPlan, no_muscle
from tongue_controllers.muscle_rho import muscle_rhos
from tongue_controllers.program import InputError

MM_PER_M = 1000.0


class EpController:
    def __init__(self, plan_spec, delay_s=0.012, velocity_factor=True, force_lag_s=0.1):
        self.spec = plan_spec
        self.delay_s, self.velocity_factor, self.force_lag_s = delay_s, velocity_factor, force_lag_s
        self.names, self.laws = [], []
        self.have_rest_lengths = False
        self.peak = None  # (level, muscle, step)

    def start(self, model):
        if not (model.dt > 0.0 and math.isfinite(model.dt)):
            raise ValueError(f"the model's dt is {model.dt:g} s, not > 0")
        self.dt = model.dt
        self.names = list(model.muscle_names)
        self.plan = MotorPlan(self.spec, self.names)
        for name, path, _ in self.spec.rho:
            if not tongue.select_muscles(name, self.names):
                raise no_muscle(self.spec.source, path, name, self.names)
        max_forces = list(model.max_forces)
        try:
            rho = muscle_rhos(self.names, max_forces,
                              [(name, r) for name, _, r in self.spec.rho])
        except ValueError as error:
            raise InputError(self.spec.source, "rho", str(error)) from None
        self.laws = [MuscleLaw(r, f) for r, f in zip(rho, max_forces)]
        self.history = DelayBuffer(max(1.0, self.delay_s / self.dt))
        self.lag = ForceLag(len(self.names), self.force_lag_s, self.dt)

    def last_step(self):
        return None

    def observe(self, state):
        lengths, velocities = list(state.muscle_lengths), list(state.muscle_velocities)
        for name, l, v in zip(self.names, lengths, velocities):
            if not (math.isfinite(l) and l > 0.0 and math.isfinite(v)):
                raise ValueError(f"the state of step {state.step} gives {name} length {l:g} m, "
                                 f"velocity {v:g} m/s: not usable feedback")
        if not self.have_rest_lengths:
            for law, l in zip(self.laws, lengths):
                law.rest_length_mm = l * MM_PER_M
            self.have_rest_lengths = True
        self.history.push(state.step, lengths, velocities)

    def command(self, step):
        lengths, velocities = self.history.for_step(step)
        t = float(step) * self.dt
        law_levels = [
            muscle_level(law, law.rest_length_mm + self.plan.delta_lambda_mm(m, t),
                         lengths[m] * MM_PER_M, velocities[m] * MM_PER_M, self.velocity_factor)
            for m, law in enumerate(self.laws)]
        levels = self.lag.update(step, law_levels)
        for name, level in zip(self.names, levels):
            if level > (self.peak[0] if self.peak else 0.0):
                self.peak = (level, name, step)
        return list(levels)

    def summary(self):
        steps = self.history.delay_steps if self.laws else 0.0
        dt = self.dt if self.laws else 0.0
        text = (f"delay {steps:.3g} steps ({steps * dt * 1e3:.3g} ms at dt {dt * 1e3:.3g} ms), "
                f"velocity factor {'on' if self.velocity_factor else 'off'}, "
                f"force lag {self.force_lag_s * 1e3:.3g} ms")
        if self.peak:
            return text + f"; highest level {self.peak[0]:.3g} ({self.peak[1]}, step {self.peak[2]})"
        return text + "; every level 0"
