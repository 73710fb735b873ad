"""Force development: the levels sent follow the law's through a first-order lag, discretized
exactly for an input moving linearly over the step (a first-order hold; Franklin, Powell &
Workman 1998, sec. 6.3.2): y(k+n) = E y(k) + a u(k) + b u(k+n), E = exp(-h / tau), h = n dt
(controllers/ep_controller/force_lag.hpp)."""
import math


class ForceLag:
    def __init__(self, size, tau_s, dt_s):
        if not (tau_s >= 0.0 and math.isfinite(tau_s)):
            raise ValueError("the force lag's time constant must be a finite number >= 0 s")
        self.tau_s, self.dt_s = tau_s, dt_s
        self.y = [0.0] * size
        self.u = [0.0] * size  # the previous update's input
        self.last_step = None

    def update(self, step, u):
        steps = 1
        if self.last_step is not None and step > self.last_step:
            steps = step - self.last_step
        elif self.last_step is not None:  # a reset: the server starts from 0 again
            self.y = [0.0] * len(self.y)
            self.u = [0.0] * len(self.u)
        self.last_step = step
        if self.tau_s == 0.0:
            self.y = list(u)
            return self.y
        x = float(steps) * self.dt_s / self.tau_s  # h / tau
        one_minus_e = -math.expm1(-x)
        e = 1.0 - one_minus_e
        b = 1.0 - one_minus_e / x
        a = one_minus_e - b
        self.y = [e * y + a * u0 + b * u1 for y, u0, u1 in zip(self.y, self.u, u)]
        self.u = list(u)
        return self.y
