"""The step controller: plays an activation sequence (activation_sequence.py), the levels for
step k those at t = k dt, and ends after the step reaching the sequence's duration."""
from tongue_controllers.activation_sequence import ActivationSequence, steps_covering


class SequencePlayer:
    def __init__(self, spec):
        self.spec = spec
        self.sequence = None
        self.dt = 0.0
        self.end_step = None

    def start(self, model):
        if not model.dt > 0.0:
            raise ValueError(f"the model's dt is {model.dt:g} s, not > 0")
        self.dt = model.dt
        self.sequence = ActivationSequence(self.spec, model.muscle_names, model.max_forces)
        if self.spec.duration_s is not None:
            self.end_step = steps_covering(self.spec.duration_s, self.dt)

    def last_step(self):
        return self.end_step

    def observe(self, state):
        pass  # open loop

    def command(self, step):
        return self.sequence.levels_at(float(step) * self.dt)

    def summary(self):
        if self.sequence is None:
            return ""
        return (f"{len(self.spec.entries)} entries over {len(self.sequence.driven)} muscles "
                f"from {self.spec.source}")
