"""A motor plan: per muscle or group, the targets of Delta-lambda (mm) reached one after the
other, each approached linearly over `transition` and held for `hold`, from `start` on
(controllers/ep_controller/motor_plan.hpp gives the file format)."""
import math

import tongue

from tongue_controllers.program import InputError
from tongue_controllers.yaml_input import YamlInput


class DeltaLambdaTrack:
    def __init__(self, targets_mm, transition_s, hold_s, start_s):
        self.targets_mm, self.transition_s = targets_mm, transition_s
        self.hold_s, self.start_s = hold_s, start_s

    def at(self, t):
        """Delta-lambda [mm] at time t [s]."""
        if not self.targets_mm or t <= self.start_s:
            return 0.0
        elapsed = t - self.start_s
        period = self.transition_s + self.hold_s
        n = len(self.targets_mm)
        if not period > 0.0:
            return self.targets_mm[-1]
        segments = float(math.floor(elapsed / period))
        if segments >= float(n):
            return self.targets_mm[-1]
        i = int(segments)
        start = 0.0 if i == 0 else self.targets_mm[i - 1]
        into = elapsed - segments * period
        if into < self.transition_s:
            return start + (self.targets_mm[i] - start) * (into / self.transition_s)
        return self.targets_mm[i]


def _durations(file, node, path, defaults):
    out = dict(defaults)
    for key in ("transition", "hold", "start"):
        if node.get(key) is not None:
            out[key] = file.non_negative(node[key], f"{path}.{key}" if path else key, "s")
    return out


def _targets(file, node, path):
    if not isinstance(node, list) or not node:
        file.fail(path, "expected a non-empty list of Delta-lambda targets in mm")
    return [file.number(v, f"{path}[{i}]") for i, v in enumerate(node)]


class MotorPlanSpec:
    """A plan file read and checked; InputError naming the file and key when it cannot be used."""

    def __init__(self, path):
        file = YamlInput(path)
        root = file.mapping(file.root, "", ["transition", "hold", "start", "delta_lambda_mm",
                                            "rho"])
        self.source = path
        defaults = _durations(file, root, "", {"transition": 0.05, "hold": 0.1, "start": 0.0})
        plan = file.required(root, "", "delta_lambda_mm")
        if not isinstance(plan, dict):
            file.fail("delta_lambda_mm", "expected a map of muscle or group -> targets")
        self.entries = []  # (name, key path, track)
        for name, node in plan.items():
            path = f"delta_lambda_mm.{name}"
            if isinstance(node, dict):
                file.mapping(node, path, ["targets", "transition", "hold", "start"])
                targets = _targets(file, file.required(node, path, "targets"), f"{path}.targets")
                d = _durations(file, node, path, defaults)
            elif isinstance(node, list):
                targets, d = _targets(file, node, path), defaults
            else:
                file.fail(path, "expected a list of Delta-lambda targets in mm, or {targets: "
                          "[...], transition, hold, start}")
            if len(targets) > 1 and not d["transition"] + d["hold"] > 0.0:
                file.fail(path, "transition and hold are both 0 s: only the last of several "
                          "targets would ever be used")
            self.entries.append((str(name), path, DeltaLambdaTrack(
                targets, d["transition"], d["hold"], d["start"])))
        self.rho = []  # (name, key path, rho [N])
        rho = root.get("rho")
        if rho is not None:
            if not isinstance(rho, dict):
                file.fail("rho", "expected a map of muscle or group -> rho in N")
            for name, value in rho.items():
                path = f"rho.{name}"
                r = file.number(value, path)
                if not r > 0.0:
                    file.fail(path, f"rho must be positive, got {r:g} N")
                self.rho.append((str(name), path, r))


def no_muscle(source, key_path, name, muscle_names):
    return InputError(source, key_path,
                      f"no muscle is named '{name}' or starts with '{name}_' (the server's "
                      f"muscles: {', '.join(muscle_names)})")


class MotorPlan:
    """A plan resolved against the model's muscles."""

    def __init__(self, spec, muscle_names):
        self.track_of = [None] * len(muscle_names)
        set_by = [None] * len(muscle_names)
        for name, path, track in spec.entries:
            members = tongue.select_muscles(name, muscle_names)
            if not members:
                raise no_muscle(spec.source, path, name, muscle_names)
            for m in members:
                if self.track_of[m] is not None:
                    raise InputError(spec.source, path,
                                     f"muscle {muscle_names[m]} is also set by {set_by[m]}")
                self.track_of[m], set_by[m] = track, path

    def delta_lambda_mm(self, muscle, t):
        track = self.track_of[muscle]
        return 0.0 if track is None else track.at(t)
