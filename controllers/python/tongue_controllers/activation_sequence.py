"""An activation sequence: steps and ramps of activation per muscle or group over time, the file
format and rules of the C++ sequence player (controllers/sequence_player/activation_sequence.hpp):
levels in [0, 1] of F_max or forces in N split over the named muscles by F_max; an entry is
active while start <= t <= end; a later entry wins where active entries overlap; a muscle some
entry names is at 0 while none of its entries is active; muscles no entry names are not sent."""
import math

import tongue

from tongue_controllers.program import InputError
from tongue_controllers.yaml_input import YamlInput

TIME_TOLERANCE = 1e-9  # s: (k + 1) dt and a written end time differ by round-off


def steps_covering(duration_s, dt_s):
    """The number of steps of dt that cover duration, as sim_batch counts a scene's steps."""
    return max(1, int(math.ceil(duration_s / dt_s - 1e-9)))


class SequenceEntry:
    def __init__(self, file, node, path):
        file.mapping(node, path, ["muscle", "start", "end", "level", "force", "level_from",
                                  "level_to", "force_from", "force_to"])
        self.key_path = path
        self.muscle = file.required(node, path, "muscle")
        if not isinstance(self.muscle, str):
            file.fail(f"{path}.muscle", "expected a muscle or group name")
        self.start_s = file.non_negative(node.get("start", 0.0), f"{path}.start", "s")
        self.end_s = math.inf
        if "end" in node:
            self.end_s = file.number(node["end"], f"{path}.end")
            if not self.end_s > self.start_s:
                file.fail(f"{path}.end", f"must be after start ({self.start_s:g} s), "
                          f"got {self.end_s:g} s")
        kinds = [k for k in ("level", "force") if k in node]
        ramps = [k for k in ("level", "force") if f"{k}_from" in node or f"{k}_to" in node]
        if len(kinds) + len(ramps) != 1:
            file.fail(path, "give exactly one of level, force (a step), level_from + level_to, "
                      "force_from + force_to (a ramp)")
        self.unit = (kinds + ramps)[0]
        self.ramp = bool(ramps)
        if self.ramp:
            self.start_value = self._value(file, node, path, f"{self.unit}_from")
            self.end_value = self._value(file, node, path, f"{self.unit}_to")
            if math.isinf(self.end_s):
                file.fail(f"{path}.end", "a ramp needs an end time")
        else:
            self.start_value = self.end_value = self._value(file, node, path, self.unit)

    def _value(self, file, node, path, key):
        key_path = f"{path}.{key}"
        if self.unit == "force":
            return file.non_negative(file.required(node, path, key), key_path, "N")
        level = file.number(file.required(node, path, key), key_path)
        if not 0.0 <= level <= 1.0:
            file.fail(key_path, f"a level must be in [0, 1] of F_max, got {level:g}")
        return level


class SequenceSpec:
    """A sequence file read and checked; InputError naming the file and key when it cannot be
    used."""

    def __init__(self, path):
        file = YamlInput(path)
        root = file.mapping(file.root, "", ["duration", "entries"])
        self.source = path
        self.duration_s = None
        if root.get("duration") is not None:
            self.duration_s = file.number(root["duration"], "duration")
            if not self.duration_s > 0.0:
                file.fail("duration", f"must be positive, got {self.duration_s:g} s")
        entries = file.required(root, "", "entries")
        if not isinstance(entries, list):
            file.fail("entries", "expected a list")
        self.entries = [SequenceEntry(file, e, f"entries[{i}]") for i, e in enumerate(entries)]


class ActivationSequence:
    """A sequence resolved against the model's muscles."""

    def __init__(self, spec, muscle_names, max_forces_n):
        self.names = list(muscle_names)
        self.entries = []  # (muscles, start, end, from level, to level, ramp)
        driven = set()
        for e in spec.entries:
            muscles = tongue.select_muscles(e.muscle, self.names)
            if not muscles:
                raise InputError(spec.source, f"{e.key_path}.muscle",
                                 f"no muscle is named '{e.muscle}' or starts with '{e.muscle}_' "
                                 f"(the server's muscles: {', '.join(self.names)})")
            start_level, end_level = e.start_value, e.end_value
            if e.unit == "force":
                total = 0.0
                for m in muscles:
                    total += max_forces_n[m]
                largest = max(e.start_value, e.end_value)
                if largest > total * (1.0 + 1e-12):
                    raise InputError(spec.source, e.key_path,
                                     f"{largest:g} N exceeds the summed F_max of {e.muscle}, "
                                     f"{total:g} N")
                start_level = min(1.0, e.start_value / total)
                end_level = min(1.0, e.end_value / total)
            self.entries.append((muscles, e.start_s, e.end_s, start_level, end_level, e.ramp))
            driven.update(muscles)
        self.driven = sorted(driven)

    def levels_at(self, t):
        """{muscle: level} at time t [s] of every muscle some entry names, in model order."""
        level = [0.0] * len(self.names)
        for muscles, start, end, first, last, ramp in self.entries:
            if t < start - TIME_TOLERANCE or t > end + TIME_TOLERANCE:
                continue
            value = first
            if ramp:
                s = min(max((t - start) / (end - start), 0.0), 1.0)
                value = first + (last - first) * s
            for m in muscles:
                level[m] = value
        return {self.names[m]: level[m] for m in self.driven}
