"""The reflex delay: past muscle lengths and velocities by step, the feedback for the command of
step k taken at k - D (D = delay / dt >= 1 steps), interpolated linearly between the states
around it, the oldest kept before the history starts, the latest after it
(controllers/ep_controller/delay_buffer.hpp)."""
import math

WHOLE_STEPS = 1e-9  # relative: d / dt off a whole number by round-off only


def _round_half_away(x):  # C's round()
    return math.copysign(math.floor(abs(x) + 0.5), x)


class DelayBuffer:
    def __init__(self, delay_steps):
        nearest = _round_half_away(delay_steps)
        if abs(delay_steps - nearest) <= WHOLE_STEPS * nearest:
            delay_steps = nearest
        if not (delay_steps >= 1.0 and math.isfinite(delay_steps)):
            raise ValueError(f"the delay must be at least 1 step, got {delay_steps:g}")
        self.delay_steps = delay_steps
        self.entries = []  # (step, lengths [m], velocities [m/s])

    def push(self, step, lengths_m, velocities_m_s):
        while self.entries and self.entries[-1][0] >= step:
            self.entries.pop()  # a reset: the server went back
        self.entries.append((step, list(lengths_m), list(velocities_m_s)))
        oldest_wanted = float(self.entries[-1][0]) + 1.0 - self.delay_steps
        while len(self.entries) > 1 and float(self.entries[1][0]) <= oldest_wanted:
            self.entries.pop(0)

    def for_step(self, step):
        """(lengths, velocities) for the command of `step`."""
        wanted = float(step) - self.delay_steps
        if wanted <= float(self.entries[0][0]):
            return self.entries[0][1], self.entries[0][2]
        if wanted >= float(self.entries[-1][0]):
            return self.entries[-1][1], self.entries[-1][2]
        i = 1
        while float(self.entries[i][0]) <= wanted:
            i += 1
        (s0, l0, v0), (s1, l1, v1) = self.entries[i - 1], self.entries[i]
        theta = (wanted - float(s0)) / (float(s1) - float(s0))
        return ([a + theta * (b - a) for a, b in zip(l0, l1)],
                [a + theta * (b - a) for a, b in zip(v0, v1)])
